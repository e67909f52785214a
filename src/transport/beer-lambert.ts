import { requireNumberInRange, requireVec } from '../errors/validate.ts';

/**
 * Transmittance through a homogeneous absorbing medium, KHR_materials_volume: the attenuation
 * coefficient is sigma_t = -ln(attenuationColor) / attenuationDistance, so
 * T(x) = exp(-sigma_t x) = attenuationColor ^ (x / attenuationDistance) per channel. The default
 * attenuationDistance is +Infinity, meaning the medium does not attenuate.
 */
export function beerLambertTransmittance(
  attenuationColor: readonly number[],
  attenuationDistance: number,
  distance: number,
): [number, number, number] {
  const color = requireVec(attenuationColor, 3, 'attenuationColor');
  color.forEach((c, i) => requireNumberInRange(c, `attenuationColor[${i}]`, { min: 0, max: 1 }));
  // +Infinity is a legal value for both lengths, so only finiteness is relaxed here.
  if (attenuationDistance !== Infinity) requireNumberInRange(attenuationDistance, 'attenuationDistance', { min: Number.MIN_VALUE });
  if (distance !== Infinity) requireNumberInRange(distance, 'distance', { min: 0 });
  if (attenuationDistance === Infinity || distance === 0) return [1, 1, 1];
  const ratio = distance / attenuationDistance;
  // A channel of colour 1 never attenuates, even over an infinite distance (1 ** Infinity is NaN in JS).
  const channel = (c: number): number => (c === 1 ? 1 : c ** ratio);
  return [channel(color[0]!), channel(color[1]!), channel(color[2]!)];
}
