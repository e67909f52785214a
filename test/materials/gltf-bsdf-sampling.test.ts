// bsdf_sample of src/shaders/wgsl/bsdf-gltf.wgsl: consistency with bsdf_eval / bsdf_pdf, the pdf's
// normalisation, an unbiased albedo estimate, and Mitsuba 3 style chi-square goodness-of-fit tests
// of the sampled directions against bsdf_pdf.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { gltfBsdfEval, gltfBsdfPdf, type GltfBsdfMaterial, type Vec3 } from '../../src/materials/index.ts';
import { chiSquarePValue, chiSquareTest, gammaQ, histogram, integrateCellsOnGpu, packMaterials, runKernel, sampleAt, sampleOnGpu, sum, viewAt } from './bsdf-harness.ts';

interface Config {
  name: string;
  m: GltfBsdfMaterial;
  view: number;
}

const f = Math.fround;
const configs: Config[] = [
  { name: 'diffuse (ior 1)', m: { baseColor: [0.8, 0.6, 0.4], metallic: 0, roughness: 0.5, ior: 1 }, view: 30 },
  { name: 'rough dielectric, normal view', m: { baseColor: [0.5, 0.5, 0.5], metallic: 0, roughness: 0.3, ior: 1.5 }, view: 0 },
  { name: 'rough dielectric, grazing view', m: { baseColor: [0.5, 0.5, 0.5], metallic: 0, roughness: 0.3, ior: 1.5 }, view: 75 },
  { name: 'black rough dielectric (specular only)', m: { baseColor: [0, 0, 0], metallic: 0, roughness: 0.35, ior: 2 }, view: 45 },
  { name: 'rough metal', m: { baseColor: [0.9, 0.6, 0.3], metallic: 1, roughness: 0.4, ior: 1.5 }, view: 20 },
  { name: 'very rough metal, grazing view', m: { baseColor: [0.9, 0.6, 0.3], metallic: 1, roughness: 1, ior: 1.5 }, view: 70 },
  { name: 'mixed', m: { baseColor: [0.2, 0.7, 0.4], metallic: 0.5, roughness: 0.6, ior: 1.8 }, view: 60 },
].map((c) => ({ ...c, m: { ...c.m, roughness: f(c.m.roughness), ior: f(c.m.ior), baseColor: c.m.baseColor.map(f) as unknown as Vec3 } }));

// bsdf_sample's f and pdf and bsdf_eval / bsdf_pdf at the sampled direction take different
// operation orders (the sample goes through the sampled microfacet normal), so they agree to
// rounding, not bit for bit: how far depends on the GPU's compiler (fused multiply-adds; NVIDIA
// through Dawn differs by 1.5e-6 relative where lavapipe agrees to 1e-7). 64 f32 ULPs leaves
// margin for that and still fails any real inconsistency, which is orders of magnitude larger.
const ROUNDING = 64 * 2 ** -23;
const N_THETA = 20;
const N_PHI = 40;
const SUPERSAMPLE = 16;
const SAMPLES = 250_000;
// Mitsuba 3's ChiSquareTest: family-wise significance 0.01 over all configurations, Sidak-corrected
// per test, so a correct sampler fails this file with probability 1% whatever the seeds.
const SIGNIFICANCE = 1 - Math.pow(1 - 0.01, 1 / configs.length);

test('the chi-square p-value helper matches known quantiles', () => {
  // chi2 quantiles: P(X > 3.841) = 0.05 (1 dof), P(X > 18.307) = 0.05 (10 dof), P(X > 135.807) = 0.01 (100 dof).
  assert.ok(Math.abs(chiSquarePValue(3.841459, 1) - 0.05) < 1e-6);
  assert.ok(Math.abs(chiSquarePValue(18.307038, 10) - 0.05) < 1e-6);
  assert.ok(Math.abs(chiSquarePValue(135.806723, 100) - 0.01) < 1e-6);
  assert.ok(Math.abs(gammaQ(1, 2) - Math.exp(-2)) < 1e-14);
});

