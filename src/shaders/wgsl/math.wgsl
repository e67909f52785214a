const PI: f32 = 3.14159265358979323846;
const TWO_PI: f32 = 6.28318530717958647692;
const INV_PI: f32 = 0.31830988618379067154;
const INV_FOUR_PI: f32 = 0.07957747154594766788;
const F32_INF: f32 = 3.4028234663852886e38;

// Rec. 709 / sRGB primaries luminance.
fn luminance(c: vec3f) -> f32 {
  return dot(c, vec3f(0.2126, 0.7152, 0.0722));
}

fn max_component(v: vec3f) -> f32 {
  return max(v.x, max(v.y, v.z));
}

fn is_finite_vec3(v: vec3f) -> bool {
  // NaN fails every comparison; Inf fails the bound.
  return all(abs(v) <= vec3f(F32_INF));
}

struct Frame {
  t: vec3f,
  b: vec3f,
  n: vec3f,
}

// Orthonormal basis around a unit normal: Duff et al., "Building an Orthonormal Basis, Revisited",
// JCGT 6(1), 2017.
fn make_frame(n: vec3f) -> Frame {
  let s = select(-1.0, 1.0, n.z >= 0.0);
  let a = -1.0 / (s + n.z);
  let b = n.x * n.y * a;
  return Frame(vec3f(1.0 + s * n.x * n.x * a, s * b, -s * n.x), vec3f(b, s + n.y * n.y * a, -n.y), n);
}

fn to_local(f: Frame, v: vec3f) -> vec3f {
  return vec3f(dot(v, f.t), dot(v, f.b), dot(v, f.n));
}

fn to_world(f: Frame, v: vec3f) -> vec3f {
  return f.t * v.x + f.b * v.y + f.n * v.z;
}

// Spawned-ray origin pushed off the surface along n by a few ulps: Waechter and Binder,
// "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6 (2019).
// `n` must point to the side the new ray leaves towards.
fn offset_ray_origin(p: vec3f, n: vec3f) -> vec3f {
  let origin = 1.0 / 32.0;
  let float_scale = 1.0 / 65536.0;
  let int_scale = 256.0;
  let of_i = vec3i(int_scale * n);
  let p_i = vec3f(
    bitcast<f32>(bitcast<i32>(p.x) + select(of_i.x, -of_i.x, p.x < 0.0)),
    bitcast<f32>(bitcast<i32>(p.y) + select(of_i.y, -of_i.y, p.y < 0.0)),
    bitcast<f32>(bitcast<i32>(p.z) + select(of_i.z, -of_i.z, p.z < 0.0)));
  return vec3f(
    select(p_i.x, p.x + float_scale * n.x, abs(p.x) < origin),
    select(p_i.y, p.y + float_scale * n.y, abs(p.y) < origin),
    select(p_i.z, p.z + float_scale * n.z, abs(p.z) < origin));
}
