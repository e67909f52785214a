// Surface interaction of every path in the input queue (pbrt-v4 PathIntegrator::Li, wavefront form):
// emission at the hit (MIS-weighted against light sampling), then at a scattering vertex one
// next-event estimation sample (a shadow ray into the shadow queue) and one BSDF sample that
// continues the path (Russian roulette once the continuation reaches RUSSIAN_ROULETTE_DEPTH, a
// constant generated from records.ts and published by the render plan).

struct SurfaceHit {
  position: vec3f,
  ng: vec3f,
  ns: vec3f,
  material_id: u32,
  light_pmf: f32,
  area: f32,
}

fn commit_radiance(slot: u32, value: vec3f) {
  if (all(value == vec3f(0.0))) { return; }
  // Invalid samples are dropped and counted, never clamped.
  if (!is_finite_vec3(value) || any(value < vec3f(0.0))) {
    atomicAdd(&counters[COUNTER_INVALID_SAMPLES], 1u);
    return;
  }
  tileRadiance[slot] += vec4f(value, 0.0);
}

fn box_face_normal(obj: SceneObject, p: vec3f) -> vec3f {
  let c = 0.5 * (obj.a + obj.b);
  let h = 0.5 * (obj.b - obj.a);
  let d = (p - c) / h;
  let ad = abs(d);
  if (ad.x >= ad.y && ad.x >= ad.z) { return vec3f(sign(d.x), 0.0, 0.0); }
  if (ad.y >= ad.z) { return vec3f(0.0, sign(d.y), 0.0); }
  return vec3f(0.0, 0.0, sign(d.z));
}

