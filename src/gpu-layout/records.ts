import { defineStructLayout, type StructLayout } from './struct-layout.ts';

/**
 * The GPU record contracts of the wavefront path tracer: the single source of truth for the WGSL
 * structs (generated from these layouts) and for every TypeScript packer and reader.
 */

/** One path in a wavefront queue; the extension kernel writes the closest hit into it. */
export const pathStateLayout: StructLayout = defineStructLayout('PathState', 1, [
  ['origin', 'vec3f'],
  ['slot', 'u32', 'tile-local pixel slot the path contributes to'],
  ['direction', 'vec3f', 'unit length'],
  ['depth', 'u32', 'scattering vertices so far (pbrt-v4 depth)'],
  ['throughput', 'vec3f', 'path weight beta'],
  ['misPdf', 'f32', 'solid-angle pdf of the BSDF sample that made this ray; 0 = camera or delta lobe'],
  ['hitT', 'f32', 'closest hit distance, or -1 on a miss'],
  ['hitPrimitive', 'u32', 'primitive id: kind in the top 2 bits'],
  ['hitU', 'f32', 'barycentric u of the hit'],
  ['hitV', 'f32', 'barycentric v of the hit'],
  ['etaScale', 'f32', 'accumulated eta^2 for Russian roulette across refraction'],
  ['mediumId', 'u32', 'innermost medium (0 = none); nested media arrive with transmission'],
  ['flags', 'u32', 'PATH_FLAG_* bits'],
  ['reserved', 'u32'],
]);

/** An any-hit query carrying the contribution it adds if unoccluded (NEE, pbrt-v4 style). */
export const shadowRayLayout: StructLayout = defineStructLayout('ShadowRay', 1, [
  ['origin', 'vec3f'],
  ['slot', 'u32'],
  ['direction', 'vec3f'],
  ['tMax', 'f32'],
  ['radiance', 'vec3f', 'contribution added when the segment is unoccluded'],
  ['reserved', 'u32'],
]);

/** Intersection data, kept compact for traversal (Moller-Trumbore form). */
export const triangleLayout: StructLayout = defineStructLayout('Triangle', 1, [
  ['v0', 'vec3f'],
  ['materialId', 'u32'],
  ['e1', 'vec3f', 'v1 - v0'],
  ['meshIndex', 'u32'],
  ['e2', 'vec3f', 'v2 - v0'],
  ['sourceIndex', 'u32', 'triangle index before BVH reordering'],
]);

/** Shading data of a triangle, read only at hits. */
export const triangleAttributesLayout: StructLayout = defineStructLayout('TriangleAttributes', 1, [
  ['n0', 'vec3f'],
  ['lightPmf', 'f32', 'probability that light sampling picks this triangle (0: not a light)'],
  ['n1', 'vec3f'],
  ['area', 'f32'],
  ['n2', 'vec3f'],
  ['flags', 'u32', 'TRIANGLE_FLAG_* bits'],
  ['uv0', 'vec2f'],
  ['uv1', 'vec2f'],
  ['uv2', 'vec2f'],
  ['geometricNormal', 'u32', 'unit cross(e1, e2), octahedral snorm16x2 (front face = CCW winding)'],
  ['materialId', 'u32'],
]);

/** Flattened BVH node: interior nodes keep both children adjacent at leftOrFirst, leftOrFirst + 1. */
export const bvhNodeLayout: StructLayout = defineStructLayout('BvhNode', 1, [
  ['boundsMin', 'vec3f'],
  ['leftOrFirst', 'u32', 'first child (interior) or first triangle (leaf)'],
  ['boundsMax', 'vec3f'],
  ['primitiveCount', 'u32', '0 for interior nodes'],
]);

