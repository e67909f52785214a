/**
 * Moved instances without re-flattening the scene: a geometry update that only moves instances
 * (and refits) rewrites the top-level records of those instances alone, in the slots the uploaded
 * tree put them, and keeps every other record as it was. Moving 10,000 placements of shared meshes
 * then costs 10,000 records, not a pass over every flattened triangle of the scene as well.
 *
 * The records are bit for bit what flattenPrimitives + packPrimitives would write for the moved
 * scene (test/pathtracer/top-level-patch.test.ts holds the two paths to that).
 */
import { PRIMITIVE_FLAG_MIRRORED, PRIMITIVE_FLAG_SINGLE_SIDED, PRIMITIVE_SHAPE_INSTANCE } from '../../gpu-layout/constants.ts';
import { primitiveLayout } from '../../gpu-layout/records.ts';
import { PRIMITIVE_FIELD_WORDS, PRIMITIVE_WORDS, writePrimitiveGeometry } from '../../accel/triangle-packing.ts';
import type { NormalizedScene } from '../../scene/normalize-scene.ts';
import { instanceMaterial, placeTriangle, sceneBounds, sidednessBits, topLevelFirstRecords, type FlatPrimitives, type SceneBounds } from './flatten-primitives.ts';
import { bottomLevelRoots, meshBounds, placementBounds, placementTransformRecords } from './instancing.ts';
import type { PreparedScene } from './prepare-scene.ts';

/**
 * The top level after a geometry update: the whole scene flattened again (moved meshes, a
 * rebuild), or a patch of the records of the moved instances.
 */
export type TopLevelUpdate = { flat: FlatPrimitives; patch?: never } | { patch: TopLevelPatch; flat?: never };

/** The rewritten records of the moved instances, packed before anything is written. */
export interface TopLevelPatch {
  /** Slot of each rewritten record in `prepared.primitives` (the uploaded order). */
  slots: Uint32Array;
  /** One primitiveLayout record per slot. */
  records: ArrayBuffer;
  /** Every placement's transform record (placementTransformRecords), as a full flatten writes them. */
  placementTransforms: ArrayBuffer;
  instanceBounds: Float64Array;
  bounds: SceneBounds;
}

const SIDEDNESS_BITS = PRIMITIVE_FLAG_SINGLE_SIDED | PRIMITIVE_FLAG_MIRRORED;
const { v0: V0, e1: E1, e2: E2, instance: INSTANCE, primitive: PRIMITIVE, shape: SHAPE } = PRIMITIVE_FIELD_WORDS;

function copyRecord(from: Uint32Array, fromSlot: number, to: Uint32Array, toSlot: number): void {
  const a = fromSlot * PRIMITIVE_WORDS;
  const b = toSlot * PRIMITIVE_WORDS;
  for (let i = 0; i < PRIMITIVE_WORDS; i++) to[b + i] = from[a + i]!;
}

// The slot of each flat record in the uploaded order (the inverse of the build's order), kept per order.
const slotsOfOrder = new WeakMap<Uint32Array, Uint32Array>();

function slotsOf(prepared: PreparedScene): Uint32Array | null {
  const order = prepared.acceleration.order;
  // 'gpu' mode keeps the records in scene order: the slot is the flat index.
  if (!order) return null;
  let slots = slotsOfOrder.get(order);
  if (!slots) {
    slots = new Uint32Array(order.length);
    for (let s = 0; s < order.length; s++) slots[order[s]!] = s;
    slotsOfOrder.set(order, slots);
  }
  return slots;
}

/**
 * The records of `moved` instances (indices into `scene.instances`, whose transforms changed; the
 * meshes did not) for `prepared`'s uploaded top level. Reads `prepared`, writes nothing.
 */
