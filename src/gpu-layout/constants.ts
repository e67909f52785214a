/**
 * Constants shared by TypeScript and WGSL: the single definition of every slot number, flag bit,
 * kind id and size both sides must agree on. The `package::layout::constants` WGSL module is
 * generated from `gpuConstants` (see scripts/shader-build/layout-modules.ts), so nothing is kept equal by comment.
 */
import {
  anisotropy,
  anyMaterialExtensions,
  clearcoat,
  diffuseTransmission,
  dispersion,
  iridescence,
  sheen,
  specular,
  transmission,
  volume,
} from '../materials/extensions/index.ts';

/**
 * Statistics words at the head of the `queues` buffer (atomics in WGSL), read back per frame.
 * The luminance tallies are 64-bit fixed point (lo word, then hi word; LUMINANCE_FRACTION_BITS
 * fractional bits), summed per workgroup.
 */
export const queueCounterSlots = {
  cameraRays: 0,
  extensionRays: 1,
  shadowRays: 2,
  escapedPaths: 3,
  russianRouletteTerminations: 4,
  maxDepthTerminations: 5,
  invalidSamples: 6,
  emitterHits: 7,
  absorbedPaths: 8,
  invalidBsdfSamples: 9,
  traversalFallbacks: 10,
  invalidPathSamples: 11,
  invalidThroughputTerminations: 12,
  clampEquivalentSamples: 13,
  totalLuminanceLo: 14,
  totalLuminanceHi: 15,
  emitterLuminanceLo: 16,
  emitterLuminanceHi: 17,
  environmentLuminanceLo: 18,
  environmentLuminanceHi: 19,
} as const;

export type QueueCounterName = keyof typeof queueCounterSlots;

/** Statistics words (the block read back per frame). */
export const queueCounterCount = 32;

/** Bytes of one statistics record (the counter block) read back per frame. */
export const rendererWavefrontComputeStatsStride = queueCounterCount * 4;

/**
 * The rest of the `queues` buffer: after the statistics, four length words per bounce (rays to
 * trace at that depth, shadow rays its scatter queued, and its rays that hit and that escaped),
 * indexed from depth -1 (whose words stay 0: the camera queues no shadow ray) to maxDepth + 1;
 * then the entries (path slots) of the two ping-pong ray queues, of the shadow queue and of the
 * shading queue (hits from the front, escaped rays from the back), `capacity` words each.
 */
export const queueLayoutWords = {
  lengthsBase: queueCounterCount,
  wordsPerBounce: 4,
  entriesBase: 256,
} as const;

/** The length words of a bounce, in order. */
export const queueLengthKinds = { rays: 0, shadows: 1, hits: 2, misses: 3 } as const;

/** Length word of queue `kind` of bounce `depth` (>= -1). */
export function queueLengthWord(depth: number, kind: keyof typeof queueLengthKinds): number {
  return queueLayoutWords.lengthsBase + queueLayoutWords.wordsPerBounce * (depth + 1) + queueLengthKinds[kind];
}

/** Words of the `queues` buffer for waves of `capacity` paths. */
export function queueBufferWords(capacity: number): number {
  return queueLayoutWords.entriesBase + 4 * capacity;
}

/** Paths continuing to this depth or deeper play Russian roulette (pbrt-v4 survival rule). */
export const russianRouletteStartDepth = 3;

/** Workgroup size of every 1-D wavefront kernel. */
export const rendererWavefrontComputeWorkgroupSize = 64;

/** Words of one indirect dispatch's arguments (workgroups in x, y and z; WebGPU §21.2.2). */
export const indirectDispatchWords = 3;

/** Bytes of one indirect dispatch's arguments. */
export const indirectDispatchBytes = indirectDispatchWords * 4;

/** Uniform slots bound with dynamic offsets sit on this alignment (WebGPU's guaranteed minimum). */
export const dynamicUniformStride = 256;

