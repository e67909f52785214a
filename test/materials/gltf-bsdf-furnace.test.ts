// Energy tests of the glTF BSDF: the weak white furnace test of the GGX distribution (Heitz 2014,
// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", section 5.2), the
// albedo of a rough conductor with F0 = 1, the Lambertian limit, and the delta (mirror) lobe.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fresnelDielectric, gltfBsdfEval, gltfSpecularProbability, type GltfBsdfMaterial, type Vec3 } from '../../src/materials/index.ts';
import { integrateCellsOnGpu, runKernel, sampleAt, sampleOnGpu, sum, viewAt } from './bsdf-harness.ts';

const f = Math.fround;
const ALPHAS = [0.1, 0.3, 0.6, 1.0];
const VIEWS = [0, 30, 60, 80];
const NZ = 1024;
const NPHI = 2048;

interface FurnaceRow {
  alpha: number;
  view: number;
  /** Integral over the whole sphere of wi of D(h) G1(wo) / (4 wo.z): 1 for a normalised VNDF. */
  weak: number;
  /** The same over the upper hemisphere only. */
  weakUpper: number;
  /** Upper-hemisphere integral of D G1(wo) G1(wi) / (4 wo.z) (uncorrelated Smith G2). */
  separable: number;
  /** Directional albedo of the F0 = 1 conductor: integral of bsdf_eval * cos (height-correlated G2). */
  albedo: number;
}

/**
 * Midpoint quadrature in (z, phi), where d omega = dz dphi exactly: z over [-1, 1] in NZ rows,
 * phi in NPHI columns; one invocation sums one row of one (alpha, view) combination.
 */
async function furnaceIntegrals(): Promise<FurnaceRow[]> {
  const combos = ALPHAS.flatMap((alpha) => VIEWS.map((view) => ({ alpha, view })));
  const input = new Float32Array(combos.length * 4);
  combos.forEach((c, i) => input.set([...viewAt(c.view), f(Math.sqrt(c.alpha))], i * 4));
  const raw = await runKernel({
    imports: 'import package::materials::microfacet::{ggx_d, smith_g1};',
    inputs: [{ data: input, type: 'vec4f' }],
    outputFloats: combos.length * NZ * 4,
    count: combos.length * NZ,
    body: `
  let combo = in0[i / ${NZ}u];
  let wo = combo.xyz;
  let roughness = combo.w;
  let alpha = roughness * roughness;
  let m = lobe::params(vec3f(1.0), 1.0, roughness, 1.5);
  let dz = 2.0 / f32(${NZ});
  let dphi = TWO_PI / f32(${NPHI});
  let z = -1.0 + (f32(i % ${NZ}u) + 0.5) * dz;
  let r = sqrt(max(0.0, 1.0 - z * z));
  let g1o = smith_g1(wo, alpha);
  var weak = 0.0;
  var separable = 0.0;
  var albedo = 0.0;
  for (var p = 0u; p < ${NPHI}u; p++) {
    let phi = (f32(p) + 0.5) * dphi;
    let wi = vec3f(r * cos(phi), r * sin(phi), z);
    let h = normalize(wo + wi);
    let d = ggx_d(h, alpha);
    weak += d * g1o / (4.0 * wo.z);
    separable += d * g1o * smith_g1(wi, alpha) / (4.0 * wo.z);
    albedo += bsdf_eval(m, wo, wi).x * max(wi.z, 0.0);
  }
  let o = i * 4u;
  out[o] = weak * dz * dphi;
  out[o + 1u] = select(0.0, weak * dz * dphi, z > 0.0);
  out[o + 2u] = separable * dz * dphi;
  out[o + 3u] = albedo * dz * dphi;`,
  });
  return combos.map((c, k) => {
    const row = raw.subarray(k * NZ * 4, (k + 1) * NZ * 4);
    return { ...c, weak: sum(row, 4, 0), weakUpper: sum(row, 4, 1), separable: sum(row, 4, 2), albedo: sum(row, 4, 3) };
  });
}

