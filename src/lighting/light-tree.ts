import { allocateStructArray, writeStruct } from '../gpu-layout/struct-layout.ts';
import { lightBoundsImportance, unionBounds, type LightBounds } from './light-bounds.ts';
import { ONE_MINUS_EPSILON_F32 } from './environment-sampling.ts';
import type { Vec3 } from './vec3.ts';
import { LIGHT_TREE_FLAG_LEAF, LIGHT_TREE_FLAG_TWO_SIDED } from '../gpu-layout/constants.ts';
import { lightTreeNodeLayout } from '../gpu-layout/records.ts';

export { LIGHT_TREE_FLAG_LEAF, LIGHT_TREE_FLAG_TWO_SIDED };
export { lightTreeNodeLayout };

/**
 * A light hierarchy (BVH over emitters) for many-light sampling: Conty Estevez and Kulla 2018,
 * "Importance Sampling of Many Lights with Adaptive Tree Splitting", with single-sample stochastic
 * traversal (no splitting), as pbrt-v4's BVHLightSampler (4th ed., sec. 12.6.3):
 * - build: top-down, one light per leaf, splits chosen among 12 buckets per axis by the surface
 *   area orientation heuristic (SAOH, Conty and Kulla sec. 4.4; pbrt's EvaluateCost);
 * - sample: from the root, pick a child with probability proportional to its importance at the
 *   shading point (light-bounds.ts), reusing the rescaled random number; pmf = product of choices.
 *   Where both children have importance 0 (their bounds cannot reach the point, though the parent's
 *   looser bounds could), the choice falls back to the children's phi: pbrt-v4 gives up there, but
 *   this way the pmfs of all lights sum to exactly 1 at every point, and such a path only picks a
 *   light that contributes nothing (a wasted sample, as pbrt's empty one);
 * - pmf of a given light (MIS): walk from its leaf to the root through the parent links,
 *   multiplying importance(node) / (importance(left) + importance(right)) of every ancestor.
 *
 * GPU layout: LightTreeNode records (64 bytes each, depth-first: the first child of an interior
 * node is the next record) in the lights heap, and each light's leaf (`lightToLeaf`, light index ->
 * node index, 0xffffffff for lights not in the tree) in its LightSelectionEntry. Light indices are
 * the caller's (light-sampler.ts and gpu-lighting.ts use [emissive triangles | area lights | point
 * and spot lights]). The WGSL port (light-tree.wesl): both walks are plain loops over node indices.
 */

export const LIGHT_TREE_NONE = 0xffffffff;


export interface LightTreeNode {
  bounds: LightBounds;
  /** Interior: index of the second child. Leaf: the light index. */
  childOrLight: number;
  parent: number;
  leaf: boolean;
}

export interface LightTree {
  nodes: LightTreeNode[];
  /** Light index -> leaf node index (LIGHT_TREE_NONE when absent). */
  lightToLeaf: Uint32Array;
}

export interface LightTreeItem {
  /** The caller's light index (what sampling returns). */
  light: number;
  bounds: LightBounds;
}

const BUCKETS = 12;

/** SAOH cost of a cluster (pbrt-v4 BVHLightSampler::EvaluateCost). */
function evaluateCost(b: LightBounds, extent: Vec3, dim: number): number {
  const thetaO = Math.acos(Math.min(1, Math.max(-1, b.cosThetaO)));
  const thetaE = Math.acos(Math.min(1, Math.max(-1, b.cosThetaE)));
  const thetaW = Math.min(thetaO + thetaE, Math.PI);
  const sinThetaO = Math.sqrt(Math.max(0, 1 - b.cosThetaO * b.cosThetaO));
  const mOmega = 2 * Math.PI * (1 - b.cosThetaO) + (Math.PI / 2) * (2 * thetaW * sinThetaO - Math.cos(thetaO - 2 * thetaW) - 2 * thetaO * sinThetaO + b.cosThetaO);
  const kr = Math.max(extent[0], extent[1], extent[2]) / extent[dim]!;
  const d = [b.boundsMax[0] - b.boundsMin[0], b.boundsMax[1] - b.boundsMin[1], b.boundsMax[2] - b.boundsMin[2]];
  const area = 2 * (d[0]! * d[1]! + d[1]! * d[2]! + d[2]! * d[0]!);
  return b.phi * mOmega * kr * area;
}

