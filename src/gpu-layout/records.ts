import { anyMaterialExtensions } from '../materials/extensions/index.ts';
import { defineStructLayout, type StructFieldSpec, type StructLayout } from './struct-layout.ts';
import { VERTEX_COLOR_WORDS, VERTEX_NORMAL_WORDS, VERTEX_POSITION_WORDS, VERTEX_TANGENT_WORDS, VERTEX_UV_WORDS } from './constants.ts';

/**
 * The GPU record contracts of the renderer: the single source of truth for the WGSL structs
 * (generated into the `package::layout::records` module) and for every TypeScript packer and
 * reader. Records are grouped by the bind group that holds them (see bindings.ts).
 */

// ---- Geometry (bind group 0, static) --------------------------------------------------------------

/**
 * One traceable primitive in BVH order: a world-space triangle in Moller-Trumbore form, an
 * analytic shape (sphere: v0 = centre, e1.x = radius; box: v0 = min, e1 = max), or a placement of a
 * shared mesh (PRIMITIVE_SHAPE_INSTANCE: v0 = world min, e1 = world max, `primitive` the root node
 * of its bottom level, e2.x the bits of its transform record's slot). After the top level come the
 * bottom levels' triangles (object space, `instance` INDEX_NONE), then one transform record per
 * placement: the rows of its world-to-object matrix in v0, e1, e2 and the bits of their
 * translations in instance, primitive, shape (instancing.ts; the buffer has one record type). `shape` packs the
 * kind (PRIMITIVE_SHAPE_MASK), the alpha-tested flag and the alpha record index (see primitive-shape.ts).
 */
export const primitiveLayout: StructLayout = defineStructLayout('Primitive', 2, [
  ['v0', 'vec3f'],
  ['instance', 'u32', 'index into instances'],
  ['e1', 'vec3f', 'v1 - v0'],
  ['primitive', 'u32', 'triangle index within the instance mesh'],
  ['e2', 'vec3f', 'v2 - v0'],
  ['shape', 'u32', 'kind | PRIMITIVE_FLAG_ALPHA | PRIMITIVE_FLAG_SINGLE_SIDED | PRIMITIVE_FLAG_MIRRORED | alpha record index << PRIMITIVE_ALPHA_SHIFT'],
]);

/** Flattened BVH node: interior nodes keep both children adjacent at leftOrFirst, leftOrFirst + 1. */
export const bvhNodeLayout: StructLayout = defineStructLayout('BvhNode', 1, [
  ['boundsMin', 'vec3f'],
  ['leftOrFirst', 'u32', 'first child (interior) or first primitive (leaf)'],
  ['boundsMax', 'vec3f'],
  ['primitiveCount', 'u32', '0 for interior nodes'],
]);

/**
 * Constants of one dispatch of the GPU BVH builder (src/accel/gpu-build/): the same record for every
 * pass, with the pass-specific fields (sort digit, scan level, node count) filled in per slot.
 */
export const bvhBuildUniformsLayout: StructLayout = defineStructLayout('BvhBuildUniforms', 1, [
  ['primitiveCount', 'u32', 'n: leaves of the LBVH'],
  ['internalCount', 'u32', 'n - 1: interior nodes of the LBVH'],
  ['keyWords', 'u32', 'Morton key words per primitive: 1 (30-bit codes) or 2 (60-bit)'],
  ['maxLeafSize', 'u32', 'subtrees of at most this many primitives may collapse into one leaf'],
  ['traversalCost', 'f32', 'SAH C_trav of the leaf-collapse decision'],
  ['intersectionCost', 'f32', 'SAH C_isect of the leaf-collapse decision'],
  ['digitShift', 'u32', 'radix sort: bit offset of this pass\'s 4-bit digit in its key word'],
  ['digitWord', 'u32', 'radix sort: key word of this pass\'s digit'],
  ['blockCount', 'u32', 'radix sort: blocks of SORT_BLOCK keys'],
  ['scanLength', 'u32', 'prefix scan: elements of this level'],
  ['nodeCount', 'u32', 'refit: records of the finished tree'],
  ['reserved0', 'u32'],
]);

/**
 * What any-hit and closest-hit traversal need to alpha test a primitive whose material is MASK or
 * BLEND: its three base-colour uvs (KHR_texture_transform already applied), vertex-colour alphas and
 * the material's alpha terms.
 */
