// The layers of src/, lowest first. A module may import its own unit and any unit in a lower
// layer, never one in a higher layer: the graph stays acyclic, so each unit can be read, tested
// and reused with only what is below it. A unit is a folder of src/ (`scene`), or a subfolder or
// file inside one (`io/gltf`) where the folder's parts sit at different heights (a `*` segment
// matches any one folder: `materials/extensions/*/extension.ts`); a module belongs
// to the longest unit that contains it. Units in one layer are peers (they may import each other);
// keep such groups rare. A new folder under src/ must be placed here (the layering test fails
// until it is). Files directly in src/ are the package's entry points and may import any layer.
export const layers: readonly (readonly string[])[] = [
  // Typed errors and input validation: everything throws them.
  ['errors'],
  // Numeric helpers with no dependencies: matrices, half floats, colour transfer functions.
  ['math', 'color'],
  // Files, URLs and the platform: reading a path or URL within the resource policy's bounds, data
  // URIs, image headers, codecs. Everything that reads bytes goes through here. The glTF primitive
  // reader sits here too (accessor data to vertex streams, triangles, influences, morph targets),
  // below both of its callers: the glTF scene loader and the animated-model reader.
  ['io', 'io/gltf/primitive'],
  // The WebGPU device and its constants (Dawn is found through the platform layer).
  ['gpu'],
  // Struct layouts (the std430 rules) and the types a material uses to name textures: what the
  // material-extension registry's entries are written in.
  ['gpu-layout/struct-layout.ts', 'scene/texture-refs.ts'],
  // The material-extension registry: one declarative entry per KHR material extension (its glTF
  // and scene-file keys, validation, record block, flag and feature), read by the layers above
  // that derive records, features, validation and packing from it. The physics beside each entry
  // sits in the materials layer.
  [
    'materials/extensions/index.ts',
    'materials/extensions/material-extension.ts',
    'materials/extensions/volume/absorption.ts',
    'materials/extensions/*/extension.ts',
  ],
  // Byte layouts shared by TypeScript and WGSL: records, bindings, constants.
  ['gpu-layout'],
  // Generated WGSL modules and their composition (the program registry).
  ['shaders'],
  // Light transport between surfaces: media, Fresnel interfaces, spectral samples (CPU references).
  ['transport'],
  // The scene description: types, validation, normalisation, the scene JSON format.
  ['scene'],
  // Lights and environments (sampling tables, skies, portals).
  ['lighting'],
  // Materials: BSDFs, textures, their CPU references.
  ['materials'],
  // Skeletal animation: sampling, poses, skinning, camera rigs, timelines.
  ['animation'],
  // Acceleration structures (CPU and GPU BVH builds).
  ['accel'],
  // The film: accumulation, AOVs, adaptive sampling, denoisers, display, tone mapping.
  ['film'],
  // The wavefront path tracer.
  ['pathtracer'],
  // Asset loaders: glTF and scene files into scene descriptions (on the platform layer of io).
  // Image files written from the film (AOV layers, tone-mapped PNGs) sit here too.
  ['io/gltf', 'io/scene-file-loader.ts', 'io/index.ts', 'io/images/image-file.ts', 'io/images/exr-encode.ts', 'io/images/index.ts'],
  // Frame planning and worker manifests.
  ['planning'],
  // WebXR session binding.
  ['xr'],
  // The general frame-loop runtime.
  ['runtime'],
  // The raster renderer and the animated scenes on it.
  ['raster'],
  // Image sequences of a glTF asset (animation frames, turntables, variants).
  ['sequence'],
  // Applications of the package: the command line and the render farm (the farm runs CLI jobs).
  ['cli', 'farm'],
];
