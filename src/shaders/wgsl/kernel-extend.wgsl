// Closest-hit extension of every active path; the hit is written into the path record.
@compute @workgroup_size(WORKGROUP_SIZE)
fn extend_paths(@builtin(global_invocation_id) gid: vec3u, @builtin(local_invocation_index) lid: u32) {
  let n = atomicLoad(&counters[bounce.inCounter]);
  if (lid == 0u && bounce.depth > 0u) {
    let first = gid.x;
    if (first < n) { atomicAdd(&counters[COUNTER_EXTENSION_RAYS], min(WORKGROUP_SIZE, n - first)); }
  }
  if (gid.x >= n) { return; }
  let i = bounce.inBase + gid.x;
  let origin = paths[i].origin;
  let direction = paths[i].direction;
  let hit = trace_closest(origin, direction, F32_INF);
  paths[i].hitT = hit.t;
  paths[i].hitPrimitive = hit.primitive;
  paths[i].hitU = hit.u;
  paths[i].hitV = hit.v;
}