function centroid(b: LightBounds, dim: number): number {
  return (b.boundsMin[dim]! + b.boundsMax[dim]!) / 2;
}

/** Builds the tree over `items` (lights of zero power are left out: they can never be chosen). */
export function buildLightTree(items: readonly LightTreeItem[], lightCount = 0): LightTree {
  const usable = items.filter((it) => it.bounds.phi > 0 && Number.isFinite(it.bounds.phi));
  const maxLight = items.reduce((m, it) => Math.max(m, it.light + 1), lightCount);
  const lightToLeaf = new Uint32Array(maxLight).fill(LIGHT_TREE_NONE);
  const nodes: LightTreeNode[] = [];
  if (usable.length === 0) return { nodes, lightToLeaf };
  const order = usable.slice();
  // Explicit stack (a degenerate split sequence could be as deep as the light count).
  const stack: { start: number; end: number; parent: number }[] = [{ start: 0, end: order.length, parent: LIGHT_TREE_NONE }];
  while (stack.length > 0) {
    const { start, end, parent } = stack.pop()!;
    const index = nodes.length;
    // The second child of `parent` is the node created after its first subtree: link it here.
    if (parent !== LIGHT_TREE_NONE && index !== parent + 1) nodes[parent]!.childOrLight = index;
    if (end - start === 1) {
      const it = order[start]!;
      nodes.push({ bounds: it.bounds, childOrLight: it.light, parent, leaf: true });
      lightToLeaf[it.light] = index;
      continue;
    }
    let bounds = order[start]!.bounds;
    const cMin = [Infinity, Infinity, Infinity];
    const cMax = [-Infinity, -Infinity, -Infinity];
    for (let k = start; k < end; k++) {
      const b = order[k]!.bounds;
      if (k > start) bounds = unionBounds(bounds, b);
      for (let d = 0; d < 3; d++) {
        cMin[d] = Math.min(cMin[d]!, centroid(b, d));
        cMax[d] = Math.max(cMax[d]!, centroid(b, d));
      }
    }
    const extent: Vec3 = [bounds.boundsMax[0] - bounds.boundsMin[0], bounds.boundsMax[1] - bounds.boundsMin[1], bounds.boundsMax[2] - bounds.boundsMin[2]];
    let bestCost = Infinity;
    let bestDim = -1;
    let bestBucket = -1;
    const bucketOf = (b: LightBounds, d: number): number =>
      Math.min(BUCKETS - 1, Math.max(0, Math.floor((BUCKETS * (centroid(b, d) - cMin[d]!)) / (cMax[d]! - cMin[d]!))));
    for (let d = 0; d < 3; d++) {
      if (!(cMax[d]! > cMin[d]!) || !(extent[d]! > 0)) continue;
      const buckets: (LightBounds | null)[] = new Array(BUCKETS).fill(null);
      for (let k = start; k < end; k++) {
        const b = order[k]!.bounds;
        const i = bucketOf(b, d);
        buckets[i] = buckets[i] === null ? b : unionBounds(buckets[i]!, b);
      }
      for (let split = 0; split < BUCKETS - 1; split++) {
        let below: LightBounds | null = null;
        let above: LightBounds | null = null;
        for (let i = 0; i <= split; i++) if (buckets[i]) below = below ? unionBounds(below, buckets[i]!) : buckets[i]!;
        for (let i = split + 1; i < BUCKETS; i++) if (buckets[i]) above = above ? unionBounds(above, buckets[i]!) : buckets[i]!;
        if (!below || !above) continue;
        const cost = evaluateCost(below, extent, d) + evaluateCost(above, extent, d);
        if (cost < bestCost) {
          bestCost = cost;
          bestDim = d;
          bestBucket = split;
        }
      }
    }
    let mid = (start + end) >> 1;
    if (bestDim >= 0) {
      const part = order.slice(start, end);
      const left = part.filter((it) => bucketOf(it.bounds, bestDim) <= bestBucket);
      const right = part.filter((it) => bucketOf(it.bounds, bestDim) > bestBucket);
      if (left.length > 0 && right.length > 0) {
        order.splice(start, end - start, ...left, ...right);
        mid = start + left.length;
      }
    }
    nodes.push({ bounds, childOrLight: LIGHT_TREE_NONE, parent, leaf: false });
    // Second child first on the stack, so the first child is built next (index + 1).
    stack.push({ start: mid, end, parent: index });
    stack.push({ start, end: mid, parent: index });
  }
  return { nodes, lightToLeaf };
}

