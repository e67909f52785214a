/**
 * Two-level acceleration: which placements of a mesh share one bottom-level tree, and those trees.
 *
 * A mesh placed many times (reused glTF nodes, EXT_mesh_gpu_instancing, `instances` of the scene
 * API) is stored once, in object space, with a BVH of its own (a bottom level); each placement is
 * one primitive of the top-level tree (PRIMITIVE_SHAPE_INSTANCE: its world box), and a ray that
 * reaches it continues in the mesh's object space (bvh-traversal.wesl). Memory and build time then
 * grow with unique geometry, plus one small record per placement, as in pbrt-v4's
 * BVHAggregate over `Instance`s or Embree's two-level scenes. Everything else (meshes placed once,
 * analytic shapes) stays flattened into the top level in world space, where traversal is
 * fastest, so a scene without shared meshes is traced exactly as before.
 *
 * A bottom level is keyed by its mesh and what the traversal reads of the material (alpha test,
 * sidedness), so placements with different opaque materials share one tree.
 */
import { buildBvhAsync } from '../../accel/bvh-builder.ts';
import { bvhParentLinks, packPrimitives, packWavefrontBvhNodes } from '../../accel/triangle-packing.ts';
import { INDEX_NONE, PRIMITIVE_ALPHA_SHIFT, PRIMITIVE_FLAG_ALPHA, PRIMITIVE_FLAG_SINGLE_SIDED, PRIMITIVE_SHAPE_TRIANGLE } from '../../gpu-layout/constants.ts';
import { alphaPrimitiveLayout, bvhNodeLayout, instanceLayout, primitiveLayout } from '../../gpu-layout/records.ts';
import { allocateStructArray, fieldOf } from '../../gpu-layout/struct-layout.ts';
import type { NormalizedInstance } from '../../scene/instance.ts';
import type { NormalizedMesh } from '../../scene/mesh.ts';
import type { NormalizedScene } from '../../scene/normalize-scene.ts';
import { writeAlphaRecord } from './alpha-records.ts';
import type { TextureInfoOffsets } from './pack-materials.ts';

/**
 * How placements of meshes are traced: 'auto' (default) gives a mesh its own bottom-level tree when
 * it is placed more than once and its copies would add at least `autoInstancingMinTriangles`
 * triangles; 'off' flattens every placement into world-space triangles (one tree); 'always' traces
 * every mesh placement through a bottom level.
 */
export type InstancingMode = 'auto' | 'off' | 'always';

export const instancingModes: readonly InstancingMode[] = ['auto', 'off', 'always'];

/**
 * 'auto' keeps a repeated mesh flat below this many added triangles: a few copies of a small part
 * cost less memory than they save in traversal (each entry into a bottom level transforms the ray).
 */
export const autoInstancingMinTriangles = 1024;

/** One bottom-level tree: a mesh under one alpha/sidedness key. */
export interface BottomLevelSpec {
  mesh: number;
  /** The material whose alpha test and sidedness the tree's triangles carry. */
  material: number;
  placements: number;
}

export interface InstancingPlan {
  mode: InstancingMode;
  /** Per scene instance: its bottom level, or -1 when its triangles are in the top level. */
  bottomLevelOf: Int32Array;
  bottomLevels: BottomLevelSpec[];
  /** Triangles flattened into the top level. */
  flattenedTriangles: number;
  /** Placements traced through a bottom level. */
  placements: number;
  /** Triangles stored once in bottom levels. */
  bottomLevelTriangles: number;
  /** Records of the top level: flattened triangles, placements and analytic shapes (at least 1). */
  topPrimitiveCount: number;
  /** Alpha-tested triangles over the top level and the bottom levels. */
  alphaTriangles: number;
  /** Alpha-tested triangles flattened into the top level. */
  topAlphaTriangles: number;
}

/** Instance material: its override or its mesh's. */
export function instanceMaterial(scene: NormalizedScene, inst: NormalizedInstance): number {
  return inst.material ?? scene.meshMaterials[inst.mesh]!;
}

