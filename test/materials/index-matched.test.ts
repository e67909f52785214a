// ior 1 (KHR_materials_ior). An index-matched refractive interface (with KHR_materials_volume):
// Snell's law deflects nothing at any microfacet, so the transmission is the delta wi = -wo at every
// roughness (Walter et al. 2007's eta -> 1 limit; pbrt-v4 DielectricBxDF), weighted by the light the
// visible microfacets do not reflect; a thin film on it (KHR_materials_iridescence) still reflects
// through the rough lobe. A thin wall (no volume) of ior 1: its microfacet prisms deflect nothing
// either (KHR_materials_transmission: the blur is "modulated by the material's index of
// refraction"). The BSDF on the GPU against the CPU reference, then the renderer: an ior-1 slab of
// any roughness shows what lies behind it unchanged.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { gltfBsdfEval, gltfBsdfPdf, gltfDielectricFresnel, gltfStraightTransmittance, type GltfBsdfMaterial, type Vec3 } from '../../src/materials/gltf-bsdf-reference.ts';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { WavefrontMaterialInput, WavefrontMeshInput } from '../../src/scene/types.ts';
import { testDevice } from '../helpers/gpu.ts';
import { chiSquareTest, gltfExtensionLobe, histogram, integrateCellsOnGpu, sampleAt, sampleOnGpu, sum, viewAt } from './bsdf-harness.ts';
import { box } from './slab-scene.ts';

const f = Math.fround;
const lobe = gltfExtensionLobe('glTF + transmission, volume, iridescence, energy compensation', [
  'FEATURE_TRANSMISSION', 'FEATURE_VOLUME', 'FEATURE_IRIDESCENCE', 'FEATURE_ENERGY_COMPENSATION',
]);
const refractive = { factor: 1, refractive: true };
const thin = { factor: 1, refractive: false };
const film = { factor: 1, thickness: 420, ior: 1.35 };

const cases: { name: string; m: GltfBsdfMaterial }[] = [
  { name: 'rough clear (roughness 0.5)', m: { baseColor: [1, 1, 1], metallic: 0, roughness: 0.5, ior: 1, transmission: refractive } },
  { name: 'very rough tinted, compensated', m: { baseColor: [f(0.9), f(0.6), f(0.3)], metallic: 0, roughness: 1, ior: 1, transmission: refractive, energyCompensation: true } },
  { name: 'rough lens with a thin film', m: { baseColor: [1, 1, 1], metallic: 0, roughness: f(0.4), ior: 1, transmission: refractive, iridescence: film } },
  { name: 'smooth lens with a thin film', m: { baseColor: [1, 1, 1], metallic: 0, roughness: 0, ior: 1, transmission: refractive, iridescence: film } },
  { name: 'rough thin wall', m: { baseColor: [f(0.9), f(0.8), f(0.7)], metallic: 0, roughness: f(0.6), ior: 1, transmission: thin } },
  { name: 'rough thin wall with a thin film, compensated', m: { baseColor: [1, 1, 1], metallic: 0, roughness: f(0.5), ior: 1, transmission: thin, iridescence: film, energyCompensation: true } },
  {
    name: 'rough half-transmissive film, compensated',
    m: { baseColor: [f(0.8), f(0.8), f(0.5)], metallic: 0, roughness: f(0.6), ior: 1, transmission: { factor: f(0.5), refractive: true }, iridescence: film, energyCompensation: true },
  },
];

const SAMPLES = 1 << 17;

