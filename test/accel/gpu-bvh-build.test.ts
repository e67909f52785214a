// The GPU LBVH builder on real WebGPU (Dawn; lavapipe here): its radix sort against a stable CPU
// sort, its trees against every structural promise of the traversal (checked on the CPU after
// readback), its tree quality against the CPU binned-SAH builder, the traversal over its trees
// against the traversal over the CPU builder's, and the refit of moved geometry.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { buildBvh } from '../../src/accel/bvh-builder.ts';
import { GpuBvhBuilder, GpuBvhRefitter } from '../../src/accel/gpu-build/gpu-bvh-builder.ts';
import { sortPairsOnGpu } from '../../src/accel/gpu-build/radix-sort.ts';
import { bvhParentLinks, packPrimitives, packWavefrontBvhNodes, packWavefrontTriangles } from '../../src/accel/triangle-packing.ts';
import { PRIMITIVE_SHAPE_BOX, PRIMITIVE_SHAPE_SPHERE, PRIMITIVE_SHAPE_TRIANGLE } from '../../src/gpu-layout/constants.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { benchmarkMesh } from '../../bench/bvh.ts';
import { readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { duplicatedSoup, gridMesh, hugeRangeSoup, identicalTriangles, makeRays, randomSoup, rng } from './bvh-fixtures.ts';
import { buildOnGpu, buildRecordsOnGpu, checkBuild, checkGpuTree, destroyBuild, readTree, sourceRecords, type GpuBuild } from './gpu-bvh-check.ts';
import { traceOnGpu } from './gpu-traversal.ts';

/** Indices 0..n-1 ordered by key (keyWords words, high word compared first), stable. */
function stableOrder(keys: Uint32Array, n: number, keyWords: 1 | 2): number[] {
  const hi = (i: number): number => keys[i * keyWords + keyWords - 1]!;
  const lo = (i: number): number => keys[i * keyWords]!;
  return Array.from({ length: n }, (_, i) => i).sort((a, b) => hi(a) - hi(b) || (keyWords === 2 ? lo(a) - lo(b) : 0) || a - b);
}

test('GPU radix sort: 70k 30-bit keys with many duplicates (two scan levels) sort exactly like a stable CPU sort', async () => {
  const device = await testDevice();
  const n = 70_000;
  const r = rng(5);
  // Few distinct high bits, so equal keys are common and stability shows.
  const keys = Uint32Array.from({ length: n }, () => (Math.floor(r() * 64) << 24) | Math.floor(r() * 3));
  const values = Uint32Array.from({ length: n }, (_, i) => i);
  const got = await sortPairsOnGpu(device, keys, values, 1);
  const want = stableOrder(keys, n, 1);
  for (let i = 0; i < n; i++) {
    assert.equal(got.values[i], want[i], `position ${i}`);
    assert.equal(got.keys[i], keys[want[i]!]);
  }
});

test('GPU radix sort: 60-bit keys (two words), and sizes around a block boundary', async () => {
  const device = await testDevice();
  for (const [n, keyWords] of [[3001, 2], [1, 1], [1024, 1], [1025, 2]] as const) {
    const r = rng(n);
    const keys = Uint32Array.from({ length: n * keyWords }, (_, i) => (i % keyWords === keyWords - 1 ? Math.floor(r() * 8) : Math.floor(r() * 2 ** 30)));
    const values = Uint32Array.from({ length: n }, (_, i) => i);
    const got = await sortPairsOnGpu(device, keys, values, keyWords);
    assert.deepEqual([...got.values], stableOrder(keys, n, keyWords), `${n} keys of ${keyWords} words`);
  }
});

const shapes: Array<[string, Float32Array]> = [
  ['one triangle', randomSoup(1, 1)],
  ['two triangles', randomSoup(2, 2)],
  ['3000-triangle random soup (two-level kept-node scan)', randomSoup(3000, 3)],
  ['displaced grid', gridMesh(30)],
  ['500 identical triangles (every key equal)', identicalTriangles(500)],
  ['duplicated coincident triangles', duplicatedSoup(400, 3, 4)],
  ['clusters twenty orders of magnitude apart', hugeRangeSoup(600, 5)],
];

for (const [name, triangles] of shapes) {
  test(`GPU LBVH is a valid tree in the traversal's format: ${name}`, async () => {
    for (const mortonBits of [30, 60] as const) {
      const b = await buildOnGpu(triangles, { mortonBits });
      try {
        const stats = checkBuild(b);
        assert.ok(stats.maxLeaf <= 8, `leaves hold at most maxLeafSize primitives (${stats.maxLeaf})`);
        assert.equal(stats.tight, b.result.nodeCount, 'every box is exactly the union of its children (or primitives)');
      } finally {
        destroyBuild(b);
      }
    }
  });
}

test('GPU LBVH over spheres and boxes: leaf boxes contain the analytic shapes', async () => {
  const n = 300;
  const r = rng(9);
  const geometry = new Float32Array(n * 9);
  const shape = new Uint32Array(n);
  for (let i = 0; i < n; i++) {
    const c = [r() * 10, r() * 10, r() * 10];
    const kind = i % 3 === 0 ? PRIMITIVE_SHAPE_SPHERE : i % 3 === 1 ? PRIMITIVE_SHAPE_BOX : PRIMITIVE_SHAPE_TRIANGLE;
    shape[i] = kind;
    if (kind === PRIMITIVE_SHAPE_SPHERE) geometry.set([...c, 0.1 + r(), 0, 0, 0, 0, 0], i * 9);
    else if (kind === PRIMITIVE_SHAPE_BOX) geometry.set([...c, c[0]! + r(), c[1]! + r(), c[2]! + r(), 0, 0, 0], i * 9);
    else geometry.set([...c, r(), 0, 0, 0, r(), 0], i * 9);
  }
  const identity = Uint32Array.from({ length: n }, (_, i) => i);
  const b = await buildRecordsOnGpu(packPrimitives({ geometry, instance: new Uint32Array(n), primitive: identity, shape }, identity));
  try {
    const stats = checkBuild(b);
    assert.equal(stats.tight, b.result.nodeCount, 'every box is exactly the union of its children (or shapes)');
  } finally {
    destroyBuild(b);
  }
});

test('GPU LBVH SAH cost against the CPU binned SAH builder on the 20k terrain+clutter bench mesh (LBVH: expected 10-30 % above)', async (t) => {
  const triangles = benchmarkMesh(20_000);
  const cpu = buildBvh(triangles, { maxLeafSize: 4, binCount: 16 });
  const b = await buildOnGpu(triangles);
  try {
    checkBuild(b);
    const ratio = b.result.sahCost / cpu.sahCost;
    t.diagnostic(`SAH: GPU LBVH ${b.result.sahCost.toFixed(2)}, CPU binned SAH ${cpu.sahCost.toFixed(2)}, ratio ${ratio.toFixed(3)}; depth ${b.result.depth} vs ${cpu.depth}`);
    // A broken sort or hierarchy gives a valid but much worse tree; a plain LBVH stays within ~1.4x.
    assert.ok(ratio > 0.9 && ratio < 1.4, `SAH ratio ${ratio}`);
  } finally {
    destroyBuild(b);
  }
});

/** Traces the same rays through two trees of the same triangles on the GPU: the closest t must agree exactly. */
async function sameHits(a: { primitives: ArrayBuffer; nodes: ArrayBuffer; parents: Uint32Array }, b: typeof a, triangles: Float32Array, seed: number): Promise<{ hits: number }> {
  const rays = makeRays(triangles, 2048, seed).map((ray, k) => ({ ...ray, tMax: 3e38, anyTMax: k % 2 === 0 ? 3e38 : 0.5 }));
  const [ra, rb] = await Promise.all([traceOnGpu(a, rays), traceOnGpu(b, rays)]);
  const ua = new Uint32Array(a.primitives);
  const ub = new Uint32Array(b.primitives);
  let hits = 0;
  for (let k = 0; k < rays.length; k++) {
    assert.equal(ra.t[k], rb.t[k], `ray ${k}: closest t`);
    assert.equal(ra.occluded[k], rb.occluded[k], `ray ${k}: occlusion`);
    if (ra.t[k]! > 0) {
      hits++;
      // The same triangle (up to exact ties, which this scene does not have).
      assert.equal(ua[ra.slot[k]! * 12 + 7], ub[rb.slot[k]! * 12 + 7], `ray ${k}: triangle hit`);
    }
  }
  return { hits };
}

test('traversal over the GPU LBVH finds exactly the hits it finds over the CPU-built tree (4096 rays)', async () => {
  const triangles = randomSoup(4000, 11, 20, 1);
  const n = triangles.length / 9;
  const cpu = buildBvh(triangles);
  const cpuNodes = packWavefrontBvhNodes(cpu);
  const b = await buildOnGpu(triangles);
  try {
    const { hits } = await sameHits(
      { primitives: packWavefrontTriangles(triangles, cpu.triangleOrder), nodes: cpuNodes, parents: bvhParentLinks(cpuNodes, cpu.nodeCount) },
      { primitives: b.primitives, nodes: b.nodes, parents: b.parents },
      triangles,
      n,
    );
    assert.ok(hits > 500, `${hits} rays hit something`);
  } finally {
    destroyBuild(b);
  }
});

/** The triangles moved: a wave through the grid and a drift of everything (same topology). */
function moved(triangles: Float32Array, phase: number): Float32Array {
  const out = new Float32Array(triangles.length);
  for (let i = 0; i < triangles.length; i += 3) {
    const x = triangles[i]!, y = triangles[i + 1]!, z = triangles[i + 2]!;
    out[i] = x + 0.3 * Math.sin(y * 0.2 + phase);
    out[i + 1] = y + 0.5 * phase;
    out[i + 2] = z + 2 * Math.sin(x * 0.3 + phase) * Math.cos(y * 0.25);
  }
  return out;
}

test('GPU refit after moving every vertex: exact boxes, and the same hits as a fresh GPU build of the moved mesh', async () => {
  const device = await testDevice();
  const rest = gridMesh(24, 0.5);
  const n = rest.length / 9;
  const b: GpuBuild = await buildOnGpu(rest);
  const posed = moved(rest, 1.3);
  try {
    const source = sourceRecords(posed);
    device.queue.writeBuffer(b.buffers.source, 0, source);
    await b.builder.refit();
    const tree = await readTree(b.buffers, b.result.nodeCount, n);
    const refitted = { ...tree, source };
    const stats = checkGpuTree(refitted, b.result.nodeCount);
    assert.equal(stats.tight, b.result.nodeCount, 'every refitted box is exactly the union of its children (or primitives)');
    assert.equal(stats.leaves, b.result.leafCount, 'the refit keeps the topology');
    const fresh = await buildOnGpu(posed);
    try {
      const { hits } = await sameHits(tree, { primitives: fresh.primitives, nodes: fresh.nodes, parents: fresh.parents }, posed, 31);
      assert.ok(hits > 500, `${hits} rays hit the posed grid`);
    } finally {
      destroyBuild(fresh);
    }
  } finally {
    destroyBuild(b);
  }
});

test('GPU refit of a CPU-built tree (cpu-upload mode) after moving its vertices: exact boxes, same hits as a CPU rebuild', async () => {
  const device = await testDevice();
  const rest = randomSoup(2500, 21, 15, 1);
  const n = rest.length / 9;
  const cpu = buildBvh(rest);
  const nodesData = packWavefrontBvhNodes(cpu);
  const parentsData = bvhParentLinks(nodesData, cpu.nodeCount);
  const posed = moved(rest, 0.7);
  const posedRecords = packWavefrontTriangles(posed, cpu.triangleOrder);
  const nodes = uploadBuffer(device, nodesData);
  const parents = uploadBuffer(device, parentsData);
  const primitives = uploadBuffer(device, posedRecords);
  const refitter = await GpuBvhRefitter.create(device, { nodes, parents, primitives, nodeCount: cpu.nodeCount });
  try {
    await refitter.refit();
    const refitNodes = await readBuffer(device, nodes, nodesData.byteLength);
    const identity = Uint32Array.from({ length: n }, (_, i) => i);
    // checkGpuTree wants scene-order records whose `primitive` field names them: the posed soup in original order.
    const stats = checkGpuTree({ nodes: refitNodes, parents: parentsData, primitives: posedRecords, source: packWavefrontTriangles(posed, identity) }, cpu.nodeCount);
    assert.equal(stats.tight, cpu.nodeCount, 'every refitted box is exactly the union of its children (or primitives)');
    const rebuilt = buildBvh(posed);
    const rebuiltNodes = packWavefrontBvhNodes(rebuilt);
    const { hits } = await sameHits(
      { primitives: posedRecords, nodes: refitNodes, parents: parentsData },
      { primitives: packWavefrontTriangles(posed, rebuilt.triangleOrder), nodes: rebuiltNodes, parents: bvhParentLinks(rebuiltNodes, rebuilt.nodeCount) },
      posed,
      41,
    );
    assert.ok(hits > 300, `${hits} rays hit the posed soup`);
  } finally {
    refitter.destroy();
    for (const x of [nodes, parents, primitives]) x.destroy();
  }
});

test('GpuBvhBuilder: refit before build and undersized buffers are refused', async () => {
  const device = await testDevice();
  const source = uploadBuffer(device, sourceRecords(randomSoup(10, 1)));
  const small = device.createBuffer({ size: 64, usage: 0x80 });
  try {
    await assert.rejects(GpuBvhBuilder.create(device, { source, primitiveCount: 10, primitives: small, nodes: small, parents: small }), RangeError);
    const big = device.createBuffer({ size: 4096, usage: 0x80 | 0x8 | 0x4 });
    const builder = await GpuBvhBuilder.create(device, { source, primitiveCount: 10, primitives: big, nodes: big, parents: big });
    await assert.rejects(builder.refit(), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_STATE');
    builder.destroy();
    big.destroy();
  } finally {
    source.destroy();
    small.destroy();
  }
});