function alphaTested(scene: NormalizedScene, material: number): boolean {
  return scene.materials[material]!.alphaMode !== 'OPAQUE';
}

export function planInstancing(scene: NormalizedScene, mode: InstancingMode = 'auto'): InstancingPlan {
  const keyOf = (inst: NormalizedInstance): string => {
    const material = instanceMaterial(scene, inst);
    const m = scene.materials[material]!;
    return m.alphaMode !== 'OPAQUE' ? `${inst.mesh}/alpha ${material}` : `${inst.mesh}/${m.doubleSided ? 'double' : 'single'}`;
  };
  const groups = new Map<string, number[]>();
  scene.instances.forEach((inst, i) => {
    const key = keyOf(inst);
    const group = groups.get(key);
    if (group) group.push(i);
    else groups.set(key, [i]);
  });
  const bottomLevelOf = new Int32Array(scene.instances.length).fill(-1);
  const bottomLevels: BottomLevelSpec[] = [];
  let flattenedTriangles = 0;
  let bottomLevelTriangles = 0;
  let alphaTriangles = 0;
  let topAlphaTriangles = 0;
  for (const members of groups.values()) {
    const first = scene.instances[members[0]!]!;
    const triangles = scene.meshes[first.mesh]!.triangleCount;
    const material = instanceMaterial(scene, first);
    const alpha = alphaTested(scene, material);
    const shared = mode === 'always' || (mode === 'auto' && members.length > 1 && (members.length - 1) * triangles >= autoInstancingMinTriangles);
    if (!shared || triangles === 0) {
      flattenedTriangles += members.length * triangles;
      if (alpha) {
        alphaTriangles += members.length * triangles;
        topAlphaTriangles += members.length * triangles;
      }
      continue;
    }
    for (const i of members) bottomLevelOf[i] = bottomLevels.length;
    bottomLevels.push({ mesh: first.mesh, material, placements: members.length });
    bottomLevelTriangles += triangles;
    if (alpha) alphaTriangles += triangles;
  }
  const placements = bottomLevels.reduce((sum, b) => sum + b.placements, 0);
  const topPrimitiveCount = Math.max(1, flattenedTriangles + placements + scene.sceneObjects.length);
  return { mode, bottomLevelOf, bottomLevels, flattenedTriangles, placements, bottomLevelTriangles, topPrimitiveCount, alphaTriangles, topAlphaTriangles };
}

/** Upper bound of BVH nodes over the top level and every bottom level (a binary tree over n has 2n - 1). */
/** Records of the primitive buffer: the top level, the bottom levels' triangles and the placements' transforms. */
export function primitiveRecordCount(plan: InstancingPlan): number {
  return plan.topPrimitiveCount + plan.bottomLevelTriangles + plan.placements;
}

export function bvhNodeCapacity(plan: InstancingPlan): number {
  return 2 * plan.topPrimitiveCount - 1 + 2 * plan.bottomLevelTriangles - plan.bottomLevels.length;
}

// Boxes per positions array: every flatten and every patch of moved placements needs them, and a
// geometry update that moves a mesh gives it a new positions array.
const boxesOfPositions = new WeakMap<object, Float64Array>();

/** Object-space box of a mesh's positions (min xyz, max xyz); read only (it is shared). */
export function meshBounds(mesh: NormalizedMesh): Float64Array {
  const cached = boxesOfPositions.get(mesh.positions);
  if (cached) return cached;
  const b = new Float64Array([Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity]);
  const p = mesh.positions;
  for (let v = 0; v < mesh.vertexCount; v++) {
    for (let c = 0; c < 3; c++) {
      const x = p[3 * v + c]!;
      if (x < b[c]!) b[c] = x;
      if (x > b[3 + c]!) b[3 + c] = x;
    }
  }
  boxesOfPositions.set(mesh.positions, b);
  return b;
}

