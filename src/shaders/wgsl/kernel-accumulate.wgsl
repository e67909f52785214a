// Adds one wave's per-slot radiance into the full-frame accumulation; alpha counts samples.
@compute @workgroup_size(WORKGROUP_SIZE)
fn accumulate_tile(@builtin(global_invocation_id) gid: vec3u) {
  let slot = gid.x;
  if (slot >= wave.tileSize.x * wave.tileSize.y) { return; }
  let pixel = wave.tileOrigin + vec2u(slot % wave.tileSize.x, slot / wave.tileSize.x);
  let index = pixel.y * frame.imageSize.x + pixel.x;
  accumulation[index] += vec4f(tileRadiance[slot].xyz, 1.0);
}
