// The raster renderer's view of an animated glTF asset at a time: the animation module samples the
// clip and computes joint matrices (as the raster renderer's animated scenes do), the raster
// renderer skins on the GPU (skin.wesl). Silhouettes of it are the reference the path tracer's
// CPU-posed frames are compared with.
import type { Document } from '@gltf-transform/core';
import { readAnimatedModel } from '../../src/animation/model/read-model.ts';
import { evaluateClipPose } from '../../src/animation/pose/evaluate-clip.ts';
import { computeJointMatrices, computeWorldMatrices } from '../../src/animation/pose/world-matrices.ts';
import { modelRasterParts } from '../../src/raster/animated/model-meshes.ts';
import { createRasterRenderer } from '../../src/raster/index.ts';
import type { WavefrontCameraInput, WavefrontMaterialInput } from '../../src/scene/types.ts';

export interface RasterPoser {
  /** Coverage mask (red channel > 127: more than half the pixel's 4 MSAA samples) of the asset posed at `time` of `clip`, seen by `camera`. */
  maskAt(clip: string, time: number, camera: WavefrontCameraInput): Promise<Uint8Array>;
  destroy(): void;
}

export async function createRasterPoser(device: GPUDevice, document: Document, materials: WavefrontMaterialInput[], width: number, height: number): Promise<RasterPoser> {
  const model = readAnimatedModel(document);
  const parts = modelRasterParts(model, (m) => (m >= 0 ? m : undefined));
  const skinned = parts.parts.filter((p) => p.kind === 'skinned');
  const rigid = parts.parts.filter((p) => p.kind === 'static');
  const renderer = await createRasterRenderer({
    device,
    width,
    height,
    msaa: 4,
    shadow: false,
    toneMapping: 'linear',
    materials,
    meshes: parts.meshes,
    instances: rigid.map((p) => ({ mesh: p.index })),
    skinnedMeshes: parts.skinnedMeshes,
    skinnedInstances: skinned.map((p) => ({ mesh: p.index })),
  });
  return {
    async maskAt(clipName, time, camera) {
      const clip = model.clips.find((c) => c.name === clipName)!;
      const pose = evaluateClipPose(model, clip, time);
      const world = computeWorldMatrices(model, pose);
      skinned.forEach((part, i) => {
        const drawable = model.drawables[part.drawable]!;
        const joints = drawable.skin >= 0 ? computeJointMatrices(model, drawable.skin, world) : new Float64Array(0);
        renderer.setSkinPose(i, Float32Array.from(joints), pose.weights[drawable.node]);
        // A morph-only mesh is placed by its node; a skinned one by its joints alone.
        if (drawable.skin < 0) renderer.setSkinnedInstanceTransform(i, world.subarray(16 * drawable.node, 16 * drawable.node + 16));
      });
      rigid.forEach((part, i) => renderer.setInstanceTransform(i, world.subarray(16 * model.drawables[part.drawable]!.node, 16 * model.drawables[part.drawable]!.node + 16)));
      renderer.setCamera(camera);
      await renderer.render();
      return redMask((await renderer.readPixels()).data);
    },
    destroy: () => renderer.destroy(),
  };
}

export function redMask(rgba: ArrayLike<number>): Uint8Array {
  return Uint8Array.from({ length: rgba.length / 4 }, (_, i) => (rgba[4 * i]! > 127 ? 1 : 0));
}

/** Intersection over union of two masks. */
export function iou(a: Uint8Array, b: Uint8Array): number {
  let inter = 0;
  let union = 0;
  for (let i = 0; i < a.length; i++) {
    if (a[i] && b[i]) inter++;
    if (a[i] || b[i]) union++;
  }
  return union === 0 ? 1 : inter / union;
}

export function coverage(mask: Uint8Array): number {
  return mask.reduce((n, v) => n + v, 0);
}