function referenceAlbedo(m: GltfBsdfMaterial, wo: Vec3): number {
  const nt = 512;
  const np = 512;
  let total = 0;
  for (let a = 0; a < nt; a++) {
    const theta = ((a + 0.5) / nt) * (Math.PI / 2);
    const st = Math.sin(theta);
    const ct = Math.cos(theta);
    for (let b = 0; b < np; b++) {
      const phi = ((b + 0.5) / np) * 2 * Math.PI;
      total += gltfBsdfEval(m, wo, [st * Math.cos(phi), st * Math.sin(phi), ct])[0] * ct * st;
    }
  }
  return total * (Math.PI / 2 / nt) * ((2 * Math.PI) / np);
}

let rowsPromise: Promise<FurnaceRow[]> | undefined;
function rows(): Promise<FurnaceRow[]> {
  rowsPromise ??= furnaceIntegrals();
  return rowsPromise;
}

test('weak white furnace: the integral of D(h) G1(wo) / (4 |wo.z|) over the sphere is 1 within 1%', async (t) => {
  for (const r of await rows()) {
    t.diagnostic(`alpha ${r.alpha} view ${r.view}: weak ${r.weak.toFixed(5)} upper ${r.weakUpper.toFixed(5)} G1G1 ${r.separable.toFixed(5)} albedo ${r.albedo.toFixed(5)}`);
    assert.ok(Math.abs(r.weak - 1) < 0.01, `alpha ${r.alpha}, view ${r.view}: ${r.weak}`);
  }
});

test('rough conductor with F0 = 1: albedo <= 1, bounded by the uncorrelated and G1-only energies', async () => {
  const all = await rows();
  for (const r of all) {
    const where = `alpha ${r.alpha}, view ${r.view}`;
    // Only multiple scattering (not modelled) is lost: G1(wo) G1(wi) <= G2 <= G1(wo) (Heitz 2014
    // section 6: height correlation only removes double-counted shadowing), so
    // separable <= albedo <= weakUpper <= weak = 1. Quadrature tolerance 1e-3.
    assert.ok(r.albedo <= 1 + 1e-3, `${where}: albedo ${r.albedo} > 1`);
    assert.ok(r.albedo <= r.weakUpper + 1e-3, `${where}: albedo ${r.albedo} > G1-only energy ${r.weakUpper}`);
    assert.ok(r.albedo >= r.separable - 1e-3, `${where}: albedo ${r.albedo} < uncorrelated-Smith energy ${r.separable}`);
    // Independent double-precision albedo of the Appendix B reference (midpoint rule in theta, phi).
    const m: GltfBsdfMaterial = { baseColor: [1, 1, 1], metallic: 1, roughness: f(Math.sqrt(r.alpha)), ior: 1.5 };
    const ref = referenceAlbedo(m, viewAt(r.view));
    assert.ok(Math.abs(r.albedo - ref) <= 2e-3, `${where}: albedo ${r.albedo} vs reference ${ref}`);
  }
  // Closed forms: a smooth-ish conductor loses little at normal incidence, and at alpha = 1
  // (D = 1 / pi, uniform microfacet normals) exactly half of the reflected VNDF samples at normal
  // incidence leave below the horizon (wi.z = 2 cos^2(theta_h) - 1 > 0 iff theta_h < 45 degrees).
  const at = (alpha: number, view: number) => all.find((r) => r.alpha === alpha && r.view === view) as FurnaceRow;
  assert.ok(at(0.1, 0).albedo > 0.98, `alpha 0.1: albedo ${at(0.1, 0).albedo}`);
  assert.ok(Math.abs(at(1, 0).weakUpper - 0.5) < 1e-3, `alpha 1: upper-hemisphere VNDF mass ${at(1, 0).weakUpper}`);
  // The loss grows with roughness at every view.
  for (const view of VIEWS) {
    const byAlpha = all.filter((r) => r.view === view).map((r) => r.albedo);
    for (let k = 1; k < byAlpha.length; k++) assert.ok(byAlpha[k] < byAlpha[k - 1] + 1e-4, `view ${view}: albedo not decreasing in alpha ${byAlpha}`);
  }
});

