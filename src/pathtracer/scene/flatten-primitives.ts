import {
  INDEX_NONE,
  PRIMITIVE_ALPHA_SHIFT,
  PRIMITIVE_FLAG_ALPHA,
  PRIMITIVE_FLAG_MIRRORED,
  PRIMITIVE_FLAG_SINGLE_SIDED,
  PRIMITIVE_SHAPE_BOX,
  PRIMITIVE_SHAPE_INSTANCE,
  PRIMITIVE_SHAPE_SPHERE,
  PRIMITIVE_SHAPE_TRIANGLE,
} from '../../gpu-layout/constants.ts';
import { alphaPrimitiveLayout } from '../../gpu-layout/records.ts';
import { allocateStructArray } from '../../gpu-layout/struct-layout.ts';
import type { NormalizedInstance } from '../../scene/instance.ts';
import type { NormalizedScene } from '../../scene/normalize-scene.ts';
import { writeAlphaRecord } from './alpha-records.ts';
import { instanceMaterial, meshBounds, placementBounds, placementTransformRecords, type InstancingPlan } from './instancing.ts';
import type { TextureInfoOffsets } from './pack-materials.ts';

export { instanceMaterial } from './instancing.ts';

/**
 * The top level's primitives in world space, before BVH ordering: the triangles of every flattened
 * instance (transforms applied), one record per placement of a shared mesh (its world box; the
 * mesh's triangles are in its bottom level, instancing.ts), then the analytic scene objects.
 * `boundsTriangles` feeds the BVH builder (a box is given as the triangle (min, max, max), whose
 * bounding box it is).
 */
export interface FlatPrimitives {
  count: number;
  boundsTriangles: Float32Array;
  /** Per primitive: v0 and either the edges (triangles) or the shape parameters, 9 floats. */
  geometry: Float32Array;
  instance: Uint32Array;
  primitive: Uint32Array;
  shape: Uint32Array;
  alphaPrimitives: ArrayBuffer;
  alphaCount: number;
  /** One transform record per placement (placementTransformRecords), for slots from `placementTransformBase`. */
  placementTransforms: ArrayBuffer;
  placementTransformBase: number;
  /** World box of each instance's geometry (6 per instance: min, max; empty: +inf, -inf): what a patch keeps of unmoved instances. */
  instanceBounds: Float64Array;
  bounds: SceneBounds;
}

export interface SceneBounds {
  min: [number, number, number];
  max: [number, number, number];
}

/** The scene's world box: the instances' boxes and the analytic objects (a zero box when empty). */
export function sceneBounds(scene: NormalizedScene, instanceBounds: Float64Array): SceneBounds {
  const min: [number, number, number] = [Infinity, Infinity, Infinity];
  const max: [number, number, number] = [-Infinity, -Infinity, -Infinity];
  const grow = (box: ArrayLike<number>, at: number): void => {
    for (let c = 0; c < 3; c++) {
      if (box[at + c]! < min[c]!) min[c] = box[at + c]!;
      if (box[at + 3 + c]! > max[c]!) max[c] = box[at + 3 + c]!;
    }
  };
  for (let i = 0; i < scene.instances.length; i++) grow(instanceBounds, 6 * i);
  for (const object of scene.sceneObjects) grow(objectBox(object), 0);
  return min[0] <= max[0] ? { min, max } : { min: [0, 0, 0], max: [0, 0, 0] };
}

function objectBox(object: NormalizedScene['sceneObjects'][number]): number[] {
  const lo = object.type === 'sphere' ? object.a.map((c) => c - object.b[0]) : object.a;
  const hi = object.type === 'sphere' ? object.a.map((c) => c + object.b[0]) : object.b;
  return [...lo, ...hi];
}

/**
 * The index of each instance's first top-level record in flattenPrimitives' order: the flattened
 * instances' triangles in scene order, then (from `placementsFrom`) one record per placement of a
 * shared mesh.
 */
