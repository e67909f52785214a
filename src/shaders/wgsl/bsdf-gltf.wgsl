// The glTF 2.0 metallic-roughness BSDF (glTF 2.0 specification, Appendix B "BRDF Implementation"):
//   f = mix(dielectric_brdf, metal_brdf, metallic)
//   metal_brdf      = specular_brdf * conductor_fresnel(f0 = baseColor)           (Schlick)
//   dielectric_brdf = mix(baseColor / pi, specular_brdf, F_dielectric(VdotH, ior))
//   specular_brdf   = D(H) V(wo, wi)   (GGX, height-correlated Smith visibility)
// All directions are unit vectors in the local shading frame (z = shading normal); wo points
// towards the viewer, wi towards the light. Reflection only for now: KHR_materials_transmission,
// volume, clearcoat, sheen and KHR_materials_specular carry through SurfaceMaterial unshaded and
// slot in as further lobes (each with its own selection probability in gltf_lobe_probabilities).

// Below this alpha the specular lobe is treated as a perfect mirror (pbrt-v4
// TrowbridgeReitzDistribution::EffectivelySmooth): the GGX peak 1 / (pi alpha^2) overflows the
// useful f32 range of eval/pdf and MIS cannot hit it anyway.
const GLTF_DELTA_ALPHA: f32 = 1e-3;

struct SurfaceMaterial {
  base_color: vec3f,
  metallic: f32,
  roughness: f32, // perceptual; alpha = roughness^2
  ior: f32, // KHR_materials_ior
  transmission: f32, // KHR_materials_transmission (not yet shaded)
  specular: f32, // KHR_materials_specular (not yet shaded)
  specular_color: vec3f, // KHR_materials_specular (not yet shaded)
}

// One BSDF sample. Non-delta: f = bsdf_eval(wi), pdf = bsdf_pdf(wi) (solid angle, MIS-ready, all
// non-delta lobes combined), weight = f cos / pdf. Delta (mirror) sample: is_delta = true, pdf = 0
// (no solid-angle density; matches PathState.misPdf's "0 = delta lobe"), f = F / cos so that
// f cos = F, and weight = F / (lobe selection probability). valid = false: the sample carries no
// energy (e.g. reflected below the horizon) and the path ends.
struct BsdfSample {
  wi: vec3f,
  f: vec3f,
  pdf: f32,
  weight: vec3f,
  is_delta: bool,
  valid: bool,
}

fn surface_material_from_record(m: Material) -> SurfaceMaterial {
  // glTF 2.0 restricts these factors to [0, 1]; clamping can only remove energy. KHR_materials_ior
  // allows ior >= 1; below that the Fresnel term is meaningless for a reflection-only surface.
  return SurfaceMaterial(
    clamp(m.baseColor.rgb, vec3f(0.0), vec3f(1.0)),
    clamp(m.metallic, 0.0, 1.0),
    clamp(m.roughness, 0.0, 1.0),
    max(m.ior, 1.0),
    clamp(m.transmission, 0.0, 1.0),
    max(m.specular, 0.0),
    max(m.specularColor, vec3f(0.0)));
}

fn gltf_alpha(m: SurfaceMaterial) -> f32 {
  return m.roughness * m.roughness;
}

fn gltf_specular_is_delta(m: SurfaceMaterial) -> bool {
  return gltf_alpha(m) < GLTF_DELTA_ALPHA;
}

// Probability of sampling the specular lobe, from the lobes' reflectance at normal-to-wo
// incidence (Fresnel at wo.z): specular (1 - metallic) F + metallic, diffuse
// (1 - metallic)(1 - F) luminance(baseColor). A lobe gets probability 0 only when its weight is 0.
fn gltf_specular_probability(m: SurfaceMaterial, cos_o: f32) -> f32 {
  let f = fresnel_dielectric(cos_o, m.ior);
  let spec = (1.0 - m.metallic) * f + m.metallic;
  let diff = (1.0 - m.metallic) * (1.0 - f) * luminance(m.base_color);
  let total = spec + diff;
  if (total <= 0.0) { return 0.0; }
  return spec / total;
}