/**
 * World box of a placement from its mesh's object box (Arvo, "Transforming Axis-Aligned Bounding
 * Boxes", Graphics Gems 1990: centre through the matrix, half extent through its absolute value),
 * widened by a few f32 ulps so the box the traversal tests holds every f32-rounded triangle.
 */
export function placementBounds(inst: NormalizedInstance, box: Float64Array, out: Float64Array): void {
  const m = inst.objectToWorld;
  for (let r = 0; r < 3; r++) {
    let centre = m[4 * r + 3]!;
    let extent = 0;
    for (let c = 0; c < 3; c++) {
      centre += m[4 * r + c]! * 0.5 * (box[c]! + box[3 + c]!);
      extent += Math.abs(m[4 * r + c]!) * 0.5 * (box[3 + c]! - box[c]!);
    }
    const pad = 4 * 2 ** -23 * (Math.abs(centre) + extent);
    out[r] = centre - extent - pad;
    out[3 + r] = centre + extent + pad;
  }
}

/** The inverse of an instance's object-to-world rows (rows of a 3x4 affine matrix). */
export function worldToObjectRows(inst: NormalizedInstance): [number[], number[], number[]] {
  // normalToWorld is inverse(A)^T, so row r of inverse(A) is column r of normalToWorld.
  const n = inst.normalToWorld;
  const m = inst.objectToWorld;
  const t = [m[3]!, m[7]!, m[11]!];
  return [0, 1, 2].map((r) => {
    const row = [n[r]!, n[3 + r]!, n[6 + r]!];
    return [...row, -(row[0]! * t[0]! + row[1]! * t[1]! + row[2]! * t[2]!)];
  }) as [number[], number[], number[]];
}

/**
 * A placement's world-to-object transform as one record of the primitive buffer (its one record
 * type): the rows' linear parts in v0, e1, e2 and the bits of their translations in instance,
 * primitive, shape (bvh-traversal.wesl's object_ray reads them back).
 */
export function placementTransformRecords(placements: readonly NormalizedInstance[]): ArrayBuffer {
  const out = new ArrayBuffer(placements.length * primitiveLayout.size);
  const f = new Float32Array(out);
  const rows = [fieldOf(primitiveLayout, 'v0').offset / 4, fieldOf(primitiveLayout, 'e1').offset / 4, fieldOf(primitiveLayout, 'e2').offset / 4];
  const translations = [fieldOf(primitiveLayout, 'instance').offset / 4, fieldOf(primitiveLayout, 'primitive').offset / 4, fieldOf(primitiveLayout, 'shape').offset / 4];
  placements.forEach((inst, k) => {
    const o = k * (primitiveLayout.size / 4);
    // Row r of inverse(A) is column r of normalToWorld (inverse(A)^T); the translation is -inverse(A) t.
    const n = inst.normalToWorld;
    const m = inst.objectToWorld;
    for (let r = 0; r < 3; r++) {
      const x = n[r]!, y = n[3 + r]!, z = n[6 + r]!;
      f[o + rows[r]!] = x;
      f[o + rows[r]! + 1] = y;
      f[o + rows[r]! + 2] = z;
      // The translation's f32 bits go into the record's u32 word.
      f[o + translations[r]!] = -(x * m[3]! + y * m[7]! + z * m[11]!);
    }
  });
  return out;
}

/** The bottom-level trees of a scene, laid out after the top level in the shared buffers. */
export interface BottomLevels {
  /** Slot of the first bottom-level primitive (the top level's record count). */
  primitiveBase: number;
  /** Node of the first bottom-level tree (room for any top-level tree: 2n - 1 nodes). */
  nodeBase: number;
  /** Primitive records of every bottom level, object space, in tree order. */
  primitives: ArrayBuffer;
  /** Node records with absolute child and primitive indices. */
  nodes: ArrayBuffer;
  /** Absolute parent links (INDEX_NONE at each root). */
  parents: Uint32Array;
  /** Per bottom level: its root node, first slot and node count, and its build's primitive order. */
  levels: { root: number; firstSlot: number; nodeCount: number; depth: number; order: Uint32Array }[];
  /** Alpha records of bottom-level triangles (after the top level's `alphaStart` records). */
  alphaPrimitives: ArrayBuffer;
  buildTimeMs: number;
}

