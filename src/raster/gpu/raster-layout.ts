/**
 * GPU records of the raster renderer (uniform structs), one definition for the WGSL structs
 * (generated into `package::raster::generated_layout`) and the TypeScript packers, as for the path
 * tracer's records. Matrices are stored as four vec4 columns (column-major, as WGSL's mat4x4f).
 */
import { punctualLightLayout } from '../../lighting/punctual-lights.ts';
import { defineStructLayout, type StructFieldSpec, type StructLayout } from '../../gpu-layout/struct-layout.ts';

function mat4(name: string, doc: string): StructFieldSpec[] {
  return [0, 1, 2, 3].map((c) => [`${name}${c}`, 'vec4f', c === 0 ? doc : undefined] as StructFieldSpec);
}

/** Per frame: camera, environment, lights, shadow. */
export const rasterFrameLayout: StructLayout = defineStructLayout('RasterFrame', 1, [
  ...mat4('viewProj', 'world -> clip of the camera'),
  ...mat4('inverseViewProj', 'clip -> world, for the background'),
  ...mat4('shadowViewProj', 'world -> clip of the shadow-casting light'),
  ['cameraPosition', 'vec3f'],
  ['exposure', 'f32', 'radiance multiplier before tone mapping'],
  ['environmentColor', 'vec3f', 'uniform environment radiance (environmentMode 1)'],
  ['environmentMode', 'u32', '0 black, 1 uniform colour, 2 prefiltered map'],
  ['environmentIntensity', 'f32', 'multiplier of the map radiance'],
  ['environmentRotation', 'f32', 'map rotation about +Y, radians'],
  ['specularMipCount', 'f32', 'levels of the prefiltered specular chain'],
  ['lightCount', 'u32'],
  ['shadowLight', 'u32', 'index of the light whose contribution is shadowed, or 0xffffffff'],
  ['shadowBias', 'f32', 'depth bias in light clip units'],
  ['shadowTexel', 'f32', '1 / shadow map size'],
  ['toneMapping', 'u32', 'TONE_MAPPING_* id'],
  ['viewportSize', 'vec2f'],
  ['outputSrgb', 'u32', '1 when the output texture stores sRGB-encoded bytes in a unorm format'],
  ['frameIndex', 'u32'],
  ['viewDirection', 'vec3f', 'unit vector from the target towards the eye: the direction to the viewer of an orthographic camera'],
  ['orthographic', 'u32', '1 for an orthographic camera (every fragment is viewed along viewDirection), 0 for a perspective one'],
]);

/** Per draw (dynamic offset): object -> world and its normal matrix. */
export const rasterDrawLayout: StructLayout = defineStructLayout('RasterDraw', 1, [
  ...mat4('model', 'object -> world'),
  ['normal0', 'vec4f', 'inverse transpose of the upper 3x3 (columns), for normals'],
  ['normal1', 'vec4f'],
  ['normal2', 'vec4f'],
  ['flags', 'u32', 'DRAW_HAS_* bits: which vertex streams the mesh really has'],
  ['determinantSign', 'f32', '-1 for mirroring transforms (front faces flip)'],
]);

/**
 * Texture slots of a raster material, in binding order: the glTF core textures, then the
 * extension textures the Khronos sample viewer uses for clearcoat, sheen, transmission and specular.
 */
export const rasterTextureSlots = [
  { name: 'baseColorTexture', srgb: true },
  { name: 'metallicRoughnessTexture', srgb: false },
  { name: 'normalTexture', srgb: false },
  { name: 'occlusionTexture', srgb: false },
  { name: 'emissiveTexture', srgb: true },
  { name: 'clearcoatTexture', srgb: false },
  { name: 'clearcoatRoughnessTexture', srgb: false },
  { name: 'clearcoatNormalTexture', srgb: false },
  { name: 'sheenColorTexture', srgb: true },
  { name: 'sheenRoughnessTexture', srgb: false },
  { name: 'transmissionTexture', srgb: false },
  { name: 'specularTexture', srgb: false },
  { name: 'specularColorTexture', srgb: true },
] as const;

export type RasterTextureSlot = (typeof rasterTextureSlots)[number]['name'];

