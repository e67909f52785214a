import { test } from 'node:test';
import assert from 'node:assert/strict';
import { bilinearTexel, environmentRadiance } from '../../src/lighting/environment-map.ts';
import { directionToEquirectUv, equirectUvToDirection } from '../../src/lighting/equirect.ts';
import {
  buildEnvironmentSampler,
  environmentAliasEntryLayout,
  environmentPdf,
  sampleEnvironment,
} from '../../src/lighting/environment-sampling.ts';
import { luminance } from '../../src/lighting/vec3.ts';
import { chiSquareTest, makeMap, meanAndError, relDiff, rng, uniformSphere } from './helpers.ts';

const W = 16;
const H = 8;

/** A map with smooth variation, a bright spot and a black band (rows 5..7 are zero). */
function testMap(rotation = 0) {
  return makeMap(W, H, (i, j) => (j >= 5 ? [0, 0, 0] : i === 3 && j === 1 ? [40, 30, 20] : [1 + (i % 5), 0.5 + j * 0.3, 2 + ((i * j) % 3)]), 1.5, rotation);
}

/**
 * The distribution the sampler must follow, computed here from its definition: per texel, the mean
 * of the bilinear radiance's luminance over the cell (midpoint rule, 8 x 8 points) times sin(theta)
 * at the row centre; uniform in (u, v) inside the texel.
 */
function expectedTexelProbabilities(map: ReturnType<typeof testMap>): Float64Array {
  const p = new Float64Array(W * H);
  const n = 8;
  let total = 0;
  for (let j = 0; j < H; j++) {
    for (let i = 0; i < W; i++) {
      let s = 0;
      for (let a = 0; a < n; a++) for (let b = 0; b < n; b++) s += luminance(bilinearTexel(map, (i + (a + 0.5) / n) / W, (j + (b + 0.5) / n) / H));
      p[j * W + i] = (s / (n * n)) * Math.sin((Math.PI * (j + 0.5)) / H);
      total += p[j * W + i]!;
    }
  }
  return p.map((x) => x / total);
}

test('environment table layout: H + W H records of 12 bytes', () => {
  const s = buildEnvironmentSampler(testMap());
  assert.equal(environmentAliasEntryLayout.size, 12);
  assert.equal(s.entries.byteLength, (H + W * H) * 12);
});

test('environment sampling follows filtered luminance x sin(theta) (chi-square, 2 x 2 cells per texel)', () => {
  for (const rotation of [0, 1.3]) {
    const map = testMap(rotation);
    const sampler = buildEnvironmentSampler(map);
    const texel = expectedTexelProbabilities(map);
    const n = 200_000;
    const observed = new Float64Array(W * H * 4);
    const random = rng(11);
    for (let k = 0; k < n; k++) {
      const s = sampleEnvironment(sampler, random(), random());
      assert.ok(s.pdf > 0);
      const [u, v] = directionToEquirectUv(s.direction, rotation);
      const x = Math.min(2 * W - 1, Math.floor(u * 2 * W));
      const y = Math.min(2 * H - 1, Math.floor(v * 2 * H));
      observed[y * 2 * W + x]++;
    }
    const expected = new Float64Array(W * H * 4);
    for (let y = 0; y < 2 * H; y++) for (let x = 0; x < 2 * W; x++) expected[y * 2 * W + x] = (n * texel[(y >> 1) * W + (x >> 1)]!) / 4;
    const r = chiSquareTest(observed, expected);
    assert.equal(r.outsideSupport, false);
    assert.ok(r.pValue > 0.001, `chi2 ${r.chi2.toFixed(1)} dof ${r.dof} p ${r.pValue}`);
  }
});

test('environment pdf integrates to 1 over the sphere and agrees with the sampled pdf', () => {
  const map = testMap(0.4);
  const sampler = buildEnvironmentSampler(map);
  // (theta, phi) midpoint quadrature with the sin(theta) Jacobian.
  const nt = 800;
  const np = 1600;
  let integral = 0;
  for (let a = 0; a < nt; a++) {
    const theta = ((a + 0.5) / nt) * Math.PI;
    let row = 0;
    for (let b = 0; b < np; b++) {
      const phi = ((b + 0.5) / np) * 2 * Math.PI;
      row += environmentPdf(sampler, [Math.sin(theta) * Math.cos(phi), Math.cos(theta), Math.sin(theta) * Math.sin(phi)]);
    }
    integral += row * Math.sin(theta);
  }
  integral *= (Math.PI / nt) * ((2 * Math.PI) / np);
  assert.ok(Math.abs(integral - 1) < 2e-3, `integral ${integral}`);
  const random = rng(2);
  for (let k = 0; k < 20_000; k++) {
    const s = sampleEnvironment(sampler, random(), random());
    assert.ok(relDiff(s.pdf, environmentPdf(sampler, s.direction)) < 1e-9);
    const r = environmentRadiance(map, s.direction);
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(r[c] - s.radiance[c]) <= 1e-9 * Math.max(1, r[c]));
  }
});

