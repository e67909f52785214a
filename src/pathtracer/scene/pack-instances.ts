import { INDEX_NONE, INSTANCE_FLAG_HAS_COLORS, INSTANCE_FLAG_HAS_NORMALS, INSTANCE_FLAG_HAS_TANGENTS, INSTANCE_FLAG_HAS_UV0, INSTANCE_FLAG_HAS_UV1, INSTANCE_FLAG_NEGATIVE_DETERMINANT, PRIMITIVE_SHAPE_BOX, PRIMITIVE_SHAPE_SPHERE } from '../../gpu-layout/constants.ts';
import { instanceLayout } from '../../gpu-layout/records.ts';
import { allocateStructArray, writeStruct } from '../../gpu-layout/struct-layout.ts';
import type { NormalizedScene } from '../../scene/normalize-scene.ts';
import { instanceMaterial } from './instancing.ts';
import type { PackedVertexStreams } from './pack-vertices.ts';

function rows(m: ArrayLike<number>, stride: number): [number[], number[], number[]] {
  return [0, 1, 2].map((r) => [m[r * stride]!, m[r * stride + 1]!, m[r * stride + 2]!, stride === 4 ? m[r * stride + 3]! : 0]) as [number[], number[], number[]];
}

/**
 * Instance records: mesh instances first (in scene order), then one per analytic scene object
 * (sphere: the unit sphere scaled by the radius about the centre; box: the unit cube scaled to
 * max - min at min), each pointing at its material core in the heap.
 */
export function packInstances(scene: NormalizedScene, streams: PackedVertexStreams, materialOffsets: readonly number[], objectMaterialOffsets: readonly number[], lightBase: Uint32Array): ArrayBuffer {
  const count = scene.instances.length + scene.sceneObjects.length;
  const buffer = allocateStructArray(instanceLayout, count);
  const view = new DataView(buffer);
  scene.instances.forEach((inst, i) => {
    const mesh = scene.meshes[inst.mesh]!;
    const [o0, o1, o2] = rows(inst.objectToWorld, 4);
    const [n0, n1, n2] = rows(inst.normalToWorld, 3);
    const flags =
      (inst.determinant < 0 ? INSTANCE_FLAG_NEGATIVE_DETERMINANT : 0) |
      (mesh.normals ? INSTANCE_FLAG_HAS_NORMALS : 0) |
      (mesh.tangents ? INSTANCE_FLAG_HAS_TANGENTS : 0) |
      (mesh.uvs ? INSTANCE_FLAG_HAS_UV0 : 0) |
      (mesh.uvs1 ? INSTANCE_FLAG_HAS_UV1 : 0) |
      (mesh.colors ? INSTANCE_FLAG_HAS_COLORS : 0);
    writeStruct(instanceLayout, view, i, {
      objectToWorld0: o0, objectToWorld1: o1, objectToWorld2: o2,
      normalToWorld0: n0, normalToWorld1: n1, normalToWorld2: n2,
      ...streams.streams[inst.mesh]!,
      firstIndex: streams.firstIndex[inst.mesh]!,
      material: materialOffsets[instanceMaterial(scene, inst)]!,
      flags,
      lightBase: lightBase[i]!,
      objectId: typeof inst.id === 'number' && Number.isInteger(inst.id) && inst.id >= 0 ? inst.id : i,
    });
  });
  scene.sceneObjects.forEach((object, k) => {
    const i = scene.instances.length + k;
    const sphere = object.type === 'sphere';
    const scale = sphere ? [object.b[0], object.b[0], object.b[0]] : [object.b[0] - object.a[0], object.b[1] - object.a[1], object.b[2] - object.a[2]];
    writeStruct(instanceLayout, view, i, {
      objectToWorld0: [scale[0]!, 0, 0, object.a[0]],
      objectToWorld1: [0, scale[1]!, 0, object.a[1]],
      objectToWorld2: [0, 0, scale[2]!, object.a[2]],
      normalToWorld0: [1 / scale[0]!, 0, 0, 0],
      normalToWorld1: [0, 1 / scale[1]!, 0, 0],
      normalToWorld2: [0, 0, 1 / scale[2]!, 0],
      positions: INDEX_NONE, normals: INDEX_NONE, tangents: INDEX_NONE, colors: INDEX_NONE, uv0: INDEX_NONE, uv1: INDEX_NONE,
      material: objectMaterialOffsets[k]!,
      flags: sphere ? PRIMITIVE_SHAPE_SPHERE : PRIMITIVE_SHAPE_BOX,
      lightBase: INDEX_NONE,
      objectId: i,
    });
  });
  return buffer;
}