export function topLevelFirstRecords(scene: NormalizedScene, plan: InstancingPlan): { first: Uint32Array; placementsFrom: number } {
  const first = new Uint32Array(scene.instances.length);
  let k = 0;
  scene.instances.forEach((inst, i) => {
    if (plan.bottomLevelOf[i]! >= 0) return;
    first[i] = k;
    k += scene.meshes[inst.mesh]!.triangleCount;
  });
  const placementsFrom = k;
  scene.instances.forEach((_, i) => {
    if (plan.bottomLevelOf[i]! >= 0) first[i] = k++;
  });
  return { first, placementsFrom };
}

/**
 * The world-space triangle t of a flattened instance into `w` (9 f64: v0, v1, v2), and its corners
 * grown into the instance's box (`bounds` at 6 i).
 */
export function placeTriangle(mesh: NormalizedScene['meshes'][number], inst: NormalizedInstance, t: number, w: Float64Array, bounds: Float64Array, at: number): void {
  for (let c = 0; c < 3; c++) {
    const v = mesh.indices[3 * t + c]!;
    transformPoint(inst, mesh.positions[3 * v]!, mesh.positions[3 * v + 1]!, mesh.positions[3 * v + 2]!, w, 3 * c);
    for (let a = 0; a < 3; a++) {
      const x = w[3 * c + a]!;
      if (x < bounds[at + a]!) bounds[at + a] = x;
      if (x > bounds[at + 3 + a]!) bounds[at + 3 + a] = x;
    }
  }
}

/** The instance's sidedness and handedness bits of its triangle records (back-face culling, bvh-traversal.wesl). */
export function sidednessBits(doubleSided: boolean, inst: NormalizedInstance): number {
  return (doubleSided ? 0 : PRIMITIVE_FLAG_SINGLE_SIDED) | (inst.determinant < 0 ? PRIMITIVE_FLAG_MIRRORED : 0);
}

const EMPTY_BOX = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];

export function transformPoint(inst: NormalizedInstance, x: number, y: number, z: number, out: Float64Array, at: number): void {
  const m = inst.objectToWorld;
  out[at] = m[0]! * x + m[1]! * y + m[2]! * z + m[3]!;
  out[at + 1] = m[4]! * x + m[5]! * y + m[6]! * z + m[7]!;
  out[at + 2] = m[8]! * x + m[9]! * y + m[10]! * z + m[11]!;
}

/**
 * `bottomLevelRoots`: the root node of each of the plan's bottom levels (null when it has none),
 * which the placements' top-level records name.
 */
