import { test } from 'node:test';
import assert from 'node:assert/strict';
import { buildBvh, BVH_MAX_DEPTH, type BvhBuildResult } from '../../src/accel/bvh-builder.ts';
import { computeSahCost } from '../../src/accel/bvh-sah.ts';
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

interface Stats {
  depth: number;
  leaves: number;
  maxLeaf: number;
}

/**
 * Walks the tree from the root and checks every structural promise the GPU traversal relies on.
 * Returns what it saw so the caller can compare it with what the builder reported.
 */
function checkInvariants(positions: Float32Array, r: BvhBuildResult, leafCap: number): Stats {
  const n = positions.length / 9;
  const f = new Float32Array(r.nodes);
  const u = new Uint32Array(r.nodes);
  assert.equal(r.nodes.byteLength, r.nodeCount * 32);
  assert.equal(r.triangleOrder.length, n);
  // Every triangle appears exactly once in the order.
  const seen = new Uint8Array(n);
  for (const t of r.triangleOrder) {
    assert.ok(t < n, `order holds ${t} >= ${n}`);
    assert.equal(seen[t], 0, `triangle ${t} appears twice`);
    seen[t] = 1;
  }
  const slotCovered = new Uint8Array(n);
  const visited = new Uint8Array(r.nodeCount);
  const stats: Stats = { depth: 0, leaves: 0, maxLeaf: 0 };
  const stack: Array<[node: number, depth: number]> = [[0, 0]];
  const box = (i: number): number[] => [f[i * 8]!, f[i * 8 + 1]!, f[i * 8 + 2]!, f[i * 8 + 4]!, f[i * 8 + 5]!, f[i * 8 + 6]!];
  while (stack.length > 0) {
    const [node, depth] = stack.pop()!;
    assert.ok(node < r.nodeCount, `node ${node} out of range`);
    assert.equal(visited[node], 0, `node ${node} reached twice`);
    visited[node] = 1;
    const b = box(node);
    for (let c = 0; c < 3; c++) assert.ok(b[c]! <= b[3 + c]!, `node ${node} has an inverted box`);
    const count = u[node * 8 + 7]!;
    const first = u[node * 8 + 3]!;
    if (count > 0) {
      stats.leaves++;
      stats.depth = Math.max(stats.depth, depth);
      stats.maxLeaf = Math.max(stats.maxLeaf, count);
      if (depth < BVH_MAX_DEPTH) assert.ok(count <= leafCap, `leaf of ${count} > cap ${leafCap} at depth ${depth}`);
      // Leaf boxes contain their triangles' vertices.
      for (let s = first; s < first + count; s++) {
        assert.equal(slotCovered[s], 0, `slot ${s} in two leaves`);
        slotCovered[s] = 1;
        const t = r.triangleOrder[s]!;
        for (let v = 0; v < 9; v++) {
          const x = positions[t * 9 + v]!;
          assert.ok(x >= b[v % 3]! && x <= b[3 + (v % 3)]!, `leaf ${node}: triangle ${t} leaves the box`);
        }
      }
    } else {
      assert.ok(first + 1 < r.nodeCount && first > node, `interior ${node} has children ${first}, ${first + 1}`);
      for (const child of [first, first + 1]) {
        const cb = box(child);
        for (let c = 0; c < 3; c++) {
          assert.ok(cb[c]! >= b[c]! && cb[3 + c]! <= b[3 + c]!, `child ${child} sticks out of parent ${node}`);
        }
      }
      stack.push([first + 1, depth + 1], [first, depth + 1]);
    }
  }
  assert.ok(visited.every((v) => v === 1), 'every node is reachable from the root');
  assert.ok(slotCovered.every((v) => v === 1), 'every slot belongs to exactly one leaf');
  assert.ok(stats.depth <= BVH_MAX_DEPTH);
  assert.equal(stats.depth, r.depth);
  assert.equal(stats.leaves, r.leafCount);
  assert.equal(r.sahCost, computeSahCost(r.nodes, { nodeCount: r.nodeCount }));
  return stats;
}

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