export interface LightTreeSample {
  light: number;
  pmf: number;
}

/** Probability of descending into the first child of interior node `index`. */
function firstChildProbability(nodes: readonly LightTreeNode[], index: number, p: readonly number[], n: readonly number[]): number {
  const a = nodes[index + 1]!.bounds;
  const b = nodes[nodes[index]!.childOrLight]!.bounds;
  const i0 = lightBoundsImportance(a, p, n);
  const i1 = lightBoundsImportance(b, p, n);
  if (i0 + i1 > 0) return i0 / (i0 + i1);
  return a.phi / (a.phi + b.phi);
}

/** Stochastic single-path traversal; null only for an empty tree. */
export function sampleLightTree(tree: LightTree, p: readonly number[], n: readonly number[], u: number): LightTreeSample | null {
  const { nodes } = tree;
  if (nodes.length === 0) return null;
  let index = 0;
  let pmf = 1;
  for (;;) {
    const node = nodes[index]!;
    if (node.leaf) return { light: node.childOrLight, pmf };
    const p0 = firstChildProbability(nodes, index, p, n);
    if (u < p0) {
      index = index + 1;
      u = Math.min(u / p0, ONE_MINUS_EPSILON_F32);
      pmf *= p0;
    } else {
      index = node.childOrLight;
      u = Math.min((u - p0) / (1 - p0), ONE_MINUS_EPSILON_F32);
      pmf *= 1 - p0;
    }
  }
}

/** Probability that `sampleLightTree` returns `light` at (p, n). */
export function lightTreePmf(tree: LightTree, p: readonly number[], n: readonly number[], light: number): number {
  const { nodes } = tree;
  let index = light < tree.lightToLeaf.length ? tree.lightToLeaf[light]! : LIGHT_TREE_NONE;
  if (index === LIGHT_TREE_NONE) return 0;
  let pmf = 1;
  while (index !== 0) {
    const parent = nodes[index]!.parent;
    const p0 = firstChildProbability(nodes, parent, p, n);
    pmf *= index === parent + 1 ? p0 : 1 - p0;
    index = parent;
  }
  return pmf;
}

/** Packs the nodes as LightTreeNode records (one zeroed record when empty). */
export function packLightTree(tree: LightTree): ArrayBuffer {
  const buffer = allocateStructArray(lightTreeNodeLayout, tree.nodes.length);
  const view = new DataView(buffer);
  tree.nodes.forEach((node, i) => {
    writeStruct(lightTreeNodeLayout, view, i, {
      boundsMin: node.bounds.boundsMin,
      phi: node.bounds.phi,
      boundsMax: node.bounds.boundsMax,
      cosThetaO: node.bounds.cosThetaO,
      axis: node.bounds.axis,
      cosThetaE: node.bounds.cosThetaE,
      childOrLight: node.childOrLight,
      parent: node.parent,
      flags: (node.leaf ? LIGHT_TREE_FLAG_LEAF : 0) | (node.bounds.twoSided ? LIGHT_TREE_FLAG_TWO_SIDED : 0),
    });
  });
  return buffer;
}