test('bsdf_sample returns f = bsdf_eval(wi), pdf = bsdf_pdf(wi), weight = f cos / pdf, matching the reference', async () => {
  for (const [k, c] of configs.entries()) {
    const wo = viewAt(c.view);
    const n = 20_000;
    const data = await sampleOnGpu(c.m, wo, n, 100 + k);
    let valid = 0;
    for (let i = 0; i < n; i++) {
      const s = sampleAt(data, i);
      assert.equal(s.isDelta, false, `${c.name}: rough materials have no delta lobe`);
      if (!s.valid) continue;
      valid++;
      const where = `${c.name} sample ${i}`;
      assert.ok(Math.abs(Math.hypot(...s.wi) - 1) < 1e-5 && s.wi[2] > 0, `${where}: wi ${s.wi}`);
      assert.ok(s.pdf > 0 && Number.isFinite(s.pdf), `${where}: pdf ${s.pdf}`);
      assert.ok(Math.abs(s.pdf - s.pdfAtWi) <= ROUNDING * s.pdf, `${where}: sample pdf ${s.pdf} vs bsdf_pdf ${s.pdfAtWi}`);
      const refPdf = gltfBsdfPdf(c.m, wo, s.wi);
      assert.ok(Math.abs(s.pdf - refPdf) <= 2e-3 * refPdf + 1e-6, `${where}: pdf ${s.pdf} vs reference ${refPdf}`);
      const refF = gltfBsdfEval(c.m, wo, s.wi);
      for (let ch = 0; ch < 3; ch++) {
        assert.ok(Math.abs(s.f[ch] - s.evalAtWi[ch]) <= ROUNDING * s.f[ch], `${where}: f ${s.f} vs bsdf_eval ${s.evalAtWi}`);
        assert.ok(Math.abs(s.f[ch] - refF[ch]) <= 2e-3 * refF[ch] + 1e-6, `${where}: f ${s.f} vs reference ${refF}`);
        const w = (s.f[ch] * s.wi[2]) / s.pdf;
        assert.ok(Math.abs(s.weight[ch] - w) <= 1e-5 * w + 1e-7, `${where}: weight ${s.weight} vs f cos / pdf`);
      }
    }
    assert.ok(valid > n / 2, `${c.name}: only ${valid} valid samples`);
  }
});

test('bsdf_pdf integrates to the probability of a valid sample, and E[weight] equals the albedo', async () => {
  for (const [k, c] of configs.entries()) {
    const wo = viewAt(c.view);
    const cells = await integrateCellsOnGpu(c.m, wo, N_THETA, N_PHI, SUPERSAMPLE);
    const pdfIntegral = sum(cells.pdf);
    const n = 100_000;
    const data = await sampleOnGpu(c.m, wo, n, 200 + k);
    let valid = 0;
    const w = [0, 0, 0];
    const w2 = [0, 0, 0];
    for (let i = 0; i < n; i++) {
      const s = sampleAt(data, i);
      if (!s.valid) continue;
      valid++;
      for (let ch = 0; ch < 3; ch++) {
        w[ch] += s.weight[ch];
        w2[ch] += s.weight[ch] * s.weight[ch];
      }
    }
    // The pdf covers only the upper hemisphere: VNDF reflections below the horizon are discarded,
    // so its integral is the valid fraction (1 for pure cosine sampling). Binomial 5 sigma plus the
    // quadrature error (< 1e-3 at 16 x 16 points per cell, see the diffuse case).
    const p = valid / n;
    const sigma = Math.sqrt(Math.max(p * (1 - p), 1 / n) / n);
    assert.ok(pdfIntegral <= 1 + 1e-3, `${c.name}: pdf integrates to ${pdfIntegral} > 1`);
    assert.ok(Math.abs(pdfIntegral - p) <= 5 * sigma + 1e-3, `${c.name}: integral of pdf ${pdfIntegral}, valid fraction ${p}`);
    if (c.m.metallic === 0 && c.m.ior === 1) assert.ok(Math.abs(pdfIntegral - 1) < 1e-3, `${c.name}: cosine pdf integrates to ${pdfIntegral}`);
    for (let ch = 0; ch < 3; ch++) {
      const albedo = sum(cells.fCos, 3, ch);
      const mean = w[ch] / n;
      const variance = Math.max(w2[ch] / n - mean * mean, 0);
      const se = Math.sqrt(variance / n);
      assert.ok(Math.abs(mean - albedo) <= 5 * se + 2e-3 * albedo + 1e-5, `${c.name} channel ${ch}: E[weight] ${mean} +- ${se} vs albedo ${albedo}`);
      assert.ok(albedo <= 1 + 1e-3, `${c.name} channel ${ch}: albedo ${albedo} > 1`);
    }
  }
});

