/**
 * Structural validation of glTF 2.0 JSON before @gltf-transform reads it, so that bad input becomes
 * a typed error with an exact JSON pointer instead of a plain exception deep inside the reader (or
 * silently wrong data). Checks follow the glTF 2.0 specification: object references (section 3.3),
 * buffers and buffer views (3.6), accessor bounds (3.6.2.4: byteOffset + stride * (count - 1) +
 * element size must fit the buffer view), sparse accessors (3.6.2.3), meshes (3.7), node hierarchy (3.5.3:
 * a strict forest), and the extensions a file requires (3.12).
 */
import { failGltf, pointer } from './errors.ts';
import { isObject, type Json } from './json-object.ts';
import { SUPPORTED_EXTENSIONS } from './extensions.ts';
import { validateGltfProperties } from './property-validation.ts';

export { isObject } from './json-object.ts';

const COMPONENT_SIZES: Readonly<Record<number, number>> = { 5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4, 5131: 2, 5130: 8 };
const TYPE_SIZES: Readonly<Record<string, number>> = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT2: 4, MAT3: 9, MAT4: 16 };

/** A buffer the loader never reads: an EXT_meshopt_compression fallback, in an asset that uses the extension. */
export function isMeshoptFallback(json: Json, buffer: unknown): boolean {
  const used = Array.isArray(json.extensionsUsed) && json.extensionsUsed.includes('EXT_meshopt_compression');
  return used && isObject(buffer) && isObject(buffer.extensions) && isObject(buffer.extensions.EXT_meshopt_compression) && buffer.extensions.EXT_meshopt_compression.fallback === true;
}

function object(value: unknown, field: string): Json {
  if (!isObject(value)) failGltf(field, `expected an object, got ${value === null ? 'null' : Array.isArray(value) ? 'an array' : typeof value}`);
  return value;
}

function list(json: Json, key: string): unknown[] {
  const value = json[key];
  if (value === undefined) return [];
  if (!Array.isArray(value)) failGltf(pointer(key), 'expected an array');
  return value;
}

function integer(value: unknown, field: string, min = 0): number {
  if (typeof value !== 'number' || !Number.isInteger(value) || value < min) failGltf(field, `expected an integer >= ${min}, got ${JSON.stringify(value)}`);
  return value;
}

function optionalInteger(value: unknown, field: string, fallback: number, min = 0): number {
  return value === undefined ? fallback : integer(value, field, min);
}

/** A reference to element `value` of a top-level array of `length` entries named `target`. */
function reference(value: unknown, field: string, length: number, target: string): number {
  const index = integer(value, field);
  if (index >= length) failGltf(field, `${target} index ${index} is out of range (the asset has ${length} ${target})`);
  return index;
}

/** Element size in bytes, with matrix column padding (section 3.6.2.4, data alignment). */
export function accessorElementSize(componentType: number, type: string): number {
  const component = COMPONENT_SIZES[componentType];
  if (type === 'MAT2' && component === 1) return 8;
  if (type === 'MAT3' && component === 1) return 12;
  if (type === 'MAT3' && component === 2) return 24;
  return component * TYPE_SIZES[type];
}

/** Texture extensions that name the texture's image by `source`. */
const IMAGE_SOURCE_EXTENSIONS: ReadonlySet<string> = new Set(['KHR_texture_basisu', 'EXT_texture_webp', 'EXT_texture_avif']);

export interface ValidatedJson {
  json: Json;
  /** Declared byte lengths of the buffers. */
  bufferByteLengths: number[];
}