/**
 * Entries of the BVH traversal stack: one push per level, so every tree of depth <= this (every
 * tree the CPU builder makes, BVH_MAX_DEPTH = 48) traverses with the stack alone. A deeper tree
 * (another builder's) does not lose geometry: a ray that would overflow the stack restarts from
 * the root in stackless mode, walking parent links (counted in `traversalFallbacks`).
 */
export const bvhTraversalStackSize = 48;

export const INDEX_NONE = 0xffffffff;

export const PRIMITIVE_SHAPE_TRIANGLE = 0;
export const PRIMITIVE_SHAPE_SPHERE = 1;
export const PRIMITIVE_SHAPE_BOX = 2;
/**
 * A placement of a shared mesh in the top level (two-level acceleration, pathtracer/scene/instancing.ts):
 * v0 and e1 are its world-space box, `instance` the placement, whose bottom-level tree the ray enters
 * in object space.
 */
export const PRIMITIVE_SHAPE_INSTANCE = 3;
export const PRIMITIVE_SHAPE_MASK = 3;
export const PRIMITIVE_FLAG_ALPHA = 4;
/** A triangle of a single-sided material (glTF `doubleSided: false`): camera rays cull its back face. */
export const PRIMITIVE_FLAG_SINGLE_SIDED = 8;
/** Its instance mirrors (negative determinant): the front face is clockwise in world space. */
export const PRIMITIVE_FLAG_MIRRORED = 16;
export const PRIMITIVE_ALPHA_SHIFT = 5;

export const INSTANCE_FLAG_NEGATIVE_DETERMINANT = 1 << 2;
export const INSTANCE_FLAG_HAS_NORMALS = 1 << 3;
export const INSTANCE_FLAG_HAS_TANGENTS = 1 << 4;
export const INSTANCE_FLAG_HAS_UV0 = 1 << 5;
export const INSTANCE_FLAG_HAS_UV1 = 1 << 6;
export const INSTANCE_FLAG_HAS_COLORS = 1 << 7;

/**
 * Words per vertex of each vertex stream (the shared `vertexStreams` buffer holds, per mesh, one
 * stream per attribute it has): position xyz (f32), normal (octahedral snorm16x2), tangent
 * (octahedral snorm16x2, bitangent sign as f32), colour (unorm8x4), uv0 and uv1 (f32 pairs).
 */
export const VERTEX_POSITION_WORDS = 3;
export const VERTEX_NORMAL_WORDS = 1;
export const VERTEX_TANGENT_WORDS = 2;
export const VERTEX_COLOR_WORDS = 1;
export const VERTEX_UV_WORDS = 2;
/**
 * A normal-stream word that pack2x16snorm never produces (-32768 in both halves): the vertex's
 * normal was zero or degenerate, and triangles using it shade with the geometric normal.
 */
export const VERTEX_NORMAL_INVALID = 0x80008000;

export const MATERIAL_FLAG_DOUBLE_SIDED = 1;
export const MATERIAL_ALPHA_MODE_SHIFT = 1;
export const MATERIAL_ALPHA_MODE_MASK = 3 << 1;
export const ALPHA_MODE_OPAQUE = 0;
export const ALPHA_MODE_MASK = 1;
export const ALPHA_MODE_BLEND = 2;

export const TEXTURE_BINDING_FLAG_SRGB = 1;

// ---- Materials: KHR extensions, tables, media (materials subsystem) ----------------------------
/**
 * MaterialCore.flags bits, one per KHR material extension that changes the BSDF (set only when the
 * extension's factors make a difference). SurfaceRecord.flags carries the same bits (above the
 * SURFACE_FLAG_* bits), so the scatter kernel knows which packed parameters and blocks to read.
 */
