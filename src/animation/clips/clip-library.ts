import type { Document } from '@gltf-transform/core';
import { fail, isArrayLike } from '../../errors/validate.ts';
import type { AnimatedModel } from '../model/model-types.ts';
import { readNodeHierarchy } from '../model/read-node-hierarchy.ts';
import { measureRootMotionPerLoop, resolveRootMotionNode, type RootMotionNode } from '../pose/root-motion.ts';
import { bindClipByNodeName } from './bind-clips.ts';
import type { AnimationClip } from './clip-types.ts';
import { validateMovementProfile, type ClipMovementProfile, type ClipMovementProfileInput } from './movement-profile.ts';
import { readAnimationClips } from './read-clips.ts';

/** One entry of `clipAssets`: a clip from the model itself or from a separate glTF document. */
export interface ClipAssetInput {
  id: string;
  /** Document holding the animation; omitted: the model's own animations. Bound to the model by node name. */
  document?: Document;
  /** Animation name or index in that document; default the first animation. */
  animation?: string | number;
  movementProfile?: ClipMovementProfileInput;
}

export interface LibraryClip {
  readonly id: string;
  /** The clip bound to the model's nodes. */
  readonly clip: AnimationClip;
  readonly durationMs: number;
  readonly profile: ClipMovementProfile | null;
  /** Root-motion node of this clip (profile.rootNode or the model's default), or null. */
  readonly root: RootMotionNode | null;
  /** Horizontal root travel per loop measured from the clip's keyframes, in model units. */
  readonly measuredDistancePerLoop: number;
  /** Declared distance when given, else the measured one. */
  readonly distancePerLoop: number;
  /** Where this clip was declared (`clipAssets[2]`, or the animation's glTF path). */
  readonly field: string;
}

export interface ClipLibrary {
  readonly clips: ReadonlyMap<string, LibraryClip>;
}

function pickAnimation(clips: AnimationClip[], selector: string | number | undefined, field: string): AnimationClip {
  if (clips.length === 0) fail('INVALID_OPTION', `${field}.document`, 'the document has no animations');
  if (selector === undefined) return clips[0];
  if (typeof selector === 'number') {
    if (!Number.isInteger(selector) || selector < 0 || selector >= clips.length) {
      fail('INVALID_OPTION', `${field}.animation`, `animation index ${selector} is out of range for ${clips.length} animations`);
    }
    return clips[selector];
  }
  const found = clips.find((clip) => clip.name === selector);
  if (found === undefined) fail('INVALID_OPTION', `${field}.animation`, `no animation named ${JSON.stringify(selector)} (have ${clips.map((c) => JSON.stringify(c.name)).join(', ')})`);
  return found;
}

function libraryClip(model: AnimatedModel, id: string, clip: AnimationClip, profile: ClipMovementProfile | null, field: string): LibraryClip {
  const root = resolveRootMotionNode(model, profile?.rootNode ?? undefined, `${field}.movementProfile.rootNode`);
  const measured = measureRootMotionPerLoop(clip, root);
  return {
    id,
    clip,
    durationMs: clip.durationS * 1000,
    profile,
    root,
    measuredDistancePerLoop: measured,
    distancePerLoop: profile?.declaredDistancePerLoop ?? measured,
    field,
  };
}

/**
 * The clips a scene can play, by id. Without `clipAssets` every animation of the model is a clip
 * (id = its name) without a movement profile. With `clipAssets`, each entry names a clip id, its
 * source (the model or another document, bound by node name) and its movement profile.
 */
export function createClipLibrary(model: AnimatedModel, clipAssets?: readonly ClipAssetInput[], field = 'clipAssets'): ClipLibrary {
  const clips = new Map<string, LibraryClip>();
  if (clipAssets === undefined) {
    for (const clip of model.clips) clips.set(clip.id, libraryClip(model, clip.id, clip, null, clip.field));
    return { clips };
  }
  if (!isArrayLike(clipAssets)) fail('INVALID_OPTION', field, 'expected an array of clip assets');
  clipAssets.forEach((asset, i) => {
    const assetField = `${field}[${i}]`;
    if (typeof asset !== 'object' || asset === null) fail('INVALID_OPTION', assetField, 'expected a clip asset object');
    if (typeof asset.id !== 'string' || asset.id === '') fail('INVALID_OPTION', `${assetField}.id`, 'expected a non-empty string');
    if (clips.has(asset.id)) fail('INVALID_OPTION', `${assetField}.id`, `duplicate clip id ${JSON.stringify(asset.id)}`);
    let clip: AnimationClip;
    if (asset.document === undefined) {
      clip = { ...pickAnimation([...model.clips], asset.animation, assetField), id: asset.id };
    } else {
      const hierarchy = readNodeHierarchy(asset.document, `${assetField}.`);
      const source = pickAnimation(readAnimationClips(asset.document, hierarchy.indexOf, `${assetField}.`), asset.animation, assetField);
      clip = bindClipByNodeName(model, source, asset.id);
    }
    const profile = asset.movementProfile === undefined ? null : validateMovementProfile(asset.movementProfile, `${assetField}.movementProfile`);
    clips.set(asset.id, libraryClip(model, asset.id, clip, profile, assetField));
  });
  return { clips };
}
