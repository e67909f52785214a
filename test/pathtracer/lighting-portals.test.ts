// Environment portals change only how the environment is sampled: the GPU portal sampler follows
// its density (chi-square over the portal's rectified cells) and reports the CPU pdf; a room lit
// through a window by an HDRI renders the same image without portals, with 'guide' and with
// 'guide-and-gate' portals, within noise, and the portals lower the noise.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { WavefrontPathTracingOptions } from '../../src/pathtracer/types.ts';
import { readBuffer, testDevice } from '../helpers/gpu.ts';
import { runTestProgram } from '../helpers/wgsl.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import { buildPortalEnvironmentSampler, portalDirectionToUv, portalEnvironmentPdf, portalWindow, validateEnvironmentPortals, type EnvironmentPortalMode } from '../../src/lighting/portals.ts';
import { chiSquareTest } from '../lighting/helpers.ts';
import { lightingFor, lightingResources, mapOption, testHdri } from '../lighting/gpu-fixtures.ts';
import { windowPortal, windowRoomMesh } from '../helpers/window-room.ts';

const portalKernel = (p: readonly number[]): string => `
import package::lighting::portals::{sample_portal_environment, portal_environment_pdf};
import package::shaders::lib::sampling::hash_u32;

@group(3) @binding(20) var<storage, read_write> out: array<vec4f>;

fn unit(x: u32) -> f32 { return f32(hash_u32(x) >> 8u) * (1.0 / 16777216.0); }

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3u) {
  let i = gid.x;
  let p = vec3f(${p.join(', ')});
  let s = sample_portal_environment(p, unit(3u * i + 7u), vec2f(unit(3u * i + 8u), unit(3u * i + 9u)));
  out[2u * i] = vec4f(s.wi, s.pdf);
  out[2u * i + 1u] = vec4f(portal_environment_pdf(p, s.wi), 0.0, 0.0, 0.0);
}
`;

for (const mode of ['guide-and-gate', 'guide'] as const) {
  test(`GPU portal sampling ('${mode}') follows its density (chi-square over rectified cells); sampled pdf = evaluated pdf = CPU pdf`, async () => {
    const device = await testDevice();
    const map = testHdri(64, 32, 50);
    const portals = validateEnvironmentPortals([windowPortal]);
    const lighting = lightingFor({ environment: { kind: 'map', map, sun: null, preset: null }, portals, portalMode: mode as EnvironmentPortalMode });
    const cpu = buildPortalEnvironmentSampler(lighting.environmentSampler!, portals, { mode });
    const p = [-1.2, 0.9, 0.6];
    const n = 1 << 16;
    const out = device.createBuffer({ size: n * 32, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
    await runTestProgram(device, { source: portalKernel(p), resources: { ...lightingResources(device, lighting), out }, workgroups: n / 64 });
    const data = new Float32Array(await readBuffer(device, out));
    const grid = cpu.distributions[0]!.n;
    const window = portalWindow(portals[0]!, p)!;
    const observed = new Float64Array(grid * grid);
    let outside = 0;
    let mismatches = 0;
    for (let s = 0; s < n; s++) {
      const d = [data[8 * s]!, data[8 * s + 1]!, data[8 * s + 2]!];
      const pdf = data[8 * s + 3]!;
      assert.ok(pdf > 0, `sample ${s}: pdf ${pdf}`);
      const want = portalEnvironmentPdf(cpu, p, d);
      if (Math.abs(pdf - want) > 2e-3 * want || Math.abs(pdf - data[8 * s + 4]!) > 1e-5 * pdf) mismatches++;
      const uv = portalDirectionToUv(portals[0]!, d);
      if (!uv || uv.u < window[0] || uv.u > window[1] || uv.v < window[2] || uv.v > window[3]) {
        outside++;
        continue;
      }
      observed[Math.min(grid - 1, Math.floor(uv.v * grid)) * grid + Math.min(grid - 1, Math.floor(uv.u * grid))]! += 1;
    }
    assert.ok(mismatches < n * 1e-3, `${mismatches} sampled pdfs differ from the evaluated or CPU pdf`);
    // Through the window: probability of each rectified cell = value x (cell area inside the window)
    // / window integral, times the portal branch's share.
    const f = cpu.distributions[0]!.func;
    let integral = 0;
    const expected = new Float64Array(grid * grid);
    for (let j = 0; j < grid; j++) {
      for (let i = 0; i < grid; i++) {
        const du = Math.max(0, Math.min(window[1], (i + 1) / grid) - Math.max(window[0], i / grid));
        const dv = Math.max(0, Math.min(window[3], (j + 1) / grid) - Math.max(window[2], j / grid));
        expected[j * grid + i] = f[j * grid + i]! * du * dv;
        integral += expected[j * grid + i]!;
      }
    }
    const inside = n - outside;
    if (mode === 'guide-and-gate') assert.equal(outside, 0, 'gate: every sample passes through the portal');
    else assert.ok(Math.abs(inside / n - 0.75) < 0.05, `guide: ${inside / n} of the samples pass through the portal`);
    // In 'guide' mode the map's own samples that happen to pass through the window add to the
    // cells; compare the portal branch alone only for the gate.
    if (mode === 'guide-and-gate') {
      const chi = chiSquareTest(observed, Array.from(expected, (e) => (inside * e) / integral));
      assert.ok(!chi.outsideSupport && chi.pValue > 1e-4, `chi-square ${chi.chi2.toFixed(1)}, ${chi.dof} dof, p = ${chi.pValue}`);
    }
  });
}

const size = 24;
const camera = { position: [-1.8, 1.6, 1.7], target: [0.5, 0.5, -0.5], up: [0, 1, 0], fovYDegrees: 70 };

async function renderRoom(options: Partial<WavefrontPathTracingOptions>, seed: number, spp: number): Promise<Float32Array> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, samplesPerPixel: spp, seed, maxDepth: 4, camera, meshes: [windowRoomMesh()], environmentMap: mapOption(testHdri(64, 32, 50)), ...options,
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    return (await renderer.readRadiance()).data;
  } finally {
    renderer.destroy();
  }
}

