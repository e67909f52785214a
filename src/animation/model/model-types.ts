/**
 * Renderer-independent data of an animated glTF model, read once from a `@gltf-transform/core`
 * Document: the node hierarchy with rest transforms, skins, meshes with their vertex streams,
 * morph targets and skin influences, and a material summary. Indices follow the glTF JSON order
 * (`root.listNodes()`, `listSkins()`, `listMeshes()`, `listMaterials()`), so they match the indices
 * a glTF loader assigns and the `field` paths in errors.
 */
import type { GltfMorphTarget, GltfPrimitive } from '../../io/gltf/primitive/read-primitive.ts';
import type { AnimationClip } from '../clips/clip-types.ts';

export type Vec3 = [number, number, number];
/** Quaternion x, y, z, w (glTF order). */
export type Quat = [number, number, number, number];

export interface ModelNode {
  readonly name: string;
  /** Index of the parent node; -1 for a root. */
  readonly parent: number;
  readonly children: readonly number[];
  /** Rest (bind-time) local transform: translation, rotation, scale (glTF 2.0 section 3.5.3). */
  readonly translation: Readonly<Vec3>;
  readonly rotation: Readonly<Quat>;
  readonly scale: Readonly<Vec3>;
  /** Mesh index or -1. */
  readonly mesh: number;
  /** Skin index or -1. */
  readonly skin: number;
  /** Default morph weights: node.weights, else mesh.weights, else zeros (one per morph target). */
  readonly weights: readonly number[];
}

export interface ModelSkin {
  readonly name: string;
  /** Node index of each joint, in the skin's joint order (the order JOINTS_n refers to). */
  readonly joints: Int32Array;
  /** One column-major 4x4 matrix per joint (identity when the skin has none, as glTF specifies). */
  readonly inverseBindMatrices: Float64Array;
  /** skin.skeleton node index or -1. */
  readonly skeleton: number;
}

/** Morph target deltas (glTF 2.0 section 3.7.2.2); tangent deltas are xyz only. */
export type ModelMorphTarget = GltfMorphTarget;

/**
 * A primitive's vertex streams, triangle list (strips and fans converted), skin influences and
 * morph targets, as the one glTF primitive reader reads them, with its material.
 */
export interface ModelPrimitive extends GltfPrimitive {
  /** glTF material index or -1. */
  readonly material: number;
}

export interface ModelMesh {
  readonly name: string;
  readonly primitives: readonly ModelPrimitive[];
  /** mesh.weights, else zeros (one per morph target). */
  readonly weights: readonly number[];
  readonly targetCount: number;
}

/** What validators need to know about a material (the full material is the glTF loader's job). */
export interface ModelMaterialSummary {
  readonly name: string;
  readonly hasBaseColorTexture: boolean;
  readonly hasNormalTexture: boolean;
}

/** A node of the rendered scene that draws a mesh. Skinned when `skin >= 0`. */
export interface ModelDrawable {
  readonly node: number;
  readonly mesh: number;
  readonly skin: number;
}

export interface AnimatedModel {
  readonly nodes: readonly ModelNode[];
  /** Every node once, parents before children (for world-matrix evaluation). */
  readonly nodeOrder: Int32Array;
  readonly skins: readonly ModelSkin[];
  readonly meshes: readonly ModelMesh[];
  readonly drawables: readonly ModelDrawable[];
  readonly materials: readonly ModelMaterialSummary[];
  /** The model's own animations, bound to its nodes. */
  readonly clips: readonly AnimationClip[];
  /** Field prefix used in errors about this model (e.g. `modelAsset`). */
  readonly field: string;
}
