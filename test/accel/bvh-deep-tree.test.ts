// A BVH deeper than the GPU traversal stack (another builder's tree, not the CPU builder's, which
// caps depth at BVH_MAX_DEPTH) loses no geometry: rays whose stack would overflow finish in
// stackless mode through the parent links, and agree with brute force exactly.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { bvhParentLinks, packWavefrontTriangles } from '../../src/accel/triangle-packing.ts';
import { bruteForceAny, bruteForceClosest, traceClosestReference } from '../../src/accel/bvh-reference-traversal.ts';
import { bvhTraversalStackSize, INDEX_NONE } from '../../src/gpu-layout/constants.ts';
import { rng } from './bvh-fixtures.ts';
import { traceOnGpu } from './gpu-traversal.ts';

/**
 * N small triangles, triangle k in the plane x = k at a pseudo-random place in y and z, under a
 * chain-shaped tree: node 2k (k < N - 1) bounds triangles k..N-1 and has the leaf of triangle k
 * (node 2k + 1) and the rest of the chain (node 2k + 2) as children. Depth N - 1.
 */
function chainScene(n: number): { positions: Float32Array; nodes: ArrayBuffer; nodeCount: number } {
  const random = rng(1234);
  const positions = new Float32Array(9 * n);
  for (let k = 0; k < n; k++) {
    const y = random() * 2 - 1;
    const z = random() * 2 - 1;
    positions.set([k, y - 0.6, z - 0.6, k, y + 0.6, z - 0.6, k, y - 0.6, z + 0.6], 9 * k);
  }
  const nodeCount = 2 * n - 1;
  const nodes = new ArrayBuffer(nodeCount * 32);
  const f = new Float32Array(nodes);
  const u = new Uint32Array(nodes);
  const bounds = (k: number): number[] => {
    const p = positions.subarray(9 * k, 9 * k + 9);
    return [0, 1, 2].map((c) => Math.min(p[c]!, p[3 + c]!, p[6 + c]!)).concat([0, 1, 2].map((c) => Math.max(p[c]!, p[3 + c]!, p[6 + c]!)));
  };
  const write = (node: number, b: number[], leftOrFirst: number, count: number): void => {
    f.set(b.slice(0, 3), node * 8);
    u[node * 8 + 3] = leftOrFirst;
    f.set(b.slice(3), node * 8 + 4);
    u[node * 8 + 7] = count;
  };
  let chain = bounds(n - 1);
  write(2 * (n - 1), chain, n - 1, 1);
  for (let k = n - 2; k >= 0; k--) {
    const leaf = bounds(k);
    write(2 * k + 1, leaf, k, 1);
    chain = [0, 1, 2].map((c) => Math.min(leaf[c]!, chain[c]!)).concat([3, 4, 5].map((c) => Math.max(leaf[c]!, chain[c]!)));
    write(2 * k, chain, 2 * k + 1, 0);
  }
  return { positions, nodes, nodeCount };
}

test('a BVH four times deeper than the traversal stack loses no geometry on the GPU', async () => {
  const n = 4 * bvhTraversalStackSize;
  const { positions, nodes, nodeCount } = chainScene(n);
  const order = Uint32Array.from({ length: n }, (_, i) => i);
  const primitives = packWavefrontTriangles(positions, order);
  const scene = { triangles: primitives, triangleCount: n, nodes };
  const random = rng(99);
  // Rays along -x meet the deep end of the chain first (near-first traversal pushes a leaf at every
  // level and overflows); rays along +x do not; oblique rays mix.
  const rays = Array.from({ length: 2048 }, (_, i) => {
    const kind = i % 3;
    const sx = kind === 0 ? -1 : kind === 1 ? 1 : random() < 0.5 ? -1 : 1;
    const origin = [sx < 0 ? n + 1 : -1, random() * 2.4 - 1.2, random() * 2.4 - 1.2];
    const d = [sx, (random() - 0.5) * (kind === 2 ? 0.02 : 0.002), (random() - 0.5) * (kind === 2 ? 0.02 : 0.002)];
    const l = Math.hypot(d[0]!, d[1]!, d[2]!);
    return { origin, direction: d.map((c) => c / l), tMax: 3e38, anyTMax: (n + 2) * (random() < 0.5 ? 0.5 : 1.5) };
  });
  const got = await traceOnGpu({ primitives, nodes, parents: bvhParentLinks(nodes, nodeCount) }, rays);
  let hits = 0;
  let fallbacks = 0;
  rays.forEach((ray, k) => {
    const want = bruteForceClosest(primitives, n, ray);
    // The JS mirror, with an unbounded stack, finds the same.
    assert.deepEqual(traceClosestReference(scene, ray)?.slot ?? null, want?.slot ?? null);
    if (got.fallbacks[k]! & 1) fallbacks++;
    if (want === null) {
      assert.equal(got.slot[k], INDEX_NONE, `ray ${k} hits nothing`);
    } else {
      hits++;
      assert.equal(got.slot[k], want.slot, `ray ${k}: closest triangle`);
      assert.ok(Math.abs(got.t[k]! - want.t) <= 1e-5 * want.t, `ray ${k}: t ${got.t[k]} vs ${want.t}`);
    }
    assert.equal(got.occluded[k] === 1, bruteForceAny(primitives, n, { ...ray, tMax: ray.anyTMax }), `ray ${k}: any hit`);
  });
  assert.ok(hits > 1000, `${hits} rays hit`);
  // The stackless path really ran, and was exact.
  assert.ok(fallbacks > 300, `${fallbacks} rays overflowed the stack`);
  console.log(`# depth ${n - 1} chain: ${hits} hits, ${fallbacks} closest-hit queries finished stackless`);
});
