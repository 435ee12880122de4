// GLSL of the WebGL splat renderer (splat_renderer.js), two passes per frame:
//  1. PROJECT_VS, one vertex per drawn splat, rasteriser discarded, written out by
//     transform feedback: the splat's EWA footprint on screen (centre and the two scaled
//     axes of its ellipse, in pixels) and its colour.
//  2. QUAD_VS + SPLAT_FS: two triangles per splat from gl_VertexID that only read the
//     footprint (copied into a float texture) and place a corner.
// The projection used to run in each of a splat's six quad vertices: on SwiftShader
// (software WebGL, no GPU) that vertex work was most of a low-resolution frame.
export const NEAR = 0.2;  // the rasteriser's near plane
export const ORDER_ROW = 2048;  // sorted entries per row of the order texture
export const PROJ_ROW = 1024;  // footprints per row of the footprint texture (2 texels each)

// Follows the INRIA rasteriser: EWA projection with the perspective Jacobian (x/z, y/z
// clamped to 1.3x the half field of view), +0.3 px on the 2D covariance diagonal, the
// ellipse cut where alpha falls below 1/255 (at most 3 sigma). Outputs (pixels):
//   v_a = (centre x, y, axis 1 x, y), v_b = (axis 2 x, y, r + 256 g + 65536 b, 4 a + k)
// with the colour in bytes (exact in a float; bytes over [0, u_colour_scale]) and k the cut
// in sigmas; v_b.w < 0: not drawn.
export const projectVS = (splatRow) => `#version 300 es
precision highp float; precision highp int; precision highp usampler2D;
uniform usampler2D u_splats; uniform usampler2D u_mask; uniform usampler2D u_order;
uniform mat3 u_R; uniform vec3 u_t; uniform vec2 u_focal; uniform vec2 u_size; uniform vec2 u_tan;
uniform float u_tint; uniform float u_colour_scale;
out vec4 v_a; out vec4 v_b;
void main() {
  gl_Position = vec4(0.0); gl_PointSize = 1.0;
  int slot = gl_VertexID;
  uvec2 entry = texelFetch(u_order, ivec2(slot % ${ORDER_ROW}, slot / ${ORDER_ROW}), 0).rg;
  uint index = entry.r;
  ivec2 at = ivec2(int(index % ${splatRow}u) * 3, int(index / ${splatRow}u));
  uvec4 A = texelFetch(u_splats, at, 0), B = texelFetch(u_splats, at + ivec2(1, 0), 0),
        C = texelFetch(u_splats, at + ivec2(2, 0), 0);
  uint flags = texelFetch(u_mask, ivec2(int(index % 2048u), int(index / 2048u)), 0).r;
  vec3 c = u_R * uintBitsToFloat(A.xyz) + u_t;
  uvec4 rgba8 = uvec4(entry.g & 255u, (entry.g >> 8) & 255u, (entry.g >> 16) & 255u, entry.g >> 24);
  if ((flags & 2u) != 0u || c.z < ${NEAR} || rgba8.a == 0u) { v_a = vec4(0.0); v_b = vec4(0.0, 0.0, 0.0, -1.0); return; }
  vec4 b = uintBitsToFloat(B); vec2 cc = uintBitsToFloat(C.xy);
  mat3 V = mat3(b.x, b.y, b.z, b.y, b.w, cc.x, b.z, cc.x, cc.y);
  vec2 lim = 1.3 * u_tan;
  float tx = clamp(c.x / c.z, -lim.x, lim.x) * c.z, ty = clamp(c.y / c.z, -lim.y, lim.y) * c.z;
  float iz = 1.0 / c.z;
  mat3 J = mat3(u_focal.x * iz, 0.0, 0.0, 0.0, u_focal.y * iz, 0.0,
                -u_focal.x * tx * iz * iz, -u_focal.y * ty * iz * iz, 0.0);
  mat3 T = J * u_R;
  mat3 S = T * V * transpose(T);
  float a = S[0][0] + 0.3, bb = S[0][1], d = S[1][1] + 0.3;
  float mid = 0.5 * (a + d), rad = length(vec2(0.5 * (a - d), bb));
  float l1 = mid + rad, l2 = max(mid - rad, 1e-4);
  vec2 e1 = abs(bb) > 1e-9 ? normalize(vec2(bb, l1 - a)) : (a >= d ? vec2(1.0, 0.0) : vec2(0.0, 1.0));
  vec2 e2 = vec2(-e1.y, e1.x);
  float k = min(3.0, sqrt(2.0 * log(255.0 * float(rgba8.a) / 255.0)));
  vec2 px = vec2(u_focal.x * c.x * iz, u_focal.y * c.y * iz) + 0.5 * u_size;
  vec3 col = vec3(rgba8.rgb);
  if ((flags & 1u) != 0u) col = floor(mix(col, vec3(255.0, 51.0, 204.0) / u_colour_scale, u_tint) + 0.5);
  v_a = vec4(px, k * sqrt(l1) * e1);
  v_b = vec4(k * sqrt(l2) * e2, col.r + 256.0 * col.g + 65536.0 * col.b, 4.0 * float(rgba8.a) + k);
}`;

// Discards everything (the projection pass only feeds transform feedback).
export const NOTHING_FS = `#version 300 es
precision mediump float; out vec4 o; void main() { discard; }`;

// Two triangles per splat from gl_VertexID, no attributes (instancing is ~3x slower on
// SwiftShader, which draws instances one by one); the splat is footprint gl_VertexID / 6.
export const QUAD_VS = `#version 300 es
precision highp float; precision highp int;
uniform highp sampler2D u_proj; uniform vec2 u_size; uniform float u_colour_scale;
out vec4 v_color; out vec2 v_pos;
const vec2 CORNERS[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(-1, 1), vec2(-1, 1), vec2(1, -1), vec2(1, 1));
void main() {
  int slot = gl_VertexID / 6;
  vec2 corner = CORNERS[gl_VertexID % 6];
  ivec2 at = ivec2((slot % ${PROJ_ROW}) * 2, slot / ${PROJ_ROW});
  vec4 a = texelFetch(u_proj, at, 0), b = texelFetch(u_proj, at + ivec2(1, 0), 0);
  if (b.w < 0.0) { gl_Position = vec4(0.0, 0.0, 2.0, 1.0); return; }
  vec2 px = a.xy + corner.x * a.zw + corner.y * b.xy;
  gl_Position = vec4(2.0 * px.x / u_size.x - 1.0, 1.0 - 2.0 * px.y / u_size.y, 0.0, 1.0);
  float alpha = floor(b.w * 0.25), k = b.w - 4.0 * alpha;
  float blue = floor(b.z / 65536.0), green = floor((b.z - 65536.0 * blue) / 256.0);
  v_color = vec4(b.z - 65536.0 * blue - 256.0 * green, green, blue, alpha) / 255.0;
  v_color.rgb *= u_colour_scale;  // bytes over [0, hi]: colours above 1 blend as such
  v_pos = corner * k;
}`;

// alpha = min(0.99, o exp(-d^2/2)) cut at 1/255, premultiplied, blended far to near.
export const SPLAT_FS = `#version 300 es
precision highp float;
in vec4 v_color; in vec2 v_pos; out vec4 o;
void main() {
  float alpha = min(0.99, v_color.a * exp(-0.5 * dot(v_pos, v_pos)));
  if (alpha < 1.0 / 255.0) discard;
  o = vec4(v_color.rgb * alpha, alpha);
}`;