// Each registry extension declares its bit (materials/extensions/<name>/extension.ts).
export const MATERIAL_FLAG_SPECULAR = extensionFlag(specular);
export const MATERIAL_FLAG_TRANSMISSION = extensionFlag(transmission);
/** A refractive solid: KHR_materials_volume with thicknessFactor > 0 and some transmission. */
export const MATERIAL_FLAG_VOLUME = extensionFlag(volume);
export const MATERIAL_FLAG_CLEARCOAT = extensionFlag(clearcoat);
export const MATERIAL_FLAG_SHEEN = extensionFlag(sheen);
export const MATERIAL_FLAG_IRIDESCENCE = extensionFlag(iridescence);
export const MATERIAL_FLAG_ANISOTROPY = extensionFlag(anisotropy);
export const MATERIAL_FLAG_DIFFUSE_TRANSMISSION = extensionFlag(diffuseTransmission);
export const MATERIAL_FLAG_DISPERSION = extensionFlag(dispersion);
/** Multiple-scattering energy compensation (the renderer's energyCompensation option). */
export const MATERIAL_FLAG_ENERGY_COMPENSATION = 1 << 17;
/** KHR_materials_ior ior = 0: the specular-glossiness compatibility mode, Fresnel = 1. */
export const MATERIAL_FLAG_IOR_INFINITE = 1 << 18;
/** The flag constants of every registry extension, by name (MATERIAL_FLAG_<NAME>: bit). */
const materialExtensionFlags: Record<string, number> = Object.fromEntries(anyMaterialExtensions.map((e) => [e.flag.name, extensionFlag(e)]));
/** Every extension bit (what evaluate-materials copies into SurfaceRecord.flags). */
export const MATERIAL_EXTENSION_MASK = Object.values(materialExtensionFlags).reduce((a, b) => a | b, MATERIAL_FLAG_ENERGY_COMPENSATION | MATERIAL_FLAG_IOR_INFINITE);

/**
 * vec4s of PackedLobeParams.layers (materials/bsdf.wesl): two for each KHR extension that is a layer
 * over the base BSDF (its layer.wesl `unpack_params`), in registry order.
 */
export const PACKED_LAYER_VEC4S = 2 * anyMaterialExtensions.filter((e) => e.layer !== undefined).length;

function extensionFlag(e: { flag: { bit: number } }): number {
  return 1 << e.flag.bit;
}

/** Heap offset of the MaterialTables directory (the tables, when present, open the heap). */
export const MATERIAL_TABLES_OFFSET = 0;
/**
 * Resolution of the albedo tables (materials/energy): cosine nodes mu_i = i / (n - 1) and
 * perceptual-roughness nodes r_j = j / (n - 1); dielectric tables add nodes over
 * y = sign(x) sqrt(|x|), x = (eta - 1) / (eta + 1), in [-1, 1] (energy/albedo-tables.ts).
 */
export const ENERGY_TABLE_MU_NODES = 32;
export const ENERGY_TABLE_ROUGHNESS_NODES = 32;
export const DIELECTRIC_TABLE_MU_NODES = 16;
export const DIELECTRIC_TABLE_ROUGHNESS_NODES = 16;
export const DIELECTRIC_TABLE_ETA_NODES = 33;
/** Sheen albedo table resolution (cosine x sheen roughness). */
export const SHEEN_TABLE_NODES = 32;
/** Spectral response table: RGB of one wavelength at SPECTRAL_TABLE_NODES nodes over [SPECTRAL_MIN_NM, SPECTRAL_MAX_NM]. */
export const SPECTRAL_TABLE_NODES = 95;
export const SPECTRAL_MIN_NM = 360;
export const SPECTRAL_MAX_NM = 830;
/**
 * PathState.media holds MEDIUM_STACK_DEPTH 8-bit medium ids: one u32 of the path record, so a path
 * nests at most four media. The CPU transport helpers (src/transport/medium-stack.ts) take their
 * bound from here, so the reference and the kernels cannot disagree.
 */