/** glTF metallic-roughness material; extension factors slot in at the reserved tail. */
export const materialLayout: StructLayout = defineStructLayout('Material', 1, [
  ['baseColor', 'vec4f', 'linear RGB + alpha'],
  ['emission', 'vec3f', 'emissiveFactor * emissiveStrength'],
  ['metallic', 'f32'],
  ['roughness', 'f32', 'perceptual; alpha = roughness^2'],
  ['ior', 'f32', 'KHR_materials_ior'],
  ['transmission', 'f32', 'KHR_materials_transmission (not yet shaded)'],
  ['flags', 'u32', 'MATERIAL_FLAG_* bits'],
  ['specularColor', 'vec3f', 'KHR_materials_specular (not yet shaded)'],
  ['specular', 'f32'],
]);

/** Analytic debug fixtures: a = center (sphere) or min (box); b.x = radius (sphere) or b = max (box). */
export const sceneObjectLayout: StructLayout = defineStructLayout('SceneObject', 1, [
  ['a', 'vec3f'],
  ['kind', 'u32', 'SCENE_OBJECT_SPHERE or SCENE_OBJECT_BOX'],
  ['b', 'vec3f'],
  ['materialId', 'u32'],
]);

/** Alias-table bin over emissive triangles (Walker/Vose), carrying the light's geometry. */
export const lightEntryLayout: StructLayout = defineStructLayout('LightEntry', 1, [
  ['v0', 'vec3f'],
  ['threshold', 'f32', 'keep this bin when u < threshold, else take aliasIndex'],
  ['e1', 'vec3f'],
  ['aliasIndex', 'u32'],
  ['e2', 'vec3f'],
  ['triangle', 'u32', 'index into triangles/triangleAttributes; bit 31 = LIGHT_FLAG_DOUBLE_SIDED'],
  ['emission', 'vec3f', 'emitted radiance of the front face'],
  ['pmf', 'f32', 'probability of choosing this light'],
]);

/** Per-render constants: camera, environment, scene extents. */
export const frameUniformsLayout: StructLayout = defineStructLayout('FrameUniforms', 1, [
  ['cameraPosition', 'vec3f'],
  ['tanHalfFovY', 'f32'],
  ['cameraRight', 'vec3f'],
  ['aspect', 'f32'],
  ['cameraUp', 'vec3f'],
  ['lightCount', 'u32'],
  ['cameraForward', 'vec3f'],
  ['sceneObjectCount', 'u32'],
  ['environmentRadiance', 'vec3f'],
  ['environmentSelectProbability', 'f32', 'probability NEE samples the environment instead of a triangle'],
  ['sceneCenter', 'vec3f'],
  ['sceneRadius', 'f32'],
  ['imageSize', 'vec2u'],
  ['maxDepth', 'u32'],
  ['seed', 'u32'],
  ['queueCapacity', 'u32'],
  ['triangleCount', 'u32'],
  ['rayEpsilon', 'f32', '1e-4 x scene radius; reserved (spawned rays use the ulp offset of offset_ray_origin)'],
  ['reserved', 'u32'],
]);