/** Per material: glTF factors (extensions included) and which textures are bound. */
export const rasterMaterialLayout: StructLayout = defineStructLayout('RasterMaterial', 1, [
  ['baseColor', 'vec4f'],
  ['emissive', 'vec3f', 'emissiveFactor x emissiveStrength'],
  ['metallic', 'f32'],
  ['roughness', 'f32'],
  ['ior', 'f32'],
  ['alphaCutoff', 'f32'],
  ['alphaMode', 'u32', 'ALPHA_OPAQUE, ALPHA_MASK or ALPHA_BLEND'],
  ['normalScale', 'f32'],
  ['occlusionStrength', 'f32'],
  ['clearcoat', 'f32'],
  ['clearcoatRoughness', 'f32'],
  ['sheenColor', 'vec3f'],
  ['sheenRoughness', 'f32'],
  ['specularColor', 'vec3f'],
  ['specular', 'f32'],
  ['attenuationColor', 'vec3f'],
  ['transmission', 'f32'],
  ['clearcoatNormalScale', 'f32'],
  ['thickness', 'f32'],
  ['attenuationDistance', 'f32', '0 = no absorption'],
  ['textureMask', 'u32', 'bit i: texture slot i is bound'],
  ['texCoordMask', 'u32', 'bit i: texture slot i reads uv set 1'],
  ['doubleSided', 'u32'],
]);

/** Per skinned primitive: where its streams live in the skinning buffers. */
export const rasterSkinParamsLayout: StructLayout = defineStructLayout('RasterSkinParams', 1, [
  ['vertexCount', 'u32'],
  ['influences', 'u32', '4 or 8 joints per vertex'],
  ['targetCount', 'u32', 'morph targets'],
  ['flags', 'u32', 'SKIN_HAS_* bits'],
  ['positions', 'u32', 'word offsets in skinSource: base streams'],
  ['normals', 'u32'],
  ['tangents', 'u32'],
  ['targets', 'u32', 'first morph target block; a target is 9 words per vertex: position, normal, tangent deltas, stream by stream'],
  ['influenceOffset', 'u32', 'word offset in skinInfluences: per vertex `influences` joints then `influences` weights (bit-cast f32)'],
  ['jointOffset', 'u32', 'first joint matrix in jointMatrices'],
  ['weightOffset', 'u32', 'first morph weight in morphWeights'],
  ['outPositions', 'u32', 'word offsets in skinOutput'],
  ['outNormals', 'u32'],
  ['outTangents', 'u32'],
  ['jointCount', 'u32'],
]);

/** Uniforms of the image-based-lighting precomputation passes. */
export const rasterIblParamsLayout: StructLayout = defineStructLayout('RasterIblParams', 1, [
  ['outputSize', 'vec2u'],
  ['sourceSize', 'vec2u'],
  ['roughness', 'f32'],
  ['sampleCount', 'u32'],
  ['sourceMipCount', 'f32'],
  ['level', 'u32'],
]);

export const rasterRecordLayouts = {
  RasterFrame: rasterFrameLayout,
  RasterDraw: rasterDrawLayout,
  RasterMaterial: rasterMaterialLayout,
  RasterSkinParams: rasterSkinParamsLayout,
  RasterIblParams: rasterIblParamsLayout,
  PunctualLight: punctualLightLayout,
} as const;

/** Constants the raster WGSL shares with TypeScript. */
export const rasterConstants = {
  ALPHA_OPAQUE: 0,
  ALPHA_MASK: 1,
  ALPHA_BLEND: 2,
  DRAW_HAS_NORMALS: 1,
  DRAW_HAS_TANGENTS: 2,
  DRAW_HAS_UV0: 4,
  DRAW_HAS_UV1: 8,
  DRAW_HAS_COLORS: 16,
  SKIN_HAS_NORMALS: 1,
  SKIN_HAS_TANGENTS: 2,
  SKIN_IS_SKINNED: 4,
  SKIN_TARGET_WORDS: 9,
  ENVIRONMENT_BLACK: 0,
  ENVIRONMENT_UNIFORM: 1,
  ENVIRONMENT_MAP: 2,
  SHADOW_NONE: 0xffffffff,
  SKIN_WORKGROUP_SIZE: 64,
  IBL_WORKGROUP_SIZE: 8,
  SH_WORKGROUP_SIZE: 256,
  TEXTURE_SLOT_COUNT: rasterTextureSlots.length,
} as const;
