// bsdf_eval / bsdf_pdf of src/shaders/wgsl/bsdf-gltf.wgsl against the independent double-precision
// reference (glTF 2.0 Appendix B, src/materials/gltf-bsdf-reference.ts), reciprocity, the ior = 1
// Lambertian limit, and the Material record conversion.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { gltfBsdfEval, gltfBsdfPdf, fresnelDielectric, type GltfBsdfMaterial, type Vec3 } from '../../src/materials/index.ts';
import { packDirections, packMaterials, randomUpperDirection, rng, runKernel } from './bsdf-harness.ts';

const f = Math.fround;

function randomMaterial(random: () => number): GltfBsdfMaterial {
  const pick = random();
  // Exact 0 / 1 metallic and ior 1 / 1.5 cases appear often; the rest is uniform.
  const metallic = pick < 0.2 ? 0 : pick < 0.4 ? 1 : random();
  const ior = random() < 0.2 ? 1 : random() < 0.25 ? 1.5 : 1 + 1.5 * random();
  return {
    baseColor: [f(random()), f(random()), f(random())],
    metallic: f(metallic),
    roughness: f(0.08 + 0.92 * random()),
    ior: f(ior),
  };
}

function roundDir(d: Vec3): Vec3 {
  return [f(d[0]), f(d[1]), f(d[2])];
}

interface Case {
  m: GltfBsdfMaterial;
  wo: Vec3;
  wi: Vec3;
}

function randomCases(seed: number, n: number): Case[] {
  const random = rng(seed);
  return Array.from({ length: n }, () => ({
    m: randomMaterial(random),
    wo: roundDir(randomUpperDirection(random)),
    wi: roundDir(randomUpperDirection(random)),
  }));
}

/** Per case: f(wo, wi).rgb, pdf(wo, wi), f(wi, wo).rgb, pdf of the swapped pair (8 floats). */
async function evalOnGpu(cases: Case[]): Promise<Float32Array> {
  return runKernel({
    inputs: [
      { data: packMaterials(cases.map((c) => c.m)), type: 'TestMaterial' },
      { data: packDirections(cases.map((c) => c.wo)), type: 'vec4f' },
      { data: packDirections(cases.map((c) => c.wi)), type: 'vec4f' },
    ],
    outputFloats: cases.length * 8,
    count: cases.length,
    body: `
  let m = t_material(in0[i]);
  let wo = in1[i].xyz;
  let wi = in2[i].xyz;
  let fw = bsdf_eval(m, wo, wi);
  let fr = bsdf_eval(m, wi, wo);
  out[i * 8u + 0u] = fw.x; out[i * 8u + 1u] = fw.y; out[i * 8u + 2u] = fw.z;
  out[i * 8u + 3u] = bsdf_pdf(m, wo, wi);
  out[i * 8u + 4u] = fr.x; out[i * 8u + 5u] = fr.y; out[i * 8u + 6u] = fr.z;
  out[i * 8u + 7u] = bsdf_pdf(m, wi, wo);`,
  });
}

test('bsdf_eval and bsdf_pdf match the double-precision glTF Appendix B reference', async () => {
  const cases = randomCases(1, 4096);
  const gpu = await evalOnGpu(cases);
  // f32 evaluation of D near a sharp peak (roughness >= 0.08) stays well inside 2e-3 relative.
  const rel = 2e-3;
  const abs = 1e-6;
  let worst = 0;
  cases.forEach((c, i) => {
    const ref = gltfBsdfEval(c.m, c.wo, c.wi);
    for (let k = 0; k < 3; k++) {
      const err = Math.abs(gpu[i * 8 + k] - ref[k]);
      worst = Math.max(worst, err / (Math.abs(ref[k]) + abs / rel));
      assert.ok(err <= rel * Math.abs(ref[k]) + abs, `case ${i} channel ${k}: gpu ${gpu[i * 8 + k]} ref ${ref[k]} (${JSON.stringify(c)})`);
    }
    const pdfRef = gltfBsdfPdf(c.m, c.wo, c.wi);
    assert.ok(Math.abs(gpu[i * 8 + 3] - pdfRef) <= rel * pdfRef + abs, `case ${i} pdf: gpu ${gpu[i * 8 + 3]} ref ${pdfRef}`);
  });
  assert.ok(worst < rel);
});

test('bsdf_eval is reciprocal: f(wo, wi) = f(wi, wo)', async () => {
  const cases = randomCases(2, 4096);
  const gpu = await evalOnGpu(cases);
  cases.forEach((c, i) => {
    for (let k = 0; k < 3; k++) {
      const a = gpu[i * 8 + k];
      const b = gpu[i * 8 + 4 + k];
      assert.ok(Number.isFinite(a) && a >= 0, `case ${i}: f = ${a}`);
      // Both orders evaluate the same symmetric formulas; only f32 rounding differs.
      assert.ok(Math.abs(a - b) <= 1e-4 * Math.max(a, b) + 1e-7, `case ${i} channel ${k}: ${a} vs ${b}`);
    }
  });
});