export function validateGltfJson(value: unknown): ValidatedJson {
  const json = object(value, '');
  const asset = object(json.asset, '/asset');
  if (typeof asset.version !== 'string' || !/^2\.\d+$/.test(asset.version)) failGltf('/asset/version', `expected a glTF 2.x version string, got ${JSON.stringify(asset.version)}`);
  if (asset.minVersion !== undefined && asset.minVersion !== '2.0') failGltf('/asset/minVersion', `this loader reads glTF 2.0, the asset needs ${JSON.stringify(asset.minVersion)}`);

  const used = list(json, 'extensionsUsed');
  used.forEach((name, i) => {
    if (typeof name !== 'string') failGltf(pointer('extensionsUsed', i), 'expected an extension name');
  });
  const required = list(json, 'extensionsRequired');
  required.forEach((name, i) => {
    if (typeof name !== 'string') failGltf(pointer('extensionsRequired', i), 'expected an extension name');
    if (!SUPPORTED_EXTENSIONS.has(name)) failGltf(pointer('extensionsRequired', i), `required extension ${name} is not supported`);
    // glTF 2.0 section 3.12: every required extension is also listed in extensionsUsed.
    if (!used.includes(name)) failGltf(pointer('extensionsRequired', i), `${name} is required but not listed in extensionsUsed`);
  });

  const counts = {
    accessors: list(json, 'accessors').length,
    bufferViews: list(json, 'bufferViews').length,
    buffers: list(json, 'buffers').length,
    cameras: list(json, 'cameras').length,
    images: list(json, 'images').length,
    materials: list(json, 'materials').length,
    meshes: list(json, 'meshes').length,
    nodes: list(json, 'nodes').length,
    samplers: list(json, 'samplers').length,
    scenes: list(json, 'scenes').length,
    skins: list(json, 'skins').length,
    textures: list(json, 'textures').length,
  };

  const bufferByteLengths = list(json, 'buffers').map((entry, i) => {
    const buffer = object(entry, pointer('buffers', i));
    if (buffer.uri !== undefined && typeof buffer.uri !== 'string') failGltf(pointer('buffers', i, 'uri'), 'expected a string');
    return integer(buffer.byteLength, pointer('buffers', i, 'byteLength'), 1);
  });

  // EXT_meshopt_compression fallback buffers carry no data: only compressed views may use them.
  const fallbacks = list(json, 'buffers').map((b) => isMeshoptFallback(json, b));
  list(json, 'bufferViews').forEach((entry, i) => validateBufferView(entry, i, bufferByteLengths, counts.buffers, fallbacks));
  const views = list(json, 'bufferViews') as Json[];
  list(json, 'accessors').forEach((entry, i) => validateAccessor(entry, i, views));
  list(json, 'images').forEach((entry, i) => {
    const image = object(entry, pointer('images', i));
    if (image.bufferView !== undefined) reference(image.bufferView, pointer('images', i, 'bufferView'), counts.bufferViews, 'bufferViews');
    else if (typeof image.uri !== 'string') failGltf(pointer('images', i), 'an image needs a uri or a bufferView');
  });
  list(json, 'textures').forEach((entry, i) => {
    const texture = object(entry, pointer('textures', i));
    if (texture.source !== undefined) reference(texture.source, pointer('textures', i, 'source'), counts.images, 'images');
    // glTF 2.0 section 5.29: without `source` an extension must supply the image, and only an
    // extension the asset lists in extensionsUsed is read at all.
    const extensionSource = isObject(texture.extensions) && Object.entries(texture.extensions).some(([name, ext]) => used.includes(name) && isObject(ext) && ext.source !== undefined);
    if (texture.source === undefined && !extensionSource) failGltf(pointer('textures', i), 'the texture has no source image (no source, and no extension that supplies one)');
    if (texture.sampler !== undefined) reference(texture.sampler, pointer('textures', i, 'sampler'), counts.samplers, 'samplers');
    if (isObject(texture.extensions)) {
      for (const [name, ext] of Object.entries(texture.extensions)) {
        // The image-supplying extensions require their `source` (each one's texture schema).
        const required = IMAGE_SOURCE_EXTENSIONS.has(name) && used.includes(name);
        if (isObject(ext) && (ext.source !== undefined || required)) reference(ext.source, pointer('textures', i, 'extensions', name, 'source'), counts.images, 'images');
      }
    }
  });
  list(json, 'materials').forEach((entry, i) => validateTextureReferences(object(entry, pointer('materials', i)), pointer('materials', i), counts.textures));
  list(json, 'meshes').forEach((entry, i) => validateMesh(entry, i, json, counts));
  list(json, 'cameras').forEach((entry, i) => validateCamera(entry, i));
  list(json, 'skins').forEach((entry, i) => {
    const skin = object(entry, pointer('skins', i));
    if (skin.inverseBindMatrices !== undefined) reference(skin.inverseBindMatrices, pointer('skins', i, 'inverseBindMatrices'), counts.accessors, 'accessors');
    if (!Array.isArray(skin.joints)) failGltf(pointer('skins', i, 'joints'), 'expected an array of node indices');
    skin.joints.forEach((joint, j) => reference(joint, pointer('skins', i, 'joints', j), counts.nodes, 'nodes'));
  });
  list(json, 'animations').forEach((entry, i) => {
    const animation = object(entry, pointer('animations', i));
    list(animation, 'samplers').forEach((s, j) => {
      const sampler = object(s, pointer('animations', i, 'samplers', j));
      reference(sampler.input, pointer('animations', i, 'samplers', j, 'input'), counts.accessors, 'accessors');
      reference(sampler.output, pointer('animations', i, 'samplers', j, 'output'), counts.accessors, 'accessors');
    });
  });
  validateNodes(json, counts);
  list(json, 'scenes').forEach((entry, i) => {
    const scene = object(entry, pointer('scenes', i));
    list(scene, 'nodes').forEach((node, j) => reference(node, pointer('scenes', i, 'nodes', j), counts.nodes, 'nodes'));
  });
  if (json.scene !== undefined) reference(json.scene, '/scene', counts.scenes, 'scenes');
  validateGltfProperties(json, counts);
  return { json, bufferByteLengths };
}

