// The page's copy of the project's one SH basis (src/core/sh.h: the 3DGS trainers' real
// spherical harmonics up to degree 3, same constants, same coefficient order and signs).
// Used by the sort worker to colour each drawn splat for the current view direction.
export const SH_C0 = 0.28209479177387814;
const C1 = 0.4886025119029199;
const C2 = [1.0925484305920792, -1.0925484305920792, 0.31539156525252005, -1.0925484305920792, 0.5462742152960396];
const C3 = [-0.5900435899266435, 2.890611442640554, -0.4570457994644658, 0.3731763325901154, -0.4570457994644658,
  1.445305721320277, -0.5900435899266435];

// Basis values 1 .. (degree+1)^2 - 1 (the DC term is not needed) for the unit direction
// (x, y, z) into b[0 ..], as core/sh.h's sh_basis writes b[1 ..].
export function shBasisRest(degree, x, y, z, b) {
  b[0] = -C1 * y; b[1] = C1 * z; b[2] = -C1 * x;
  if (degree < 2) return;
  const xx = x * x, yy = y * y, zz = z * z, xy = x * y, yz = y * z, xz = x * z;
  b[3] = C2[0] * xy; b[4] = C2[1] * yz; b[5] = C2[2] * (2 * zz - xx - yy); b[6] = C2[3] * xz; b[7] = C2[4] * (xx - yy);
  if (degree < 3) return;
  b[8] = C3[0] * y * (3 * xx - yy);
  b[9] = C3[1] * xy * z;
  b[10] = C3[2] * y * (4 * zz - xx - yy);
  b[11] = C3[3] * z * (2 * zz - 3 * xx - 3 * yy);
  b[12] = C3[4] * x * (4 * zz - xx - yy);
  b[13] = C3[5] * z * (xx - yy);
  b[14] = C3[6] * x * (xx - 3 * yy);
}
