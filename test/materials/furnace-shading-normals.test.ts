// White furnace of a smooth glass sphere with interpolated vertex normals. A coarse icosphere's
// shading normals lean up to a few degrees away from its facets' geometric normals, so a delta
// reflection or refraction about the shading normal can leave on the wrong side of the facet
// (grazing reflections near the rim, refractions leaving near the critical angle). Smooth glass
// with no absorption conserves energy, and in a uniform environment L every path escapes to L: the
// whole image must render L. Each sample is a chain of Fresnel-chosen delta events whose weight is
// 1 (reflection: F / F; refraction: (1 - F) / (1 - F), the 1 / eta^2 of entering undone on leaving),
// so a sample is L or, where the path ends early, 0: the image's mean over L is one minus the
// fraction of lost paths, which the renderer's termination counters account for exactly.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { icosphere } from '../helpers/meshes.ts';

const size = 32;
const spp = 64;
const L = [0.8, 1.0, 1.3];

test('furnace: a smooth glass sphere with interpolated normals (ior 1.5, no absorption) renders the environment L over the whole image', async (t) => {
  const device = await testDevice();
  // Two subdivisions: 320 facets, shading normals up to ~6 degrees off the facet normals.
  const sphere = icosphere(1, [0, 0, 0], 2);
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, maxDepth: 32, samplesPerPixel: spp, seed: 5,
    camera: { type: 'orthographic', position: [0, 0, 4], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 2.2 },
    environment: { color: L },
    meshes: [{
      positions: sphere.positions, indices: sphere.indices, normals: sphere.positions,
      material: { baseColorFactor: [1, 1, 1], metallicFactor: 0, roughnessFactor: 0, ior: 1.5, transmissionFactor: 1, thicknessFactor: 2 },
    }],
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const { data } = await renderer.readRadiance();
    let sum = 0;
    for (let p = 0; p < size * size; p++) for (let c = 0; c < 3; c++) sum += data[4 * p + c]! / L[c]! / 3;
    const mean = sum / (size * size);
    const samples = size * size * spp;
    const { invalidBsdfSample, maxDepth } = stats.terminations;
    t.diagnostic(`radiance / L = ${mean.toFixed(5)} over ${samples} samples; ${invalidBsdfSample} ended on an invalid BSDF sample, ${maxDepth} at maxDepth`);
    assert.ok(mean <= 1 + 1e-4, `gains energy: ${mean}`);
    // Every sample weighs 1 (Russian roulette never fires: throughput x etaScale stays 1), so the
    // only loss allowed is the paths maxDepth cuts, each exactly one sample's L: the mean must be
    // 1 - cut / N up to f32 round-off. Paths that stay inside past 32 bounces are those that meet
    // the facets near the critical angle, where total internal reflection traps them (a faceted
    // solid can trap light, unlike a true sphere): at most 1% here.
    assert.equal(invalidBsdfSample, 0, 'a delta sample on the wrong side of the facet ended its path');
    assert.ok(maxDepth / samples < 0.01, `${maxDepth} of ${samples} paths reach maxDepth`);
    assert.ok(Math.abs(mean - (1 - maxDepth / samples)) <= 1e-4, `loses energy beyond the cut paths: ${mean} vs ${1 - maxDepth / samples}`);
  } finally {
    renderer.destroy();
  }
});