const NODE_WORDS = bvhNodeLayout.size / 4;

/** Object-space triangles of a mesh as the builder's 9-float soup. */
function meshTriangles(mesh: NormalizedMesh): Float32Array {
  const out = new Float32Array(9 * mesh.triangleCount);
  for (let t = 0; t < mesh.triangleCount; t++) {
    for (let c = 0; c < 3; c++) {
      const v = mesh.indices[3 * t + c]!;
      out.set(mesh.positions.subarray(3 * v, 3 * v + 3), 9 * t + 3 * c);
    }
  }
  return out;
}

/** Per-triangle primitive fields of one bottom level, in mesh order (packPrimitives reorders them). */
function bottomLevelRecords(scene: NormalizedScene, spec: BottomLevelSpec, infoOffset: TextureInfoOffsets, alpha: { view: DataView; local: number; absolute: number }): { geometry: Float32Array; instance: Uint32Array; primitive: Uint32Array; shape: Uint32Array; alphaCount: number } {
  const mesh = scene.meshes[spec.mesh]!;
  const material = scene.materials[spec.material]!;
  const n = mesh.triangleCount;
  const triangles = meshTriangles(mesh);
  const geometry = new Float32Array(9 * n);
  for (let t = 0; t < n; t++) {
    for (let c = 0; c < 3; c++) {
      const v0 = triangles[9 * t + c]!;
      geometry[9 * t + c] = v0;
      geometry[9 * t + 3 + c] = triangles[9 * t + 3 + c]! - v0;
      geometry[9 * t + 6 + c] = triangles[9 * t + 6 + c]! - v0;
    }
  }
  const shape = new Uint32Array(n);
  const sides = material.doubleSided ? 0 : PRIMITIVE_FLAG_SINGLE_SIDED;
  const alphaTest = material.alphaMode !== 'OPAQUE';
  for (let t = 0; t < n; t++) {
    shape[t] = PRIMITIVE_SHAPE_TRIANGLE | sides;
    if (alphaTest) {
      writeAlphaRecord(alpha.view, alpha.local + t, mesh, material, t, infoOffset);
      shape[t] |= PRIMITIVE_FLAG_ALPHA | ((alpha.absolute + t) << PRIMITIVE_ALPHA_SHIFT);
    }
  }
  return { geometry, instance: new Uint32Array(n).fill(INDEX_NONE), primitive: Uint32Array.from({ length: n }, (_, i) => i), shape, alphaCount: alphaTest ? n : 0 };
}

/**
 * Builds every bottom level on the CPU (binned SAH, bvh-builder.ts) and lays them out after a top
 * level of `plan.topPrimitiveCount` records. `alphaStart` is the number of records of the top
 * level's alpha buffer (at least one, even when no top-level triangle is alpha tested).
 */
