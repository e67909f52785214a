// The CPU side of GPU lighting: light-group probabilities, the lights heap's layout (no overlaps,
// every record where the uniforms say), the selection table and tree leaves, coarse environment
// tables for large maps (still consistent: chi-square and normalisation), and the features a scene
// turns on.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { lightGroupProbabilities, MIN_GROUP_PROBABILITY } from '../../src/lighting/gpu-lighting.ts';
import { buildEnvironmentSampler, environmentPdf, sampleEnvironment, environmentTableSize } from '../../src/lighting/environment-sampling.ts';
import { validateAreaLight } from '../../src/lighting/area-lights.ts';
import { validatePunctualLight } from '../../src/lighting/punctual-lights.ts';
import { lightingUniformsLayout, lightSelectionEntryLayout, lightTreeNodeLayout } from '../../src/gpu-layout/records.ts';
import { readStruct } from '../../src/gpu-layout/struct-layout.ts';
import { INDEX_NONE } from '../../src/gpu-layout/constants.ts';
import { createEnvironmentLighting } from '../../src/lighting/environment-lighting.ts';
import { chiSquareTest, rng, uniformSphere } from './helpers.ts';
import { lightingFor, testHdri } from './gpu-fixtures.ts';

test('light groups: probabilities follow power, sum to 1, and keep every present group alive', () => {
  const p = lightGroupProbabilities({ environment: 1, sun: 3, directional: 0, bounded: 1e-6 });
  assert.ok(Math.abs(p.environment + p.sun + p.directional + p.bounded - 1) < 1e-12);
  assert.equal(p.directional, 0);
  assert.ok(p.bounded >= MIN_GROUP_PROBABILITY / 1.2, `bounded ${p.bounded}`);
  assert.ok(Math.abs(p.sun / p.environment - 3) < 1e-9);
  assert.deepEqual(lightGroupProbabilities({ environment: 0, sun: 0, directional: 2, bounded: 0 }), { environment: 0, sun: 0, directional: 1, bounded: 0 });
  assert.deepEqual(lightGroupProbabilities({ environment: 0, sun: 0, directional: 0, bounded: 0 }), { environment: 0, sun: 0, directional: 0, bounded: 0 });
});

