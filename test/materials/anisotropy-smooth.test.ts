// KHR_materials_anisotropy at roughness 0: alpha_b = 0 while alpha_t = strength^2 is rough, a lobe
// that is a delta across the anisotropy direction and glossy along it. The lobe keeps alpha_b at
// least 1e-4 (pbrt-v4 TrowbridgeReitzDistribution), so it samples and evaluates finitely; its
// albedo is the visible-normal integral E(wo) = int D_wo(h) G2(wo, wi) / G1(wo) dh over reflections
// above the horizon (Heitz 2018, eq. 17 with the VNDF sampling weight G2 / G1), computed here in
// double precision over the sampling mapping's unit square, independent of the GPU.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { gltfBsdfEval, gltfBsdfPdf, type GltfBsdfMaterial, type Vec3 } from '../../src/materials/gltf-bsdf-reference.ts';
import { anisotropicAlphas, ggxG1Aniso, ggxG2, reflect, sampleGgxVisibleNormal, type Alphas } from '../../src/materials/reference/microfacet.ts';
import { lobeAlphas } from '../../src/materials/reference/lobes.ts';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { gltfExtensionLobe, sampleAt, sampleOnGpu } from './bsdf-harness.ts';

const f = Math.fround;
const lobe = gltfExtensionLobe('glTF + anisotropy', ['FEATURE_ANISOTROPY']);

/** Directional albedo of a white (F = 1) GGX conductor: midpoint rule in the VNDF sampling square. */
function conductorAlbedo(a: Alphas, wo: Vec3, n = 512): number {
  let sum = 0;
  for (let i = 0; i < n; i++) {
    for (let j = 0; j < n; j++) {
      const wi = reflect(wo, sampleGgxVisibleNormal(wo, a, (i + 0.5) / n, (j + 0.5) / n));
      if (wi[2] > 0) sum += ggxG2(wo, wi, a) / ggxG1Aniso(wo, a);
    }
  }
  return sum / (n * n);
}

const direction = (thetaDegrees: number, phiDegrees: number): Vec3 => {
  const t = (thetaDegrees * Math.PI) / 180;
  const p = (phiDegrees * Math.PI) / 180;
  return [f(Math.sin(t) * Math.cos(p)), f(Math.sin(t) * Math.sin(p)), f(Math.cos(t))];
};

test('anisotropy at roughness 0: finite samples consistent with eval_pdf and the reference, E[weight] = the albedo <= 1', async (t) => {
  const n = 1 << 16;
  for (const strength of [0.5, 1]) {
    const m: GltfBsdfMaterial = { baseColor: [1, 1, 1], metallic: 1, roughness: 0, ior: 1.5, anisotropy: strength };
    const a = lobeAlphas(anisotropicAlphas(0, strength));
    // Views along the anisotropy direction, across it, and in between.
    for (const [theta, phi] of [[0, 0], [45, 0], [45, 90], [70, 30]] as const) {
      const wo = direction(theta, phi);
      const where = `strength ${strength}, view (${theta}, ${phi})`;
      const data = await sampleOnGpu(m, wo, n, 2000 + theta + phi, lobe);
      let sum = 0;
      let sum2 = 0;
      for (let i = 0; i < n; i++) {
        const s = sampleAt(data, i);
        for (const v of [...s.wi, s.pdf, ...s.f, ...s.weight]) assert.ok(Number.isFinite(v), `${where} sample ${i}: not finite (${s.wi} ${s.pdf} ${s.f})`);
        if (!s.valid) continue;
        assert.equal(s.isDelta, false, `${where}: the glossy axis makes the lobe non-delta`);
        assert.ok(Math.abs(s.pdf - s.pdfAtWi) <= 1e-4 * s.pdf, `${where}: sample pdf ${s.pdf} vs eval_pdf ${s.pdfAtWi}`);
        assert.ok(Math.abs(s.f[1] - s.evalAtWi[1]) <= 1e-4 * s.f[1], `${where}: sample f ${s.f[1]} vs eval_pdf ${s.evalAtWi[1]}`);
        if (i % 64 === 0) {
          const refF = gltfBsdfEval(m, wo, s.wi)[1];
          const refPdf = gltfBsdfPdf(m, wo, s.wi);
          assert.ok(Math.abs(s.f[1] - refF) <= 1e-2 * refF + 1e-6, `${where}: f ${s.f[1]} vs reference ${refF}`);
          assert.ok(Math.abs(s.pdf - refPdf) <= 1e-2 * refPdf + 1e-6, `${where}: pdf ${s.pdf} vs reference ${refPdf}`);
        }
        sum += s.weight[1];
        sum2 += s.weight[1] * s.weight[1];
      }
      const mean = sum / n;
      const se = Math.sqrt(Math.max(sum2 / n - mean * mean, 0) / n);
      const albedo = conductorAlbedo(a, wo);
      t.diagnostic(`${where}: E[weight] ${mean.toFixed(5)} +- ${se.toExponential(1)}, albedo ${albedo.toFixed(5)}`);
      assert.ok(Math.abs(mean - albedo) <= 5 * se + 2e-3, `${where}: E[weight] ${mean} +- ${se} vs albedo ${albedo}`);
      assert.ok(albedo <= 1 && mean - 5 * se <= 1, `${where}: gains energy`);
    }
  }
});

test('furnace: a roughness-0 anisotropic white conductor facing the camera renders L E(normal incidence), with no invalid samples', async (t) => {
  const device = await testDevice();
  const L = [0.8, 1, 1.2];
  const size = 12;
  for (const strength of [0.5, 1]) {
    const renderer = await createWavefrontPathTracingComputeRenderer({
      device, width: size, height: size, maxDepth: 4, samplesPerPixel: 64, seed: 7, environment: { color: L },
      camera: { type: 'orthographic', position: [0, 0, 3], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 1 },
      meshes: [{
        positions: [-2, -2, 0, 2, -2, 0, 2, 2, 0, -2, 2, 0], indices: [0, 1, 2, 0, 2, 3],
        material: { baseColorFactor: [1, 1, 1], metallicFactor: 1, roughnessFactor: 0, anisotropyStrength: strength },
      }],
    });
    try {
      const stats = await renderer.renderFrame();
      assert.equal(stats.invalidSamples, 0, `strength ${strength}: invalid samples`);
      const { data } = await renderer.readRadiance();
      // Pixels are independent estimates of the same value (every camera ray meets the quad head on).
      const values = Array.from({ length: size * size }, (_, p) => (data[4 * p]! / L[0]! + data[4 * p + 1]! / L[1]! + data[4 * p + 2]! / L[2]!) / 3);
      const mean = values.reduce((x, y) => x + y, 0) / values.length;
      const se = Math.sqrt(values.reduce((x, y) => x + (y - mean) ** 2, 0) / (values.length - 1) / values.length);
      const expected = conductorAlbedo(lobeAlphas(anisotropicAlphas(0, strength)), [0, 0, 1]);
      t.diagnostic(`strength ${strength}: radiance / L = ${mean.toFixed(4)} +- ${se.toFixed(4)}, E = ${expected.toFixed(4)}`);
      assert.ok(Math.abs(mean - expected) <= 4 * se + 2e-3, `strength ${strength}: ${mean} +- ${se} vs ${expected}`);
    } finally {
      renderer.destroy();
    }
  }
});
