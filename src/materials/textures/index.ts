// The material texture atlas: packing (CPU), upload, KHR_texture_transform rows and the CPU mirror
// of texture-sampling.wesl.
export { buildTextureAtlas, type TextureAtlas, type TextureUsage } from './texture-atlas.ts';
export { uploadTextureAtlas, type UploadedTextureAtlas } from './upload-texture-atlas.ts';
export { packAtlas, shelfPack, fitTextureToLimit, type AtlasLimits, type AtlasPacking, type BlockPlacement, type BlockSize } from './atlas-packer.ts';
export { fullMipCount, mipLevelSize, mipLevelOrigin, mipBlockSize, mipChainLayout, type MipChainLayout, type TexelRect } from './atlas-layout.ts';
export { areaResample, generateMipChain, downscaleImage, type Rgba8Image, type TexelEncoding } from './mip-chain.ts';
export { resolveSampler, samplerBits, samplerUsesMipmaps, defaultSampler, type ResolvedSampler } from './sampler-state.ts';
export { textureTransformMatrix, identityTextureTransform, applyTextureTransform, type TextureTransformRows, type Vec3Row } from '../../scene/texture-transform.ts';
export {
  sampleTexture,
  sampleTextureInfo,
  sampleBoundTexture,
  sampleLevel,
  transformUv,
  textureLod,
  wrapTexel,
  readTextureInfo,
  readTextureBinding,
  type AtlasTexels,
  type Rgba,
  type TextureInfoRecord,
  type TextureBindingRecord,
  type TextureFootprint,
} from './reference-sampler.ts';