function validateBufferView(entry: unknown, i: number, bufferByteLengths: number[], bufferCount: number, fallbacks: boolean[]): void {
  const at = pointer('bufferViews', i);
  const view = object(entry, at);
  const buffer = reference(view.buffer, `${at}/buffer`, bufferCount, 'buffers');
  const byteOffset = optionalInteger(view.byteOffset, `${at}/byteOffset`, 0);
  const byteLength = integer(view.byteLength, `${at}/byteLength`, 1);
  if (view.byteStride !== undefined) {
    const stride = integer(view.byteStride, `${at}/byteStride`, 4);
    if (stride > 252 || stride % 4 !== 0) failGltf(`${at}/byteStride`, `byteStride must be a multiple of 4 in 4..252, got ${stride}`);
  }
  if (byteOffset + byteLength > bufferByteLengths[buffer]) {
    failGltf(at, `bytes ${byteOffset}..${byteOffset + byteLength} run past the end of buffer ${buffer} (${bufferByteLengths[buffer]} bytes)`);
  }
  const meshopt = isObject(view.extensions) ? view.extensions.EXT_meshopt_compression : undefined;
  if (meshopt === undefined && fallbacks[buffer]) failGltf(`${at}/buffer`, `buffer ${buffer} is an EXT_meshopt_compression fallback without data; only a compressed view may use it`);
  if (meshopt !== undefined) {
    const mat = `${at}/extensions/EXT_meshopt_compression`;
    const m = object(meshopt, mat);
    const source = reference(m.buffer, `${mat}/buffer`, bufferCount, 'buffers');
    if (fallbacks[source]) failGltf(`${mat}/buffer`, `buffer ${source} is a fallback without data; the compressed bytes must be in a buffer with data`);
    const offset = optionalInteger(m.byteOffset, `${mat}/byteOffset`, 0);
    const length = integer(m.byteLength, `${mat}/byteLength`, 1);
    if (offset + length > bufferByteLengths[source]) failGltf(mat, `compressed bytes ${offset}..${offset + length} run past the end of buffer ${source}`);
    const stride = integer(m.byteStride, `${mat}/byteStride`, 1);
    const count = integer(m.count, `${mat}/count`, 1);
    if (stride * count > byteLength) failGltf(mat, `${count} elements of ${stride} bytes exceed the buffer view's ${byteLength} bytes`);
    // EXT_meshopt_compression "Specifying compressed views": modes, filters and their strides.
    if (m.mode !== 'ATTRIBUTES' && m.mode !== 'TRIANGLES' && m.mode !== 'INDICES') failGltf(`${mat}/mode`, `expected "ATTRIBUTES", "TRIANGLES" or "INDICES", got ${JSON.stringify(m.mode)}`);
    if (m.mode === 'ATTRIBUTES' ? stride % 4 !== 0 || stride > 256 : stride !== 2 && stride !== 4) {
      failGltf(`${mat}/byteStride`, `byteStride ${stride} is not valid for mode ${m.mode}`);
    }
    if (m.mode === 'TRIANGLES' && count % 3 !== 0) failGltf(`${mat}/count`, `a TRIANGLES view needs a multiple of 3 indices, got ${count}`);
    if (m.filter !== undefined && !['NONE', 'OCTAHEDRAL', 'QUATERNION', 'EXPONENTIAL', 'COLOR'].includes(m.filter as string)) {
      failGltf(`${mat}/filter`, `unknown filter ${JSON.stringify(m.filter)}`);
    }
    if (m.filter !== undefined && m.filter !== 'NONE' && m.mode !== 'ATTRIBUTES') failGltf(`${mat}/filter`, 'filters apply to ATTRIBUTES views only');
  }
}

