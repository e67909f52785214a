/**
 * Which glTF extensions the loader honours. Every Khronos/EXT extension that @gltf-transform
 * implements is registered for reading; this table says which of them the renderer's scene can
 * express, so that a file *requiring* one it cannot is rejected instead of being drawn wrongly,
 * and one merely *using* it gets a warning that it is ignored.
 */

import { anyMaterialExtensions } from '../../materials/extensions/index.ts';

/** Extensions whose content the loader maps (or that carry no rendering content at all). */
export const SUPPORTED_EXTENSIONS: ReadonlySet<string> = new Set([
  'KHR_draco_mesh_compression',
  'EXT_meshopt_compression',
  'KHR_mesh_quantization',
  'EXT_mesh_gpu_instancing',
  'KHR_mesh_primitive_restart',
  'KHR_accessor_float16',
  'KHR_accessor_float64',
  'KHR_texture_transform',
  'KHR_texture_basisu',
  'EXT_texture_webp',
  'EXT_texture_avif',
  'KHR_materials_emissive_strength',
  'KHR_materials_ior',
  // The KHR BSDF extensions of the material registry (materials/extensions/).
  ...anyMaterialExtensions.map((e) => e.name),
  'KHR_materials_variants',
  'KHR_materials_pbrSpecularGlossiness',
  'KHR_materials_unlit',
  'KHR_lights_punctual',
  'KHR_node_visibility',
  // Metadata only: nothing to render (FB_ngon_encoding says how the triangles came from polygons).
  'KHR_xmp_json_ld',
  'FB_ngon_encoding',
  'EXT_mesh_features',
  'EXT_structural_metadata',
]);
