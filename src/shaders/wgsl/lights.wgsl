// Light sampling: emissive triangles through a power-proportional alias table plus the uniform
// environment, for next-event estimation combined with BSDF sampling by MIS (Veach 1997, ch. 9).

// Power heuristic with beta = 2 (Veach 1997, eq. 9.13).
fn power_heuristic(pdf_a: f32, pdf_b: f32) -> f32 {
  let a = pdf_a * pdf_a;
  let b = pdf_b * pdf_b;
  if (a + b <= 0.0) { return 0.0; }
  return a / (a + b);
}

// Walker/Vose alias table lookup with one uniform number.
fn sample_light_index(u: f32) -> u32 {
  let n = frame.lightCount;
  let scaled = u * f32(n);
  let bin = min(u32(scaled), n - 1u);
  let frac = scaled - f32(bin);
  let entry = lights[bin];
  return select(entry.aliasIndex, bin, frac < entry.threshold);
}

// Uniform point on a triangle (barycentrics by the square-root warp, pbrt-v4 SampleUniformTriangle).
fn sample_triangle_point(v0: vec3f, e1: vec3f, e2: vec3f, u: vec2f) -> vec3f {
  let su = sqrt(u.x);
  let b1 = 1.0 - su;
  let b2 = u.y * su;
  return v0 + b1 * e1 + b2 * e2;
}

fn uniform_sphere_direction(u: vec2f) -> vec3f {
  let z = 1.0 - 2.0 * u.x;
  let r = sqrt(max(0.0, 1.0 - z * z));
  let phi = TWO_PI * u.y;
  return vec3f(r * cos(phi), r * sin(phi), z);
}

// Solid-angle density with which NEE would have chosen an emitter point seen at distance `dist`
// with cosine `cos_light` on a triangle of `area` and selection probability `pmf`.
fn triangle_light_pdf(pmf: f32, area: f32, dist: f32, cos_light: f32) -> f32 {
  if (cos_light <= 0.0 || area <= 0.0) { return 0.0; }
  return (1.0 - frame.environmentSelectProbability) * pmf * dist * dist / (area * cos_light);
}

fn environment_light_pdf() -> f32 {
  return frame.environmentSelectProbability * INV_FOUR_PI;
}

// Octahedral snorm16x2 decode (Cigolle et al. 2014); mirrors src/gpu-layout/octahedral.ts.
fn decode_octahedral(bits: u32) -> vec3f {
  let e = unpack2x16snorm(bits);
  var n = vec3f(e.x, e.y, 1.0 - abs(e.x) - abs(e.y));
  let t = max(-n.z, 0.0);
  n.x += select(t, -t, n.x >= 0.0);
  n.y += select(t, -t, n.y >= 0.0);
  return normalize(n);
}
