// Pinhole camera; mirrored by createWavefrontReferenceRay in src/pathtracer/reference.ts.
// `pixel` is continuous: integer pixel coordinates plus a jitter in [0, 1)^2, top-left origin, y down.
fn camera_ray_direction(pixel: vec2f) -> vec3f {
  let ndc_x = 2.0 * pixel.x / f32(frame.imageSize.x) - 1.0;
  let ndc_y = 1.0 - 2.0 * pixel.y / f32(frame.imageSize.y);
  let sx = ndc_x * frame.tanHalfFovY * frame.aspect;
  let sy = ndc_y * frame.tanHalfFovY;
  return normalize(frame.cameraForward + sx * frame.cameraRight + sy * frame.cameraUp);
}

fn wave_pixel(slot: u32) -> vec2u {
  return wave.tileOrigin + vec2u(slot % wave.tileSize.x, slot / wave.tileSize.x);
}

fn wave_pixel_index(slot: u32) -> u32 {
  let p = wave_pixel(slot);
  return p.y * frame.imageSize.x + p.x;
}