function validateAccessor(entry: unknown, i: number, views: Json[]): void {
  const viewLengths = views.map((v) => v.byteLength as number);
  const viewCount = views.length;
  const at = pointer('accessors', i);
  const accessor = object(entry, at);
  const componentType = integer(accessor.componentType, `${at}/componentType`);
  if (!(componentType in COMPONENT_SIZES)) failGltf(`${at}/componentType`, `unknown component type ${componentType}`);
  if (typeof accessor.type !== 'string' || !(accessor.type in TYPE_SIZES)) failGltf(`${at}/type`, `unknown accessor type ${JSON.stringify(accessor.type)}`);
  const count = integer(accessor.count, `${at}/count`, 1);
  const elementSize = accessorElementSize(componentType, accessor.type);
  const byteOffset = optionalInteger(accessor.byteOffset, `${at}/byteOffset`, 0);
  if (accessor.bufferView !== undefined) {
    const viewIndex = reference(accessor.bufferView, `${at}/bufferView`, views.length, 'bufferViews');
    const view = views[viewIndex];
    if (byteOffset % COMPONENT_SIZES[componentType] !== 0) failGltf(`${at}/byteOffset`, `byteOffset ${byteOffset} is not a multiple of the component size`);
    const stride = (view.byteStride as number | undefined) ?? elementSize;
    if (stride < elementSize) failGltf(pointer('bufferViews', viewIndex, 'byteStride'), `byteStride ${stride} is smaller than accessor ${i}'s ${elementSize}-byte elements`);
    const end = byteOffset + stride * (count - 1) + elementSize;
    const viewLength = view.byteLength as number;
    if (end > viewLength) {
      failGltf(at, `${count} elements of ${elementSize} bytes (stride ${stride}) from byte ${byteOffset} need ${end} bytes, bufferView ${viewIndex} has ${viewLength}`);
    }
  } else if (accessor.byteOffset !== undefined) {
    failGltf(`${at}/byteOffset`, 'byteOffset needs a bufferView');
  }
  if (accessor.sparse !== undefined) {
    const sat = `${at}/sparse`;
    const sparse = object(accessor.sparse, sat);
    const sparseCount = integer(sparse.count, `${sat}/count`, 1);
    if (sparseCount > count) failGltf(`${sat}/count`, `${sparseCount} sparse elements exceed the accessor's ${count}`);
    const indices = object(sparse.indices, `${sat}/indices`);
    const indexView = reference(indices.bufferView, `${sat}/indices/bufferView`, viewCount, 'bufferViews');
    const indexType = integer(indices.componentType, `${sat}/indices/componentType`);
    if (indexType !== 5121 && indexType !== 5123 && indexType !== 5125) failGltf(`${sat}/indices/componentType`, `sparse indices must be unsigned, got ${indexType}`);
    const indexOffset = optionalInteger(indices.byteOffset, `${sat}/indices/byteOffset`, 0);
    if (indexOffset + sparseCount * COMPONENT_SIZES[indexType] > viewLengths[indexView]) failGltf(`${sat}/indices`, `${sparseCount} indices run past the end of bufferView ${indexView}`);
    const values = object(sparse.values, `${sat}/values`);
    const valueView = reference(values.bufferView, `${sat}/values/bufferView`, viewCount, 'bufferViews');
    const valueOffset = optionalInteger(values.byteOffset, `${sat}/values/byteOffset`, 0);
    if (valueOffset + sparseCount * elementSize > viewLengths[valueView]) failGltf(`${sat}/values`, `${sparseCount} values run past the end of bufferView ${valueView}`);
  }
}

const ATTRIBUTE_TYPES: Readonly<Record<string, readonly string[]>> = {
  POSITION: ['VEC3'],
  NORMAL: ['VEC3'],
  TANGENT: ['VEC4'],
  TEXCOORD_0: ['VEC2'],
  TEXCOORD_1: ['VEC2'],
  COLOR_0: ['VEC3', 'VEC4'],
};