export async function buildBottomLevels(
  scene: NormalizedScene,
  plan: InstancingPlan,
  infoOffset: TextureInfoOffsets,
  alphaStart: number,
  options: { signal?: AbortSignal } = {},
): Promise<BottomLevels> {
  const started = performance.now();
  const primitiveBase = plan.topPrimitiveCount;
  const nodeBase = 2 * plan.topPrimitiveCount - 1;
  const alphaCount = plan.bottomLevels.reduce((sum, b) => sum + (alphaTested(scene, b.material) ? scene.meshes[b.mesh]!.triangleCount : 0), 0);
  const alphaPrimitives = allocateStructArray(alphaPrimitiveLayout, alphaCount);
  const alphaView = new DataView(alphaPrimitives);
  const built: { prims: ArrayBuffer; nodes: ArrayBuffer; nodeCount: number; depth: number; order: Uint32Array }[] = [];
  // Bottom-level alpha records follow the top level's alphaStart records in the shared buffer.
  let alphaLocal = 0;
  for (const spec of plan.bottomLevels) {
    const mesh = scene.meshes[spec.mesh]!;
    const records = bottomLevelRecords(scene, spec, infoOffset, { view: alphaView, local: alphaLocal, absolute: alphaStart + alphaLocal });
    alphaLocal += records.alphaCount;
    const bvh = await buildBvhAsync(meshTriangles(mesh), options.signal ? { signal: options.signal } : {});
    built.push({ prims: packPrimitives(records, bvh.triangleOrder), nodes: packWavefrontBvhNodes(bvh), nodeCount: Math.max(1, bvh.nodeCount), depth: bvh.depth, order: bvh.triangleOrder });
  }
  const totalSlots = plan.bottomLevelTriangles;
  const totalNodes = built.reduce((sum, b) => sum + b.nodeCount, 0);
  const primitives = new Uint8Array(totalSlots * primitiveLayout.size);
  const nodes = new Uint32Array(totalNodes * NODE_WORDS);
  const parents = new Uint32Array(totalNodes);
  const levels: BottomLevels['levels'] = [];
  let slot = 0;
  let node = 0;
  for (const b of built) {
    const slots = b.order.length;
    primitives.set(new Uint8Array(b.prims, 0, slots * primitiveLayout.size), slot * primitiveLayout.size);
    const local = new Uint32Array(b.nodes, 0, b.nodeCount * NODE_WORDS);
    const localParents = bvhParentLinks(b.nodes, b.nodeCount);
    for (let i = 0; i < b.nodeCount; i++) {
      const o = (node + i) * NODE_WORDS;
      nodes.set(local.subarray(i * NODE_WORDS, (i + 1) * NODE_WORDS), o);
      // Children and leaf slots become absolute indices into the shared buffers.
      const leaf = local[i * NODE_WORDS + 7]! > 0;
      nodes[o + 3] = local[i * NODE_WORDS + 3]! + (leaf ? primitiveBase + slot : nodeBase + node);
      parents[node + i] = localParents[i] === INDEX_NONE ? INDEX_NONE : localParents[i]! + nodeBase + node;
    }
    levels.push({ root: nodeBase + node, firstSlot: primitiveBase + slot, nodeCount: b.nodeCount, depth: b.depth, order: b.order });
    slot += slots;
    node += b.nodeCount;
  }
  return { primitiveBase, nodeBase, primitives: primitives.buffer, nodes: nodes.buffer, parents, levels, alphaPrimitives, buildTimeMs: performance.now() - started };
}

/**
 * Bottom levels after their meshes moved (skinning, morphing; same triangles): the records are
 * packed again in each tree's order and every box is recomputed bottom-up, keeping the topology
 * (a refit, as the GPU refit does for the top level). Only the levels of `meshes` change.
 */
