// Display resolve: mean radiance -> exposure -> tone mapping -> exact sRGB -> RGBA8, into a buffer
// (readPixels) or a canvas (full-screen triangle).
@group(0) @binding(0) var<uniform> resolve: ResolveUniforms;
@group(0) @binding(1) var<storage, read> resolveAccumulation: array<vec4f>;
@group(0) @binding(2) var<storage, read_write> resolvedPixels: array<u32>;

fn resolved_color(index: u32) -> vec4f {
  let a = resolveAccumulation[index];
  if (a.w <= 0.0) { return vec4f(0.0, 0.0, 0.0, 1.0); }
  let mapped = apply_tone_mapping(a.xyz / a.w * resolve.exposure, resolve.toneMapping);
  return vec4f(linear_to_srgb(clamp(mapped, vec3f(0.0), vec3f(1.0))), 1.0);
}

@compute @workgroup_size(8, 8)
fn resolve_pixels(@builtin(global_invocation_id) gid: vec3u) {
  if (gid.x >= resolve.imageSize.x || gid.y >= resolve.imageSize.y) { return; }
  let index = gid.y * resolve.imageSize.x + gid.x;
  resolvedPixels[index] = pack4x8unorm(resolved_color(index));
}