function quadrants(image: Float32Array): number[] {
  const q = [0, 0, 0, 0];
  for (let y = 0; y < size; y++) for (let x = 0; x < size; x++) for (let c = 0; c < 3; c++) q[2 * Math.floor((2 * y) / size) + Math.floor((2 * x) / size)]! += image[4 * (y * size + x) + c]!;
  return q.map((v) => v / ((size * size) / 4) / 3);
}

/** Mean squared difference of two independent renders: twice the per-pixel variance. */
function pixelVariance(a: Float32Array, b: Float32Array): number {
  let s = 0;
  for (let k = 0; k < size * size; k++) for (let c = 0; c < 3; c++) s += (a[4 * k + c]! - b[4 * k + c]!) ** 2;
  return s / (2 * 3 * size * size);
}

test('a room lit through a window renders the same with and without portals; portals lower the variance', async () => {
  const spp = 128;
  const plain = await renderRoom({}, 1, spp);
  const plain2 = await renderRoom({}, 2, spp);
  const guide = await renderRoom({ environmentPortals: [windowPortal] }, 3, spp);
  const guide2 = await renderRoom({ environmentPortals: [windowPortal] }, 4, spp);
  const gate = await renderRoom({ environmentPortals: [windowPortal], environmentPortalMode: 'guide-and-gate' }, 5, spp);
  const reference = quadrants(plain).map((v, i) => (v + quadrants(plain2)[i]!) / 2);
  for (const [name, image] of [['guide', guide], ['guide-and-gate', gate]] as const) {
    quadrants(image).forEach((v, i) => {
      assert.ok(Math.abs(v - reference[i]!) < 0.05 * reference[i]!, `${name} quadrant ${i}: ${v} vs ${reference[i]} without portals`);
    });
  }
  const mean = reference.reduce((a, b) => a + b, 0) / 4;
  assert.ok(mean > 0.01, `the room is lit (${mean})`);
  const varPlain = pixelVariance(plain, plain2);
  const varGuide = pixelVariance(guide, guide2);
  assert.ok(varGuide < 0.8 * varPlain, `variance with portals ${varGuide} vs without ${varPlain}`);
});