export const MEDIUM_STACK_DEPTH = 4;
/** Medium ids are 8-bit: at most this many refractive-solid materials per scene. */
export const MAX_MEDIA = 255;
/** PathState.flags: the f16 wavelength of a dispersive path sits above this shift. */
export const PATH_WAVELENGTH_SHIFT = 16;
/**
 * The Fraunhofer F, D and C lines (486.1, 587.6 and 656.3 nm) that define the Abbe number of
 * KHR_materials_dispersion, in tenths of a nanometre (integers, as every generated WGSL constant
 * is). src/transport/spectral-samples.ts derives its nanometre values from these.
 */
export const FRAUNHOFER_F_TENTHS_NM = 4861;
export const FRAUNHOFER_D_TENTHS_NM = 5876;
export const FRAUNHOFER_C_TENTHS_NM = 6563;

/** TextureInfo.sampler bit fields. */
export const SAMPLER_WRAP_REPEAT = 0;
export const SAMPLER_WRAP_CLAMP = 1;
export const SAMPLER_WRAP_MIRROR = 2;
export const SAMPLER_WRAP_S_SHIFT = 0;
export const SAMPLER_WRAP_T_SHIFT = 2;
/** Bit set: magnification filter is linear. */
export const SAMPLER_MAG_LINEAR = 1 << 4;
/** Bit set: minification within a level is linear. */
export const SAMPLER_MIN_LINEAR = 1 << 5;
/** Bit set: mip levels are used at all. */
export const SAMPLER_MIPMAPS = 1 << 6;
/** Bit set: blend between two mip levels. */
export const SAMPLER_MIP_LINEAR = 1 << 7;

export const LIGHT_KIND_TRIANGLE = 0;
export const LIGHT_FLAG_DOUBLE_SIDED = 1;
export const LIGHT_FLAG_TEXTURED = 2;
// Lighting: kinds inside the lights heap's records (see src/lighting/gpu-lighting.ts).
/** AreaLight.kind. */
export const AREA_LIGHT_RECTANGLE = 0;
export const AREA_LIGHT_DISK = 1;
export const AREA_LIGHT_SPHERE = 2;
export const AREA_LIGHT_FLAG_TWO_SIDED = 1;
/** PunctualLight.kind. */
export const PUNCTUAL_LIGHT_POINT = 0;
export const PUNCTUAL_LIGHT_SPOT = 1;
export const PUNCTUAL_LIGHT_DIRECTIONAL = 2;
/** LightTreeNode.flags. */
export const LIGHT_TREE_FLAG_LEAF = 1;
export const LIGHT_TREE_FLAG_TWO_SIDED = 2;
/** LightingUniforms.portalMode. */
export const PORTAL_MODE_GUIDE = 0;
export const PORTAL_MODE_GUIDE_AND_GATE = 1;

export const CAMERA_PERSPECTIVE = 0;
export const CAMERA_ORTHOGRAPHIC = 1;

export const PATH_FLAG_SPECULAR_BOUNCE = 1;

export const SURFACE_FLAG_FRONT_FACE = 1;
export const SURFACE_FLAG_DOUBLE_SIDED = 2;
export const SURFACE_FLAG_ANALYTIC = 4;
/** The record is an escaped ray (wo = -direction): the environment's radiance reaches it. */
export const SURFACE_FLAG_ESCAPED = 8;

/** Fractional bits of the 64-bit fixed-point luminance tallies of the frame diagnostics. */
export const LUMINANCE_FRACTION_BITS = 16;
/**
 * Samples with a channel above this count as `legacyClampEquivalentSamples`: what the 0.2
 * API's legacy 4.0 clamp would have altered (a figure its hosts track). Counted only; nothing is clamped.
 */
export const LEGACY_CLAMP_EQUIVALENT_RADIANCE = 4;

/** Header words of the adaptive-sampling pixel list (then the active pixel indices). */
export const adaptiveListSlots = {
  /** Pixels still sampling (the list length). */
  activeCount: 0,
  /** Predicted samples the active pixels still need, 64-bit (lo, hi). */
  predictedSamplesLo: 2,
  predictedSamplesHi: 3,
  listStart: 4,
} as const;

