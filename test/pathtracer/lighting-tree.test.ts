// The light hierarchy on the GPU: the pmf its traversal reports equals the pmf the MIS weights
// evaluate (leaf-to-root walk) and the CPU tree's, traversal frequencies follow that pmf
// (chi-square), and a scene of many emitters of every bounded kind renders the same image with the
// tree as with the power alias table, within noise.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { lightTreePmf } from '../../src/lighting/light-tree.ts';
import { validateAreaLight } from '../../src/lighting/area-lights.ts';
import { validatePunctualLight } from '../../src/lighting/punctual-lights.ts';
import { lightRecordLayout } from '../../src/gpu-layout/records.ts';
import { writeStruct } from '../../src/gpu-layout/struct-layout.ts';
import { LIGHT_FLAG_DOUBLE_SIDED, LIGHT_KIND_TRIANGLE, INDEX_NONE } from '../../src/gpu-layout/constants.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import type { WavefrontMeshInput } from '../../src/scene/types.ts';
import { readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { runTestProgram } from '../helpers/wgsl.ts';
import { chiSquareTest, rng, uniformSphere } from '../lighting/helpers.ts';
import { lightingFor, lightingResources } from '../lighting/gpu-fixtures.ts';

/** n random emissive triangles in [-2, 2]^3 as LightRecords (some single-, some double-sided). */
function randomTriangles(n: number, seed: number): { records: ArrayBuffer; count: number } {
  const random = rng(seed);
  const records = new ArrayBuffer(n * lightRecordLayout.size);
  const view = new DataView(records);
  for (let t = 0; t < n; t++) {
    const v0 = [4 * random() - 2, 4 * random() - 2, 4 * random() - 2];
    const e1 = [0.3 * random() - 0.15, 0.3 * random() - 0.15, 0.3 * random() - 0.15];
    const e2 = [0.3 * random() - 0.15, 0.3 * random() - 0.15, 0.3 * random() - 0.15];
    const c = [e1[1]! * e2[2]! - e1[2]! * e2[1]!, e1[2]! * e2[0]! - e1[0]! * e2[2]!, e1[0]! * e2[1]! - e1[1]! * e2[0]!];
    const area = 0.5 * Math.hypot(c[0]!, c[1]!, c[2]!);
    const k = 1 + 9 * random();
    writeStruct(lightRecordLayout, view, t, {
      v0, kind: LIGHT_KIND_TRIANGLE, e1, e2, flags: random() < 0.3 ? LIGHT_FLAG_DOUBLE_SIDED : 0,
      emission: [k, k * random(), k * random()], area, texture: INDEX_NONE,
    });
  }
  return { records, count: n };
}

const mixedLights = {
  area: [
    validateAreaLight({ type: 'rectangle', center: [0, 1.5, 0], edgeU: [0.5, 0, 0], edgeV: [0, 0, -0.4], intensity: 3 }),
    validateAreaLight({ type: 'disk', center: [1, 0, 1], normal: [-1, 0, -1], radius: 0.3, intensity: 2, twoSided: true }),
    validateAreaLight({ type: 'sphere', center: [-1, -1, 0.5], radius: 0.2, intensity: 4 }),
  ],
  punctual: [
    validatePunctualLight({ type: 'point', position: [0.5, -0.5, -1], intensity: 2 }),
    validatePunctualLight({ type: 'spot', position: [-1.5, 1, -1], direction: [1, -1, 0.5], intensity: 6, innerConeAngle: 0.2, outerConeAngle: 0.7 }),
  ],
};

const treeKernel = `
import package::lighting::light_tree::{sample_light_tree, tree_pmf};
import package::lighting::light_sampling::bounded_light_pmf;
import package::layout::heaps::load_light_selection_entry;
import package::layout::bindings::lighting;

@group(3) @binding(20) var<storage, read> points: array<vec4f>;
@group(3) @binding(21) var<storage, read_write> out: array<vec4f>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3u) {
  let i = gid.x;
  let p = points[2u * i].xyz;
  let n = points[2u * i + 1u].xyz;
  let u = points[2u * i + 1u].w;
  let s = sample_light_tree(p, n, u);
  let leaf = load_light_selection_entry(lighting.selectionOffset + s.light).treeLeaf;
  out[i] = vec4f(bitcast<f32>(s.light), s.pmf, tree_pmf(leaf, p, n), bounded_light_pmf(s.light, p, n) / lighting.boundedSelectProbability);
}
`;

async function runTree(device: GPUDevice, lighting: ReturnType<typeof lightingFor>, points: Float32Array): Promise<Float32Array> {
  const n = points.length / 8;
  const out = device.createBuffer({ size: n * 16, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
  await runTestProgram(device, {
    source: treeKernel,
    resources: { ...lightingResources(device, lighting), points: uploadBuffer(device, points), out },
    workgroups: Math.ceil(n / 64),
  });
  return new Float32Array(await readBuffer(device, out));
}

test('GPU light tree: the sampled pmf equals the evaluated pmf (leaf-to-root) and the CPU tree pmf', async () => {
  const device = await testDevice();
  const lighting = lightingFor({ ...mixedLights, lightSampler: 'tree' }, { triangles: randomTriangles(400, 3) });
  const tree = lighting.tree!;
  assert.ok(tree.nodes.length > 400);
  const random = rng(9);
  const n = 4096;
  const points = new Float32Array(8 * n);
  for (let i = 0; i < n; i++) {
    const normal = i % 4 === 0 ? [0, 0, 0] : uniformSphere(random);
    points.set([5 * random() - 2.5, 5 * random() - 2.5, 5 * random() - 2.5, 0, ...normal, random()], 8 * i);
  }
  const out = await runTree(device, lighting, points);
  const u32 = new Uint32Array(out.buffer);
  let cpuMismatch = 0;
  for (let i = 0; i < n; i++) {
    const light = u32[4 * i]!;
    const [sampled, evaluated, viaSelection] = [out[4 * i + 1]!, out[4 * i + 2]!, out[4 * i + 3]!];
    assert.ok(sampled > 0 && light < lighting.boundedCount, `point ${i}: light ${light}, pmf ${sampled}`);
    assert.ok(Math.abs(sampled - evaluated) <= 2e-6 * sampled, `point ${i}: sampled ${sampled} vs evaluated ${evaluated}`);
    assert.ok(Math.abs(sampled - viaSelection) <= 2e-6 * sampled, `point ${i}: sampled ${sampled} vs bounded_light_pmf ${viaSelection}`);
    const p = [points[8 * i]!, points[8 * i + 1]!, points[8 * i + 2]!];
    const nrm = [points[8 * i + 4]!, points[8 * i + 5]!, points[8 * i + 6]!];
    const cpu = lightTreePmf(tree, p, nrm, light);
    if (!(Math.abs(cpu - sampled) <= 1e-3 * cpu)) cpuMismatch++;
  }
  // f32 against f64 can differ where an importance crosses the emission cone's cut-off.
  assert.ok(cpuMismatch <= n * 0.002, `${cpuMismatch} of ${n} pmfs differ from the CPU tree's`);
});

test('GPU light tree traversal frequencies follow the tree pmf (chi-square at two shading points)', async () => {
  const device = await testDevice();
  const lighting = lightingFor({ ...mixedLights, lightSampler: 'tree' }, { triangles: randomTriangles(60, 5) });
  const tree = lighting.tree!;
  const random = rng(21);
  for (const [p, nrm] of [[[0.2, -0.3, 0.1], [0, 1, 0]], [[2.6, 0.5, -1], [0, 0, 0]]] as const) {
    const n = 1 << 16;
    const points = new Float32Array(8 * n);
    for (let i = 0; i < n; i++) points.set([...p, 0, ...nrm, random()], 8 * i);
    const out = await runTree(device, lighting, points);
    const u32 = new Uint32Array(out.buffer);
    const observed = new Float64Array(lighting.boundedCount);
    for (let i = 0; i < n; i++) observed[u32[4 * i]!]! += 1;
    const expected = Array.from({ length: lighting.boundedCount }, (_, g) => n * lightTreePmf(tree, p, nrm, g));
    const chi = chiSquareTest(observed, expected);
    assert.ok(!chi.outsideSupport && chi.pValue > 1e-4, `at ${p}: chi-square ${chi.chi2.toFixed(1)}, ${chi.dof} dof, p = ${chi.pValue}`);
  }
});

/** A floor under a ceiling of small emissive triangles facing in random directions. */
function manyEmitterScene(count: number, seed: number): WavefrontMeshInput[] {
  const random = rng(seed);
  const positions: number[] = [];
  for (let t = 0; t < count; t++) {
    const c = [3 * random() - 1.5, 0.6 + 0.8 * random(), 3 * random() - 1.5];
    const d = uniformSphere(random);
    // Two edges orthogonal to d (so the triangle faces d), 0.05 long.
    const a = Math.abs(d[0]) > 0.9 ? [0, 1, 0] : [1, 0, 0];
    const e1 = [a[1]! * d[2] - a[2]! * d[1], a[2]! * d[0] - a[0]! * d[2], a[0]! * d[1] - a[1]! * d[0]];
    const l1 = Math.hypot(e1[0]!, e1[1]!, e1[2]!);
    const e2 = [d[1] * e1[2]! - d[2] * e1[1]!, d[2] * e1[0]! - d[0] * e1[2]!, d[0] * e1[1]! - d[1] * e1[0]!];
    const l2 = Math.hypot(e2[0]!, e2[1]!, e2[2]!);
    positions.push(...c, ...c.map((v, i) => v + (0.05 * e1[i]!) / l1), ...c.map((v, i) => v + (0.05 * e2[i]!) / l2));
  }
  return [
    { positions: [-3, 0, -3, 3, 0, -3, 3, 0, 3, -3, 0, 3], indices: [0, 2, 1, 0, 3, 2], material: { baseColorFactor: [0.6, 0.6, 0.6, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 } },
    { positions, material: { baseColorFactor: [0, 0, 0, 1], emissiveFactor: [1, 0.9, 0.7], emissiveStrength: 40, doubleSided: false } },
  ];
}

test('many emitters of every bounded kind: the tree renders the power table\'s image within noise', async () => {
  const device = await testDevice();
  const size = 24;
  const camera = { position: [0, 2.5, 3], target: [0, 0.3, 0], up: [0, 1, 0], fovYDegrees: 60 };
  const scene = {
    meshes: manyEmitterScene(300, 4),
    lights: [
      { type: 'rectangle' as const, center: [0.5, 1.2, -0.5], edgeU: [0.4, 0, 0], edgeV: [0, 0, 0.3], intensity: 6 },
      { type: 'sphere' as const, center: [-0.8, 0.5, 0.3], radius: 0.15, intensity: 8 },
      { type: 'spot' as const, position: [1, 1.5, 1], direction: [-0.5, -1, -0.5], intensity: 4, innerConeAngle: 0.3, outerConeAngle: 0.6 },
      { type: 'point' as const, position: [-1, 1, -1], intensity: 1.5 },
    ],
  };
  const means: Float64Array[] = [];
  for (const lightSampler of ['tree', 'power'] as const) {
    const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: size, height: size, samplesPerPixel: 128, seed: 1, maxDepth: 3, camera, ...scene, lightSampler });
    try {
      const stats = await renderer.renderFrame();
      assert.equal(stats.invalidSamples, 0);
      const image = (await renderer.readRadiance()).data;
      const blocks = new Float64Array(9);
      for (let y = 0; y < size; y++) for (let x = 0; x < size; x++) blocks[3 * Math.floor(y / 8) + Math.floor(x / 8)]! += image[4 * (y * size + x) + 1]! / 64;
      means.push(blocks);
    } finally {
      renderer.destroy();
    }
  }
  // The same seed gives both the same camera samples (the directly seen emitters, most of the
  // noise), so the blocks differ only by how the lights were sampled: 3% is several standard errors.
  for (let b = 0; b < 9; b++) {
    const [tree, power] = [means[0]![b]!, means[1]![b]!];
    assert.ok(Math.abs(tree - power) < 0.03 * power + 1e-3, `block ${b}: tree ${tree} vs power ${power}`);
  }
});
