// Canvas presentation of the resolve: a full-screen triangle that tone maps in the fragment stage.
@group(0) @binding(0) var<uniform> resolve: ResolveUniforms;
@group(0) @binding(1) var<storage, read> resolveAccumulation: array<vec4f>;

@vertex
fn present_vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
  let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
  return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn present_fragment(@builtin(position) position: vec4f) -> @location(0) vec4f {
  let p = vec2u(position.xy);
  let index = min(p.y, resolve.imageSize.y - 1u) * resolve.imageSize.x + min(p.x, resolve.imageSize.x - 1u);
  let a = resolveAccumulation[index];
  if (a.w <= 0.0) { return vec4f(0.0, 0.0, 0.0, 1.0); }
  let mapped = apply_tone_mapping(a.xyz / a.w * resolve.exposure, resolve.toneMapping);
  return vec4f(linear_to_srgb(clamp(mapped, vec3f(0.0), vec3f(1.0))), 1.0);
}