export const PRESENTATION_TONEMAPPED = 0;
export const PRESENTATION_LINEAR = 1;

export const TONE_MAPPING_NEUTRAL = 0;
export const TONE_MAPPING_ACES = 1;
export const TONE_MAPPING_LINEAR = 2;
export const TONE_MAPPING_AGX = 3;

/**
 * Fixed sizes of the GPU BVH builder (src/accel/gpu-build/): workgroups of 256 threads; the radix
 * sort moves 4-bit digits in blocks of 4 keys per thread; the scan handles 4 elements per thread.
 */
export const bvhBuildConstants = {
  BVH_BUILD_WORKGROUP: 256,
  BVH_SORT_ITEMS: 16,
  BVH_SORT_BLOCK: 4096,
  BVH_SORT_RADIX: 16,
  BVH_SCAN_BLOCK: 1024,
  /** Primitives per invocation of the centroid-bounds reduction. */
  BVH_REDUCE_ITEMS: 16,
  /** Words per LBVH interior node in lbvhData: box (6), SAH cost, height and flags. */
  BVH_DATA_WORDS: 8,
  /** A box word not yet written (the NaN pattern no finite box produces). */
  BVH_UNWRITTEN: 0xffffffff,
  /** Read attempts of a box another invocation published before giving up (see lbvh-fit.wesl). */
  BVH_PUBLISH_SPIN_LIMIT: 1 << 20,
  /** buildSummary words. */
  BVH_SUMMARY_NODE_COUNT: 0,
  BVH_SUMMARY_DEPTH: 1,
  BVH_SUMMARY_SAH_COST: 2,
  BVH_SUMMARY_LEAF_COUNT: 3,
  BVH_SUMMARY_ERRORS: 4,
  BVH_SUMMARY_WORDS: 8,
} as const;

