import { fail } from '../errors/validate.ts';
import type { ClipLibrary } from './clips/clip-library.ts';
import type { AnimatedModel } from './model/model-types.ts';
import type { AnimationBeat } from './timeline/beats.ts';

function prefix(model: AnimatedModel): string {
  return model.field === '' ? '' : `${model.field}.`;
}

/** An animated character must be skinned: a model without a skinned mesh is an INVALID_MODEL error. */
export function requireSkinnedCharacter(model: AnimatedModel): void {
  if (!model.drawables.some((d) => d.skin >= 0)) {
    fail('INVALID_MODEL', `${prefix(model)}skins`, model.skins.length === 0 ? 'the model has no skin: an animated character needs a skinned mesh' : 'no mesh node uses the model\'s skins');
  }
}

/**
 * The professional (fail-closed) path's model and clip requirements, checked before any GPU work:
 * every skinned primitive has normals, TEXCOORD_0 and a material with a base colour texture and a
 * normal texture; every clip a travel or jump beat plays has an authored-root-motion profile with
 * non-zero travel. The first missing piece is a typed error naming it.
 */
export function requireProfessionalCharacter(model: AnimatedModel, library: ClipLibrary, beats: readonly AnimationBeat[], beatsField = 'beats'): void {
  requireSkinnedCharacter(model);
  const p = prefix(model);
  for (const drawable of model.drawables) {
    if (drawable.skin < 0) continue;
    model.meshes[drawable.mesh].primitives.forEach((primitive, i) => {
      const field = `${p}meshes[${drawable.mesh}].primitives[${i}]`;
      if (primitive.normals === null) fail('INVALID_MODEL', `${field}.attributes.NORMAL`, 'the professional renderer needs vertex normals');
      if (primitive.uvs === null) fail('INVALID_MODEL', `${field}.attributes.TEXCOORD_0`, 'the professional renderer needs texture coordinates');
      if (primitive.material < 0) fail('INVALID_MODEL', `${field}.material`, 'the professional renderer needs a material with base colour and normal textures');
      const material = model.materials[primitive.material];
      const materialField = `${p}materials[${primitive.material}]`;
      if (!material.hasBaseColorTexture) fail('INVALID_MODEL', `${materialField}.pbrMetallicRoughness.baseColorTexture`, `material ${JSON.stringify(material.name)} has no base colour texture`);
      if (!material.hasNormalTexture) fail('INVALID_MODEL', `${materialField}.normalTexture`, `material ${JSON.stringify(material.name)} has no normal texture`);
    });
  }
  for (const beat of beats) {
    const kind = beat.requirement?.kind;
    if (kind !== 'travel' && kind !== 'jump') continue;
    const clip = beat.clip;
    if (clip.profile === null) fail('INVALID_ANIMATION', `${clip.field}.movementProfile`, `${kind} beat ${JSON.stringify(beat.id)} (${beatsField}[${beat.inputIndex}]) plays clip ${JSON.stringify(clip.id)}, which has no movement profile`);
    if (clip.profile.rootMotion !== 'authored') fail('INVALID_ANIMATION', `${clip.field}.movementProfile.rootMotion`, `${kind} beat ${JSON.stringify(beat.id)} needs a clip with authored root motion, ${JSON.stringify(clip.id)} is in place`);
    if (!(clip.distancePerLoop > 0)) fail('INVALID_ANIMATION', `${clip.field}.movementProfile.distancePerLoop`, `clip ${JSON.stringify(clip.id)} is marked as authored root motion but travels 0 m per loop`);
  }
}