test('lights heap: records where the uniforms say, without overlap; selection pmfs sum to 1; tree leaves map back', () => {
  const area = [
    validateAreaLight({ type: 'rectangle', center: [0, 2, 0], edgeU: [1, 0, 0], edgeV: [0, 0, -1], intensity: 2 }),
    validateAreaLight({ type: 'sphere', center: [1, 1, 1], radius: 0.2 }),
  ];
  const punctual = [
    validatePunctualLight({ type: 'point', position: [0, 1, 0], intensity: 3 }),
    validatePunctualLight({ type: 'directional', direction: [0, -1, 0], intensity: 2 }),
    validatePunctualLight({ type: 'spot', position: [0, 1, 1], direction: [0, -1, 0] }),
    validatePunctualLight({ type: 'point', position: [0, 1, 0], intensity: 0 }),
  ];
  const sky = createEnvironmentLighting({ preset: 'noon', width: 32, height: 16 });
  for (const lightSampler of ['tree', 'power'] as const) {
    const l = lightingFor({ area, punctual, environment: { kind: 'map', map: sky.map, sun: sky.sun, preset: 'noon' }, portals: [], lightSampler });
    const u = readStruct(lightingUniformsLayout, new DataView(l.uniforms), 0) as Record<string, number | number[]>;
    assert.equal(u.areaCount, 2);
    assert.equal(u.punctualCount, 2, 'point and spot (the black point light is dropped)');
    assert.equal(u.directionalCount, 1);
    assert.equal(u.boundedCount, 4);
    const [tw, th] = u.environmentTableSize as number[];
    const ranges: [string, number, number][] = [
      ['selection', u.selectionOffset as number, 4],
      ['area', u.areaOffset as number, 2 * 5],
      ['punctual', u.punctualOffset as number, 3 * 4],
      ['tree', u.treeOffset as number, (u.treeNodeCount as number) * 4],
      ['table', u.environmentTableOffset as number, th! + tw! * th!],
    ];
    ranges.sort((a, b) => a[1] - b[1]);
    for (let k = 1; k < ranges.length; k++) assert.ok(ranges[k]![1] >= ranges[k - 1]![1] + ranges[k - 1]![2], `${ranges[k - 1]![0]} overlaps ${ranges[k]![0]}`);
    const last = ranges[ranges.length - 1]!;
    assert.ok(l.heap.byteLength / 16 >= last[1] + last[2]);
    const view = new DataView(l.heap);
    let total = 0;
    for (let g = 0; g < 4; g++) {
      const e = readStruct(lightSelectionEntryLayout, new DataView(l.heap, 16 * ((u.selectionOffset as number) + g), 16), 0);
      total += e.pmf as number;
      if (lightSampler === 'tree') {
        const node = readStruct(lightTreeNodeLayout, view, (u.treeOffset as number) / 4 + (e.treeLeaf as number));
        assert.equal(node.childOrLight, g, 'the leaf holds the light');
      } else {
        assert.equal(e.treeLeaf, INDEX_NONE);
      }
    }
    assert.ok(Math.abs(total - 1) < 1e-6);
    assert.ok(Math.abs(l.probabilities.environment + l.probabilities.sun + l.probabilities.directional + l.probabilities.bounded - 1) < 1e-12);
    assert.deepEqual(l.uses, { environment: true, environmentMap: true, sun: true, portals: false, punctualLights: true, areaLights: true, lightTree: lightSampler === 'tree' });
  }
  const none = lightingFor({});
  assert.deepEqual(Object.values(none.uses), [false, false, false, false, false, false, false]);
});

test('a map above the table budget gets coarser tables: sampling still follows them and the pdf integrates to 1', () => {
  const map = testHdri(64, 32, 200);
  assert.deepEqual(environmentTableSize(64, 32, 300), [16, 8]);
  const sampler = buildEnvironmentSampler(map, { maxTableCells: 300 });
  assert.equal(sampler.tableWidth * sampler.tableHeight, 128);
  const random = rng(5);
  const n = 200_000;
  const observed = new Float64Array(128);
  let mismatch = 0;
  for (let s = 0; s < n; s++) {
    const x = sampleEnvironment(sampler, random(), random());
    assert.ok(x.pdf > 0);
    const d = x.direction;
    const u = ((Math.atan2(d[2], d[0]) / (2 * Math.PI) + 0.5) % 1 + 1) % 1;
    const v = Math.acos(Math.max(-1, Math.min(1, d[1]))) / Math.PI;
    observed[Math.min(7, Math.floor(v * 8)) * 16 + Math.min(15, Math.floor(u * 16))]! += 1;
    if (Math.abs(environmentPdf(sampler, d) - x.pdf) > 1e-9 * x.pdf) mismatch++;
  }
  assert.ok(mismatch < n * 1e-4, `${mismatch} pdf mismatches`);
  let total = 0;
  for (const w of sampler.weights) total += w;
  const chi = chiSquareTest(observed, Array.from(sampler.weights, (w) => (n * w) / total));
  assert.ok(chi.pValue > 1e-4, `chi-square p = ${chi.pValue}`);
  // Monte Carlo integral of the pdf over the sphere (uniform directions).
  let integral = 0;
  const m = 200_000;
  for (let s = 0; s < m; s++) integral += environmentPdf(sampler, uniformSphere(random)) * 4 * Math.PI;
  assert.ok(Math.abs(integral / m - 1) < 0.02, `pdf integrates to ${integral / m}`);
  // The sun's cell keeps a positive density even though it is averaged with dim texels.
  const sunCell = sampler.weights.reduce((best, w, k) => (w > sampler.weights[best]! ? k : best), 0);
  assert.ok(sampler.weights[sunCell]! > 10 * (total / 128));
});