export function refitBottomLevels(scene: NormalizedScene, plan: InstancingPlan, bottom: BottomLevels, meshes: ReadonlySet<number>): void {
  const f = new Float32Array(bottom.primitives);
  const words = primitiveLayout.size / 4;
  const at = { v0: fieldOf(primitiveLayout, 'v0').offset / 4, e1: fieldOf(primitiveLayout, 'e1').offset / 4, e2: fieldOf(primitiveLayout, 'e2').offset / 4 };
  const nodes = new Float32Array(bottom.nodes);
  const nodeWords = new Uint32Array(bottom.nodes);
  plan.bottomLevels.forEach((spec, k) => {
    if (!meshes.has(spec.mesh)) return;
    const level = bottom.levels[k]!;
    const triangles = meshTriangles(scene.meshes[spec.mesh]!);
    const firstLocal = level.firstSlot - bottom.primitiveBase;
    for (let s = 0; s < level.order.length; s++) {
      const t = level.order[s]!;
      const o = (firstLocal + s) * words;
      for (let c = 0; c < 3; c++) {
        const v0 = triangles[9 * t + c]!;
        f[o + at.v0 + c] = v0;
        f[o + at.e1 + c] = triangles[9 * t + 3 + c]! - v0;
        f[o + at.e2 + c] = triangles[9 * t + 6 + c]! - v0;
      }
    }
    // Reversed pre-order visits every child before its parent.
    const preorder: number[] = [];
    const stack = [level.root - bottom.nodeBase];
    while (stack.length > 0) {
      const i = stack.pop()!;
      preorder.push(i);
      if (nodeWords[i * NODE_WORDS + 7] === 0) {
        const left = nodeWords[i * NODE_WORDS + 3]! - bottom.nodeBase;
        stack.push(left, left + 1);
      }
    }
    for (let k = preorder.length - 1; k >= 0; k--) {
      const o = preorder[k]! * NODE_WORDS;
      const count = nodeWords[o + 7]!;
      const lo = [Infinity, Infinity, Infinity];
      const hi = [-Infinity, -Infinity, -Infinity];
      if (count > 0) {
        const first = nodeWords[o + 3]! - bottom.primitiveBase;
        for (let s = first; s < first + count; s++) {
          for (let v = 0; v < 3; v++) {
            for (let c = 0; c < 3; c++) {
              const x = f[s * words + at.v0 + c]! + (v === 0 ? 0 : f[s * words + (v === 1 ? at.e1 : at.e2) + c]!);
              lo[c] = Math.min(lo[c]!, x);
              hi[c] = Math.max(hi[c]!, x);
            }
          }
        }
      } else {
        const left = nodeWords[o + 3]! - bottom.nodeBase;
        for (const child of [left, left + 1]) {
          for (let c = 0; c < 3; c++) {
            lo[c] = Math.min(lo[c]!, nodes[child * NODE_WORDS + c]!);
            hi[c] = Math.max(hi[c]!, nodes[child * NODE_WORDS + 4 + c]!);
          }
        }
      }
      for (let c = 0; c < 3; c++) {
        nodes[o + c] = lo[c]!;
        nodes[o + 4 + c] = hi[c]!;
      }
    }
  });
}

export interface WavefrontInstancingStats {
  mode: InstancingMode;
  /** Meshes stored once with a bottom-level tree (per alpha/sidedness key). */
  sharedMeshes: number;
  /** Placements traced through a bottom level. */
  placements: number;
  /** Triangles stored once in bottom levels (they stand for `placedTriangles`). */
  bottomLevelTriangles: number;
  placedTriangles: number;
  /** Triangles flattened into the top level in world space. */
  flattenedTriangles: number;
  /** Records of the top-level tree: flattened triangles, placements and analytic shapes. */
  topLevelRecords: number;
  /** GPU bytes each placement adds: its instance record, its top-level and transform records and about two tree nodes. */
  bytesPerPlacement: number;
}

/** What the renderer reports of a plan (WavefrontInstancingStats). */
export function instancingStats(scene: NormalizedScene, plan: InstancingPlan): WavefrontInstancingStats {
  let placedTriangles = 0;
  scene.instances.forEach((inst, i) => {
    if (plan.bottomLevelOf[i]! >= 0) placedTriangles += scene.meshes[inst.mesh]!.triangleCount;
  });
  return {
    mode: plan.mode,
    sharedMeshes: plan.bottomLevels.length,
    placements: plan.placements,
    bottomLevelTriangles: plan.bottomLevelTriangles,
    placedTriangles,
    flattenedTriangles: plan.flattenedTriangles,
    topLevelRecords: plan.topPrimitiveCount,
    bytesPerPlacement: instanceLayout.size + 2 * primitiveLayout.size + 2 * (bvhNodeLayout.size + 4),
  };
}

/** Per bottom level of `bottom`: its root node. */
export function bottomLevelRoots(bottom: BottomLevels): Uint32Array {
  return Uint32Array.from(bottom.levels, (l) => l.root);
}