test('index-matched interface: straight delta transmission at any roughness, reflection consistent, E[weight] = albedo + transmittance <= 1', async (t) => {
  for (const [k, c] of cases.entries()) {
    for (const view of [0, 45, 75]) {
      const wo = viewAt(view).map(f) as unknown as Vec3;
      const where = `${c.name} at ${view} deg`;
      const data = await sampleOnGpu(c.m, wo, SAMPLES, 1300 + 10 * k + view, lobe);
      const delta = [0, 0, 0];
      const rest = [0, 0, 0];
      const w2 = [0, 0, 0];
      let valid = 0;
      for (let i = 0; i < SAMPLES; i++) {
        const s = sampleAt(data, i);
        if (!s.valid) continue;
        valid++;
        for (let ch = 0; ch < 3; ch++) w2[ch] += s.weight[ch] * s.weight[ch];
        if (s.isDelta && s.wi[2] > 0) {
          // The smooth film's mirror reflection.
          assert.ok(c.m.roughness === 0 && s.wi[0] === -wo[0] && s.wi[1] === -wo[1] && s.wi[2] === wo[2], `${where}: delta reflection ${s.wi}`);
          for (let ch = 0; ch < 3; ch++) delta[ch] += s.weight[ch];
          continue;
        }
        if (s.isDelta) {
          // Straight through, exactly: no microfacet deflects the light.
          assert.ok(s.wi[0] === -wo[0] && s.wi[1] === -wo[1] && s.wi[2] === -wo[2], `${where}: delta wi ${s.wi}`);
          for (let ch = 0; ch < 3; ch++) delta[ch] += s.weight[ch];
          continue;
        }
        // Rough reflection (the film): the sample is eval_pdf's, and the reference's.
        assert.ok(s.wi[2] > 0, `${where}: a non-delta sample transmits (${s.wi})`);
        assert.ok(Math.abs(s.pdf - s.pdfAtWi) <= 1e-5 * s.pdf, `${where}: sample pdf ${s.pdf} vs eval_pdf ${s.pdfAtWi}`);
        const refPdf = gltfBsdfPdf(c.m, wo, s.wi);
        assert.ok(Math.abs(s.pdf - refPdf) <= 2e-3 * refPdf + 1e-6, `${where}: pdf ${s.pdf} vs reference ${refPdf}`);
        const refF = gltfBsdfEval(c.m, wo, s.wi);
        for (let ch = 0; ch < 3; ch++) {
          assert.ok(Math.abs(s.f[ch] - s.evalAtWi[ch]) <= 1e-5 * s.f[ch] + 1e-9, `${where}: f ${s.f} vs eval_pdf ${s.evalAtWi}`);
          assert.ok(Math.abs(s.f[ch] - refF[ch]) <= 2e-3 * refF[ch] + 1e-6, `${where}: f ${s.f} vs reference ${refF}`);
          rest[ch] += s.weight[ch];
        }
      }
      // Only rough reflections that leave below the horizon are discarded (a few % at grazing views).
      assert.ok(valid >= SAMPLES * 0.9, `${where}: ${SAMPLES - valid} invalid samples`);
      const cells = await integrateCellsOnGpu(c.m, wo, 64, 128, 6, lobe, true);
      // Reflected directions follow the pdf (the transmission has none: it is a delta).
      const coarse = await integrateCellsOnGpu(c.m, wo, 32, 32, 6, lobe, true);
      const chi = chiSquareTest(histogram(data, SAMPLES, 32, 32, true), Float64Array.from(coarse.pdf, (x) => x * SAMPLES));
      t.diagnostic(`${where}: chi2 ${chi.chi2.toFixed(1)} dof ${chi.dof} p ${chi.pValue.toFixed(3)}`);
      assert.equal(chi.outsideSupport, false, `${where}: samples where the pdf is 0`);
      assert.ok(chi.pValue > 1e-3, `${where}: chi2 ${chi.chi2} dof ${chi.dof} p ${chi.pValue}`);
      const transmittance = gltfStraightTransmittance(c.m, wo);
      // A smooth surface's reflection is a delta too: the film's Fresnel term at wo.
      const mirror = c.m.roughness === 0 ? gltfDielectricFresnel(c.m, wo[2]) : [0, 0, 0];
      for (let ch = 0; ch < 3; ch++) {
        // eval_pdf has no transmission at all (a delta), only the film's reflection.
        let below = 0;
        for (let cell = 0; cell < cells.fCos.length / 3; cell++) if (Math.floor(cell / 128) >= 32) below += cells.fCos[cell * 3 + ch]!;
        assert.equal(below, 0, `${where}: eval_pdf transmits ${below} off the delta`);
        const albedo = sum(cells.fCos, 3, ch);
        const mean = (delta[ch]! + rest[ch]!) / SAMPLES;
        const se = Math.sqrt(Math.max(w2[ch]! / SAMPLES - mean * mean, 0) / SAMPLES);
        const expected = albedo + mirror[ch]! + transmittance[ch]!;
        t.diagnostic(`${where} channel ${ch}: E[weight] ${mean.toFixed(5)} +- ${se.toExponential(1)}, reflection ${albedo.toFixed(5)} + transmission ${transmittance[ch]!.toFixed(5)}`);
        assert.ok(Math.abs(mean - expected) <= 5 * se + 3e-3 * expected + 1e-6, `${where} channel ${ch}: E[weight] ${mean} +- ${se} vs ${expected}`);
        // Energy: nothing is created.
        assert.ok(expected <= 1 + 2e-3 && mean - 5 * se <= 1, `${where} channel ${ch}: ${expected} > 1`);
        if (!c.m.iridescence) {
          // Without a film, ior 1 reflects nothing and transmits baseColor (times transmission) whole.
          assert.ok(albedo < 1e-6, `${where}: reflects ${albedo}`);
          assert.ok(Math.abs(mean - c.m.baseColor[ch]!) <= 1e-5, `${where} channel ${ch}: E[weight] ${mean} vs ${c.m.baseColor[ch]}`);
        }
      }
      // The film reflects a visible part: the reflection must be reachable by sampling.
      if (c.m.iridescence && c.m.roughness > 0) assert.ok(rest[1]! > 0, `${where}: no reflection sampled`);
    }
  }
});