export function patchTopLevel(scene: NormalizedScene, prepared: PreparedScene, moved: readonly number[]): TopLevelPatch {
  const plan = prepared.instancing;
  const { first, placementsFrom } = topLevelFirstRecords(scene, plan);
  const roots = prepared.bottomLevels ? bottomLevelRoots(prepared.bottomLevels) : null;
  const transformBase = prepared.placementTransforms.base;
  const slotOf = slotsOf(prepared);
  let count = 0;
  for (const i of moved) count += plan.bottomLevelOf[i]! >= 0 ? 1 : scene.meshes[scene.instances[i]!.mesh]!.triangleCount;
  const slots = new Uint32Array(count);
  const records = new ArrayBuffer(count * primitiveLayout.size);
  const f = new Float32Array(records);
  const u = new Uint32Array(records);
  const old = new Uint32Array(prepared.primitives);
  const instanceBounds = prepared.instanceBounds.slice();
  const w = new Float64Array(9);
  const g = new Float64Array(9);
  const box = new Float64Array(6);
  const objectBoxes = new Map<number, Float64Array>();
  let n = 0;
  for (const i of moved) {
    const inst = scene.instances[i]!;
    const mesh = scene.meshes[inst.mesh]!;
    const at = 6 * i;
    if (plan.bottomLevelOf[i]! >= 0) {
      // A placement: its world box in v0 and e1, its transform record's slot in e2.x, its bottom level's root.
      let objectBox = objectBoxes.get(inst.mesh);
      if (!objectBox) objectBoxes.set(inst.mesh, (objectBox = meshBounds(mesh)));
      placementBounds(inst, objectBox, box);
      const slot = slotOf ? slotOf[first[i]!]! : first[i]!;
      const o = n * PRIMITIVE_WORDS;
      for (let c = 0; c < 3; c++) {
        instanceBounds[at + c] = box[c]!;
        instanceBounds[at + 3 + c] = box[3 + c]!;
        f[o + V0 + c] = box[c]!;
        f[o + E1 + c] = box[3 + c]!;
      }
      u[o + E2] = transformBase + first[i]! - placementsFrom;
      u[o + INSTANCE] = i;
      u[o + PRIMITIVE] = roots![plan.bottomLevelOf[i]!]!;
      u[o + SHAPE] = PRIMITIVE_SHAPE_INSTANCE;
      slots[n++] = slot;
      continue;
    }
    // A flattened instance: each triangle in world space; its sidedness bits follow the handedness.
    const sides = sidednessBits(scene.materials[instanceMaterial(scene, inst)]!.doubleSided, inst);
    instanceBounds.fill(Infinity, at, at + 3);
    instanceBounds.fill(-Infinity, at + 3, at + 6);
    for (let t = 0; t < mesh.triangleCount; t++) {
      placeTriangle(mesh, inst, t, w, instanceBounds, at);
      // The f32 values flattenPrimitives stores: v0, then the edges rounded once.
      for (let c = 0; c < 3; c++) {
        g[c] = Math.fround(w[c]!);
        g[3 + c] = Math.fround(w[3 + c]! - w[c]!);
        g[6 + c] = Math.fround(w[6 + c]! - w[c]!);
      }
      const slot = slotOf ? slotOf[first[i]! + t]! : first[i]! + t;
      const o = n * PRIMITIVE_WORDS;
      // The alpha-test bits and record index are the scene's, unchanged by a move.
      const shape = (old[slot * PRIMITIVE_WORDS + SHAPE]! & ~SIDEDNESS_BITS) | sides;
      writePrimitiveGeometry(f, o, g, 0, shape);
      u[o + INSTANCE] = i;
      u[o + PRIMITIVE] = t;
      u[o + SHAPE] = shape;
      slots[n++] = slot;
    }
  }
  const placements = scene.instances.filter((_, i) => plan.bottomLevelOf[i]! >= 0);
  return { slots, records, placementTransforms: placementTransformRecords(placements), instanceBounds, bounds: sceneBounds(scene, instanceBounds) };
}

/**
 * Writes a patch into `prepared` (its records, placement transforms and instance boxes). Returns
 * the range of slots it touched, [first, end), what needs uploading.
 */
export function applyTopLevelPatch(prepared: PreparedScene, patch: TopLevelPatch): { first: number; end: number } {
  const target = new Uint32Array(prepared.primitives);
  const records = new Uint32Array(patch.records);
  let first = Infinity;
  let end = 0;
  patch.slots.forEach((slot, n) => {
    copyRecord(records, n, target, slot);
    if (slot < first) first = slot;
    if (slot + 1 > end) end = slot + 1;
  });
  prepared.placementTransforms = { base: prepared.placementTransforms.base, records: patch.placementTransforms };
  prepared.instanceBounds = patch.instanceBounds;
  return patch.slots.length === 0 ? { first: 0, end: 0 } : { first, end };
}
