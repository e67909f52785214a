export {
  toneMapPbrNeutral,
  toneMapAces,
  linearToSrgb,
  srgbToLinear,
  applyToneMapping,
  encodeRadianceToRgba8,
  isToneMapping,
  toneMappingModeIds,
  toneMappingNames,
  type EncodeRadianceOptions,
  type Rgb,
} from './tone-mapping.ts';
export { encodePng, type Rgba8Image } from './png.ts';
export { writePng } from './png-node.ts';
