// Ray-primitive intersection. Results are vec3f(t, u, v) with t < 0 for "no hit".

// Moller and Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection", JGT 2(1), 1997.
// Two-sided: shading decides what the back face does.
fn intersect_triangle(origin: vec3f, direction: vec3f, tri: Triangle, t_max: f32) -> vec3f {
  let p = cross(direction, tri.e2);
  let det = dot(tri.e1, p);
  if (abs(det) < 1e-20) { return vec3f(-1.0, 0.0, 0.0); }
  let inv_det = 1.0 / det;
  let s = origin - tri.v0;
  let u = dot(s, p) * inv_det;
  if (u < 0.0 || u > 1.0) { return vec3f(-1.0, 0.0, 0.0); }
  let q = cross(s, tri.e1);
  let v = dot(direction, q) * inv_det;
  if (v < 0.0 || u + v > 1.0) { return vec3f(-1.0, 0.0, 0.0); }
  let t = dot(tri.e2, q) * inv_det;
  if (t <= 0.0 || t >= t_max) { return vec3f(-1.0, 0.0, 0.0); }
  return vec3f(t, u, v);
}

// Ray/sphere with the numerically careful discriminant of Haines et al., "Precision Improvements
// for Ray/Sphere Intersection", Ray Tracing Gems ch. 7 (2019). `direction` is unit length.
fn intersect_sphere(origin: vec3f, direction: vec3f, center: vec3f, radius: f32, t_max: f32) -> f32 {
  let f = origin - center;
  let b = -dot(f, direction);
  let l = f + b * direction;
  let disc = radius * radius - dot(l, l);
  if (disc < 0.0) { return -1.0; }
  let sq = sqrt(disc);
  let c = dot(f, f) - radius * radius;
  let q = b + select(-sq, sq, b >= 0.0);
  var t0 = c / q;
  var t1 = q;
  if (t0 > t1) { let tmp = t0; t0 = t1; t1 = tmp; }
  // A ray leaving the surface it starts on sees its own sphere at t ~ 0; require a small margin
  // relative to the radius.
  let eps = 1e-4 * radius;
  if (t0 > eps && t0 < t_max) { return t0; }
  if (t1 > eps && t1 < t_max) { return t1; }
  return -1.0;
}

// Slab test for an axis-aligned box; returns the first crossing beyond a small margin.
fn intersect_box(origin: vec3f, direction: vec3f, bmin: vec3f, bmax: vec3f, t_max: f32) -> f32 {
  let inv = 1.0 / direction;
  let t0 = (bmin - origin) * inv;
  let t1 = (bmax - origin) * inv;
  let tn = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), min(t0.z, t1.z));
  let tf = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z));
  if (tn > tf) { return -1.0; }
  let eps = 1e-4 * max_component(bmax - bmin);
  if (tn > eps && tn < t_max) { return tn; }
  if (tf > eps && tf < t_max) { return tf; }
  return -1.0;
}

// Entry distance of a ray into an AABB, or F32_INF when it misses within [0, t_max].
fn intersect_aabb(origin: vec3f, inv_direction: vec3f, bmin: vec3f, bmax: vec3f, t_max: f32) -> f32 {
  let t0 = (bmin - origin) * inv_direction;
  let t1 = (bmax - origin) * inv_direction;
  let tn = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
  let tf = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), t_max));
  return select(F32_INF, tn, tn <= tf);
}
