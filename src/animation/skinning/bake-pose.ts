import { mat4d } from 'wgpu-matrix';
import type { AnimationClip } from '../clips/clip-types.ts';
import type { AnimatedModel } from '../model/model-types.ts';
import type { WavefrontInstanceInput, WavefrontMaterialInput, WavefrontMeshInput } from '../../scene/types.ts';
import { loopClipTimeMs } from '../pose/evaluate-clip.ts';
import { evaluateLayeredPose, type ClipLayer } from '../pose/evaluate-layers.ts';
import type { Pose } from '../pose/pose.ts';
import { computeJointMatrices, computeWorldMatrices } from '../pose/world-matrices.ts';
import { applyMorphTargets } from './morph-targets.ts';
import { skinVertices } from './skin-vertices.ts';

/** A single clip played from `startMs` (default 0), looping unless `loop` is false. */
export interface ClipPlayback {
  readonly clip: AnimationClip;
  readonly loop?: boolean;
  readonly startMs?: number;
}

/** Anything that knows the clip layers and character placement at a time (a scene timeline). */
export interface PoseSource {
  poseAt(tMs: number): { readonly layers: readonly ClipLayer[]; readonly rootTransform: ArrayLike<number> };
}

export type ClipState = ClipPlayback | PoseSource;

export interface BakePoseOptions {
  /**
   * Material of a baked primitive from its glTF material index (-1: none). Default: the index
   * itself, so the baked meshes refer to the scene's `materials` in glTF document order (the
   * order the glTF loader emits them in).
   */
  material?: (gltfMaterialIndex: number) => WavefrontMaterialInput | number | undefined;
  /** Character placement (column-major 4x4) for a `ClipPlayback`; default identity. */
  rootTransform?: ArrayLike<number>;
}

export interface BakedPose {
  /** One mesh per drawn primitive, vertices in model space (skinned) or node space (rigid). */
  readonly meshes: WavefrontMeshInput[];
  /** One instance per mesh: the character placement, times the node's world matrix for rigid meshes. */
  readonly instances: WavefrontInstanceInput[];
  readonly pose: Pose;
  /** Node world matrices in model space (16 per node). */
  readonly worldMatrices: Float64Array;
}

function layersOf(state: ClipState, tMs: number, options: BakePoseOptions): { layers: readonly ClipLayer[]; rootTransform: ArrayLike<number> } {
  if ('poseAt' in state) return state.poseAt(tMs);
  const local = tMs - (state.startMs ?? 0);
  const durationMs = state.clip.durationS * 1000;
  const clipTimeMs = state.loop === false ? Math.min(Math.max(local, 0), durationMs) : loopClipTimeMs(local, state.clip.durationS);
  return { layers: [{ clip: state.clip, clipTimeMs, weight: 1, rootMotion: 'authored', root: null }], rootTransform: options.rootTransform ?? mat4d.identity() };
}

/**
 * Bakes the posed model at scene time `tMs` into the renderer's scene types, so a still of an
 * animation can be handed to the path tracer: skinned primitives are skinned on the CPU
 * (morph targets first, then linear blend skinning) into model space; rigid primitives keep
 * their (morphed) vertices and get their node's world matrix as instance transform.
 */
export function bakePose(model: AnimatedModel, clipState: ClipState, tMs: number, options: BakePoseOptions = {}): BakedPose {
  const { layers, rootTransform } = layersOf(clipState, tMs, options);
  const pose = evaluateLayeredPose(model, layers);
  const world = computeWorldMatrices(model, pose);
  const root = Float64Array.from(rootTransform);
  const meshes: WavefrontMeshInput[] = [];
  const instances: WavefrontInstanceInput[] = [];
  const materialOf = options.material ?? ((index: number) => (index >= 0 ? index : undefined));
  const jointCache = new Map<number, Float64Array>();
  for (const drawable of model.drawables) {
    const mesh = model.meshes[drawable.mesh];
    const weights = pose.weights[drawable.node];
    let jointMatrices: Float64Array | null = null;
    if (drawable.skin >= 0) {
      jointMatrices = jointCache.get(drawable.skin) ?? computeJointMatrices(model, drawable.skin, world);
      jointCache.set(drawable.skin, jointMatrices);
    }
    mesh.primitives.forEach((primitive, p) => {
      const morphed = applyMorphTargets(primitive, weights);
      const streams = jointMatrices === null ? morphed : skinVertices(primitive, morphed, jointMatrices);
      const out: WavefrontMeshInput = {
        id: `node${drawable.node}.mesh${drawable.mesh}.primitive${p}`,
        positions: Float32Array.from(streams.positions),
        indices: primitive.indices,
      };
      if (streams.normals !== null) out.normals = Float32Array.from(streams.normals);
      if (streams.tangents !== null) out.tangents = Float32Array.from(streams.tangents);
      if (primitive.uvs !== null) out.uvs = primitive.uvs;
      if (primitive.uvs1 !== null) out.uvs1 = primitive.uvs1;
      if (primitive.colors !== null) out.colors = primitive.colors;
      const material = materialOf(primitive.material);
      if (material !== undefined) out.material = material;
      const transform = jointMatrices === null ? mat4d.multiply(root, world.subarray(16 * drawable.node, 16 * drawable.node + 16)) : root;
      instances.push({ id: out.id, mesh: meshes.length, transform: Array.from(transform) });
      meshes.push(out);
    });
  }
  return { meshes, instances, pose, worldMatrices: world };
}