export function flattenPrimitives(scene: NormalizedScene, infoOffset: TextureInfoOffsets, plan: InstancingPlan, bottomLevelRoots: Uint32Array | null = null): FlatPrimitives {
  // An empty scene still needs one record: a zero triangle every traversal rejects.
  const count = plan.topPrimitiveCount;
  const boundsTriangles = new Float32Array(count * 9);
  const geometry = new Float32Array(count * 9);
  const instance = new Uint32Array(count).fill(INDEX_NONE);
  const primitive = new Uint32Array(count);
  const shape = new Uint32Array(count);
  const instanceBounds = new Float64Array(6 * scene.instances.length);
  for (let i = 0; i < scene.instances.length; i++) instanceBounds.set(EMPTY_BOX, 6 * i);
  let alphaCount = 0;
  scene.instances.forEach((inst, i) => {
    const mesh = scene.meshes[inst.mesh]!;
    const material = scene.materials[instanceMaterial(scene, inst)]!;
    if (material.alphaMode !== 'OPAQUE' && plan.bottomLevelOf[i]! < 0) alphaCount += mesh.triangleCount;
  });
  const alphaPrimitives = allocateStructArray(alphaPrimitiveLayout, alphaCount);
  const alphaView = new DataView(alphaPrimitives);
  let alphaIndex = 0;
  const w = new Float64Array(9);
  let k = 0;
  const boxes = new Map<number, Float64Array>();
  const box = new Float64Array(6);
  const placements: number[] = [];
  scene.instances.forEach((inst, instanceIndex) => {
    if (plan.bottomLevelOf[instanceIndex]! >= 0) {
      placements.push(instanceIndex);
      return;
    }
    const mesh = scene.meshes[inst.mesh]!;
    const material = scene.materials[instanceMaterial(scene, inst)]!;
    const alpha = material.alphaMode !== 'OPAQUE';
    const sides = sidednessBits(material.doubleSided, inst);
    for (let t = 0; t < mesh.triangleCount; t++, k++) {
      placeTriangle(mesh, inst, t, w, instanceBounds, 6 * instanceIndex);
      const o = 9 * k;
      for (let i = 0; i < 9; i++) boundsTriangles[o + i] = w[i]!;
      geometry[o] = w[0]!;
      geometry[o + 1] = w[1]!;
      geometry[o + 2] = w[2]!;
      for (let i = 0; i < 3; i++) {
        geometry[o + 3 + i] = w[3 + i]! - w[i]!;
        geometry[o + 6 + i] = w[6 + i]! - w[i]!;
      }
      instance[k] = instanceIndex;
      primitive[k] = t;
      shape[k] = PRIMITIVE_SHAPE_TRIANGLE | sides;
      if (alpha) {
        writeAlphaRecord(alphaView, alphaIndex, mesh, material, t, infoOffset);
        shape[k] = PRIMITIVE_SHAPE_TRIANGLE | sides | PRIMITIVE_FLAG_ALPHA | (alphaIndex << PRIMITIVE_ALPHA_SHIFT);
        alphaIndex++;
      }
    }
  });
  const placementTransformBase = plan.topPrimitiveCount + plan.bottomLevelTriangles;
  const geometryBits = new Uint32Array(geometry.buffer);
  for (const [ordinal, instanceIndex] of placements.entries()) {
    const inst = scene.instances[instanceIndex]!;
    let objectBox = boxes.get(inst.mesh);
    if (!objectBox) boxes.set(inst.mesh, (objectBox = meshBounds(scene.meshes[inst.mesh]!)));
    placementBounds(inst, objectBox, box);
    const o = 9 * k;
    for (let c = 0; c < 3; c++) {
      boundsTriangles[o + c] = box[c]!;
      boundsTriangles[o + 3 + c] = box[3 + c]!;
      boundsTriangles[o + 6 + c] = box[3 + c]!;
      geometry[o + c] = box[c]!;
      geometry[o + 3 + c] = box[3 + c]!;
    }
    geometryBits[o + 6] = placementTransformBase + ordinal;
    instanceBounds.set(box, 6 * instanceIndex);
    instance[k] = instanceIndex;
    primitive[k] = bottomLevelRoots ? bottomLevelRoots[plan.bottomLevelOf[instanceIndex]!]! : INDEX_NONE;
    shape[k] = PRIMITIVE_SHAPE_INSTANCE;
    k++;
  }
  scene.sceneObjects.forEach((object, i) => {
    const o = 9 * k;
    const box = objectBox(object);
    boundsTriangles.set([...box, ...box.slice(3)], o);
    geometry.set([...object.a, ...object.b, 0, 0, 0], o);
    instance[k] = scene.instances.length + i;
    primitive[k] = 0;
    shape[k] = object.type === 'sphere' ? PRIMITIVE_SHAPE_SPHERE : PRIMITIVE_SHAPE_BOX;
    k++;
  });
  return {
    count,
    boundsTriangles,
    geometry,
    instance,
    primitive,
    shape,
    alphaPrimitives,
    alphaCount,
    placementTransforms: placementTransformRecords(placements.map((i) => scene.instances[i]!)),
    placementTransformBase,
    instanceBounds,
    bounds: sceneBounds(scene, instanceBounds),
  };
}