test('every direction with radiance has a positive pdf; zero-radiance regions are never sampled', () => {
  const map = testMap();
  const sampler = buildEnvironmentSampler(map);
  const random = rng(8);
  for (let k = 0; k < 50_000; k++) {
    const d = uniformSphere(random);
    if (luminance(environmentRadiance(map, d)) > 0) assert.ok(environmentPdf(sampler, d) > 0, `direction ${d}`);
  }
  // Rows 5..7 are black: the filtered radiance vanishes from the centre of row 4 (v = 4.5 / 8) down,
  // and texels of rows 6 and 7 have an all-black 3 x 3 neighbourhood.
  for (let k = 0; k < 100_000; k++) {
    const s = sampleEnvironment(sampler, random(), random());
    const v = directionToEquirectUv(s.direction)[1];
    assert.ok(v < 6 / H, `sample in the black band, v = ${v}`);
  }
});

test('a one-texel sun: all samples land next to it and the estimator of total power is exact to noise', () => {
  const w = 64;
  const h = 32;
  const map = makeMap(w, h, (i, j) => (i === 40 && j === 9 ? [5000, 4000, 3000] : [0, 0, 0]));
  const sampler = buildEnvironmentSampler(map);
  // Reference: integral of the bilinear radiance over the sphere, by the midpoint rule in (u, v)
  // over the 3 x 3 texels around the sun (the only place it is non-zero).
  let reference = 0;
  const m = 64;
  for (let y = 8 * m; y < 11 * m; y++) {
    for (let x = 39 * m; x < 42 * m; x++) {
      const u = (x + 0.5) / (w * m);
      const v = (y + 0.5) / (h * m);
      reference += luminance(bilinearTexel(map, u, v)) * 2 * Math.PI * Math.PI * Math.sin(Math.PI * v);
    }
  }
  reference /= w * m * h * m;
  const random = rng(4);
  const n = 40_000;
  const estimates = new Float64Array(n);
  for (let k = 0; k < n; k++) {
    const s = sampleEnvironment(sampler, random(), random());
    const [u, v] = directionToEquirectUv(s.direction);
    assert.ok(Math.floor(u * w) >= 39 && Math.floor(u * w) <= 41 && Math.floor(v * h) >= 8 && Math.floor(v * h) <= 10);
    estimates[k] = luminance(s.radiance) / s.pdf;
  }
  const { mean, stderr } = meanAndError(estimates);
  assert.ok(Math.abs(mean - reference) < 4 * stderr + 1e-9 * reference, `mean ${mean} reference ${reference} stderr ${stderr}`);
  assert.ok(stderr < 0.01 * reference);
});

test('a black map samples nothing', () => {
  const sampler = buildEnvironmentSampler(makeMap(4, 2, () => [0, 0, 0]));
  assert.equal(sampler.weightIntegral, 0);
  assert.equal(sampleEnvironment(sampler, 0.3, 0.7).pdf, 0);
  assert.equal(environmentPdf(sampler, [0, 1, 0]), 0);
});

test('extreme random numbers stay inside the map (u -> 1 from below)', () => {
  const sampler = buildEnvironmentSampler(testMap());
  for (const u of [0, 1 - 2 ** -24, 1 - 2 ** -53, 0.5]) {
    for (const w of [0, 1 - 2 ** -24, 1 - 2 ** -53]) {
      const s = sampleEnvironment(sampler, u, w);
      assert.ok(Number.isFinite(s.pdf) && s.direction.every(Number.isFinite));
      // pdf 0 only at an exact pole, where the map has no area (the caller drops the sample).
      if (s.pdf === 0) assert.ok(Math.abs(s.direction[1]) === 1);
      else assert.ok(s.pdf > 0);
    }
  }
  const d = equirectUvToDirection(0.3, 0.2);
  assert.ok(environmentPdf(sampler, d) > 0);
});
