import { test } from 'node:test';
import assert from 'node:assert/strict';
import { applyToneMapping, linearToSrgb, toneMappingModeIds } from '../../src/film/tone-mapping.ts';
import { readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { runTestProgram } from '../helpers/wgsl.ts';

// For each input colour the kernel writes the three tone mappings and the sRGB encoding of the
// clamped input, so one dispatch checks every WGSL function against its JS mirror.
const kernel = /* wgsl */ `
import package::film::display::tonemap::apply_tone_mapping;
import package::shaders::lib::color::linear_to_srgb;
import package::layout::constants::{TONE_MAPPING_NEUTRAL, TONE_MAPPING_ACES, TONE_MAPPING_LINEAR, TONE_MAPPING_AGX};
@group(0) @binding(0) var<storage, read> inputs: array<vec4f>;
@group(0) @binding(1) var<storage, read_write> outputs: array<vec4f>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= arrayLength(&inputs)) { return; }
  let c = inputs[i].xyz;
  outputs[5u * i + 0u] = vec4f(apply_tone_mapping(c, TONE_MAPPING_NEUTRAL), 1.0);
  outputs[5u * i + 1u] = vec4f(apply_tone_mapping(c, TONE_MAPPING_ACES), 1.0);
  outputs[5u * i + 2u] = vec4f(apply_tone_mapping(c, TONE_MAPPING_LINEAR), 1.0);
  outputs[5u * i + 3u] = vec4f(apply_tone_mapping(c, TONE_MAPPING_AGX), 1.0);
  outputs[5u * i + 4u] = vec4f(linear_to_srgb(clamp(c, vec3f(0.0), vec3f(1.0))), 1.0);
}
`;

/** Deterministic inputs: grey ramps across 8 decades, thresholds, and pseudo-random colours. */
function inputs(): Float32Array {
  const colours: number[][] = [];
  for (let i = 0; i <= 160; i++) {
    const x = Math.pow(10, -4 + i / 20);
    colours.push([x, x, x]);
  }
  for (const x of [0, 0.0031308, 0.04045, 0.08, 0.76, 0.8, 1]) colours.push([x, x, x]);
  let s = 0x9e3779b9;
  const rand = (): number => {
    s ^= s << 13;
    s ^= s >>> 17;
    s ^= s << 5;
    return (s >>> 0) / 4294967296;
  };
  for (let i = 0; i < 600; i++) colours.push([0, 0, 0].map(() => Math.pow(10, -3 + 5 * rand())));
  const data = new Float32Array(colours.length * 4);
  colours.forEach((c, i) => data.set([c[0], c[1], c[2], 0], 4 * i));
  return data;
}

// The modes tonemap.wesl implements, in the order the kernel writes them.
const wgslModes = ['neutral', 'aces', 'linear', 'agx'] as const;

test('WGSL tone mapping and sRGB encoding equal the JS mirror', async () => {
  assert.deepEqual(toneMappingModeIds, { neutral: 0, aces: 1, linear: 2, agx: 3 });
  const device = await testDevice();
  const data = inputs();
  const n = data.length / 4;
  const input = uploadBuffer(device, data);
  const output = uploadBuffer(device, new Float32Array(n * 20));
  await runTestProgram(device, { source: kernel, resources: { inputs: input, outputs: output }, workgroups: Math.ceil(n / 64) });
  const out = new Float32Array(await readBuffer(device, output));
  for (let i = 0; i < n; i++) {
    const c = [data[4 * i], data[4 * i + 1], data[4 * i + 2]];
    const expected = [
      ...wgslModes.map((mode) => applyToneMapping(c, mode)),
      c.map((v) => linearToSrgb(Math.min(Math.max(v, 0), 1))),
    ];
    expected.forEach((e, k) => {
      for (let ch = 0; ch < 3; ch++) {
        const got = out[20 * i + 4 * k + ch];
        const err = Math.abs(got - e[ch]);
        // f32 on the GPU vs f64 here: a few ulps of pow/division, far below one 8-bit display step.
        assert.ok(err < 2e-5, `input ${c} output ${k} channel ${ch}: gpu ${got} vs js ${e[ch]}`);
      }
    });
  }
  input.destroy();
  output.destroy();
});
