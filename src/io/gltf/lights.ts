/**
 * KHR_lights_punctual lights in world space: position from the node's translation, direction the
 * node's -Z axis (the extension's convention), units, range and cone angles as the extension
 * defines them (candela for point/spot, lux for directional).
 */
import type { Light } from '@gltf-transform/extensions';
import type { WavefrontPunctualLightInput } from '../../scene/types.ts';
import { normalize, transformDirection, type Mat4 } from '../../math/mat4.ts';

export function worldLight(light: Light, world: Mat4): WavefrontPunctualLightInput {
  const type = light.getType() as WavefrontPunctualLightInput['type'];
  const out: WavefrontPunctualLightInput = { type, color: [...light.getColor()], intensity: light.getIntensity() };
  if (light.getName() !== '') out.name = light.getName();
  if (type !== 'directional') {
    out.position = [world[12], world[13], world[14]];
    const range = light.getRange();
    if (range !== null && range !== undefined) out.range = range;
  }
  if (type !== 'point') out.direction = normalize(transformDirection(world, [0, 0, -1]));
  if (type === 'spot') {
    out.innerConeAngle = light.getInnerConeAngle();
    out.outerConeAngle = light.getOuterConeAngle();
  }
  return out;
}
