// Structural checks of a finished BVH against its input (shared by the BVH builder tests).
import assert from 'node:assert/strict';
import { BVH_MAX_DEPTH, type BvhBuildResult } from '../../src/accel/bvh-builder.ts';
import { computeSahCost } from '../../src/accel/bvh-sah.ts';

export interface Stats {
  depth: number;
  leaves: number;
  maxLeaf: number;
}

/**
 * Walks the tree from the root and checks every structural promise the GPU traversal relies on.
 * Returns what it saw so the caller can compare it with what the builder reported.
 */
export function checkInvariants(positions: Float32Array, r: BvhBuildResult, leafCap: number): Stats {
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


/** True when two builds are the same tree, bit for bit (nodes, triangle order and reported figures). */
export function sameTree(a: BvhBuildResult, b: BvhBuildResult): boolean {
  if (a.nodeCount !== b.nodeCount || a.depth !== b.depth || a.leafCount !== b.leafCount || a.sahCost !== b.sahCost) return false;
  const na = new Uint8Array(a.nodes), nb = new Uint8Array(b.nodes);
  if (na.length !== nb.length || a.triangleOrder.length !== b.triangleOrder.length) return false;
  for (let i = 0; i < na.length; i++) if (na[i] !== nb[i]) return false;
  for (let i = 0; i < a.triangleOrder.length; i++) if (a.triangleOrder[i] !== b.triangleOrder[i]) return false;
  return true;
}
