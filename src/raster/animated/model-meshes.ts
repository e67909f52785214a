/**
 * An animated glTF model's drawables as raster scene parts: a skinned (or morphed) primitive
 * becomes a deformable mesh the GPU skins every frame; a rigid primitive without morph targets a
 * static mesh placed by its node's animated world matrix.
 */
import type { AnimatedModel, ModelPrimitive } from '../../animation/model/model-types.ts';
import type { WavefrontMeshInput } from '../../scene/types.ts';
import type { RasterSkinnedMeshInput } from '../types.ts';

/** A primitive's streams and influences as a raster deformable mesh. */
export function skinnedMeshFromPrimitive(primitive: ModelPrimitive, jointCount: number, material: number | undefined): RasterSkinnedMeshInput {
  const out: RasterSkinnedMeshInput = { positions: primitive.positions, indices: primitive.indices, influences: primitive.influences };
  if (primitive.normals !== null) out.normals = primitive.normals;
  if (primitive.tangents !== null) out.tangents = primitive.tangents;
  if (primitive.uvs !== null) out.uvs = primitive.uvs;
  if (primitive.uvs1 !== null) out.uvs1 = primitive.uvs1;
  if (primitive.colors !== null) out.colors = primitive.colors;
  if (material !== undefined) out.material = material;
  if (primitive.influences > 0) {
    out.joints = primitive.joints!;
    out.weights = primitive.weights!;
    out.jointCount = jointCount;
  }
  if (primitive.targets.length > 0) {
    out.targets = primitive.targets.map((t) => {
      const target: { positions?: Float32Array; normals?: Float32Array; tangents?: Float32Array } = {};
      if (t.positions !== null) target.positions = t.positions;
      if (t.normals !== null) target.normals = t.normals;
      if (t.tangents !== null) target.tangents = t.tangents;
      return target;
    });
  }
  return out;
}

export function staticMeshFromPrimitive(primitive: ModelPrimitive, material: number | undefined): WavefrontMeshInput {
  const out: WavefrontMeshInput = { positions: primitive.positions, indices: primitive.indices };
  if (primitive.normals !== null) out.normals = primitive.normals;
  if (primitive.tangents !== null) out.tangents = primitive.tangents;
  if (primitive.uvs !== null) out.uvs = primitive.uvs;
  if (primitive.uvs1 !== null) out.uvs1 = primitive.uvs1;
  if (primitive.colors !== null) out.colors = primitive.colors;
  if (material !== undefined) out.material = material;
  return out;
}

/** Where each drawable primitive of a model went: a skinned instance or a static instance. */
export interface ModelDrawPart {
  readonly drawable: number;
  readonly primitive: number;
  readonly kind: 'skinned' | 'static';
  /** Index in skinnedInstances or instances of the raster scene. */
  readonly index: number;
}

export interface ModelRasterParts {
  meshes: WavefrontMeshInput[];
  skinnedMeshes: RasterSkinnedMeshInput[];
  parts: ModelDrawPart[];
}

/**
 * Splits a model's drawables into raster meshes; `material` maps a glTF material index to the
 * scene's material index (undefined: the default material). Instances are created by the caller
 * (one per part, in `parts` order per kind).
 */
export function modelRasterParts(model: AnimatedModel, material: (gltfMaterial: number) => number | undefined, firstMesh = 0, firstSkinnedMesh = 0): ModelRasterParts {
  const meshes: WavefrontMeshInput[] = [];
  const skinnedMeshes: RasterSkinnedMeshInput[] = [];
  const parts: ModelDrawPart[] = [];
  model.drawables.forEach((drawable, d) => {
    model.meshes[drawable.mesh]!.primitives.forEach((primitive, p) => {
      const m = material(primitive.material);
      if (drawable.skin >= 0 || primitive.targets.length > 0) {
        const jointCount = drawable.skin >= 0 ? model.skins[drawable.skin]!.joints.length : 0;
        const input = skinnedMeshFromPrimitive(drawable.skin >= 0 ? primitive : { ...primitive, influences: 0, joints: null, weights: null }, jointCount, m);
        parts.push({ drawable: d, primitive: p, kind: 'skinned', index: firstSkinnedMesh + skinnedMeshes.length });
        skinnedMeshes.push(input);
      } else {
        parts.push({ drawable: d, primitive: p, kind: 'static', index: firstMesh + meshes.length });
        meshes.push(staticMeshFromPrimitive(primitive, m));
      }
    });
  });
  return { meshes, skinnedMeshes, parts };
}
