// Generic properties every BSDF lobe must have, run on the GPU for each lobe of lobes.ts through
// the lobe interface (unpack_params / eval_pdf / sample / flags): eval and pdf against an independent
// CPU reference, reciprocity (Helmholtz for reflection, the generalised form of radiance transport
// for transmission), sample consistency (a sample's f and pdf are eval_pdf's at its direction), the
// chi-square of sampled directions against the integrated pdf (Mitsuba 3's test, over the sphere
// for lobes that transmit), and a weak white furnace: E[sample weight] equals the quadrature of
// f |cos| and, for lobes that conserve energy, stays <= 1.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import type { Vec3 } from '../../src/materials/gltf-bsdf-reference.ts';
import { chiSquareTest, histogram, integrateCellsOnGpu, packDirections, packParams, randomUpperDirection, rng, runKernel, sampleAt, sampleOnGpu, sum, viewAt } from './bsdf-harness.ts';
import { lobeCases } from './lobes.ts';

const SAMPLES = 1 << 17;
const N_PHI = 32;

const negate = (v: Vec3): Vec3 => [-v[0], -v[1], -v[2]];

for (const c of lobeCases) {
  const sphere = c.transmission !== undefined;
  const nTheta = sphere ? 32 : 16;

  test(`${c.lobe.name}: eval_pdf matches the CPU reference and is reciprocal`, async () => {
    const random = rng(17);
    const pairs = Array.from({ length: 512 }, (_, k) => {
      const wo = randomUpperDirection(random, 1e-2);
      const wi = randomUpperDirection(random, 1e-2);
      // Transmission lobes: every other pair crosses the surface.
      return [wo, sphere && k % 2 === 1 ? ([wi[0], wi[1], -wi[2]] as Vec3) : wi] as const;
    });
    for (const p of c.params) {
      const swapped = c.transmission?.swap?.(p.value) ?? p.value;
      const gpu = await runKernel({
        module: c.lobe.module,
        ...(c.lobe.constants ? { constants: c.lobe.constants } : {}),
        inputs: [
          { data: packParams(c.lobe, [p.value, swapped]), type: 'TestMaterial' },
          { data: packDirections(pairs.flatMap(([a, b]) => [a, b])), type: 'vec4f' },
        ],
        outputFloats: pairs.length * 8,
        count: pairs.length,
        body: `
  let m = t_material(in0[0]);
  let wo = in1[2u * i].xyz;
  let wi = in1[2u * i + 1u].xyz;
  let e = lobe::eval_pdf(m, wo, wi);
  // Reciprocity: the reversed pair (reflection), or the pair seen from the other side (transmission).
  var r: vec3f;
  if (wi.z > 0.0) { r = lobe::eval_pdf(m, wi, wo).f; } else { r = lobe::eval_pdf(t_material(in0[1]), -wi, -wo).f; }
  out[i * 8u] = e.f.x; out[i * 8u + 1u] = e.f.y; out[i * 8u + 2u] = e.f.z; out[i * 8u + 3u] = e.pdf;
  out[i * 8u + 4u] = r.x; out[i * 8u + 5u] = r.y; out[i * 8u + 6u] = r.z;`,
      });
      pairs.forEach(([wo, wi], k) => {
        const f = c.reference.f(p.value, wo, wi);
        const pdf = c.reference.pdf(p.value, wo, wi);
        const transmits = wi[2] < 0;
        const factor = transmits ? (c.transmission?.factor?.(p.value) ?? 1) : 1;
        const checkReciprocity = transmits ? c.reciprocal && c.transmission !== undefined : c.reciprocal;
        const tol = c.tolerance ?? 2e-4;
        for (let ch = 0; ch < 3; ch++) {
          assert.ok(Math.abs(gpu[k * 8 + ch]! - f[ch]!) <= tol * f[ch]! + 1e-6, `${p.name} pair ${k}: f ${gpu[k * 8 + ch]} vs ${f[ch]}`);
          if (checkReciprocity) {
            const expected = factor * gpu[k * 8 + ch]!;
            assert.ok(Math.abs(gpu[k * 8 + 4 + ch]! - expected) <= 3e-4 * expected + 1e-6, `${p.name} pair ${k}: f not reciprocal (${gpu[k * 8 + 4 + ch]} vs ${expected})`);
          }
        }
        assert.ok(Math.abs(gpu[k * 8 + 3]! - pdf) <= tol * pdf + 1e-6, `${p.name} pair ${k}: pdf ${gpu[k * 8 + 3]} vs ${pdf}`);
      });
      // The CPU reference itself obeys the same reciprocity (independent of the GPU).
      if (c.reciprocal && c.transmission?.factor) {
        for (const [wo, wi] of pairs.filter(([, wi]) => wi[2] < 0).slice(0, 32)) {
          const f = c.reference.f(p.value, wo, wi)[0]!;
          const r = c.reference.f(swapped, negate(wi), negate(wo))[0]!;
          assert.ok(Math.abs(r - c.transmission.factor(p.value) * f) <= 1e-9 * Math.max(1, r), `${p.name}: reference not reciprocal`);
        }
      }
    }
  });

  test(`${c.lobe.name}: samples carry eval_pdf's f and pdf, follow the pdf (chi-square), and E[weight] = albedo`, async (t) => {
    for (const [k, p] of c.params.entries()) {
      for (const view of [10, 70]) {
        const wo: Vec3 = viewAt(view);
        const data = await sampleOnGpu(p.value, wo, SAMPLES, 900 + 10 * k + view, c.lobe);
        const cells = await integrateCellsOnGpu(p.value, wo, nTheta, N_PHI, 6, c.lobe, sphere);
        let weight = 0;
        let weight2 = 0;
        for (let i = 0; i < SAMPLES; i++) {
          const s = sampleAt(data, i);
          if (!s.valid) continue;
          weight += s.weight[1];
          weight2 += s.weight[1] * s.weight[1];
          if (s.isDelta) continue;
          assert.ok(Math.abs(s.pdf - s.pdfAtWi) <= 1e-5 * s.pdf, `${p.name}: sample pdf ${s.pdf} vs eval_pdf ${s.pdfAtWi}`);
          assert.ok(Math.abs(s.f[1] - s.evalAtWi[1]) <= 1e-5 * s.f[1] + 1e-9, `${p.name}: sample f ${s.f[1]} vs eval_pdf ${s.evalAtWi[1]}`);
        }
        // Chi-square of the directions against the pdf integrated over each cell.
        const observed = histogram(data, SAMPLES, nTheta, N_PHI, sphere);
        const expected = Float64Array.from(cells.pdf, (x) => x * SAMPLES);
        const chi = chiSquareTest(observed, expected);
        t.diagnostic(`${p.name} at ${view} deg: chi2 ${chi.chi2.toFixed(1)} dof ${chi.dof} p ${chi.pValue.toFixed(3)}`);
        assert.equal(chi.outsideSupport, false, `${p.name}: samples where the pdf is 0`);
        // Many lobe sets x two views: p > 0.001 each keeps the family-wise false alarm rate low.
        assert.ok(chi.pValue > 1e-3, `${p.name} at ${view} deg: chi2 ${chi.chi2} dof ${chi.dof} p ${chi.pValue}`);
        // Weak white furnace: the mean weight estimates the albedo (green channel) within 5 sigma.
        const mean = weight / SAMPLES;
        const se = Math.sqrt(Math.max(weight2 / SAMPLES - mean * mean, 0) / SAMPLES);
        // The albedo from a finer quadrature than the chi-square cells: narrow lobes need it.
        const albedo = sum((await integrateCellsOnGpu(p.value, wo, sphere ? 128 : 64, 128, 8, c.lobe, sphere)).fCos, 3, 1);
        // Delta components carry weight the quadrature of f cannot see: compare non-delta lobes only.
        if (!hasDelta(data)) assert.ok(Math.abs(mean - albedo) <= 5 * se + 3e-3 * albedo + 1e-6, `${p.name} at ${view} deg: E[weight] ${mean} +- ${se} vs albedo ${albedo}`);
        if (c.energyConserving) assert.ok(Math.max(albedo, mean - 5 * se) <= 1 + 3e-3, `${p.name} at ${view} deg: albedo ${albedo}, E[weight] ${mean} > 1`);
      }
    }
  });
}

function hasDelta(data: Float32Array): boolean {
  for (let i = 0; i < SAMPLES; i++) if (sampleAt(data, i).isDelta) return true;
  return false;
}