// Malley's method: cosine-weighted hemisphere via Shirley-Chiu concentric disk mapping (pbrt-v4
// SampleConcentricDisk / SampleCosineHemisphere).
fn gltf_sample_cosine_hemisphere(u: vec2f) -> vec3f {
  let o = 2.0 * u - vec2f(1.0);
  if (o.x == 0.0 && o.y == 0.0) { return vec3f(0.0, 0.0, 1.0); }
  var r: f32;
  var theta: f32;
  if (abs(o.x) > abs(o.y)) {
    r = o.x;
    theta = (PI / 4.0) * (o.y / o.x);
  } else {
    r = o.y;
    theta = PI / 2.0 - (PI / 4.0) * (o.x / o.y);
  }
  let d = r * vec2f(cos(theta), sin(theta));
  return vec3f(d, sqrt(max(0.0, 1.0 - dot(d, d))));
}

// Fresnel-weighted reflectance of the delta (mirror) specular lobe at incidence cosine cos_o.
fn gltf_mirror_reflectance(m: SurfaceMaterial, cos_o: f32) -> vec3f {
  let dielectric = vec3f(fresnel_dielectric(cos_o, m.ior));
  let metal = fresnel_schlick(m.base_color, cos_o);
  return mix(dielectric, metal, m.metallic);
}

// f(wo, wi) without the cosine, non-delta lobes only.
fn bsdf_eval(m: SurfaceMaterial, wo: vec3f, wi: vec3f) -> vec3f {
  if (wo.z <= 0.0 || wi.z <= 0.0) { return vec3f(0.0); }
  let h = normalize(wo + wi);
  let v_dot_h = clamp(dot(wo, h), 0.0, 1.0);
  var specular_brdf = 0.0;
  if (!gltf_specular_is_delta(m)) {
    let alpha = gltf_alpha(m);
    specular_brdf = ggx_d(h, alpha) * smith_height_correlated_v(wo, wi, alpha);
  }
  let f_dielectric = fresnel_dielectric(v_dot_h, m.ior);
  let dielectric_brdf = (1.0 - f_dielectric) * m.base_color * INV_PI + vec3f(f_dielectric * specular_brdf);
  let metal_brdf = fresnel_schlick(m.base_color, v_dot_h) * specular_brdf;
  return mix(dielectric_brdf, metal_brdf, m.metallic);
}

// Solid-angle pdf with which bsdf_sample produces wi through its non-delta lobes.
fn bsdf_pdf(m: SurfaceMaterial, wo: vec3f, wi: vec3f) -> f32 {
  if (wo.z <= 0.0 || wi.z <= 0.0) { return 0.0; }
  let p_spec = gltf_specular_probability(m, wo.z);
  var pdf = (1.0 - p_spec) * wi.z * INV_PI;
  if (!gltf_specular_is_delta(m)) {
    pdf += p_spec * ggx_vndf_reflect_pdf(wo, wi, gltf_alpha(m));
  }
  return pdf;
}

// u_lobe picks the lobe; u samples the direction within it.
fn bsdf_sample(m: SurfaceMaterial, wo: vec3f, u_lobe: f32, u: vec2f) -> BsdfSample {
  var s = BsdfSample(vec3f(0.0, 0.0, 1.0), vec3f(0.0), 0.0, vec3f(0.0), false, false);
  if (wo.z <= 0.0) { return s; }
  let p_spec = gltf_specular_probability(m, wo.z);
  if (u_lobe < p_spec && gltf_specular_is_delta(m)) {
    s.wi = vec3f(-wo.x, -wo.y, wo.z);
    let reflectance = gltf_mirror_reflectance(m, wo.z);
    s.f = reflectance / wo.z;
    s.weight = reflectance / p_spec;
    s.is_delta = true;
    s.valid = true;
    return s;
  }
  var wi: vec3f;
  if (u_lobe < p_spec) {
    let h = sample_ggx_vndf(wo, gltf_alpha(m), u);
    wi = reflect(-wo, h);
  } else {
    wi = gltf_sample_cosine_hemisphere(u);
  }
  if (wi.z <= 0.0) { return s; }
  let pdf = bsdf_pdf(m, wo, wi);
  if (pdf <= 0.0) { return s; }
  s.wi = wi;
  s.f = bsdf_eval(m, wo, wi);
  s.pdf = pdf;
  s.weight = s.f * (wi.z / pdf);
  s.valid = true;
  return s;
}