/** Per-wave constants (one tile, one sample): bound with a dynamic offset. */
export const waveUniformsLayout: StructLayout = defineStructLayout('WaveUniforms', 1, [
  ['tileOrigin', 'vec2u'],
  ['tileSize', 'vec2u'],
  ['sampleIndex', 'u32', 'index of this sample within the pixel sequence'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
  ['reserved2', 'u32'],
]);

/** Per-bounce constants: which half of the ping-pong path buffer is read and which is written. */
export const bounceUniformsLayout: StructLayout = defineStructLayout('BounceUniforms', 1, [
  ['depth', 'u32'],
  ['inCounter', 'u32', 'counter slot holding the input queue length'],
  ['outCounter', 'u32', 'counter slot receiving the output queue length'],
  ['inBase', 'u32', 'first path index of the input queue'],
  ['outBase', 'u32', 'first path index of the output queue'],
]);

/** Display resolve constants. */
export const resolveUniformsLayout: StructLayout = defineStructLayout('ResolveUniforms', 1, [
  ['imageSize', 'vec2u'],
  ['toneMapping', 'u32', 'TONE_MAPPING_* of tonemap.wgsl'],
  ['exposure', 'f32'],
]);

/**
 * Slots of the u32 counter buffer (atomics in WGSL). Queue lengths first, then per-render statistics.
 */
export const queueCounterSlots = {
  pathCount0: 0,
  pathCount1: 1,
  shadowCount: 2,
  cameraRays: 3,
  extensionRays: 4,
  shadowRays: 5,
  escapedPaths: 6,
  russianRouletteTerminations: 7,
  maxDepthTerminations: 8,
  invalidSamples: 9,
  emitterHits: 10,
} as const;

export const queueCounterCount = 16;

/** Bytes of one statistics record (the counter buffer) read back per frame. */
export const rendererWavefrontComputeStatsStride = queueCounterCount * 4;

/** Paths continuing to this depth or deeper play Russian roulette (pbrt-v4 survival rule). */
export const russianRouletteStartDepth = 3;

/** Workgroup size of every 1-D wavefront kernel. */
export const rendererWavefrontComputeWorkgroupSize = 64;

/** Uniform slots bound with dynamic offsets must sit on this alignment (WebGPU's guaranteed minimum). */
export const dynamicUniformStride = 256;

export const PRIMITIVE_KIND_TRIANGLE = 0;
export const PRIMITIVE_KIND_SPHERE = 1;
export const PRIMITIVE_KIND_BOX = 2;
export const PRIMITIVE_NONE = 0xffffffff;
export const SCENE_OBJECT_SPHERE = 1;
export const SCENE_OBJECT_BOX = 2;
export const MATERIAL_FLAG_DOUBLE_SIDED = 1;
export const TRIANGLE_FLAG_HAS_NORMALS = 1;
export const TRIANGLE_FLAG_HAS_UVS = 2;
export const PATH_FLAG_SPECULAR_BOUNCE = 1;
export const LIGHT_FLAG_DOUBLE_SIDED = 0x80000000;

/** Every record layout, by WGSL struct name. */
export const wavefrontRecordLayouts = {
  PathState: pathStateLayout,
  ShadowRay: shadowRayLayout,
  Triangle: triangleLayout,
  TriangleAttributes: triangleAttributesLayout,
  BvhNode: bvhNodeLayout,
  Material: materialLayout,
  SceneObject: sceneObjectLayout,
  LightEntry: lightEntryLayout,
  FrameUniforms: frameUniformsLayout,
  WaveUniforms: waveUniformsLayout,
  BounceUniforms: bounceUniformsLayout,
  ResolveUniforms: resolveUniformsLayout,
} as const;

/** GPU record sizes in bytes (the mirrored package's "GPU record-size constants"). */
export const rendererWavefrontRecordSizes = {
  pathState: pathStateLayout.size,
  shadowRay: shadowRayLayout.size,
  triangle: triangleLayout.size,
  triangleAttributes: triangleAttributesLayout.size,
  bvhNode: bvhNodeLayout.size,
  material: materialLayout.size,
  sceneObject: sceneObjectLayout.size,
  lightEntry: lightEntryLayout.size,
  accumulationTexel: 16,
} as const;

export const rendererWavefrontPathStateBytes = pathStateLayout.size;
export const rendererWavefrontShadowRayBytes = shadowRayLayout.size;
export const rendererWavefrontTriangleBytes = triangleLayout.size;
export const rendererWavefrontTriangleAttributesBytes = triangleAttributesLayout.size;
export const rendererWavefrontBvhNodeBytes = bvhNodeLayout.size;
export const rendererWavefrontMaterialBytes = materialLayout.size;
export const rendererWavefrontSceneObjectBytes = sceneObjectLayout.size;
export const rendererWavefrontLightEntryBytes = lightEntryLayout.size;
export const rendererWavefrontAccumulationTexelBytes = 16;
