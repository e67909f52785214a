// Any-hit shadow rays of next-event estimation: unoccluded ones add their contribution.
@compute @workgroup_size(WORKGROUP_SIZE)
fn trace_shadow_rays(@builtin(global_invocation_id) gid: vec3u, @builtin(local_invocation_index) lid: u32) {
  let n = atomicLoad(&counters[COUNTER_SHADOW_COUNT]);
  if (lid == 0u && gid.x < n) { atomicAdd(&counters[COUNTER_SHADOW_RAYS], min(WORKGROUP_SIZE, n - gid.x)); }
  if (gid.x >= n) { return; }
  let ray = shadowRays[gid.x];
  if (!trace_any(ray.origin, ray.direction, ray.tMax)) {
    tileRadiance[ray.slot] += vec4f(ray.radiance, 0.0);
  }
}
