import { test } from 'node:test';
import assert from 'node:assert/strict';
import { buildBvh, BVH_MAX_DEPTH } from '../../src/accel/bvh-builder.ts';
import { computeSahCost } from '../../src/accel/bvh-sah.ts';
import { checkInvariants, sameTree } from './bvh-invariants.ts';
import { packWavefrontBvhNodes, packWavefrontTriangles } from '../../src/accel/triangle-packing.ts';
import { bvhNodeLayout, primitiveLayout } from '../../src/gpu-layout/records.ts';
import { readStruct } from '../../src/gpu-layout/struct-layout.ts';
import {
  duplicatedSoup,
  exponentialSpacing,
  gridMesh,
  hugeRangeSoup,
  identicalTriangles,
  randomSoup,
  soupWithZeroArea,
} from './bvh-fixtures.ts';

const meshes: Array<[string, Float32Array]> = [
  ['random soup', randomSoup(3000, 1)],
  ['displaced grid', gridMesh(40)],
  ['flat grid', gridMesh(30, 0)],
  ['zero-area triangles', soupWithZeroArea(2000, 2)],
  ['identical triangles', identicalTriangles(1500)],
  ['duplicated coincident triangles', duplicatedSoup(400, 4, 3)],
  ['huge coordinate range', hugeRangeSoup(2000, 4)],
  ['single triangle', randomSoup(1, 5)],
];

for (const [name, positions] of meshes) {
  test(`structural invariants: ${name}`, () => {
    const r = buildBvh(positions);
    const stats = checkInvariants(positions, r, 16);
    assert.ok(Number.isFinite(r.sahCost) && r.sahCost > 0);
    assert.ok(r.buildTimeMs >= 0);
    if (name === 'identical triangles') {
      // No plane separates coincident centroids: index halves until leaves fit the cap.
      assert.ok(stats.maxLeaf <= 16 && stats.maxLeaf > 4, `leaves of ${stats.maxLeaf}`);
    }
  });
}

test('adversarial exponential spacing stays within the depth limit with bounded leaves', () => {
  const positions = exponentialSpacing(6000);
  const r = buildBvh(positions);
  const stats = checkInvariants(positions, r, 16);
  assert.ok(r.depth <= BVH_MAX_DEPTH);
  assert.ok(stats.maxLeaf <= 16);
  // A tiny depth limit still holds (leaves grow instead).
  const shallow = buildBvh(positions, { maxDepth: 5 });
  assert.ok(shallow.depth <= 5);
  checkInvariants(positions, shallow, Infinity);
});

test('binned SAH beats an object-median tree on the SAH cost', () => {
  const positions = randomSoup(4000, 11, 10, 2);
  const sah = buildBvh(positions, { binCount: 16 });
  // leafSizeCap == maxLeafSize with a single bin degrades to (forced) median splits everywhere.
  const median = buildBvh(positions, { binCount: 2, maxLeafSize: 4, leafSizeCap: 4 });
  checkInvariants(positions, median, 4);
  assert.ok(sah.sahCost < median.sahCost, `SAH ${sah.sahCost} vs median ${median.sahCost}`);
});

test('empty input gives one inverted root box', () => {
  const r = buildBvh(new Float32Array(0));
  assert.equal(r.nodeCount, 1);
  assert.equal(r.triangleOrder.length, 0);
  const node = readStruct(bvhNodeLayout, new DataView(r.nodes), 0);
  assert.ok((node.boundsMin as number[])[0]! > (node.boundsMax as number[])[0]!);
  assert.equal(packWavefrontBvhNodes(r).byteLength, 32);
  assert.equal(packWavefrontTriangles(new Float32Array(0), r.triangleOrder).byteLength, primitiveLayout.size);
});

test('options are validated', () => {
  assert.throws(() => buildBvh(new Float32Array(10)), RangeError);
  assert.throws(() => buildBvh(randomSoup(4, 1), { binCount: 0 }), RangeError);
  assert.throws(() => buildBvh(randomSoup(4, 1), { maxLeafSize: 1.5 }), RangeError);
});

test('packWavefrontTriangles writes triangle primitive records in BVH order', () => {
  const positions = randomSoup(50, 8);
  const r = buildBvh(positions);
  const primitives = Uint32Array.from({ length: 50 }, (_, i) => 1000 + i);
  const instances = Uint32Array.from({ length: 50 }, (_, i) => i % 3);
  const packed = packWavefrontTriangles(positions, r.triangleOrder, { primitives, instances });
  assert.equal(packed.byteLength, 50 * primitiveLayout.size);
  const view = new DataView(packed);
  for (let s = 0; s < 50; s++) {
    const t = r.triangleOrder[s]!;
    const rec = readStruct(primitiveLayout, view, s);
    assert.equal(rec.primitive, 1000 + t);
    assert.equal(rec.instance, t % 3);
    assert.equal(rec.shape, 0, 'a triangle');
    for (let c = 0; c < 3; c++) {
      assert.equal((rec.v0 as number[])[c], positions[t * 9 + c]);
      assert.equal((rec.e1 as number[])[c], Math.fround(positions[t * 9 + 3 + c]! - positions[t * 9 + c]!));
      assert.equal((rec.e2 as number[])[c], Math.fround(positions[t * 9 + 6 + c]! - positions[t * 9 + c]!));
    }
  }
  const nodes = packWavefrontBvhNodes(r);
  assert.deepEqual(new Uint8Array(nodes), new Uint8Array(r.nodes));
});

test('computeSahCost of a hand-made two-leaf tree', () => {
  // Root [0,2]x[0,1]x[0,1] (half area 2+1+2 = 5); leaves [0,1]^3 (3) with 2 tris and [1,2]x[0,1]x[0,1] (3) with 1.
  const buf = new ArrayBuffer(3 * 32);
  const f = new Float32Array(buf);
  const u = new Uint32Array(buf);
  f.set([0, 0, 0], 0); u[3] = 1; f.set([2, 1, 1], 4); u[7] = 0;
  f.set([0, 0, 0], 8); u[11] = 0; f.set([1, 1, 1], 12); u[15] = 2;
  f.set([1, 0, 0], 16); u[19] = 2; f.set([2, 1, 1], 20); u[23] = 1;
  assert.equal(computeSahCost(buf), 1 + (3 / 5) * 2 + (3 / 5) * 1);
  assert.equal(computeSahCost(buf, { traversalCost: 2, intersectionCost: 3 }), 2 + (3 / 5) * 6 + (3 / 5) * 3);
});

test('the JS loops and the WebAssembly SIMD loops build the same tree, bit for bit', () => {
  const inputs: Array<[string, Float32Array]> = [
    ...meshes,
    ['exponential spacing', exponentialSpacing(3000)],
    // Larger meshes: more levels, more of the WebAssembly loops' long runs.
    ['random soup 60k', randomSoup(60_000, 12, 100, 1)],
    ['flat grid 50k', gridMesh(160, 0)],
  ];
  for (const [name, positions] of inputs) {
    const js = buildBvh(positions, { wasm: false });
    const wasm = buildBvh(positions, { wasm: true });
    assert.ok(sameTree(js, wasm), `${name}: same tree`);
  }
  // Other settings exercise other bin counts and leaf sizes in both.
  const positions = randomSoup(20_000, 13, 30, 1);
  for (const options of [{ binCount: 8 }, { binCount: 48 }, { maxLeafSize: 1, leafSizeCap: 2 }, { maxDepth: 12 }]) {
    assert.ok(sameTree(buildBvh(positions, { ...options, wasm: false }), buildBvh(positions, options)), JSON.stringify(options));
  }
});
