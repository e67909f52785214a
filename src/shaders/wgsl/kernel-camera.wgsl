// Camera rays for one wave (one sample of every pixel in a tile) into the first path queue.
@compute @workgroup_size(WORKGROUP_SIZE)
fn generate_camera_rays(@builtin(global_invocation_id) gid: vec3u) {
  let slot = gid.x;
  let tile_pixels = wave.tileSize.x * wave.tileSize.y;
  if (slot == 0u) {
    atomicStore(&counters[COUNTER_PATH_COUNT0], tile_pixels);
    atomicAdd(&counters[COUNTER_CAMERA_RAYS], tile_pixels);
  }
  if (slot >= tile_pixels) { return; }
  let pixel = wave_pixel(slot);
  let pixel_seed = pixel_sequence_seed(frame.seed, pixel.y * frame.imageSize.x + pixel.x);
  let jitter = sample_2d(pixel_seed, wave.sampleIndex, SAMPLE_PAIR_CAMERA);
  var path: PathState;
  path.origin = frame.cameraPosition;
  path.slot = slot;
  path.direction = camera_ray_direction(vec2f(pixel) + jitter);
  path.depth = 0u;
  path.throughput = vec3f(1.0);
  path.misPdf = 0.0;
  path.hitT = -1.0;
  path.hitPrimitive = PRIMITIVE_NONE;
  path.etaScale = 1.0;
  path.mediumId = 0u;
  path.flags = 0u;
  paths[slot] = path;
  tileRadiance[slot] = vec4f(0.0);
}
