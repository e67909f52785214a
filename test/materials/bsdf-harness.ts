export { rng } from '../helpers/random.ts';
// The BSDF test harness: runs small WGSL kernels that call any lobe module's interface (the
// `unpack_params` / `eval_pdf` / `sample` / `flags` contract of src/materials/bsdf.wesl) on arrays
// of inputs (real WebGPU, no mocks), plus the statistics the tests need. A new lobe gets eval/pdf,
// sampling, chi-square, furnace and reciprocity tests by describing itself as a LobeUnderTest.
import { createShaderChecked, readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { Vec4Heap } from '../../src/gpu-layout/vec4-heap.ts';
import { packMaterialTables, type MaterialPlan } from '../../src/pathtracer/scene/pack-materials.ts';
import { anyMaterialExtensions } from '../../src/materials/extensions/index.ts';
import { linkTestProgram } from '../helpers/wgsl.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import { PACKED_LAYER_VEC4S } from '../../src/gpu-layout/constants.ts';
import type { GltfBsdfMaterial, Vec3 } from '../../src/materials/index.ts';
import { packGltfBsdfParams } from '../../src/materials/gltf-bsdf-reference.ts';

export const WORKGROUP = 64;

/** A lobe (or composed BSDF) module and how its parameters pack into its 32-float PackedLobeParams. */
export interface LobeUnderTest<P> {
  name: string;
  /** WESL module path, e.g. `package::materials::lobes::lambert`. */
  module: string;
  pack(params: P): readonly number[];
  /** Shader feature flags the kernels compile with (the rest keep their defaults). */
  constants?: Record<string, number>;
}

/** The KHR material extensions' shader feature flags (one per registry entry) and energy compensation. */
export const materialFeatureNames: readonly string[] = [...anyMaterialExtensions.map((e) => e.feature.name), 'FEATURE_ENERGY_COMPENSATION'];

/** Override constants with exactly the named material features on (smaller kernels compile faster). */
export function materialFeatureConstants(on: readonly string[]): Record<string, number> {
  return Object.fromEntries(materialFeatureNames.map((n) => [n, on.includes(n) ? 1 : 0]));
}

/** The glTF 2.0 metallic-roughness BSDF (gltf-bsdf.wesl), the composed material of the renderer. */
export const gltfLobe: LobeUnderTest<GltfBsdfMaterial> = {
  name: 'glTF metallic-roughness',
  module: 'package::materials::gltf_bsdf',
  pack: (m) => [m.baseColor[0], m.baseColor[1], m.baseColor[2], m.metallic, m.roughness, m.ior],
  constants: materialFeatureConstants([]),
};

/** The composed glTF BSDF with KHR extensions, compiled with the features `on`. */
export function gltfExtensionLobe(name: string, on: readonly string[]): LobeUnderTest<GltfBsdfMaterial> {
  return { name, module: 'package::materials::gltf_bsdf', pack: packGltfBsdfParams, constants: materialFeatureConstants(on) };
}

/**
 * WESL preamble: the lobe module under the alias `lobe`, a packed test material (TestMaterial = the
 * floats of PackedLobeParams), adapters `bsdf_eval` / `bsdf_pdf` / `bsdf_sample` over the lobe
 * interface (a sample carries its path weight f |cos| / pdf and validity), and a PCG hash RNG.
 */
export function kernelPreamble(module: string): string {
  return `import ${module} as lobe;
import package::materials::bsdf::{PackedLobeParams, BSDF_SPECULAR};
import package::shaders::lib::math::{PI, TWO_PI, max_component};
struct TestMaterial { a: vec4f, b: vec4f, c: vec4f, d: vec4f, e: vec4f, f: vec4f, g: vec4f, h: vec4f, layers: array<vec4f, ${PACKED_LAYER_VEC4S}> }
fn t_material(t: TestMaterial) -> lobe::Params {
  return lobe::unpack_params(PackedLobeParams(t.a, t.b, t.c, t.d, t.e, t.f, t.g, t.h, t.layers));
}
fn bsdf_eval(m: lobe::Params, wo: vec3f, wi: vec3f) -> vec3f { return lobe::eval_pdf(m, wo, wi).f; }
fn bsdf_pdf(m: lobe::Params, wo: vec3f, wi: vec3f) -> f32 { return lobe::eval_pdf(m, wo, wi).pdf; }
struct TestSample { wi: vec3f, f: vec3f, pdf: f32, weight: vec3f, is_delta: bool, valid: bool }
fn bsdf_sample(m: lobe::Params, wo: vec3f, u_lobe: f32, u: vec2f) -> TestSample {
  let s = lobe::sample(m, wo, u_lobe, u);
  let valid = s.flags != 0u && s.pdf > 0.0;
  let weight = select(vec3f(0.0), s.f * (abs(s.wi.z) / s.pdf), valid);
  return TestSample(s.wi, s.f, s.pdf, weight, (s.flags & BSDF_SPECULAR) != 0u, valid);
}
// PCG (O'Neill 2014) output permutation as a hash: decorrelated streams per invocation.
fn t_pcg(v: u32) -> u32 {
  let state = v * 747796405u + 2891336453u;
  let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
fn t_unit(x: u32) -> f32 { return f32(x >> 8u) * (1.0 / 16777216.0); }
`;
}

/** Floats per TestMaterial record (PackedLobeParams: 32, then the composed BSDF's layers). */
export const TEST_MATERIAL_FLOATS = 32 + 4 * PACKED_LAYER_VEC4S;

/** Packs parameters as TestMaterial records (TEST_MATERIAL_FLOATS each). */
export function packParams<P>(lobe: LobeUnderTest<P>, params: readonly P[]): Float32Array {
  const out = new Float32Array(params.length * TEST_MATERIAL_FLOATS);
  params.forEach((p, i) => out.set(lobe.pack(p), i * TEST_MATERIAL_FLOATS));
  return out;
}

let tablesBuffer: GPUBuffer | undefined;

/**
 * The `materials` heap of a test kernel whose BSDF reads the albedo tables: every table at
 * MATERIAL_TABLES_OFFSET, as a scene using every extension (and energy compensation) packs them.
 */
export function materialTablesBuffer(device: GPUDevice): GPUBuffer {
  if (tablesBuffer) return tablesBuffer;
  const heap = new Vec4Heap();
  const plan: MaterialPlan = {
    energyCompensation: true,
    mediumIds: new Map(),
    media: [],
    tables: { ggx: true, dielectric: true, dielectricTransmission: true, clearcoat: true, sheen: true, media: false, spectral: true },
    uses: Object.fromEntries([...anyMaterialExtensions.map((e) => e.key), 'energyCompensation'].map((k) => [k, true])) as MaterialPlan['uses'],
  };
  packMaterialTables(heap, plan);
  tablesBuffer = uploadBuffer(device, heap.finish());
  return tablesBuffer;
}

/** Packs glTF materials as TestMaterial records. */
export function packMaterials(materials: readonly GltfBsdfMaterial[]): Float32Array {
  return packParams(gltfLobe, materials);
}

/** Packs directions as vec4f (w = 0). */
export function packDirections(dirs: readonly Vec3[]): Float32Array {
  const out = new Float32Array(dirs.length * 4);
  dirs.forEach((d, i) => out.set([d[0], d[1], d[2], 0], i * 4));
  return out;
}

export interface KernelSpec {
  /** Storage inputs, bound read-only as `in0`, `in1`, ... with the given WGSL element types. */
  inputs: { data: Float32Array; type: string }[];
  /** Number of f32 in the output array `out`. */
  outputFloats: number;
  /** Invocations (`i` in the body); guarded against the workgroup round-up. */
  count: number;
  /** WGSL statements run per invocation with `i: u32` in scope. */
  body: string;
  /** Extra WESL imports (placed before any declaration). */
  imports?: string;
  /** Extra WGSL declarations (helper functions). */
  extra?: string;
  /** The lobe module the kernel exercises; the glTF BSDF by default. */
  module?: string;
  /** Pipeline-overridable constants (shader feature flags); unset ones keep their defaults (on). */
  constants?: Record<string, number>;
}

const pipelines = new Map<string, Promise<{ pipeline: GPUComputePipeline; bindings: { group: number; binding: number; name: string }[] }>>();

/**
 * Links and compiles a test kernel once per source and constants (the BSDF modules are large, and
 * lavapipe compiles them slowly), so kernels keep their per-call values in buffers: `kernel_meta[0]` is the
 * invocation count, `kernel_meta[1]` a seed.
 */
function kernelPipeline(device: GPUDevice, code: string, constants: Record<string, number> | undefined) {
  const key = `${JSON.stringify(constants ?? {})}\n${code}`;
  let entry = pipelines.get(key);
  if (!entry) {
    entry = (async () => {
      const program = await linkTestProgram(code);
      const module = await createShaderChecked(device, program.wgsl);
      // Only the overrides the linked kernel still declares (linking drops unused modules).
      const declared = constants ? Object.fromEntries(Object.entries(constants).filter(([k]) => program.reflection.overrides.includes(k))) : undefined;
      const pipeline = await device.createComputePipelineAsync({ layout: 'auto', compute: { module, entryPoint: 'main', ...(declared ? { constants: declared } : {}) } });
      return { pipeline, bindings: program.reflection.bindings };
    })();
    pipelines.set(key, entry);
  }
  return entry;
}

export async function runKernel(spec: KernelSpec, seed = 0): Promise<Float32Array> {
  const device = await testDevice();
  const bindings = spec.inputs.map((input, k) => `@group(3) @binding(${20 + k}) var<storage, read> in${k}: array<${input.type}>;`);
  const code = `${spec.imports ?? ''}
import package::layout::bindings::materials as t_heap;
${kernelPreamble(spec.module ?? gltfLobe.module)}
${spec.extra ?? ''}
${bindings.join('\n')}
@group(3) @binding(${20 + spec.inputs.length}) var<storage, read_write> out: array<f32>;
@group(3) @binding(${21 + spec.inputs.length}) var<storage, read> kernel_meta: array<u32>;
@compute @workgroup_size(${WORKGROUP}) fn main(@builtin(global_invocation_id) gid: vec3u) {
  let i = gid.x;
  if (i >= kernel_meta[0]) { return; }
  // Keeps the material heap in the 'auto' layout of kernels whose body never reaches it.
  if (kernel_meta[2] == 1u) { out[0] = t_heap[0].x; }
${spec.body}
}
`;
  // The plain glTF BSDF compiles without the extensions unless a test asks for them.
  const constants = spec.constants ?? (spec.module === undefined ? gltfLobe.constants : undefined);
  const { pipeline, bindings: used } = await kernelPipeline(device, code, constants);
  const buffers = spec.inputs.map((input) => uploadBuffer(device, input.data));
  const meta = uploadBuffer(device, new Uint32Array([spec.count, seed >>> 0, 0, 0]));
  const output = device.createBuffer({ size: Math.max(16, spec.outputFloats * 4), usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
  const resources: Record<string, GPUBuffer> = { out: output, kernel_meta: meta };
  buffers.forEach((b, k) => (resources[`in${k}`] = b));
  device.pushErrorScope('validation');
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipeline);
  for (const g of [...new Set(used.map((b) => b.group))].sort()) {
    const entries = used.filter((b) => b.group === g).map((b) => ({ binding: b.binding, resource: { buffer: b.name === 'materials' || b.name === 't_heap' ? materialTablesBuffer(device) : resources[b.name]! } }));
    pass.setBindGroup(g, device.createBindGroup({ layout: pipeline.getBindGroupLayout(g), entries }));
  }
  pass.dispatchWorkgroups(Math.ceil(spec.count / WORKGROUP));
  pass.end();
  device.queue.submit([encoder.finish()]);
  const error = await device.popErrorScope();
  if (error) throw new Error(error.message);
  const result = new Float32Array(await readBuffer(device, output, spec.outputFloats * 4));
  for (const b of buffers) b.destroy();
  meta.destroy();
  output.destroy();
  return result;
}

/** Uniform direction on the upper hemisphere with z >= zMin. */
export function randomUpperDirection(random: () => number, zMin = 0.02): Vec3 {
  const z = zMin + (1 - zMin) * random();
  const phi = 2 * Math.PI * random();
  const r = Math.sqrt(Math.max(0, 1 - z * z));
  return [r * Math.cos(phi), r * Math.sin(phi), z];
}

/** Direction at polar angle theta (radians) in the xz-plane. */
export function viewAt(thetaDegrees: number): Vec3 {
  const t = (thetaDegrees * Math.PI) / 180;
  return [Math.sin(t), 0, Math.cos(t)];
}

// ---- statistics --------------------------------------------------------------------------------

/** ln Gamma(x), Lanczos approximation (g = 7, n = 9), |error| < 1e-13 for x > 0. */
export function logGamma(x: number): number {
  const c = [
    0.99999999999980993, 676.5203681218851, -1259.1392167224028, 771.32342877765313, -176.61502916214059,
    12.507343278686905, -0.13857109526572012, 9.9843695780195716e-6, 1.5056327351493116e-7,
  ];
  if (x < 0.5) return Math.log(Math.PI / Math.sin(Math.PI * x)) - logGamma(1 - x);
  const xm = x - 1;
  let a = c[0];
  const t = xm + 7.5;
  for (let i = 1; i < 9; i++) a += c[i] / (xm + i);
  return 0.5 * Math.log(2 * Math.PI) + (xm + 0.5) * Math.log(t) - t + Math.log(a);
}

/**
 * Regularized upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a): series for x < a + 1,
 * Lentz continued fraction otherwise (Numerical Recipes 3rd ed., section 6.2).
 */
export function gammaQ(a: number, x: number): number {
  if (x <= 0) return 1;
  const lnPre = a * Math.log(x) - x - logGamma(a);
  if (x < a + 1) {
    let sum = 1 / a;
    let term = sum;
    for (let n = 1; n < 10000; n++) {
      term *= x / (a + n);
      sum += term;
      if (Math.abs(term) < Math.abs(sum) * 1e-16) break;
    }
    return 1 - sum * Math.exp(lnPre);
  }
  const tiny = 1e-300;
  let b = x + 1 - a;
  let c = 1 / tiny;
  let d = 1 / b;
  let h = d;
  for (let i = 1; i < 10000; i++) {
    const an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (Math.abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (Math.abs(c) < tiny) c = tiny;
    d = 1 / d;
    const del = d * c;
    h *= del;
    if (Math.abs(del - 1) < 1e-16) break;
  }
  return Math.exp(lnPre) * h;
}

/** Upper tail of the chi-square distribution with `dof` degrees of freedom. */
export function chiSquarePValue(chi2: number, dof: number): number {
  return gammaQ(dof / 2, chi2 / 2);
}

export interface ChiSquareResult {
  chi2: number;
  dof: number;
  pValue: number;
  pooledCells: number;
  /** A cell observed samples where the integrated pdf is 0 (sampling outside the support). */
  outsideSupport: boolean;
}

/**
 * Pearson chi-square test of observed against expected counts, pooling cells expecting fewer than
 * `minExpected` samples into one (as Mitsuba 3's ChiSquareTest does).
 */
export function chiSquareTest(observed: ArrayLike<number>, expected: ArrayLike<number>, minExpected = 5): ChiSquareResult {
  const order = Array.from({ length: expected.length }, (_, i) => i).sort((a, b) => expected[a] - expected[b]);
  let chi2 = 0;
  let dof = -1;
  let pooledObs = 0;
  let pooledExp = 0;
  let pooledCells = 0;
  let outsideSupport = false;
  for (const i of order) {
    if (expected[i] === 0 && observed[i] > 0) outsideSupport = true;
    if (expected[i] < minExpected) {
      pooledObs += observed[i];
      pooledExp += expected[i];
      pooledCells++;
    } else {
      const d = observed[i] - expected[i];
      chi2 += (d * d) / expected[i];
      dof++;
    }
  }
  if (pooledExp > 0) {
    const d = pooledObs - pooledExp;
    chi2 += (d * d) / pooledExp;
    dof++;
  } else if (pooledObs > 0) {
    outsideSupport = true;
  }
  return { chi2, dof, pValue: chiSquarePValue(chi2, dof), pooledCells, outsideSupport };
}

export { testDevice };

// ---- sampling and quadrature kernels ----------------------------------------------------------

/** Floats per sample written by sampleOnGpu. */
export const SAMPLE_STRIDE = 16;

export interface SampleView {
  wi: Vec3;
  pdf: number;
  f: Vec3;
  valid: boolean;
  weight: Vec3;
  isDelta: boolean;
  /** bsdf_pdf(wo, s.wi) and bsdf_eval(wo, s.wi) evaluated separately in the same kernel. */
  pdfAtWi: number;
  evalAtWi: Vec3;
}

export function sampleAt(data: Float32Array, i: number): SampleView {
  const o = i * SAMPLE_STRIDE;
  return {
    wi: [data[o], data[o + 1], data[o + 2]],
    pdf: data[o + 3],
    f: [data[o + 4], data[o + 5], data[o + 6]],
    valid: data[o + 7] !== 0,
    weight: [data[o + 8], data[o + 9], data[o + 10]],
    isDelta: data[o + 11] !== 0,
    pdfAtWi: data[o + 12],
    evalAtWi: [data[o + 13], data[o + 14], data[o + 15]],
  };
}

/** n calls of bsdf_sample(m, wo, u_lobe, u) with independent uniform (u_lobe, u) from a hash of (seed, i). */
export function sampleOnGpu<P = GltfBsdfMaterial>(m: P, wo: Vec3, n: number, seed: number, lobe: LobeUnderTest<P> = gltfLobe as unknown as LobeUnderTest<P>): Promise<Float32Array> {
  return runKernel({
    module: lobe.module,
    ...(lobe.constants ? { constants: lobe.constants } : {}),
    inputs: [
      { data: packParams(lobe, [m]), type: 'TestMaterial' },
      { data: packDirections([wo]), type: 'vec4f' },
    ],
    outputFloats: n * SAMPLE_STRIDE,
    count: n,
    body: `
  let m = t_material(in0[0]);
  let wo = in1[0].xyz;
  let h0 = t_pcg(i ^ t_pcg(kernel_meta[1]));
  let h1 = t_pcg(h0);
  let h2 = t_pcg(h1);
  let s = bsdf_sample(m, wo, t_unit(h0), vec2f(t_unit(h1), t_unit(h2)));
  let o = i * ${SAMPLE_STRIDE}u;
  out[o] = s.wi.x; out[o + 1u] = s.wi.y; out[o + 2u] = s.wi.z; out[o + 3u] = s.pdf;
  out[o + 4u] = s.f.x; out[o + 5u] = s.f.y; out[o + 6u] = s.f.z; out[o + 7u] = select(0.0, 1.0, s.valid);
  out[o + 8u] = s.weight.x; out[o + 9u] = s.weight.y; out[o + 10u] = s.weight.z; out[o + 11u] = select(0.0, 1.0, s.is_delta);
  let p = bsdf_pdf(m, wo, s.wi);
  let e = bsdf_eval(m, wo, s.wi);
  out[o + 12u] = p; out[o + 13u] = e.x; out[o + 14u] = e.y; out[o + 15u] = e.z;`,
  }, seed);
}

export interface CellIntegrals {
  nTheta: number;
  nPhi: number;
  /** Per (theta, phi) cell, theta-major: integral of bsdf_pdf over the cell's solid angle. */
  pdf: Float64Array;
  /** Per cell: integral of bsdf_eval * cos (rgb interleaved). */
  fCos: Float64Array;
}

/**
 * Integrates bsdf_pdf and bsdf_eval * |cos| over an (theta in [0, pi/2], phi in [0, 2 pi)) grid
 * (theta in [0, pi] with `sphere`, for lobes that transmit), each cell by an s x s midpoint rule in
 * (theta, phi) with the sin(theta) Jacobian.
 */
export async function integrateCellsOnGpu<P = GltfBsdfMaterial>(
  m: P,
  wo: Vec3,
  nTheta: number,
  nPhi: number,
  s: number,
  lobe: LobeUnderTest<P> = gltfLobe as unknown as LobeUnderTest<P>,
  sphere = false,
): Promise<CellIntegrals> {
  const cells = nTheta * nPhi;
  const raw = await runKernel({
    module: lobe.module,
    ...(lobe.constants ? { constants: lobe.constants } : {}),
    inputs: [
      { data: packParams(lobe, [m]), type: 'TestMaterial' },
      { data: packDirections([wo]), type: 'vec4f' },
    ],
    outputFloats: cells * 4,
    count: cells,
    body: `
  let m = t_material(in0[0]);
  let wo = in1[0].xyz;
  let it = i / ${nPhi}u;
  let ip = i % ${nPhi}u;
  let dt = (PI / ${sphere ? '1.0' : '2.0'}) / f32(${nTheta * s});
  let dp = TWO_PI / f32(${nPhi * s});
  var sum_pdf = 0.0;
  var sum_f = vec3f(0.0);
  for (var a = 0u; a < ${s}u; a++) {
    let theta = (f32(it * ${s}u + a) + 0.5) * dt;
    let st = sin(theta);
    let ct = cos(theta);
    var row_pdf = 0.0;
    var row_f = vec3f(0.0);
    for (var b = 0u; b < ${s}u; b++) {
      let phi = (f32(ip * ${s}u + b) + 0.5) * dp;
      let wi = vec3f(st * cos(phi), st * sin(phi), ct);
      row_pdf += bsdf_pdf(m, wo, wi);
      row_f += bsdf_eval(m, wo, wi) * abs(ct);
    }
    sum_pdf += row_pdf * st;
    sum_f += row_f * st;
  }
  let o = i * 4u;
  out[o] = sum_pdf * dt * dp;
  out[o + 1u] = sum_f.x * dt * dp; out[o + 2u] = sum_f.y * dt * dp; out[o + 3u] = sum_f.z * dt * dp;`,
  });
  const pdf = new Float64Array(cells);
  const fCos = new Float64Array(cells * 3);
  for (let c = 0; c < cells; c++) {
    pdf[c] = raw[c * 4];
    fCos.set([raw[c * 4 + 1], raw[c * 4 + 2], raw[c * 4 + 3]], c * 3);
  }
  return { nTheta, nPhi, pdf, fCos };
}

/** Histogram of valid, non-delta sample directions on the same (theta, phi) grid (over the sphere with `sphere`). */
export function histogram(data: Float32Array, n: number, nTheta: number, nPhi: number, sphere = false): Float64Array {
  const counts = new Float64Array(nTheta * nPhi);
  for (let i = 0; i < n; i++) {
    const o = i * SAMPLE_STRIDE;
    if (data[o + 7] === 0 || data[o + 11] !== 0) continue;
    const z = Math.min(1, Math.max(-1, data[o + 2]));
    const theta = Math.acos(z);
    let phi = Math.atan2(data[o + 1], data[o]);
    if (phi < 0) phi += 2 * Math.PI;
    const it = Math.min(nTheta - 1, Math.floor((theta / (sphere ? Math.PI : Math.PI / 2)) * nTheta));
    const ip = Math.min(nPhi - 1, Math.floor((phi / (2 * Math.PI)) * nPhi));
    counts[it * nPhi + ip]++;
  }
  return counts;
}

export function sum(values: ArrayLike<number>, stride = 1, offset = 0): number {
  let s = 0;
  for (let i = offset; i < values.length; i += stride) s += values[i];
  return s;
}
