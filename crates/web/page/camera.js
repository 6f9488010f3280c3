// The VTK camera of tetray_core::Camera, in the same arithmetic: the view
// basis in double precision from single-precision inputs, rounded to
// single precision where the Rust code rounds, so that a camera given to
// the page and to `tetray render` makes the same rays.

const f32 = Math.fround;

function sub3(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
function add3(a, b) { return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]; }
function mul3(a, s) { return [a[0] * s, a[1] * s, a[2] * s]; }
function dot3(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function cross3(a, b) {
  return [a[1] * b[2] - b[1] * a[2], a[2] * b[0] - b[2] * a[0], a[0] * b[1] - b[0] * a[1]];
}
function length3(a) { return Math.sqrt(dot3(a, a)); }
function round3(a) { return [f32(a[0]), f32(a[1]), f32(a[2])]; }
function finite3(a) { return a.every(Number.isFinite); }
// glam's normalize: times the reciprocal of the length.
function normalize3(a) { return mul3(a, 1 / length3(a)); }

class CameraError extends Error {}

// A camera: position, focal_point, view_up ([x, y, z], single precision),
// view_angle (degrees), parallel_scale (a number: orthographic, or null).
function cameraCopy(c) {
  return {
    position: round3(c.position),
    focal_point: round3(c.focal_point),
    view_up: round3(c.view_up),
    view_angle: f32(c.view_angle),
    parallel_scale: c.parallel_scale == null ? null : f32(c.parallel_scale),
  };
}

// The orthonormal view basis (Camera::basis).
function cameraBasis(c) {
  for (const [name, v] of [["position", c.position], ["focal point", c.focal_point], ["view-up", c.view_up]]) {
    if (!finite3(v)) throw new CameraError(`the camera's ${name} is not finite`);
  }
  if (!(c.view_angle > 0 && c.view_angle < 180)) throw new CameraError(`view angle ${c.view_angle} is outside (0, 180)`);
  if (c.parallel_scale != null && !(Number.isFinite(c.parallel_scale) && c.parallel_scale > 0)) {
    throw new CameraError(`parallel scale ${c.parallel_scale} must be a finite number above 0`);
  }
  let direction = sub3(c.focal_point, c.position);
  const rcp = 1 / length3(direction);
  if (!(Number.isFinite(rcp) && rcp > 0)) throw new CameraError("the camera is at its focal point");
  direction = mul3(direction, rcp);
  let right = cross3(direction, c.view_up);
  if (length3(right) <= 1e-6 * length3(c.view_up) || !finite3(right)) {
    throw new CameraError("the view-up is parallel to the view direction");
  }
  right = normalize3(right);
  const up = cross3(right, direction);
  return { direction: round3(direction), right: round3(right), up: round3(up) };
}

// Rotates `point` by `degrees` about `axis` through `centre` (Rodrigues).
function rotateAbout(point, centre, axis, degrees) {
  axis = normalize3(axis);
  const radians = f32(degrees) * (Math.PI / 180);
  const sin = Math.sin(radians), cos = Math.cos(radians);
  const p = sub3(point, centre);
  const rotated = add3(add3(mul3(p, cos), mul3(cross3(axis, p), sin)), mul3(axis, dot3(axis, p) * (1 - cos)));
  return round3(add3(centre, rotated));
}

// vtkCamera::Azimuth: about the view-up through the focal point.
function cameraAzimuth(c, degrees) {
  cameraBasis(c);
  c.position = rotateAbout(c.position, c.focal_point, c.view_up, degrees);
}

// vtkCamera::Elevation: about the negative screen right.
function cameraElevation(c, degrees) {
  const b = cameraBasis(c);
  c.position = rotateAbout(c.position, c.focal_point, mul3(b.right, -1), degrees);
}

function cameraOrthogonalize(c) {
  c.view_up = cameraBasis(c).up;
}

// The viewer's orbit: a drag across the whole view turns 200 degrees.
function cameraOrbit(c, dx, dy, width, height) {
  const next = cameraCopy(c);
  cameraAzimuth(next, f32(-dx / Math.max(width, 1) * 200));
  cameraElevation(next, f32(dy / Math.max(height, 1) * 200));
  cameraOrthogonalize(next);
  Object.assign(c, next);
}

// The viewer's pan: the point under the mouse follows it.
function cameraPan(c, dx, dy, height) {
  const b = cameraBasis(c);
  const distance = length3(sub3(c.focal_point, c.position));
  const viewHeight = c.parallel_scale != null ? 2 * c.parallel_scale
    : 2 * distance * Math.tan(c.view_angle * Math.PI / 360);
  const perPixel = viewHeight / Math.max(height, 1);
  const shift = mul3(add3(mul3(b.right, -dx), mul3(b.up, dy)), perPixel);
  c.position = round3(add3(c.position, shift));
  c.focal_point = round3(add3(c.focal_point, shift));
}

// The viewer's dolly: 10% closer per step (orthographic: zoom).
function cameraDolly(c, steps) {
  const factor = f32(Math.pow(1.1, steps));
  if (c.parallel_scale != null) {
    c.parallel_scale = f32(c.parallel_scale / factor);
  } else {
    const offset = sub3(c.position, c.focal_point);
    c.position = round3(add3(c.focal_point, offset.map((o) => o / factor)));
  }
  cameraBasis(c);
}

// WGSL ViewParams (16 words) and whether the eye is inside `bounds`
// (Camera::pixel_rays, tetray_gpu::frame_params).
function viewParams(c, width, height, bounds) {
  const b = cameraBasis(c);
  const halfHeight = c.parallel_scale != null ? c.parallel_scale
    : Math.tan(c.view_angle * (Math.PI / 180) * 0.5);
  const pixel = f32(2 * halfHeight / height);
  const orthographic = c.parallel_scale != null;
  const [lo, hi] = bounds;
  const inside = c.position.every((p, i) => p >= lo[i] && p <= hi[i]);
  return {
    position: c.position, orthographic, right: b.right, pixel, up: b.up,
    halfWidth: f32(width * 0.5), direction: b.direction, halfHeight: f32(height * 0.5),
    eyeInside: !orthographic && inside,
  };
}
