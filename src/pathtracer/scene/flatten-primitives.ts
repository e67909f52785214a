import {
  ALPHA_MODE_BLEND,
  ALPHA_MODE_MASK,
  INDEX_NONE,
  PRIMITIVE_ALPHA_SHIFT,
  PRIMITIVE_FLAG_ALPHA,
  PRIMITIVE_FLAG_MIRRORED,
  PRIMITIVE_FLAG_SINGLE_SIDED,
  PRIMITIVE_SHAPE_BOX,
  PRIMITIVE_SHAPE_SPHERE,
  PRIMITIVE_SHAPE_TRIANGLE,
} from '../../gpu-layout/constants.ts';
import { alphaPrimitiveLayout } from '../../gpu-layout/records.ts';
import { allocateStructArray, writeStruct } from '../../gpu-layout/struct-layout.ts';
import type { NormalizedInstance } from '../../scene/instance.ts';
import type { NormalizedScene } from '../../scene/normalize-scene.ts';
import { applyTextureTransform } from '../../scene/texture-transform.ts';
import type { TextureInfoOffsets } from './pack-materials.ts';

/**
 * Every traceable primitive in world space, before BVH ordering: the triangles of every instance
 * (transforms applied) followed by the analytic scene objects. `boundsTriangles` feeds the BVH
 * builder (a shape is given as the triangle (min, max, max), whose bounding box is the shape's).
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
  bounds: { min: [number, number, number]; max: [number, number, number] };
}

export function transformPoint(inst: NormalizedInstance, x: number, y: number, z: number, out: Float64Array, at: number): void {
  const m = inst.objectToWorld;
  out[at] = m[0]! * x + m[1]! * y + m[2]! * z + m[3]!;
  out[at + 1] = m[4]! * x + m[5]! * y + m[6]! * z + m[7]!;
  out[at + 2] = m[8]! * x + m[9]! * y + m[10]! * z + m[11]!;
}

/** Instance material: its override or its mesh's. */
export function instanceMaterial(scene: NormalizedScene, inst: NormalizedInstance): number {
  return inst.material ?? scene.meshMaterials[inst.mesh]!;
}

export function flattenPrimitives(scene: NormalizedScene, infoOffset: TextureInfoOffsets): FlatPrimitives {
  const objectCount = scene.sceneObjects.length;
  // An empty scene still needs one record: a zero triangle every traversal rejects.
  const count = Math.max(1, scene.triangleCount + objectCount);
  const boundsTriangles = new Float32Array(count * 9);
  const geometry = new Float32Array(count * 9);
  const instance = new Uint32Array(count).fill(INDEX_NONE);
  const primitive = new Uint32Array(count);
  const shape = new Uint32Array(count);
  const min: [number, number, number] = [Infinity, Infinity, Infinity];
  const max: [number, number, number] = [-Infinity, -Infinity, -Infinity];
  const grow = (x: number, y: number, z: number): void => {
    if (x < min[0]) min[0] = x;
    if (y < min[1]) min[1] = y;
    if (z < min[2]) min[2] = z;
    if (x > max[0]) max[0] = x;
    if (y > max[1]) max[1] = y;
    if (z > max[2]) max[2] = z;
  };
  let alphaCount = 0;
  scene.instances.forEach((inst) => {
    const mesh = scene.meshes[inst.mesh]!;
    const material = scene.materials[instanceMaterial(scene, inst)]!;
    if (material.alphaMode !== 'OPAQUE') alphaCount += mesh.triangleCount;
  });
  const alphaPrimitives = allocateStructArray(alphaPrimitiveLayout, alphaCount);
  const alphaView = new DataView(alphaPrimitives);
  let alphaIndex = 0;
  const w = new Float64Array(9);
  let k = 0;
  scene.instances.forEach((inst, instanceIndex) => {
    const mesh = scene.meshes[inst.mesh]!;
    const material = scene.materials[instanceMaterial(scene, inst)]!;
    const alpha = material.alphaMode !== 'OPAQUE';
    // Back-face culling of camera rays (bvh-traversal.wesl) needs the material's sidedness and the
    // instance's handedness.
    const sides = (material.doubleSided ? 0 : PRIMITIVE_FLAG_SINGLE_SIDED) | (inst.determinant < 0 ? PRIMITIVE_FLAG_MIRRORED : 0);
    const texture = material.baseColorTexture;
    const uvs = texture ? (texture.texCoord === 1 ? mesh.uvs1 : mesh.uvs) : null;
    for (let t = 0; t < mesh.triangleCount; t++, k++) {
      for (let c = 0; c < 3; c++) {
        const v = mesh.indices[3 * t + c]!;
        transformPoint(inst, mesh.positions[3 * v]!, mesh.positions[3 * v + 1]!, mesh.positions[3 * v + 2]!, w, 3 * c);
        grow(w[3 * c]!, w[3 * c + 1]!, w[3 * c + 2]!);
      }
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
        const vertex = (c: number): number => mesh.indices[3 * t + c]!;
        const uv = (c: number): [number, number] => (uvs && texture ? applyTextureTransform(texture.transform, uvs[2 * vertex(c)]!, uvs[2 * vertex(c) + 1]!) : [0, 0]);
        const vertexAlpha = (c: number): number => (mesh.colors ? mesh.colors[4 * vertex(c) + 3]! : 1);
        writeStruct(alphaPrimitiveLayout, alphaView, alphaIndex, {
          uv0: uv(0),
          uv1: uv(1),
          uv2: uv(2),
          alphaCutoff: material.alphaCutoff,
          alphaMode: material.alphaMode === 'MASK' ? ALPHA_MODE_MASK : ALPHA_MODE_BLEND,
          vertexAlpha: [vertexAlpha(0), vertexAlpha(1), vertexAlpha(2)],
          alphaFactor: material.baseColor[3],
          texture: texture && uvs ? infoOffset(texture.texture, true) : INDEX_NONE,
        });
        shape[k] = PRIMITIVE_SHAPE_TRIANGLE | sides | PRIMITIVE_FLAG_ALPHA | (alphaIndex << PRIMITIVE_ALPHA_SHIFT);
        alphaIndex++;
      }
    }
  });
  scene.sceneObjects.forEach((object, i) => {
    const o = 9 * k;
    const lo = object.type === 'sphere' ? object.a.map((c) => c - object.b[0]) : object.a;
    const hi = object.type === 'sphere' ? object.a.map((c) => c + object.b[0]) : object.b;
    boundsTriangles.set([...lo, ...hi, ...hi], o);
    grow(lo[0]!, lo[1]!, lo[2]!);
    grow(hi[0]!, hi[1]!, hi[2]!);
    geometry.set([...object.a, ...object.b, 0, 0, 0], o);
    instance[k] = scene.instances.length + i;
    primitive[k] = 0;
    shape[k] = object.type === 'sphere' ? PRIMITIVE_SHAPE_SPHERE : PRIMITIVE_SHAPE_BOX;
    k++;
  });
  const empty = !(min[0] <= max[0]);
  return {
    count,
    boundsTriangles,
    geometry,
    instance,
    primitive,
    shape,
    alphaPrimitives,
    alphaCount,
    bounds: empty ? { min: [0, 0, 0], max: [0, 0, 0] } : { min, max },
  };
}
