// Isotropic GGX / Trowbridge-Reitz microfacet distribution with the Smith masking-shadowing model,
// in the local shading frame (z = shading normal). alpha = perceptual roughness^2 (glTF 2.0
// Appendix B). Formulas are written with sin^2 = x^2 + y^2 instead of 1 - cos^2 so that tiny alpha
// does not cancel catastrophically in f32 (pbrt-v4 TrowbridgeReitzDistribution does the same with tan^2).

// Normal distribution D(h) (Walter et al. 2007; glTF 2.0 Appendix B "Specular BRDF"):
// alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2), with (n.h)^2 (alpha^2 - 1) + 1 = alpha^2 cos^2 + sin^2.
fn ggx_d(h: vec3f, alpha: f32) -> f32 {
  if (h.z <= 0.0) { return 0.0; }
  let a2 = alpha * alpha;
  let d = (h.x * h.x + h.y * h.y) + a2 * h.z * h.z;
  return a2 / (PI * d * d);
}

// Smith masking G1(w) for GGX (Heitz 2014, "Understanding the Masking-Shadowing Function",
// eq. 43 with Lambda = (-1 + sqrt(1 + alpha^2 tan^2)) / 2): 2 cos / (cos + sqrt(cos^2 + alpha^2 sin^2)).
// Back-facing directions are fully masked (reflection only for now).
fn smith_g1(w: vec3f, alpha: f32) -> f32 {
  if (w.z <= 0.0) { return 0.0; }
  let a2 = alpha * alpha;
  return 2.0 * w.z / (w.z + sqrt(w.z * w.z + a2 * (w.x * w.x + w.y * w.y)));
}

// Height-correlated Smith visibility V = G2 / (4 |n.l| |n.v|) (Heitz 2014 eq. 99; glTF 2.0
// Appendix B "Specular BRDF"): 0.5 / (n.l sqrt((n.v)^2 (1 - a^2) + a^2) + n.v sqrt((n.l)^2 (1 - a^2) + a^2)),
// where (n.v)^2 (1 - a^2) + a^2 = cos^2 + a^2 sin^2 for a unit vector.
fn smith_height_correlated_v(wo: vec3f, wi: vec3f, alpha: f32) -> f32 {
  if (wo.z <= 0.0 || wi.z <= 0.0) { return 0.0; }
  let a2 = alpha * alpha;
  let term_o = wi.z * sqrt(wo.z * wo.z + a2 * (wo.x * wo.x + wo.y * wo.y));
  let term_i = wo.z * sqrt(wi.z * wi.z + a2 * (wi.x * wi.x + wi.y * wi.y));
  return 0.5 / (term_o + term_i);
}

// Samples a microfacet normal H from the distribution of visible normals D_wo(H) =
// G1(wo) max(0, wo.H) D(H) / wo.z (Heitz 2018, "Sampling the GGX Distribution of Visible Normals",
// JCGT 7(4)), using the spherical-cap form of the hemisphere-section sampling (Dupuy and Benyoub
// 2023, "Sampling Visible GGX Normals with Spherical Caps"), which draws exactly the same
// distribution without Heitz's tangent-frame singularity at normal incidence. Requires wo.z > 0.
fn sample_ggx_vndf(wo: vec3f, alpha: f32, u: vec2f) -> vec3f {
  // Stretch the view direction to the hemisphere configuration (alpha = 1).
  let wo_std = normalize(vec3f(wo.x * alpha, wo.y * alpha, wo.z));
  // Uniform point on the spherical cap {z >= -wo_std.z} of the unit sphere.
  let phi = TWO_PI * u.x;
  let z = fma(1.0 - u.y, 1.0 + wo_std.z, -wo_std.z);
  let sin_theta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
  let c = vec3f(sin_theta * cos(phi), sin_theta * sin(phi), z);
  // Halfway vector in the hemisphere configuration, then unstretch.
  let h_std = c + wo_std;
  return normalize(vec3f(h_std.x * alpha, h_std.y * alpha, max(h_std.z, 0.0)));
}

// Solid-angle density of wi = reflect(-wo, H) with H ~ D_wo: D_wo(H) / (4 wo.H) =
// G1(wo) D(H) / (4 wo.z) (Heitz 2018 eq. 17 and the reflection Jacobian 1 / (4 wo.H)).
// Zero below the horizon: those samples are discarded, so over the upper hemisphere this integrates
// to 1 minus the probability that a reflected sample leaves through the surface.
fn ggx_vndf_reflect_pdf(wo: vec3f, wi: vec3f, alpha: f32) -> f32 {
  if (wo.z <= 0.0 || wi.z <= 0.0) { return 0.0; }
  let h = normalize(wo + wi);
  return smith_g1(wo, alpha) * ggx_d(h, alpha) / (4.0 * wo.z);
}