test('rough conductor with F0 = 1: E[bsdf_sample weight] equals the quadrature albedo', async () => {
  const all = await rows();
  for (const [k, r] of all.entries()) {
    const m: GltfBsdfMaterial = { baseColor: [1, 1, 1], metallic: 1, roughness: f(Math.sqrt(r.alpha)), ior: 1.5 };
    const n = 50_000;
    const data = await sampleOnGpu(m, viewAt(r.view), n, 400 + k);
    let s1 = 0;
    let s2 = 0;
    for (let i = 0; i < n; i++) {
      const s = sampleAt(data, i);
      if (!s.valid) continue;
      // weight = G2 / G1 <= 1 for F0 = 1 (VNDF sampling cancels D and G1).
      assert.ok(s.weight[0] <= 1 + 1e-5 && s.weight[0] >= 0, `sample ${i}: weight ${s.weight[0]}`);
      s1 += s.weight[0];
      s2 += s.weight[0] * s.weight[0];
    }
    const mean = s1 / n;
    const se = Math.sqrt(Math.max(s2 / n - mean * mean, 0) / n);
    assert.ok(Math.abs(mean - r.albedo) <= 5 * se + 1e-3, `alpha ${r.alpha}, view ${r.view}: E[weight] ${mean} +- ${se} vs ${r.albedo}`);
  }
});

test('Lambertian (ior 1, metallic 0): albedo equals baseColor, every sample weighs baseColor', async () => {
  const a: Vec3 = [f(0.2), f(0.5), f(0.9)];
  const m: GltfBsdfMaterial = { baseColor: a, metallic: 0, roughness: f(0.4), ior: 1 };
  for (const view of [0, 45, 85]) {
    const cells = await integrateCellsOnGpu(m, viewAt(view), 20, 40, 8);
    for (let ch = 0; ch < 3; ch++) assert.ok(Math.abs(sum(cells.fCos, 3, ch) - a[ch]) < 1e-3, `view ${view}: albedo ${sum(cells.fCos, 3, ch)} vs ${a[ch]}`);
    const n = 20_000;
    const data = await sampleOnGpu(m, viewAt(view), n, 500 + view);
    let valid = 0;
    for (let i = 0; i < n; i++) {
      const s = sampleAt(data, i);
      if (!s.valid) continue;
      valid++;
      for (let ch = 0; ch < 3; ch++) assert.ok(Math.abs(s.weight[ch] - a[ch]) <= 1e-5, `view ${view} sample ${i}: weight ${s.weight}`);
    }
    // Cosine sampling yields wi.z = 0 only on a measure-zero set.
    assert.ok(valid >= n - 2, `view ${view}: ${n - valid} invalid samples`);
  }
});

function schlick(f0: number, c: number): number {
  return f0 + (1 - f0) * Math.pow(1 - c, 5);
}