export const alphaPrimitiveLayout: StructLayout = defineStructLayout('AlphaPrimitive', 1, [
  ['uv0', 'vec2f'],
  ['uv1', 'vec2f'],
  ['uv2', 'vec2f'],
  ['alphaCutoff', 'f32', 'MASK threshold'],
  ['alphaMode', 'u32', 'ALPHA_MODE_MASK or ALPHA_MODE_BLEND'],
  ['vertexAlpha', 'vec3f', 'COLOR_0 alpha at the three vertices'],
  ['alphaFactor', 'f32', 'baseColorFactor alpha'],
  ['texture', 'u32', 'materials-heap offset of the base-colour TextureInfo, or INDEX_NONE'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
  ['reserved2', 'u32'],
]);

/** A placement of a mesh: its object-to-world transform and where its streams start. */
export const instanceLayout: StructLayout = defineStructLayout('Instance', 2, [
  ['objectToWorld0', 'vec4f', 'row 0 of the affine 3x4 object-to-world matrix'],
  ['objectToWorld1', 'vec4f', 'row 1'],
  ['objectToWorld2', 'vec4f', 'row 2'],
  ['normalToWorld0', 'vec4f', 'row 0 of the inverse transpose of the linear part'],
  ['normalToWorld1', 'vec4f', 'row 1'],
  ['normalToWorld2', 'vec4f', 'row 2'],
  ['positions', 'u32', 'word offset of the mesh position stream in vertexStreams'],
  ['normals', 'u32', 'word offset of the normal stream, or INDEX_NONE'],
  ['tangents', 'u32', 'word offset of the tangent stream, or INDEX_NONE'],
  ['colors', 'u32', 'word offset of the COLOR_0 stream, or INDEX_NONE'],
  ['uv0', 'u32', 'word offset of the TEXCOORD_0 stream, or INDEX_NONE'],
  ['uv1', 'u32', 'word offset of the TEXCOORD_1 stream, or INDEX_NONE'],
  ['firstIndex', 'u32', 'first index of the mesh in indices (indices are mesh-local vertex numbers)'],
  ['material', 'u32', 'materials-heap offset of the MaterialCore'],
  ['flags', 'u32', 'INSTANCE_FLAG_* bits and the shape kind'],
  ['lightBase', 'u32', 'light index of the mesh triangle 0 when the material emits, else INDEX_NONE'],
  ['objectId', 'u32', 'user-facing instance id (AOVs)'],
]);

// ---- Materials and textures (bind group 1) --------------------------------------------------------

/**
 * The core of a glTF metallic-roughness material. Extension blocks and texture bindings live in the
 * same vec4 heap (the `materials` binding) at the offsets (in vec4 units) stored here; `flags`
 * carries one MATERIAL_FLAG_* bit per KHR extension that changes the material's look, so kernels
 * read a block only when its bit is set.
 */
export const materialCoreLayout: StructLayout = defineStructLayout('MaterialCore', 3, [
  ['baseColor', 'vec4f', 'linear RGB + alpha'],
  ['emission', 'vec3f', 'emissiveFactor * emissiveStrength'],
  ['metallic', 'f32'],
  ['roughness', 'f32', 'perceptual; alpha = roughness^2'],
  ['ior', 'f32', 'KHR_materials_ior (0: the specular-glossiness mode, MATERIAL_FLAG_IOR_INFINITE)'],
  ['alphaCutoff', 'f32'],
  ['flags', 'u32', 'MATERIAL_FLAG_* bits and the alpha mode'],
  ['baseColorTexture', 'u32', 'TextureBinding heap offset or INDEX_NONE'],
  ['metallicRoughnessTexture', 'u32'],
  ['normalTexture', 'u32'],
  ['emissiveTexture', 'u32'],
  // One heap offset (INDEX_NONE: absent) per registry extension with a block, named by its key.
  ...extensionBlockOffsetFields(),
  ['dispersion', 'f32', 'KHR_materials_dispersion (20 / Abbe number)'],
  ['reserved', 'u32'],
]);

// KHR material extension blocks (heap records a MaterialCore points to) are declared with their
// extensions (materials/extensions/<name>/extension.ts).
const extensionBlockLayouts: StructLayout[] = anyMaterialExtensions.flatMap((e) => (e.block ? [e.block.layout] : []));

function extensionBlockOffsetFields(): StructFieldSpec[] {
  return anyMaterialExtensions.flatMap((e): StructFieldSpec[] => (e.block ? [[e.key, 'u32', `${e.block.layout.name} heap offset (${e.name})`]] : []));
}

/** One interior medium (a KHR_materials_volume material): what a path inside it sees. */
export const mediumRecordLayout: StructLayout = defineStructLayout('MediumRecord', 1, [
  ['attenuation', 'vec3f', 'absorption coefficient per unit length (Beer-Lambert)'],
  ['ior', 'f32', 'index of refraction at the Fraunhofer d line (0: infinite)'],
  ['dispersion', 'f32', 'KHR_materials_dispersion, 20 / Abbe number'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
  ['reserved2', 'u32'],
]);

/**
 * Directory of the material tables at heap offset MATERIAL_TABLES_OFFSET (present when a material
 * needs one): precomputed albedos for layering and energy compensation, the media of
 * KHR_materials_volume and the spectral response of dispersion. Offsets in vec4 units; tables of
 * f32 hold four entries per vec4.
 */
export const materialTablesLayout: StructLayout = defineStructLayout('MaterialTables', 1, [
  ['ggxAlbedo', 'u32', 'E(mu, r) of GGX reflection with F = 1, then its cosine-weighted average per r'],
  ['dielectricAlbedo', 'u32', 'E(mu, r, eta) of dielectric GGX reflection with the exact Fresnel term, then averages per (eta, r)'],
  ['dielectricTransmission', 'u32', 'E(mu, r, eta) of a rough dielectric interface, reflection + transmission'],
  ['sheenAlbedo', 'u32', 'E(mu, r) of the Charlie sheen lobe'],
  ['media', 'u32', 'MediumRecord array (medium id k at media + (k - 1) * size)'],
  ['mediumCount', 'u32'],
  ['spectral', 'u32', 'RGB response of single wavelengths (dispersion)'],
  ['clearcoatAlbedo', 'u32', 'E(mu, r) of the clearcoat layer (dielectric reflection at ior 1.5)'],
]);

/** A texture within the atlas: its mip chain occupies one block of one layer. */
export const textureInfoLayout: StructLayout = defineStructLayout('TextureInfo', 1, [
  ['origin', 'vec2u', 'texel origin of the mip-chain block in the layer'],
  ['size', 'vec2u', 'level-0 size in texels'],
  ['layer', 'u32'],
  ['mipCount', 'u32'],
  ['sampler', 'u32', 'wrap S/T, filters: SAMPLER_* fields'],
  ['reserved', 'u32'],
]);

/** A material slot's use of a texture: which texture, which uv set, the KHR_texture_transform. */
export const textureBindingLayout: StructLayout = defineStructLayout('TextureBinding', 1, [
  ['transform0', 'vec3f', 'row 0 of the 2x3 uv transform (a, b, tx)'],
  ['texture', 'u32', 'materials-heap offset of the TextureInfo'],
  ['transform1', 'vec3f', 'row 1 (c, d, ty)'],
  ['texCoord', 'u32', 'uv set, 0 or 1'],
  ['scale', 'f32', 'normal map scale or occlusion strength'],
  ['flags', 'u32', 'TEXTURE_BINDING_FLAG_SRGB'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
]);

// ---- Lighting and the frame (bind group 2) --------------------------------------------------------

/**
 * An emitter in the lights heap. Triangle lights (kind LIGHT_KIND_TRIANGLE) carry their world-space
 * geometry and the alias-table bin that selects lights in proportion to power (Vose).
 */
export const lightRecordLayout: StructLayout = defineStructLayout('LightRecord', 2, [
  ['v0', 'vec3f'],
  ['kind', 'u32', 'LIGHT_KIND_*'],
  ['e1', 'vec3f'],
  ['flags', 'u32', 'LIGHT_FLAG_* bits'],
  ['e2', 'vec3f'],
  ['instance', 'u32', 'emitting instance'],
  ['emission', 'vec3f', 'emitted radiance (material factor; textures multiply it)'],
  ['primitive', 'u32', 'emitting triangle within the instance mesh'],
  ['pmf', 'f32', 'probability that light selection picks this light'],
  ['aliasThreshold', 'f32', 'alias table: keep this bin when u < threshold'],
  ['aliasIndex', 'u32'],
  ['area', 'f32', 'world-space area'],
  ['uv0', 'vec2f', 'emissive-texture uvs of the vertices (KHR_texture_transform applied)'],
  ['uv1', 'vec2f'],
  ['uv2', 'vec2f'],
  ['texture', 'u32', 'materials-heap offset of the emissive TextureInfo, or INDEX_NONE'],
  ['reserved', 'u32'],
]);

// Lighting. Every emitter and sampling table lives in the `lights` vec4 heap (loaders
// generated below); src/lighting/gpu-lighting.ts packs it, src/lighting/*.wesl read it.

/**
 * Selection of bounded light g (emissive triangles, then area lights, then point and spot lights)
 * for next-event estimation: its Walker/Vose alias bin over estimated power, its probability under
 * that table, and its light-tree leaf (for the pmf of the tree's traversal).
 */
export const lightSelectionEntryLayout: StructLayout = defineStructLayout('LightSelectionEntry', 1, [
  ['aliasThreshold', 'f32', 'keep bin g when the scaled residual < threshold, else take aliasIndex'],
  ['aliasIndex', 'u32'],
  ['pmf', 'f32', 'probability that the power alias table picks g'],
  ['treeLeaf', 'u32', 'heap-relative light-tree node of g, or INDEX_NONE when g is not in the tree'],
]);

/** An area light (80 bytes): rectangle, disk or sphere (src/lighting/area-lights.ts). */
export const areaLightLayout: StructLayout = defineStructLayout('AreaLight', 1, [
  ['corner', 'vec3f', 'rectangle: center - edgeU/2 - edgeV/2; disk, sphere: the centre'],
  ['kind', 'u32', '0 rectangle, 1 disk, 2 sphere'],
  ['edgeU', 'vec3f', 'rectangle: full edge; disk: unit tangent'],
  ['radius', 'f32', 'disk, sphere'],
  ['edgeV', 'vec3f', 'rectangle: full edge; disk: unit bitangent'],
  ['flags', 'u32', 'bit 0: two-sided'],
  ['normal', 'vec3f', 'unit front-face normal (rectangle, disk)'],
  ['area', 'f32', 'one side'],
  ['radiance', 'vec3f', 'emission x intensity'],
]);

/**
 * A KHR_lights_punctual light (64 bytes). Infinite range is stored as invRange = 0 so the shader
 * needs no infinities: window = saturate(1 - (d * invRange)^4).
 */
export const punctualLightLayout: StructLayout = defineStructLayout('PunctualLight', 1, [
  ['position', 'vec3f', 'world position (point, spot)'],
  ['kind', 'u32', '0 point, 1 spot, 2 directional'],
  ['direction', 'vec3f', 'unit direction the light travels in (spot, directional)'],
  ['invRange', 'f32', '1 / range; 0 = unbounded'],
  ['intensity', 'vec3f', 'color x intensity: cd (point, spot) or lux (directional)'],
  ['spotScale', 'f32', '1 / max(0.001, cos(inner) - cos(outer))'],
  ['spotOffset', 'f32', '-cos(outer) * spotScale'],
]);

/** A node of the light hierarchy (64 bytes, depth-first; src/lighting/light-tree.ts). */
export const lightTreeNodeLayout: StructLayout = defineStructLayout('LightTreeNode', 1, [
  ['boundsMin', 'vec3f'],
  ['phi', 'f32', 'luminance-weighted intensity bound (sum over the subtree)'],
  ['boundsMax', 'vec3f'],
  ['cosThetaO', 'f32', 'normal cone spread'],
  ['axis', 'vec3f', 'normal cone axis (unit)'],
  ['cosThetaE', 'f32', 'emission spread around each normal'],
  ['childOrLight', 'u32', 'interior: index of the second child (the first is this + 1); leaf: light index'],
  ['parent', 'u32', '0xffffffff at the root'],
  ['flags', 'u32', 'bit 0: leaf; bit 1: two-sided'],
]);

/** One bin of the environment map's sampling tables (marginal over rows, conditional per row). */
export const environmentTableEntryLayout: StructLayout = defineStructLayout('EnvironmentTableEntry', 1, [
  ['threshold', 'f32', 'keep this bin when the scaled residual < threshold, else take aliasIndex'],
  ['aliasIndex', 'u32', 'marginal: a row; conditional: a column of the row'],
  ['pdf', 'f32', 'marginal: the row pmf; conditional: the density over (u, v) of this cell'],
  ['reserved', 'u32'],
]);

/**
 * An environment portal (64 bytes): a rectangle through which the environment lights an interior.
 * Its rectified density (n^2 values) and summed-area table ((n + 1)^2) are f32 values of the lights
 * heap, at LightingUniforms.portalDataOffset + funcOffset / satOffset (src/lighting/portals.ts).
 */
export const environmentPortalLayout: StructLayout = defineStructLayout('EnvironmentPortal', 1, [
  ['corner', 'vec3f'],
  ['resolution', 'u32', 'n: the rectified grid is n x n'],
  ['edgeU', 'vec3f'],
  ['funcOffset', 'u32', 'in f32 elements of the portal data array'],
  ['edgeV', 'vec3f'],
  ['satOffset', 'u32', 'in f32 elements of the portal data array'],
  ['normal', 'vec3f', 'unit, outward (towards the environment)'],
]);

/**
 * What next-event estimation and escaped rays need to find their way through the lights heap: the
 * environment map's size and tables, the sun disc, where each kind of emitter starts, the light
 * selection probabilities, and the portals. The environment map's radiance is the
 * `environmentTexture` binding.
 */
export const lightingUniformsLayout: StructLayout = defineStructLayout('LightingUniforms', 1, [
  ['environmentMapSize', 'vec2u', 'radiance texture width, height'],
  ['environmentTableSize', 'vec2u', 'sampling table width, height (cells; may be coarser than the map)'],
  ['environmentIntensity', 'f32', 'radiance = texel x intensity'],
  ['environmentRotationTurns', 'f32', 'rotationRadians / (2 pi), added to u'],
  ['environmentTableOffset', 'u32', 'heap cell of the marginal table (tableSize.y entries; the rows follow)'],
  ['portalCount', 'u32'],
  ['sunDirection', 'vec3f', 'unit, towards the sun'],
  ['sunOneMinusCosThetaMax', 'f32', '1 - cos(angular radius)'],
  ['sunRadiance', 'vec3f', 'mean radiance over the disc'],
  ['sunLimbDarkening', 'u32', '1: Eddington limb darkening'],
  ['sunSelectProbability', 'f32', 'probability that NEE samples the sun'],
  ['directionalSelectProbability', 'f32', 'probability that NEE samples a directional light (then uniformly)'],
  ['boundedSelectProbability', 'f32', 'probability that NEE samples a bounded light (tree or alias table)'],
  ['portalGuideProbability', 'f32', "'guide' mode: probability of sampling through the portals"],
  ['selectionOffset', 'u32', 'heap cell of LightSelectionEntry[boundedCount]'],
  ['triangleOffset', 'u32', 'heap cell of LightRecord[triangleCount] (7 cells each)'],
  ['areaOffset', 'u32', 'heap cell of AreaLight[areaCount]'],
  ['punctualOffset', 'u32', 'heap cell of PunctualLight[punctualCount + directionalCount]'],
  ['treeOffset', 'u32', 'heap cell of LightTreeNode[] (root first)'],
  ['triangleCount', 'u32'],
  ['areaCount', 'u32'],
  ['punctualCount', 'u32', 'point and spot lights (bounded)'],
  ['directionalCount', 'u32', 'directional lights, stored after the bounded punctual lights'],
  ['boundedCount', 'u32', 'triangleCount + areaCount + punctualCount'],
  ['portalOffset', 'u32', 'heap cell of EnvironmentPortal[portalCount]'],
  ['portalDataOffset', 'u32', 'f32 index (4 x heap cell) where the portals\' density and SAT values start'],
  ['portalMode', 'u32', 'PORTAL_MODE_GUIDE or PORTAL_MODE_GUIDE_AND_GATE'],
  ['treeNodeCount', 'u32', '0: bounded lights are picked by the power alias table'],
  ['environmentMapEnabled', 'u32', '1: the environment is the map (else the uniform colour)'],
  ['reserved', 'u32'],
]);

/** Per-frame constants: camera, environment, lights and scene extents. */
export const frameUniformsLayout: StructLayout = defineStructLayout('FrameUniforms', 2, [
  ['cameraPosition', 'vec3f'],
  ['tanHalfFovY', 'f32', 'perspective: tan(fovY / 2)'],
  ['cameraRight', 'vec3f'],
  ['aspect', 'f32'],
  ['cameraUp', 'vec3f'],
  ['cameraKind', 'u32', 'CAMERA_PERSPECTIVE or CAMERA_ORTHOGRAPHIC'],
  ['cameraForward', 'vec3f'],
  ['orthographicHalfHeight', 'f32'],
  ['environmentRadiance', 'vec3f', 'uniform environment radiance'],
  ['environmentSelectProbability', 'f32', 'probability that NEE samples the environment'],
  ['sceneCenter', 'vec3f'],
  ['sceneRadius', 'f32'],
  ['imageSize', 'vec2u'],
  ['maxDepth', 'u32'],
  ['seed', 'u32'],
  ['lightCount', 'u32'],
  ['queueCapacity', 'u32'],
  ['pixelSpreadAngle', 'f32', 'ray cone spread of one pixel (Akenine-Moller et al. 2019)'],
  ['reserved', 'u32'],
]);

// ---- Transport state (bind group 3, per dispatch) --------------------------------------------------

/** The persistent state of one path (one pixel sample of the wave), indexed by its slot. */
export const pathStateLayout: StructLayout = defineStructLayout('PathState', 4, [
  ['throughput', 'vec3f', 'path weight beta'],
  ['pixel', 'u32', 'global pixel index (y * width + x)'],
  ['prevPosition', 'vec3f', 'last scattering vertex (the camera for camera rays)'],
  ['misPdf', 'f32', 'solid-angle pdf of the BSDF sample that made the current ray; 0 = camera or delta'],
  ['prevNormal', 'u32', 'octahedral geometric normal at prevPosition'],
  ['sampleIndex', 'u32', 'index of this sample within the pixel sequence'],
  ['depth', 'u32', 'scattering vertices so far (pbrt-v4 depth)'],
  ['flags', 'u32', 'PATH_FLAG_* bits; high 16 bits: the f16 wavelength (nm) of a path that met a dispersive material, 0 otherwise'],
  ['etaScale', 'f32', 'accumulated eta^2 for Russian roulette across refraction'],
  ['coneSpread', 'f32', 'ray cone spread angle (the width travels with the ray)'],
  ['media', 'u32', 'nested medium stack: four 8-bit medium ids, innermost in the low byte (0: none)'],
]);

/** The path's next ray, waiting for closest-hit intersection (queued by its slot). */
export const rayWorkItemLayout: StructLayout = defineStructLayout('RayWorkItem', 3, [
  ['origin', 'vec3f'],
  ['slot', 'u32', 'path slot'],
  ['direction', 'vec3f', 'unit length'],
  ['tMax', 'f32'],
  ['coneWidth', 'f32', 'ray cone width at the origin (texture level of detail)'],
  ['coneSpread', 'f32', 'ray cone spread angle'],
]);

/**
 * What closest-hit intersection found for the path's ray: read by material evaluation. The hit
 * distance is the ray's `tMax` once traced (closest-hit traversal shortens the segment to the hit),
 * which keeps the path record at 256 bytes.
 */
export const pathHitLayout: StructLayout = defineStructLayout('PathHit', 1, [
  ['u', 'f32', 'barycentric of v1'],
  ['v', 'f32', 'barycentric of v2'],
  ['primitive', 'u32', 'the hit record in primitives (BVH order), INDEX_NONE for an escaped ray'],
  ['instance', 'u32', 'the placement whose bottom-level tree held the hit, INDEX_NONE for a top-level primitive (its record names its instance)'],
]);

/**
 * The surface at a hit after material evaluation, as the scatter stage reads it: the surface frame
 * and the resolved BSDF parameters after texture fetches and normal mapping. Material evaluation
 * and scatter run in one kernel, so the record lives in registers, never in memory. KHR extension
 * parameters that textures vary travel packed (pack2x16float pairs, colours in [0, 1] as unorm8);
 * constant ones (iridescence IOR, the medium, dispersion) the scatter stage re-reads from the
 * material heap. `flags` carries the material's MATERIAL_FLAG_* extension bits.
 */
export const surfaceRecordLayout: StructLayout = defineStructLayout('SurfaceRecord', 3, [
  ['position', 'vec3f'],
  ['slot', 'u32'],
  ['wo', 'vec3f', 'unit direction towards the previous vertex'],
  ['flags', 'u32', 'SURFACE_FLAG_* bits | MATERIAL_FLAG_* extension bits'],
  ['ng', 'vec3f', 'unit geometric normal on the front (counter-clockwise) side'],
  ['lightIndex', 'u32', 'light record of an emitting triangle, or INDEX_NONE'],
  ['shadingNormal', 'u32', 'octahedral, front side'],
  ['tangent', 'u32', 'octahedral, orthogonal to the shading normal (the anisotropy direction when anisotropic)'],
  ['instance', 'u32'],
  ['material', 'u32'],
  ['emission', 'vec3f', 'emitted radiance towards wo (zero from a single-sided back face)'],
  ['area', 'f32', 'world-space area of the hit triangle (0 for analytic shapes)'],
  ['baseColor', 'vec3f'],
  ['metallic', 'f32'],
  ['roughness', 'f32'],
  ['ior', 'f32'],
  ['coneWidth', 'f32', 'ray cone width at the hit'],
  ['extensions0', 'vec4u', "the base's KHR parameters, f16 pairs: (specular, transmission), (specularColor.rg), (specularColor.b, diffuseTransmission), (anisotropy, iridescence)"],
  ['extensions1', 'vec4u', 'f16 pair (iridescenceThickness nm, 0); unorm8 diffuseTransmissionColor; 0; 0'],
  ...layerFields(),
]);

/** One vec4u per KHR extension layer over the base BSDF: what its layer.wesl `pack` writes. */
function layerFields(): StructFieldSpec[] {
  return anyMaterialExtensions.flatMap((e): StructFieldSpec[] => (e.layer ? [[`${e.key}Layer`, 'vec4u', `${e.name} layer (its layer.wesl pack)`]] : []));
}

/** An any-hit query carrying the contribution it adds if unoccluded (NEE, pbrt-v4 style). */
export const shadowRayLayout: StructLayout = defineStructLayout('ShadowRay', 2, [
  ['origin', 'vec3f'],
  ['slot', 'u32'],
  ['direction', 'vec3f'],
  ['tMax', 'f32'],
  ['contribution', 'vec3f', 'radiance added to the slot when the segment is unoccluded'],
  ['reserved', 'u32'],
]);

/**
 * What one path sample contributes: radiance plus the first non-specular hit's AOVs, and the
 * luminance tallies of its terminal contributions (frame diagnostics `terminalRadiance`).
 */
export const sampleRecordLayout: StructLayout = defineStructLayout('SampleRecord', 2, [
  ['radiance', 'vec3f'],
  ['aovWritten', 'u32', '1 once the first non-specular hit wrote the AOVs'],
  ['albedo', 'vec3f'],
  ['depth', 'f32', 'distance from the camera to the first hit'],
  ['normal', 'vec3f', 'world shading normal'],
  ['objectId', 'u32', 'instance index of the first non-specular hit (readAov maps it to object and material ids)'],
  ['emission', 'vec3f', 'emitted radiance committed at the first non-specular hit (emission AOV; the denoiser leaves it out)'],
  ['emitterLuminance', 'f32', 'luminance committed from emitter hits (MIS-weighted)'],
  ['environmentLuminance', 'f32', 'luminance committed from escaped paths'],
  ['invalid', 'u32', '1 once a contribution of this sample was dropped as NaN, Inf or negative'],
  ['reserved', 'u32'],
]);

/**
 * Everything the wave keeps of one path, at its slot of the `paths` buffer: its state, its next ray
 * and that ray's hit, its pending shadow ray and its sample. One record per path (array of
 * structures) lets a kernel reach all of it through one binding; a kernel reads and writes only the
 * members it uses. The queues hold slot numbers.
 */
export const pathRecordLayout: StructLayout = defineStructLayout('PathRecord', 1, [
  ['state', pathStateLayout],
  ['ray', rayWorkItemLayout, 'the next ray (camera ray, then each continuation)'],
  ['hit', pathHitLayout, 'what closest-hit intersection found for `ray`'],
  ['shadow', shadowRayLayout, 'the next-event-estimation shadow ray of the last scattering vertex'],
  ['sample', sampleRecordLayout],
]);

/**
 * Per-wave constants: bound with a dynamic offset. A wave takes the contiguous run
 * [firstPath, firstPath + pathCount) of its range: full-frame waves, of the frame's pixels x
 * samples (path i of the run: pixel (firstPath + i) mod pixels, sample firstSample + (firstPath +
 * i) / pixels); list waves (adaptive sampling), of the step's active list entries x passes.
 */
export const waveUniformsLayout: StructLayout = defineStructLayout('WaveUniforms', 3, [
  ['firstPath', 'u32', 'full-frame waves: pixel of the first path (< pixels); list waves: offset into the step range'],
  ['firstSample', 'u32', 'full-frame waves: sample number of the first path'],
  ['pathCount', 'u32', 'paths of the wave (list waves: an upper bound, the GPU list length bounds it)'],
  ['passes', 'u32', 'list waves: samples each active pixel takes in this step'],
  ['list', 'u32', '1: a list wave (adaptive sampling), 0: a full-frame wave'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
  ['reserved2', 'u32'],
]);

/**
 * Per-bounce constants: word indices into the `queues` buffer. Every bounce has its own length
 * words (zeroed by the camera kernel), so no kernel resets a queue between bounces.
 */
export const bounceUniformsLayout: StructLayout = defineStructLayout('BounceUniforms', 3, [
  ['depth', 'u32'],
  ['rayCount', 'u32', 'length word of the ray queue this bounce traces and shades'],
  ['rayQueue', 'u32', 'first entry of that ray queue'],
  ['shadowCount', 'u32', 'length word of the shadow queue the previous bounce filled (traced with this bounce\'s rays)'],
  ['shadowQueue', 'u32', 'first entry of the shadow queue'],
  ['nextRayCount', 'u32', 'length word of the ray queue this bounce fills'],
  ['nextRayQueue', 'u32', 'first entry of that ray queue'],
  ['nextShadowCount', 'u32', 'length word of the shadow queue this bounce fills'],
  ['hitCount', 'u32', 'length word of the hits at the front of the shading queue'],
  ['missCount', 'u32', 'length word of the escaped rays at the back of the shading queue'],
  ['shadingQueue', 'u32', 'first entry of the shading queue'],
  ['shadingQueueLast', 'u32', 'last entry of the shading queue (escaped rays fill it backwards)'],
]);

/** Display resolve constants. */
export const resolveUniformsLayout: StructLayout = defineStructLayout('ResolveUniforms', 2, [
  ['imageSize', 'vec2u'],
  ['toneMapping', 'u32', 'TONE_MAPPING_* id'],
  ['exposure', 'f32', 'linear multiplier: exposure * 2^exposureEv'],
  ['output', 'u32', 'PRESENTATION_TONEMAPPED or PRESENTATION_LINEAR'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
  ['reserved2', 'u32'],
]);

// ---- Film (bind group 3, one record per pixel, row-major, top row first) ----------------------------
// Sums over a pixel's samples: readers divide by FilmPixel.samples. These records are the film's
// one layout: accumulate.wesl writes them, the adaptive test, the denoisers and the display read
// them, and src/film/accumulation/readback.ts and the buffer plan size and read them on the CPU.

/** One pixel of the film (the accumulation buffer). */
export const filmPixelLayout: StructLayout = defineStructLayout('FilmPixel', 1, [
  ['radiance', 'vec3f', 'sum of the radiance samples'],
  ['samples', 'f32', 'how many samples the sum holds'],
]);

/** One pixel of the AOV film: what the pixel's samples saw at their first non-specular hit. */
export const filmAovPixelLayout: StructLayout = defineStructLayout('FilmAovPixel', 1, [
  ['albedo', 'vec3f', 'sum of the hit albedos'],
  ['depth', 'f32', 'sum of the camera distances'],
  ['normal', 'vec3f', 'sum of the shading normals'],
  ['hits', 'f32', 'samples that reached a non-specular surface (coverage: hits / samples)'],
  ['emission', 'vec3f', 'sum of the emission seen at the hit (the denoisers add it back unfiltered)'],
  ['reflectedLuminanceSquared', 'f32', "sum of the squared luminance of the radiance without that emission (the a-trous filter's noise)"],
]);

/** One pixel of the film moments (adaptive sampling, the variance AOV, the denoiser). */
export const filmMomentsLayout: StructLayout = defineStructLayout('FilmMoments', 1, [
  ['evenRadiance', 'vec3f', "sum of the even-indexed samples (Cycles' half buffer)"],
  ['evenSamples', 'f32', 'how many even-indexed samples'],
  ['radianceSquared', 'vec3f', 'sum of the squared radiance'],
  ['luminanceSquared', 'f32', 'sum of the squared luminance'],
]);

/** One pixel of the a-trous denoiser's guides: means over the samples, read by every filter pass. */
export const denoiseGuideLayout: StructLayout = defineStructLayout('DenoiseGuide', 1, [
  ['albedo', 'vec3f'],
  ['depth', 'f32'],
  ['normal', 'vec3f'],
  ['coverage', 'f32', 'share of the samples that reached a non-specular surface'],
  ['emission', 'vec3f', 'mean emission at the first non-specular hit'],
  ['reserved0', 'f32'],
]);

// ---- Output: adaptive sampling and denoising (bind group 3, per pass) ------------------------------

/** Constants of the adaptive-sampling convergence test (Cycles' stop criterion). */
export const adaptiveUniformsLayout: StructLayout = defineStructLayout('AdaptiveUniforms', 1, [
  ['imageSize', 'vec2u'],
  ['threshold', 'f32', 'noise threshold of the per-pixel error'],
  ['minimumSamples', 'u32', 'pixels with fewer samples never converge'],
  ['exposure', 'f32', 'display exposure multiplying both estimates (Cycles film exposure)'],
  ['sampleCeiling', 'u32', 'most samples a pixel may take (bounds the predicted remaining samples)'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
]);

/** Constants of one pass of the edge-avoiding a-trous denoiser. */
export const denoiseUniformsLayout: StructLayout = defineStructLayout('DenoiseUniforms', 1, [
  ['imageSize', 'vec2u'],
  ['stepSize', 'u32', 'a-trous tap spacing 2^iteration in pixels'],
  ['inBase', 'u32', 'first pixel of the input half of denoiseColor'],
  ['outBase', 'u32', 'first pixel of the output half of denoiseColor'],
  ['sigmaLuminance', 'f32', 'luminance edge-stopping, in standard deviations of the noise'],
  ['sigmaNormal', 'f32', 'normal edge-stopping exponent'],
  ['sigmaDepth', 'f32', 'depth edge-stopping, in depth-gradient units'],
]);

/** One convolution of the OIDN network (src/film/denoise/oidn/conv.wesl). */
export const oidnConvUniformsLayout: StructLayout = defineStructLayout('OidnConvUniforms', 1, [
  ['size', 'vec2u', 'resolution the convolution runs at (width, height)'],
  ['sourceA', 'u32', 'vec4 channel groups of the first source'],
  ['sourceB', 'u32', 'vec4 channel groups of the concatenated second source (0: none)'],
  ['upsample', 'u32', '1: the first source is at half resolution (nearest-neighbour 2x upsampling)'],
  ['pool', 'u32', '1: the output is 2x2 max pooled'],
  ['destination', 'u32', 'vec4 channel groups of the destination'],
  ['blocks', 'u32', '16-channel output blocks (the weights hold blocks x 4 bias vec4s first)'],
]);

/** One tile of the OIDN input, output and autoexposure passes (src/film/denoise/oidn/image.wesl). */
export const oidnImageUniformsLayout: StructLayout = defineStructLayout('OidnImageUniforms', 1, [
  ['imageSize', 'vec2u'],
  ['tileOrigin', 'vec2u', 'image pixel of the tile tensor\'s pixel (0, 0)'],
  ['tileSize', 'vec2u', 'tile tensor size (multiples of 16)'],
  ['writeMin', 'vec2u', 'first image pixel the output pass writes'],
  ['writeMax', 'vec2u', 'one past the last image pixel it writes'],
  ['exposureBins', 'vec2u', 'autoexposure bins across and down'],
  ['colorStride', 'u32', 'vec4s per pixel of the colour buffer'],
  ['divideByCount', 'u32', '1: colour, albedo and normal are sums over the colour\'s alpha (a film)'],
  ['albedoStride', 'u32'],
  ['albedoOffset', 'u32'],
  ['normalStride', 'u32'],
  ['normalOffset', 'u32'],
  ['emissionStride', 'u32', '0: no emission bypass'],
  ['emissionOffset', 'u32'],
  ['inputChannels', 'u32', '3 colour, 6 + albedo, 9 + normal'],
  ['autoexposure', 'u32', '1: the input scale comes from the autoexposure pass'],
  ['inputScale', 'f32', 'the input scale when autoexposure is 0'],
]);

/** Every record layout, by WGSL struct name. */
export const wavefrontRecordLayouts = {
  Primitive: primitiveLayout,
  BvhNode: bvhNodeLayout,
  BvhBuildUniforms: bvhBuildUniformsLayout,
  AlphaPrimitive: alphaPrimitiveLayout,
  Instance: instanceLayout,
  MaterialCore: materialCoreLayout,
  ...(Object.fromEntries(extensionBlockLayouts.map((l) => [l.name, l])) as Record<string, StructLayout>),
  MediumRecord: mediumRecordLayout,
  MaterialTables: materialTablesLayout,
  TextureInfo: textureInfoLayout,
  TextureBinding: textureBindingLayout,
  LightRecord: lightRecordLayout,
  LightSelectionEntry: lightSelectionEntryLayout,
  AreaLight: areaLightLayout,
  PunctualLight: punctualLightLayout,
  LightTreeNode: lightTreeNodeLayout,
  EnvironmentTableEntry: environmentTableEntryLayout,
  EnvironmentPortal: environmentPortalLayout,
  LightingUniforms: lightingUniformsLayout,
  FrameUniforms: frameUniformsLayout,
  PathState: pathStateLayout,
  RayWorkItem: rayWorkItemLayout,
  PathHit: pathHitLayout,
  SurfaceRecord: surfaceRecordLayout,
  ShadowRay: shadowRayLayout,
  SampleRecord: sampleRecordLayout,
  PathRecord: pathRecordLayout,
  WaveUniforms: waveUniformsLayout,
  BounceUniforms: bounceUniformsLayout,
  ResolveUniforms: resolveUniformsLayout,
  FilmPixel: filmPixelLayout,
  FilmAovPixel: filmAovPixelLayout,
  FilmMoments: filmMomentsLayout,
  DenoiseGuide: denoiseGuideLayout,
  AdaptiveUniforms: adaptiveUniformsLayout,
  DenoiseUniforms: denoiseUniformsLayout,
  OidnConvUniforms: oidnConvUniformsLayout,
  OidnImageUniforms: oidnImageUniformsLayout,
} as const;

/** Records stored in vec4 heaps get generated WGSL loaders (`load_<snake name>(heap offset)`). */
export const heapRecordLayouts = {
  materials: [
    materialCoreLayout, textureInfoLayout, textureBindingLayout, ...extensionBlockLayouts, mediumRecordLayout, materialTablesLayout,
  ],
  lights: [lightRecordLayout, lightSelectionEntryLayout, areaLightLayout, punctualLightLayout, lightTreeNodeLayout, environmentTableEntryLayout, environmentPortalLayout],
} as const;

function vertexBytesAllStreams(): number {
  return 4 * (VERTEX_POSITION_WORDS + VERTEX_NORMAL_WORDS + VERTEX_TANGENT_WORDS + VERTEX_COLOR_WORDS + 2 * VERTEX_UV_WORDS);
}

/** GPU record sizes in bytes (public since the 0.2 API, so hosts can size buffers that hold these records). */
export const rendererWavefrontRecordSizes = {
  pathState: pathStateLayout.size,
  shadowRay: shadowRayLayout.size,
  rayWorkItem: rayWorkItemLayout.size,
  pathHit: pathHitLayout.size,
  pathRecord: pathRecordLayout.size,
  surfaceRecord: surfaceRecordLayout.size,
  sampleRecord: sampleRecordLayout.size,
  primitive: primitiveLayout.size,
  vertex: vertexBytesAllStreams(),
  instance: instanceLayout.size,
  bvhNode: bvhNodeLayout.size,
  materialCore: materialCoreLayout.size,
  lightRecord: lightRecordLayout.size,
  accumulationTexel: 16,
} as const;

export const rendererWavefrontPathStateBytes = pathStateLayout.size;
export const rendererWavefrontShadowRayBytes = shadowRayLayout.size;
export const rendererWavefrontPrimitiveBytes = primitiveLayout.size;
/** Bytes per vertex in the vertex streams when a mesh has every attribute. */
export const rendererWavefrontVertexBytes = vertexBytesAllStreams();
export const rendererWavefrontInstanceBytes = instanceLayout.size;
export const rendererWavefrontBvhNodeBytes = bvhNodeLayout.size;
export const rendererWavefrontMaterialBytes = materialCoreLayout.size;
export const rendererWavefrontLightRecordBytes = lightRecordLayout.size;
export const rendererWavefrontAccumulationTexelBytes = 16;