function validateMesh(entry: unknown, m: number, json: Json, counts: Record<string, number>): void {
  const at = pointer('meshes', m);
  const mesh = object(entry, at);
  const primitives = mesh.primitives;
  if (!Array.isArray(primitives) || primitives.length === 0) failGltf(`${at}/primitives`, 'a mesh needs at least one primitive');
  const accessors = list(json, 'accessors') as Json[];
  primitives.forEach((p, i) => {
    const pat = `${at}/primitives/${i}`;
    const primitive = object(p, pat);
    const attributes = object(primitive.attributes, `${pat}/attributes`);
    let vertexCount: number | undefined;
    for (const [semantic, index] of Object.entries(attributes)) {
      const aat = `${pat}/attributes/${semantic}`;
      const a = reference(index, aat, counts.accessors, 'accessors');
      const accessor = accessors[a];
      const types = ATTRIBUTE_TYPES[semantic];
      if (types !== undefined && !types.includes(accessor.type as string)) failGltf(aat, `${semantic} must be ${types.join(' or ')}, accessor ${a} is ${String(accessor.type)}`);
      const count = accessor.count as number;
      if (vertexCount !== undefined && count !== vertexCount) failGltf(aat, `accessor ${a} has ${count} elements, the primitive's other attributes have ${vertexCount}`);
      vertexCount = count;
    }
    if (primitive.indices !== undefined) {
      const a = reference(primitive.indices, `${pat}/indices`, counts.accessors, 'accessors');
      const accessor = accessors[a];
      if (accessor.type !== 'SCALAR' || ![5121, 5123, 5125].includes(accessor.componentType as number)) {
        failGltf(`${pat}/indices`, `indices must be unsigned byte/short/int scalars, accessor ${a} is ${String(accessor.type)} of ${String(accessor.componentType)}`);
      }
    }
    if (primitive.material !== undefined) reference(primitive.material, `${pat}/material`, counts.materials, 'materials');
    if (primitive.mode !== undefined) {
      const mode = integer(primitive.mode, `${pat}/mode`);
      if (mode > 6) failGltf(`${pat}/mode`, `unknown primitive mode ${mode}`);
    }
    list(primitive, 'targets').forEach((t, k) => {
      for (const [semantic, index] of Object.entries(object(t, `${pat}/targets/${k}`))) {
        const a = reference(index, `${pat}/targets/${k}/${semantic}`, counts.accessors, 'accessors');
        if (vertexCount !== undefined && (accessors[a].count as number) !== vertexCount) failGltf(`${pat}/targets/${k}/${semantic}`, `morph target accessor ${a} has ${accessors[a].count as number} elements, the primitive has ${vertexCount} vertices`);
      }
    });
    const draco = isObject(primitive.extensions) ? primitive.extensions.KHR_draco_mesh_compression : undefined;
    if (draco !== undefined) {
      const dat = `${pat}/extensions/KHR_draco_mesh_compression`;
      const d = object(draco, dat);
      reference(d.bufferView, `${dat}/bufferView`, counts.bufferViews, 'bufferViews');
      // Each compressed attribute decodes into the primitive's accessor of the same semantic
      // (KHR_draco_mesh_compression, "attributes"): a semantic the primitive lacks has none.
      for (const [semantic, id] of Object.entries(object(d.attributes, `${dat}/attributes`))) {
        integer(id, `${dat}/attributes/${semantic}`);
        if (!(semantic in attributes)) failGltf(`${dat}/attributes/${semantic}`, `the primitive has no ${semantic} attribute to decode into`);
      }
    }
    const variants = isObject(primitive.extensions) ? primitive.extensions.KHR_materials_variants : undefined;
    if (variants !== undefined) {
      const vat = `${pat}/extensions/KHR_materials_variants`;
      const variantCount = isObject(json.extensions) && isObject(json.extensions.KHR_materials_variants) && Array.isArray(json.extensions.KHR_materials_variants.variants)
        ? json.extensions.KHR_materials_variants.variants.length
        : 0;
      list(object(variants, vat), 'mappings').forEach((mp, k) => {
        const mapping = object(mp, `${vat}/mappings/${k}`);
        reference(mapping.material, `${vat}/mappings/${k}/material`, counts.materials, 'materials');
        list(mapping, 'variants').forEach((v, j) => reference(v, `${vat}/mappings/${k}/variants/${j}`, variantCount, 'variants'));
      });
    }
  });
}