// ---- Rendered: the background through an ior-1 slab --------------------------------------------

const size = 16;
const camera = { type: 'orthographic' as const, position: [0, 0, 4], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 1 };
/** A black emitter behind the slab covering x < 0.13 only: an edge across the view, which any blur would smear. */
const halfEmitter: WavefrontMeshInput = {
  positions: [-4, -4, -2, 0.13, -4, -2, 0.13, 4, -2, -4, 4, -2],
  indices: [0, 1, 2, 0, 2, 3],
  material: { baseColorFactor: [0, 0, 0], metallicFactor: 0, roughnessFactor: 1, ior: 1, emissiveFactor: [0.5, 0.75, 1], emissiveStrength: 4 },
};

async function render(slab: WavefrontMaterialInput | undefined): Promise<{ data: Float32Array; invalid: number }> {
  const device = await testDevice();
  const meshes: WavefrontMeshInput[] = slab ? [{ ...box(-0.25, 0.25), material: slab }, halfEmitter] : [halfEmitter];
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: size, height: size, maxDepth: 8, samplesPerPixel: 4, seed: 5, camera, meshes });
  try {
    const stats = await renderer.renderFrame();
    return { data: (await renderer.readRadiance()).data, invalid: stats.invalidSamples };
  } finally {
    renderer.destroy();
  }
}

test('an ior-1 glass slab (solid or thin-walled) of any roughness shows the background unchanged, pixel by pixel', async (t) => {
  const background = await render(undefined);
  // The edge is in view: some pixels see the emitter, some do not.
  let lit = 0;
  for (let p = 0; p < size * size; p++) if (background.data[4 * p]! > 0) lit++;
  assert.ok(lit > 0.3 * size * size && lit < 0.9 * size * size, `${lit} lit pixels`);
  for (const [roughness, thicknessFactor] of [[0, 0.5], [0.5, 0.5], [1, 0.5], [0.7, 0]] as const) {
    const slab: WavefrontMaterialInput = { baseColorFactor: [1, 1, 1], metallicFactor: 0, roughnessFactor: roughness, transmissionFactor: 1, ior: 1, thicknessFactor };
    const through = await render(slab);
    assert.equal(through.invalid, 0, `roughness ${roughness}: invalid samples`);
    let worst = 0;
    for (let i = 0; i < size * size * 4; i += 4) {
      for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(through.data[i + c]! - background.data[i + c]!));
    }
    const kind = thicknessFactor > 0 ? 'solid' : 'thin-walled';
    t.diagnostic(`${kind}, roughness ${roughness}: largest pixel difference ${worst}`);
    // Every sample's weight is exactly 1 along the same straight ray: equal up to f32 rounding.
    assert.ok(worst <= 1e-4, `${kind}, roughness ${roughness}: the slab changes a pixel by ${worst}`);
  }
});