test('chi-square: sampled directions follow bsdf_pdf (family-wise p > 0.01), and the test rejects a wrong pdf', async (t) => {
  for (const [k, c] of configs.entries()) {
    const wo = viewAt(c.view);
    const cells = await integrateCellsOnGpu(c.m, wo, N_THETA, N_PHI, SUPERSAMPLE);
    const data = await sampleOnGpu(c.m, wo, SAMPLES, 300 + k);
    const observed = histogram(data, SAMPLES, N_THETA, N_PHI);
    const expected = Float64Array.from(cells.pdf, (p) => p * SAMPLES);
    const result = chiSquareTest(observed, expected);
    assert.equal(result.outsideSupport, false, `${c.name}: samples where the pdf is 0`);
    assert.ok(result.dof > 50, `${c.name}: only ${result.dof} degrees of freedom`);
    assert.ok(result.pValue > SIGNIFICANCE, `${c.name}: chi2 ${result.chi2.toFixed(1)}, dof ${result.dof}, p ${result.pValue}`);
    // Power check: the same histogram against a 15% rougher (or, for the diffuse case, a
    // half-specular) material must be rejected outright.
    t.diagnostic(`${c.name}: chi2 ${result.chi2.toFixed(1)}, dof ${result.dof}, pooled ${result.pooledCells}, p ${result.pValue.toFixed(3)}`);
    const wrong: GltfBsdfMaterial =
      c.m.ior === 1 && c.m.metallic === 0 ? { ...c.m, metallic: 0.5 } : { ...c.m, roughness: c.m.roughness < 1 ? c.m.roughness * 1.15 : 0.85 };
    const wrongCells = await integrateCellsOnGpu(wrong, wo, N_THETA, N_PHI, 8);
    const wrongResult = chiSquareTest(observed, Float64Array.from(wrongCells.pdf, (p) => (p * SAMPLES * sum(cells.pdf)) / sum(wrongCells.pdf)));
    assert.ok(wrongResult.pValue < 1e-6, `${c.name}: wrong pdf not rejected (p ${wrongResult.pValue})`);
    t.diagnostic(`${c.name}: wrong pdf chi2 ${wrongResult.chi2.toFixed(1)}, p ${wrongResult.pValue.toExponential(2)}`);
  }
});

test('extreme inputs (near-delta roughness, grazing views, ior 1 and 3) give finite, non-negative results', async () => {
  const materials: GltfBsdfMaterial[] = [];
  for (const roughness of [0, 0.0316, 0.0317, 0.05, 0.2, 1]) {
    for (const metallic of [0, 0.5, 1]) {
      for (const ior of [1, 1.5, 3]) materials.push({ baseColor: [1, f(0.5), 0], metallic, roughness: f(roughness), ior });
    }
  }
  const views = [f(1), f(0.3), f(1e-2), f(1e-4), f(1e-6)];
  const perCombo = 1024;
  const count = materials.length * views.length * perCombo;
  const data = await runKernel({
    inputs: [
      { data: packMaterials(materials), type: 'TestMaterial' },
      { data: new Float32Array(views.flatMap((z) => [0, 0, z, 0])), type: 'vec4f' },
    ],
    outputFloats: count * 4,
    count,
    body: `
  let combo = i / ${perCombo}u;
  let m = t_material(in0[combo / ${views.length}u]);
  let z = in1[combo % ${views.length}u].z;
  let h0 = t_pcg(i);
  let h1 = t_pcg(h0);
  let h2 = t_pcg(h1);
  let phi = TWO_PI * t_unit(t_pcg(h2));
  let wo = vec3f(sqrt(1.0 - z * z) * cos(phi), sqrt(1.0 - z * z) * sin(phi), z);
  let s = bsdf_sample(m, wo, t_unit(h0), vec2f(t_unit(h1), t_unit(h2)));
  let wi = normalize(vec3f(t_unit(h1) - 0.5, t_unit(h2) - 0.5, t_unit(h0) + 1e-3));
  out[i * 4u] = select(0.0, max_component(s.weight) + s.pdf + max_component(s.f), s.valid);
  out[i * 4u + 1u] = select(0.0, 1.0, s.valid);
  out[i * 4u + 2u] = max_component(bsdf_eval(m, wo, wi));
  out[i * 4u + 3u] = bsdf_pdf(m, wo, wi);`,
  });
  let valid = 0;
  for (let i = 0; i < count; i++) {
    for (let k = 0; k < 4; k++) {
      const v = data[i * 4 + k];
      assert.ok(Number.isFinite(v) && v >= 0, `invocation ${i} value ${k}: ${v}`);
    }
    valid += data[i * 4 + 1];
  }
  assert.ok(valid > count / 2, `only ${valid} of ${count} samples valid`);
});
