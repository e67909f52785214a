/** -ln(attenuationColor) / attenuationDistance per channel (KHR_materials_volume, "Attenuation"), finite. */
export function absorptionCoefficient(volume: { attenuationColor: readonly number[]; attenuationDistance: number }): [number, number, number] {
  return volume.attenuationColor.map((c) => {
    if (volume.attenuationDistance === Infinity || c === 1) return 0;
    // A black channel absorbs everything at any distance; the largest f32 keeps it finite.
    return c === 0 ? 3.4e38 : Math.min(-Math.log(c) / volume.attenuationDistance, 3.4e38);
  }) as [number, number, number];
}
