// KHR_materials_volume end to end: an index-matched (ior 1) absorbing sphere in front of an emitter,
// seen by an orthographic camera. Without refraction or Fresnel, a ray at distance r from the centre
// keeps attenuationColor^(chord / attenuationDistance) of the light, chord = 2 sqrt(R^2 - r^2); over
// the disc the mean transmittance is the closed form
//   <T> = (2 / R^2) (1 - e^(-2 s R) (1 + 2 s R)) / (4 s^2),  s = -ln(attenuationColor) / attenuationDistance
// (substitute u = sqrt(R^2 - r^2) in (2 / R^2) int_0^R r e^(-2 s u) dr). The tessellated sphere's
// chords are a little shorter than the sphere's, so the image is also checked, tightly, against a
// CPU ray cast of the very triangles the GPU intersects.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { icosphere } from '../helpers/meshes.ts';
import { emitter } from './slab-scene.ts';

const size = 24;
const R = 1;
const height = 2 * R;
const E = [2, 3, 4];
const color = [0.3, 0.6, 0.9];
const distance = 1.5;
const sphere = icosphere(R, [0, 0, 0], 4);

/** Mean transmittance over the disc of a true sphere (the closed form above). */
function discMean(c: number): number {
  const s = -Math.log(c) / distance;
  return (2 / (R * R)) * (1 - Math.exp(-2 * s * R) * (1 + 2 * s * R)) / (4 * s * s);
}

/** Chord of the +z-looking ray through (x, y) in the tessellated sphere (Moller-Trumbore, both faces). */
function chord(x: number, y: number): number {
  const p = sphere.positions;
  const ts: number[] = [];
  for (let i = 0; i < sphere.indices.length; i += 3) {
    const [a, b, c] = [sphere.indices[i]!, sphere.indices[i + 1]!, sphere.indices[i + 2]!].map((k) => [p[3 * k]!, p[3 * k + 1]!, p[3 * k + 2]!]);
    // Ray o = (x, y, -10), d = (0, 0, 1): solve in 2D for barycentrics, then z.
    const e1 = [b![0]! - a![0]!, b![1]! - a![1]!, b![2]! - a![2]!];
    const e2 = [c![0]! - a![0]!, c![1]! - a![1]!, c![2]! - a![2]!];
    const det = e1[0]! * e2[1]! - e1[1]! * e2[0]!;
    if (det === 0) continue;
    const px = x - a![0]!;
    const py = y - a![1]!;
    const u = (px * e2[1]! - py * e2[0]!) / det;
    const v = (e1[0]! * py - e1[1]! * px) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    ts.push(a![2]! + u * e1[2]! + v * e2[2]!);
  }
  return ts.length >= 2 ? Math.max(...ts) - Math.min(...ts) : 0;
}

test('an index-matched absorbing sphere: Beer-Lambert along every chord, its disc mean the closed form', async (t) => {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, maxDepth: 8, samplesPerPixel: 64, seed: 5,
    camera: { type: 'orthographic', position: [0, 0, 4], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: height },
    meshes: [
      { ...sphere, material: { baseColorFactor: [1, 1, 1], metallicFactor: 0, roughnessFactor: 0, ior: 1, transmissionFactor: 1, thicknessFactor: 1, attenuationColor: color, attenuationDistance: distance } },
      emitter(E),
    ],
  });
  let gpu: number[];
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const { data } = await renderer.readRadiance();
    gpu = [0, 1, 2].map((c) => {
      let sum = 0;
      for (let p = 0; p < size * size; p++) sum += data[4 * p + c]!;
      return sum / (size * size) / E[c]!;
    });
  } finally {
    renderer.destroy();
  }
  // The image spans the disc's bounding square: background pixels transmit 1.
  const discShare = Math.PI / 4;
  // CPU reference of the same triangles: 8 x 8 stratified rays per pixel.
  const n = 8;
  const chords: number[] = [];
  for (let py = 0; py < size; py++) {
    for (let px = 0; px < size; px++) {
      for (let j = 0; j < n; j++) {
        for (let i = 0; i < n; i++) chords.push(chord(-R + (2 * R * (px + (i + 0.5) / n)) / size, -R + (2 * R * (py + (j + 0.5) / n)) / size));
      }
    }
  }
  for (let c = 0; c < 3; c++) {
    const cpu = chords.reduce((sum, d) => sum + color[c]! ** (d / distance), 0) / chords.length;
    const closed = 1 - discShare + discShare * discMean(color[c]!);
    t.diagnostic(`channel ${c}: GPU ${gpu[c]!.toFixed(4)}, CPU ray cast ${cpu.toFixed(4)}, closed form ${closed.toFixed(4)}`);
    assert.ok(Math.abs(gpu[c]! - cpu) <= 0.01 * cpu, `channel ${c}: GPU ${gpu[c]!.toFixed(4)} vs CPU ray cast ${cpu.toFixed(4)}`);
    // The tessellation's shorter chords keep the image a little above the true sphere's.
    assert.ok(Math.abs(cpu - closed) <= 0.01 * closed, `channel ${c}: tessellated ${cpu.toFixed(4)} vs sphere ${closed.toFixed(4)}`);
  }
});