/** Every `{ index }` object under a key ending in "Texture" (core slots and KHR_materials_* slots). */
function validateTextureReferences(value: Json, at: string, textureCount: number): void {
  for (const [key, child] of Object.entries(value)) {
    if (!isObject(child) || key === 'extras') continue;
    if (key.endsWith('Texture')) reference(child.index, `${at}/${key}/index`, textureCount, 'textures');
    else validateTextureReferences(child, `${at}/${key}`, textureCount);
  }
}

function validateCamera(entry: unknown, i: number): void {
  const at = pointer('cameras', i);
  const camera = object(entry, at);
  if (camera.type === 'perspective') {
    const p = object(camera.perspective, `${at}/perspective`);
    if (typeof p.yfov !== 'number' || !(p.yfov > 0 && p.yfov < Math.PI)) failGltf(`${at}/perspective/yfov`, `expected an angle in (0, pi) radians, got ${JSON.stringify(p.yfov)}`);
  } else if (camera.type === 'orthographic') {
    const o = object(camera.orthographic, `${at}/orthographic`);
    if (typeof o.ymag !== 'number' || !Number.isFinite(o.ymag) || o.ymag === 0) failGltf(`${at}/orthographic/ymag`, `expected a finite non-zero number, got ${JSON.stringify(o.ymag)}`);
  } else {
    failGltf(`${at}/type`, `expected "perspective" or "orthographic", got ${JSON.stringify(camera.type)}`);
  }
}

/** Node references, and the hierarchy a strict forest: no node with two parents, no cycles. */
function validateNodes(json: Json, counts: Record<string, number>): void {
  const nodes = list(json, 'nodes');
  const parent = new Array<number>(nodes.length).fill(-1);
  nodes.forEach((entry, i) => {
    const at = pointer('nodes', i);
    const node = object(entry, at);
    if (node.mesh !== undefined) reference(node.mesh, `${at}/mesh`, counts.meshes, 'meshes');
    if (node.camera !== undefined) reference(node.camera, `${at}/camera`, counts.cameras, 'cameras');
    if (node.skin !== undefined) reference(node.skin, `${at}/skin`, counts.skins, 'skins');
    for (const key of ['matrix', 'translation', 'rotation', 'scale'] as const) {
      const v = node[key];
      if (v === undefined) continue;
      const length = { matrix: 16, translation: 3, rotation: 4, scale: 3 }[key];
      if (!Array.isArray(v) || v.length !== length || v.some((x) => typeof x !== 'number' || !Number.isFinite(x))) failGltf(`${at}/${key}`, `expected ${length} finite numbers`);
    }
    list(node, 'children').forEach((c, j) => {
      const child = reference(c, `${at}/children/${j}`, counts.nodes, 'nodes');
      if (parent[child] !== -1) failGltf(`${at}/children/${j}`, `node ${child} already has parent ${parent[child]} (the node hierarchy must be a forest)`);
      parent[child] = i;
    });
    const instancing = isObject(node.extensions) ? node.extensions.EXT_mesh_gpu_instancing : undefined;
    if (instancing !== undefined) {
      const iat = `${at}/extensions/EXT_mesh_gpu_instancing`;
      const attributes = object(object(instancing, iat).attributes, `${iat}/attributes`);
      const accessors = list(json, 'accessors') as Json[];
      let instanceCount: number | undefined;
      for (const [semantic, index] of Object.entries(attributes)) {
        const a = reference(index, `${iat}/attributes/${semantic}`, counts.accessors, 'accessors');
        const count = accessors[a].count as number;
        if (instanceCount !== undefined && count !== instanceCount) failGltf(`${iat}/attributes/${semantic}`, `accessor ${a} has ${count} elements, the other instance attributes have ${instanceCount}`);
        instanceCount = count;
      }
    }
  });
  // Cycles: walk up from every node until a root or a node already known to reach one; a walk
  // that meets its own path is a cycle. Each node is walked once (linear in the node count, so a
  // hierarchy 100 000 deep costs no more than a flat one).
  const reachesRoot = new Uint8Array(nodes.length); // 0 unknown, 1 on the current walk, 2 reaches a root
  const path: number[] = [];
  for (let i = 0; i < nodes.length; i++) {
    path.length = 0;
    let n = i;
    while (n !== -1 && reachesRoot[n] === 0) {
      reachesRoot[n] = 1;
      path.push(n);
      n = parent[n];
    }
    if (n !== -1 && reachesRoot[n] === 1) failGltf(pointer('nodes', n), 'the node hierarchy has a cycle');
    for (const k of path) reachesRoot[k] = 2;
  }
}