fn surface_hit(path: PathState) -> SurfaceHit {
  let kind = path.hitPrimitive >> 30u;
  let index = path.hitPrimitive & 0x3fffffffu;
  let position = path.origin + path.direction * path.hitT;
  if (kind == PRIMITIVE_KIND_TRIANGLE) {
    let attr = triangleAttributes[index];
    let w = 1.0 - path.hitU - path.hitV;
    let ns = normalize(w * attr.n0 + path.hitU * attr.n1 + path.hitV * attr.n2);
    return SurfaceHit(position, decode_octahedral(attr.geometricNormal), ns, attr.materialId, attr.lightPmf, attr.area);
  }
  let obj = sceneObjects[index];
  var ng: vec3f;
  if (kind == PRIMITIVE_KIND_SPHERE) {
    ng = normalize(position - obj.a);
  } else {
    ng = box_face_normal(obj, position);
  }
  return SurfaceHit(position, ng, ng, obj.materialId, 0.0, 0.0);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn shade_hits(@builtin(global_invocation_id) gid: vec3u) {
  let n = atomicLoad(&counters[bounce.inCounter]);
  if (gid.x >= n) { return; }
  let path = paths[bounce.inBase + gid.x];
  let depth = bounce.depth;
  let pixel_seed = pixel_sequence_seed(frame.seed, wave_pixel_index(path.slot));
  let sample_index = wave.sampleIndex;
  var radiance = vec3f(0.0);

  // Escaped: the uniform environment, MIS-weighted against its light sampling.
  if (path.hitPrimitive == PRIMITIVE_NONE) {
    if (max_component(frame.environmentRadiance) > 0.0) {
      var w = 1.0;
      if (path.misPdf > 0.0) { w = power_heuristic(path.misPdf, environment_light_pdf()); }
      radiance = path.throughput * frame.environmentRadiance * w;
    }
    atomicAdd(&counters[COUNTER_ESCAPED_PATHS], 1u);
    commit_radiance(path.slot, radiance);
    return;
  }

  let hit = surface_hit(path);
  let material = materials[hit.material_id];
  let wo_world = -path.direction;
  let front_facing = dot(hit.ng, wo_world) > 0.0;

  // Emission from the front face (counter-clockwise winding) unless double sided.
  if (max_component(material.emission) > 0.0 && (front_facing || (material.flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u)) {
    var w = 1.0;
    if (path.misPdf > 0.0 && hit.light_pmf > 0.0) {
      let light_pdf = triangle_light_pdf(hit.light_pmf, hit.area, path.hitT, abs(dot(hit.ng, wo_world)));
      w = power_heuristic(path.misPdf, light_pdf);
    }
    radiance += path.throughput * material.emission * w;
    atomicAdd(&counters[COUNTER_EMITTER_HITS], 1u);
  }

  if (depth >= frame.maxDepth) {
    atomicAdd(&counters[COUNTER_MAX_DEPTH_TERMINATIONS], 1u);
    commit_radiance(path.slot, radiance);
    return;
  }

  // Reflection is two-sided: orient both normals towards the viewer.
  var ng = hit.ng;
  if (!front_facing) { ng = -ng; }
  var ns = hit.ns;
  if (dot(ns, ng) < 0.0) { ns = -ns; }
  let shading = make_frame(ns);
  let wo = to_local(shading, wo_world);
  let sm = surface_material_from_record(material);
  let u_select = sample_2d(pixel_seed, sample_index, bounce_dimension(depth, SAMPLE_PAIR_LIGHT_AND_LOBE));

  // Next-event estimation: one light sample, traced later as an any-hit shadow ray.
  let p_env = frame.environmentSelectProbability;
  if (frame.lightCount > 0u || p_env > 0.0) {
    let u_pos = sample_2d(pixel_seed, sample_index, bounce_dimension(depth, SAMPLE_PAIR_LIGHT_POSITION));
    var wi_world = vec3f(0.0, 0.0, 1.0);
    var light_radiance = vec3f(0.0);
    var light_pdf = 0.0;
    var t_max = F32_INF;
    if (u_select.x < p_env) {
      wi_world = uniform_sphere_direction(u_pos);
      light_radiance = frame.environmentRadiance;
      light_pdf = environment_light_pdf();
    } else {
      let u_tri = min((u_select.x - p_env) / (1.0 - p_env), 0.99999994);
      let light = lights[sample_light_index(u_tri)];
      let p_light = sample_triangle_point(light.v0, light.e1, light.e2, u_pos);
      let c = cross(light.e1, light.e2);
      let c_len = length(c);
      let to_light = p_light - hit.position;
      let dist = length(to_light);
      if (dist > 0.0 && c_len > 0.0) {
        wi_world = to_light / dist;
        let cos_signed = dot(c / c_len, -wi_world);
        let double_sided = (light.triangle & LIGHT_FLAG_DOUBLE_SIDED) != 0u;
        let cos_light = select(cos_signed, abs(cos_signed), double_sided);
        if (cos_light > 0.0) {
          light_radiance = light.emission;
          light_pdf = triangle_light_pdf(light.pmf, 0.5 * c_len, dist, cos_light);
          t_max = dist * (1.0 - 1e-4);
        }
      }
    }
    if (light_pdf > 0.0 && dot(wi_world, ng) > 0.0) {
      let wi = to_local(shading, wi_world);
      let f = bsdf_eval(sm, wo, wi);
      if (max_component(f) > 0.0) {
        let w = power_heuristic(light_pdf, bsdf_pdf(sm, wo, wi));
        let contribution = path.throughput * f * abs(wi.z) * light_radiance * (w / light_pdf);
        if (is_finite_vec3(contribution) && max_component(contribution) > 0.0) {
          let s = atomicAdd(&counters[COUNTER_SHADOW_COUNT], 1u);
          shadowRays[s] = ShadowRay(offset_ray_origin(hit.position, ng), path.slot, wi_world, t_max, contribution, 0u);
        }
      }
    }
  }

  // BSDF sampling continues the path.
  let u_dir = sample_2d(pixel_seed, sample_index, bounce_dimension(depth, SAMPLE_PAIR_BSDF_DIRECTION));
  let bs = bsdf_sample(sm, wo, u_select.y, u_dir);
  if (!bs.valid) {
    commit_radiance(path.slot, radiance);
    return;
  }
  let wi_world = to_world(shading, bs.wi);
  if (dot(wi_world, ng) <= 0.0) {
    commit_radiance(path.slot, radiance);
    return;
  }
  var throughput = path.throughput * bs.weight;
  // Russian roulette (pbrt-v4): survive with probability min(1, max throughput component).
  if (depth + 1u >= RUSSIAN_ROULETTE_DEPTH) {
    let m = max_component(throughput * path.etaScale);
    if (m < 1.0) {
      let q = max(0.0, 1.0 - m);
      let u_rr = sample_2d(pixel_seed, sample_index, bounce_dimension(depth, SAMPLE_PAIR_ROULETTE)).x;
      if (u_rr < q) {
        atomicAdd(&counters[COUNTER_RUSSIAN_ROULETTE_TERMINATIONS], 1u);
        commit_radiance(path.slot, radiance);
        return;
      }
      throughput = throughput / (1.0 - q);
    }
  }
  commit_radiance(path.slot, radiance);
  if (!is_finite_vec3(throughput) || max_component(throughput) <= 0.0) { return; }
  var next: PathState;
  next.origin = offset_ray_origin(hit.position, ng);
  next.slot = path.slot;
  next.direction = wi_world;
  next.depth = depth + 1u;
  next.throughput = throughput;
  next.misPdf = select(bs.pdf, 0.0, bs.is_delta);
  next.hitT = -1.0;
  next.hitPrimitive = PRIMITIVE_NONE;
  next.etaScale = path.etaScale;
  next.mediumId = path.mediumId;
  next.flags = select(0u, PATH_FLAG_SPECULAR_BOUNCE, bs.is_delta);
  let out = atomicAdd(&counters[bounce.outCounter], 1u);
  paths[bounce.outBase + out] = next;
}