test('roughness 0 mirror: the delta lobe reflects exactly, with weight = Fresnel / lobe probability', async () => {
  const materials: GltfBsdfMaterial[] = [
    { baseColor: [f(0.9), f(0.5), f(0.2)], metallic: 1, roughness: 0, ior: 1.5 },
    { baseColor: [0.5, 0.5, 0.5], metallic: 0, roughness: 0, ior: 1.5 },
    // roughness 0.02: alpha 4e-4 < 1e-3 is still treated as smooth.
    { baseColor: [f(0.3), f(0.6), f(0.1)], metallic: f(0.5), roughness: f(0.02), ior: f(1.8) },
  ];
  for (const [k, m] of materials.entries()) {
    for (const view of [0, 40, 80]) {
      const wo = viewAt(view).map(f) as unknown as Vec3;
      const cos = wo[2];
      const pSpec = gltfSpecularProbability(m, cos);
      const fd = fresnelDielectric(cos, m.ior);
      const reflectance = m.baseColor.map((b) => (1 - m.metallic) * fd + m.metallic * schlick(b, cos));
      const n = 100_000;
      const data = await sampleOnGpu(m, wo, n, 600 + k * 10 + view);
      let deltas = 0;
      const w = [0, 0, 0];
      const w2 = [0, 0, 0];
      for (let i = 0; i < n; i++) {
        const s = sampleAt(data, i);
        const where = `material ${k}, view ${view}, sample ${i}`;
        if (!s.valid) continue;
        for (let ch = 0; ch < 3; ch++) {
          w[ch] += s.weight[ch];
          w2[ch] += s.weight[ch] * s.weight[ch];
        }
        if (!s.isDelta) {
          // Diffuse sample: f excludes the delta lobe.
          const ref = gltfBsdfEval(m, wo, s.wi);
          for (let ch = 0; ch < 3; ch++) assert.ok(Math.abs(s.f[ch] - ref[ch]) <= 1e-4 * ref[ch] + 1e-7, `${where}: f ${s.f} vs ${ref}`);
          continue;
        }
        deltas++;
        assert.ok(Math.abs(s.wi[0] + wo[0]) < 1e-7 && Math.abs(s.wi[1] + wo[1]) < 1e-7 && s.wi[2] === wo[2], `${where}: wi ${s.wi}`);
        // pbrt-v4's convention: a delta sample's pdf is the probability of choosing its lobe.
        assert.ok(Math.abs(s.pdf - pSpec) <= 1e-6, `${where}: delta pdf ${s.pdf} vs lobe probability ${pSpec}`);
        for (let ch = 0; ch < 3; ch++) {
          const expected = reflectance[ch] / pSpec;
          assert.ok(Math.abs(s.weight[ch] - expected) <= 1e-5 * expected, `${where}: weight ${s.weight} vs ${expected}`);
          assert.ok(Math.abs(s.f[ch] * cos - reflectance[ch]) <= 1e-5 * reflectance[ch], `${where}: f cos ${s.f[ch] * cos} vs ${reflectance[ch]}`);
        }
      }
      // Lobe selection frequency: binomial, 5 sigma.
      const sigma = Math.sqrt((pSpec * (1 - pSpec)) / n);
      assert.ok(Math.abs(deltas / n - pSpec) <= 5 * sigma + 1e-6, `material ${k}, view ${view}: delta fraction ${deltas / n} vs ${pSpec}`);
      // E[weight] = mirror reflectance + diffuse albedo (double-precision quadrature of the reference).
      const diffuseAlbedo = [0, 0, 0];
      const nt = 256;
      const np = 256;
      for (let a = 0; a < nt; a++) {
        const theta = ((a + 0.5) / nt) * (Math.PI / 2);
        for (let b = 0; b < np; b++) {
          const phi = ((b + 0.5) / np) * 2 * Math.PI;
          const wi: Vec3 = [Math.sin(theta) * Math.cos(phi), Math.sin(theta) * Math.sin(phi), Math.cos(theta)];
          const fr = gltfBsdfEval(m, wo, wi);
          const jac = Math.cos(theta) * Math.sin(theta) * (Math.PI / 2 / nt) * ((2 * Math.PI) / np);
          for (let ch = 0; ch < 3; ch++) diffuseAlbedo[ch] += fr[ch] * jac;
        }
      }
      for (let ch = 0; ch < 3; ch++) {
        const mean = w[ch] / n;
        const se = Math.sqrt(Math.max(w2[ch] / n - mean * mean, 0) / n);
        const expected = reflectance[ch] + diffuseAlbedo[ch];
        assert.ok(Math.abs(mean - expected) <= 5 * se + 1e-4, `material ${k}, view ${view}, channel ${ch}: E[weight] ${mean} +- ${se} vs ${expected}`);
      }
    }
  }
});