test('directions below the surface get f = 0 and pdf = 0 (reflection only)', async () => {
  const random = rng(3);
  const cases: Case[] = [];
  for (let n = 0; n < 256; n++) {
    const up = randomUpperDirection(random);
    const down: Vec3 = [up[0], up[1], -up[2]];
    const other = randomUpperDirection(random);
    cases.push(n % 2 === 0 ? { m: randomMaterial(random), wo: down, wi: other } : { m: randomMaterial(random), wo: other, wi: down });
  }
  const gpu = await evalOnGpu(cases);
  cases.forEach((_, i) => {
    for (let k = 0; k < 4; k++) assert.equal(gpu[i * 8 + k], 0, `case ${i} value ${k}`);
  });
});

test('ior = 1 with metallic = 0 is exactly Lambertian: f = baseColor / pi everywhere', async () => {
  const random = rng(4);
  const cases: Case[] = Array.from({ length: 2048 }, () => ({
    m: { baseColor: [f(random()), f(random()), f(random())], metallic: 0, roughness: f(random()), ior: 1 },
    wo: roundDir(randomUpperDirection(random, 1e-3)),
    wi: roundDir(randomUpperDirection(random, 1e-3)),
  }));
  assert.equal(fresnelDielectric(0.3, 1), 0);
  const gpu = await evalOnGpu(cases);
  cases.forEach((c, i) => {
    for (let k = 0; k < 3; k++) {
      const expected = c.m.baseColor[k] / Math.PI;
      // One f32 multiply: <= 1 ulp from the double value.
      assert.ok(Math.abs(gpu[i * 8 + k] - expected) <= 2.4e-7 * expected + 1e-12, `case ${i}: ${gpu[i * 8 + k]} vs ${expected}`);
    }
    // Sampling is pure cosine: no specular lobe is ever chosen.
    assert.ok(Math.abs(gpu[i * 8 + 3] - c.wi[2] / Math.PI) <= 1e-6, `case ${i}: pdf ${gpu[i * 8 + 3]}`);
  });
});

test('fresnel_dielectric and fresnel_schlick match pbrt-v4 FrDielectric and Appendix B Schlick', async () => {
  const cosines = Array.from({ length: 201 }, (_, i) => f(-1 + i / 100));
  const etas = [1, 1.2, 1.5, 2.4, 1 / 1.5];
  const gpu = await runKernel({
    imports: 'import package::materials::fresnel::{fresnel_dielectric, fresnel_schlick};',
    inputs: [{ data: new Float32Array(cosines.flatMap((c) => etas.map((e) => [c, f(e), 0, 0])).flat()), type: 'vec4f' }],
    outputFloats: cosines.length * etas.length * 2,
    count: cosines.length * etas.length,
    body: `
  let c = in0[i];
  out[i * 2u] = fresnel_dielectric(c.x, c.y);
  out[i * 2u + 1u] = fresnel_schlick(vec3f(0.04, 0.5, 1.0), abs(c.x)).y;`,
  });
  let n = 0;
  for (const c of cosines) {
    for (const e of etas) {
      const ref = fresnelDielectric(c, f(e));
      assert.ok(Math.abs(gpu[n * 2] - ref) <= 2e-6 + 1e-4 * ref, `F(${c}, ${e}) gpu ${gpu[n * 2]} ref ${ref}`);
      const schlick = 0.5 + 0.5 * Math.pow(1 - Math.abs(c), 5);
      assert.ok(Math.abs(gpu[n * 2 + 1] - schlick) <= 1e-6, `Schlick(${c})`);
      n++;
    }
  }
  // Normal incidence gives the KHR_materials_ior F0 = ((ior - 1) / (ior + 1))^2.
  assert.ok(Math.abs(fresnelDielectric(1, 1.5) - 0.04) < 1e-12);
});

test('the glTF BSDF parameters clamp to the glTF ranges (clamping can only remove energy)', async () => {
  const records = [
    { baseColor: [0.25, 0.5, 0.75], metallic: 0.5, roughness: 0.25, ior: 1.45 },
    { baseColor: [1.5, -0.5, 0.5], metallic: 2, roughness: -1, ior: 0.5 },
  ];
  const gpu = await runKernel({
    inputs: [{ data: new Float32Array(records.flatMap((r) => [...r.baseColor, r.metallic, r.roughness, r.ior, 0, 0])), type: 'vec4f' }],
    outputFloats: records.length * 8,
    count: records.length,
    body: `
  let a = in0[2u * i];
  let b = in0[2u * i + 1u];
  let s = lobe::params(a.xyz, a.w, b.x, b.y);
  let o = i * 8u;
  out[o] = s.base_color.x; out[o + 1u] = s.base_color.y; out[o + 2u] = s.base_color.z;
  out[o + 3u] = s.metallic; out[o + 4u] = s.roughness; out[o + 5u] = s.ior;`,
  });
  const expected = [
    [0.25, 0.5, 0.75, 0.5, 0.25, f(1.45)],
    [1, 0, 0.5, 1, 0, 1],
  ];
  expected.forEach((row, i) => row.forEach((v, k) => assert.equal(gpu[i * 8 + k], v, `record ${i} field ${k}`)));
});