/** Every constant the WGSL side sees, by its WGSL name (all u32). */
export const gpuConstants: Readonly<Record<string, number>> = Object.freeze({
  QUEUE_COUNTER_COUNT: queueCounterCount,
  WORKGROUP_SIZE: rendererWavefrontComputeWorkgroupSize,
  INDIRECT_DISPATCH_WORDS: indirectDispatchWords,
  RUSSIAN_ROULETTE_DEPTH: russianRouletteStartDepth,
  BVH_STACK_SIZE: bvhTraversalStackSize,
  INDEX_NONE,
  PRIMITIVE_SHAPE_TRIANGLE,
  PRIMITIVE_SHAPE_SPHERE,
  PRIMITIVE_SHAPE_BOX,
  PRIMITIVE_SHAPE_INSTANCE,
  PRIMITIVE_SHAPE_MASK,
  PRIMITIVE_FLAG_ALPHA,
  PRIMITIVE_FLAG_SINGLE_SIDED,
  PRIMITIVE_FLAG_MIRRORED,
  PRIMITIVE_ALPHA_SHIFT,
  INSTANCE_FLAG_NEGATIVE_DETERMINANT,
  INSTANCE_FLAG_HAS_NORMALS,
  INSTANCE_FLAG_HAS_TANGENTS,
  INSTANCE_FLAG_HAS_UV0,
  INSTANCE_FLAG_HAS_UV1,
  INSTANCE_FLAG_HAS_COLORS,
  VERTEX_POSITION_WORDS,
  VERTEX_NORMAL_WORDS,
  VERTEX_TANGENT_WORDS,
  VERTEX_COLOR_WORDS,
  VERTEX_UV_WORDS,
  VERTEX_NORMAL_INVALID,
  MATERIAL_FLAG_DOUBLE_SIDED,
  MATERIAL_ALPHA_MODE_SHIFT,
  MATERIAL_ALPHA_MODE_MASK,
  ALPHA_MODE_OPAQUE,
  ALPHA_MODE_MASK,
  ALPHA_MODE_BLEND,
  TEXTURE_BINDING_FLAG_SRGB,
  ...materialExtensionFlags,
  MATERIAL_FLAG_ENERGY_COMPENSATION,
  MATERIAL_FLAG_IOR_INFINITE,
  MATERIAL_EXTENSION_MASK,
  PACKED_LAYER_VEC4S,
  MATERIAL_TABLES_OFFSET,
  ENERGY_TABLE_MU_NODES,
  ENERGY_TABLE_ROUGHNESS_NODES,
  DIELECTRIC_TABLE_MU_NODES,
  DIELECTRIC_TABLE_ROUGHNESS_NODES,
  DIELECTRIC_TABLE_ETA_NODES,
  SHEEN_TABLE_NODES,
  SPECTRAL_TABLE_NODES,
  SPECTRAL_MIN_NM,
  SPECTRAL_MAX_NM,
  MEDIUM_STACK_DEPTH,
  MAX_MEDIA,
  PATH_WAVELENGTH_SHIFT,
  FRAUNHOFER_F_TENTHS_NM,
  FRAUNHOFER_D_TENTHS_NM,
  FRAUNHOFER_C_TENTHS_NM,
  SAMPLER_WRAP_REPEAT,
  SAMPLER_WRAP_CLAMP,
  SAMPLER_WRAP_MIRROR,
  SAMPLER_WRAP_S_SHIFT,
  SAMPLER_WRAP_T_SHIFT,
  SAMPLER_MAG_LINEAR,
  SAMPLER_MIN_LINEAR,
  SAMPLER_MIPMAPS,
  SAMPLER_MIP_LINEAR,
  LIGHT_KIND_TRIANGLE,
  LIGHT_FLAG_DOUBLE_SIDED,
  LIGHT_FLAG_TEXTURED,
  AREA_LIGHT_RECTANGLE,
  AREA_LIGHT_DISK,
  AREA_LIGHT_SPHERE,
  AREA_LIGHT_FLAG_TWO_SIDED,
  PUNCTUAL_LIGHT_POINT,
  PUNCTUAL_LIGHT_SPOT,
  PUNCTUAL_LIGHT_DIRECTIONAL,
  LIGHT_TREE_FLAG_LEAF,
  LIGHT_TREE_FLAG_TWO_SIDED,
  PORTAL_MODE_GUIDE,
  PORTAL_MODE_GUIDE_AND_GATE,
  CAMERA_PERSPECTIVE,
  CAMERA_ORTHOGRAPHIC,
  PATH_FLAG_SPECULAR_BOUNCE,
  SURFACE_FLAG_FRONT_FACE,
  SURFACE_FLAG_DOUBLE_SIDED,
  SURFACE_FLAG_ANALYTIC,
  SURFACE_FLAG_ESCAPED,
  TONE_MAPPING_NEUTRAL,
  TONE_MAPPING_ACES,
  TONE_MAPPING_LINEAR,
  TONE_MAPPING_AGX,
  LUMINANCE_FRACTION_BITS,
  LEGACY_CLAMP_EQUIVALENT_RADIANCE,
  PRESENTATION_TONEMAPPED,
  PRESENTATION_LINEAR,
  ...bvhBuildConstants,
  ...Object.fromEntries(Object.entries(adaptiveListSlots).map(([name, slot]) => [`ADAPTIVE_${snakeUpper(name)}`, slot])),
  ...Object.fromEntries(Object.entries(queueCounterSlots).map(([name, slot]) => [`COUNTER_${snakeUpper(name)}`, slot])),
  QUEUE_LENGTHS_BASE: queueLayoutWords.lengthsBase,
  QUEUE_WORDS_PER_BOUNCE: queueLayoutWords.wordsPerBounce,
  QUEUE_ENTRIES_BASE: queueLayoutWords.entriesBase,
});

function snakeUpper(name: string): string {
  return name.replace(/([A-Z])/g, '_$1').toUpperCase();
}
