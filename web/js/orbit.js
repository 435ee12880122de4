// The free camera: orbit (yaw/pitch about a target around the scene's up axis), pan and
// zoom, initialised from a training camera so switching keeps the view.
const add = (a, b) => a.map((v, i) => v + b[i]);
const sub = (a, b) => a.map((v, i) => v - b[i]);
const mul = (a, s) => a.map((v) => v * s);
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => { const l = Math.hypot(...a) || 1; return mul(a, 1 / l); };

export class Orbit {
  constructor(up) {
    this.up = norm(up);
    const helper = Math.abs(this.up[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    this.e1 = norm(cross(helper, this.up));
    this.e2 = cross(this.up, this.e1);
    this.target = [0, 0, 0]; this.distance = 1; this.yaw = 0; this.pitch = 0; this.fov = 60;
  }

  // Takes a training camera's pose; the target is where its axis passes the pivot (the
  // robust centre). When the pivot is behind or beside the camera, `fallback` (the
  // server's orbit distance) sets how far ahead the target is.
  fromCamera(cam, sceneCenter, fallback = 0) {
    const f = norm(cam.forward);
    const along = dot(sub(sceneCenter, cam.center), f);
    const d = along > 0.1 * fallback && along > 0 ? along
      : fallback > 0 ? fallback : Math.max(along, 1e-3 * Math.hypot(...sub(sceneCenter, cam.center)) + 1e-6);
    this.target = add(cam.center, mul(f, d));
    this.distance = d;
    const off = norm(sub(cam.center, this.target));
    this.pitch = Math.asin(Math.max(-1, Math.min(1, dot(off, this.up))));
    this.yaw = Math.atan2(dot(off, this.e2), dot(off, this.e1));
    this.fov = cam.fov;
    this.clampPitch();
  }

  clampPitch() { const lim = (85 * Math.PI) / 180; this.pitch = Math.max(-lim, Math.min(lim, this.pitch)); }

  eye() {
    const c = Math.cos(this.pitch);
    const dir = add(add(mul(this.e1, c * Math.cos(this.yaw)), mul(this.e2, c * Math.sin(this.yaw))), mul(this.up, Math.sin(this.pitch)));
    return add(this.target, mul(dir, this.distance));
  }

  rotate(dx, dy) { this.yaw -= dx * 0.008; this.pitch += dy * 0.008; this.clampPitch(); }

  pan(dx, dy, viewHeight) {
    const eye = this.eye();
    const f = norm(sub(this.target, eye));
    const right = norm(cross(f, this.up));
    const camUp = cross(right, f);
    const k = (2 * this.distance * Math.tan((this.fov * Math.PI) / 360)) / Math.max(viewHeight, 1);
    this.target = add(this.target, add(mul(right, -dx * k), mul(camUp, dy * k)));
  }

  // Pick-to-focus: orbit around `point` from where the camera is (the view does not jump).
  focus(point) {
    const eye = this.eye();
    const off = sub(eye, point);
    const d = Math.hypot(...off);
    if (!(d > 1e-9)) return;
    this.target = point.slice();
    this.distance = d;
    const u = mul(off, 1 / d);
    this.pitch = Math.asin(Math.max(-1, Math.min(1, dot(u, this.up))));
    this.yaw = Math.atan2(dot(u, this.e2), dot(u, this.e1));
    this.clampPitch();
  }

  // Fly mode: mouse look turns the camera about its own position.
  look(dx, dy) {
    const eye = this.eye();
    this.yaw -= dx * 0.004; this.pitch += dy * 0.004; this.clampPitch();
    const c = Math.cos(this.pitch);
    const dir = add(add(mul(this.e1, c * Math.cos(this.yaw)), mul(this.e2, c * Math.sin(this.yaw))), mul(this.up, Math.sin(this.pitch)));
    this.target = sub(eye, mul(dir, this.distance));
  }

  // Fly mode: moves eye and target together (forward, right, up; world units).
  move(forward, right, up) {
    const f = norm(sub(this.target, this.eye()));
    const r = norm(cross(f, this.up));
    this.target = add(this.target, add(add(mul(f, forward), mul(r, right)), mul(this.up, up)));
  }

  zoom(factor) { this.distance = Math.max(1e-4, Math.min(1e6, this.distance * factor)); }

  // The free camera as the API takes it.
  spec(width, height) {
    const r = (v) => v.map((x) => Number(x.toPrecision(9)));
    return { eye: r(this.eye()), target: r(this.target), up: r(this.up), fov: Number(this.fov.toFixed(4)), width, height };
  }
}
