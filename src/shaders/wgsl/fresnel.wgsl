// Fresnel reflectance terms of the glTF 2.0 metallic-roughness BRDF.

// Unpolarised Fresnel reflectance of a smooth dielectric interface (pbrt-v4 FrDielectric, section
// 9.3). `cos_theta_i` is the cosine between the incident direction and the normal on the side the
// light arrives from (negative: arriving from inside, eta is inverted); `eta` = n_transmitted /
// n_incident. Equals ((eta - 1) / (eta + 1))^2 at normal incidence and 1 at grazing incidence.
//
// Why not Schlick for dielectrics: glTF 2.0 Appendix B uses Schlick with f90 = 1, which does not
// vanish for F0 = 0 (it is (1 - cos)^5 at grazing angles), but KHR_materials_ior requires ior = 1
// to leave a purely Lambertian dielectric. The exact equations are identically 0 for eta = 1 and
// match Schlick's F0; they are what pbrt-v4, Mitsuba 3 and Cycles use for dielectrics.
fn fresnel_dielectric(cos_theta_i: f32, eta_in: f32) -> f32 {
  // An index-matched interface does not reflect at all; exact 0 rather than rounding noise.
  if (eta_in == 1.0) { return 0.0; }
  var cos_i = clamp(cos_theta_i, -1.0, 1.0);
  var eta = eta_in;
  if (cos_i < 0.0) {
    eta = 1.0 / eta;
    cos_i = -cos_i;
  }
  let sin2_i = max(0.0, 1.0 - cos_i * cos_i);
  let sin2_t = sin2_i / (eta * eta);
  // Total internal reflection.
  if (sin2_t >= 1.0) { return 1.0; }
  let cos_t = sqrt(max(0.0, 1.0 - sin2_t));
  let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5 * (r_parl * r_parl + r_perp * r_perp);
}

// Schlick's approximation with f90 = 1 (glTF 2.0 Appendix B, conductor_fresnel): used for metals,
// whose base color is F0.
fn fresnel_schlick(f0: vec3f, cos_theta: f32) -> vec3f {
  let m = clamp(1.0 - cos_theta, 0.0, 1.0);
  let m2 = m * m;
  return f0 + (vec3f(1.0) - f0) * (m2 * m2 * m);
}
