/**
 * Value checks of the glTF properties the loader maps, by their JSON schemas (glTF 2.0 section 5,
 * and each KHR extension's schema): types, lengths and ranges of material factors, texture infos
 * and KHR_texture_transform, samplers, cameras, KHR_lights_punctual lights, morph weights and
 * animations. @gltf-transform reads whatever is there (a number where an array belongs throws a
 * TypeError deep inside it), and the renderer would refuse out-of-range values only later, under
 * its own field names: here each is an INVALID_GLTF error at its JSON pointer, at load.
 */
import { anyMaterialExtensions } from '../../materials/extensions/index.ts';
import { maxRadiance } from '../../scene/limits.ts';
import { failGltf, pointer } from './errors.ts';
import { isObject, type Json } from './json-object.ts';

function show(value: unknown): string {
  if (typeof value === 'string') return JSON.stringify(value.length > 40 ? `${value.slice(0, 40)}...` : value);
  if (Array.isArray(value)) return `an array of length ${value.length}`;
  if (value === null) return 'null';
  return typeof value === 'object' ? 'an object' : String(value);
}

interface Range {
  min?: number;
  max?: number;
  /** Exclusive bounds. */
  above?: number;
  below?: number;
}

function describeRange(r: Range): string {
  const lo = r.above !== undefined ? `> ${r.above}` : r.min !== undefined ? `>= ${r.min}` : '';
  const hi = r.below !== undefined ? `< ${r.below}` : r.max !== undefined ? `<= ${r.max}` : '';
  return [lo, hi].filter((s) => s !== '').join(' and ');
}

function number(value: unknown, at: string, range: Range = {}): number {
  if (typeof value !== 'number' || !Number.isFinite(value)) failGltf(at, `expected a finite number${Object.keys(range).length ? ` ${describeRange(range)}` : ''}, got ${show(value)}`);
  const ok = (range.min === undefined || value >= range.min) && (range.max === undefined || value <= range.max) && (range.above === undefined || value > range.above) && (range.below === undefined || value < range.below);
  if (!ok) failGltf(at, `must be ${describeRange(range)}, got ${value}`);
  return value;
}

function optionalNumber(json: Json, key: string, at: string, range: Range = {}): void {
  if (json[key] !== undefined) number(json[key], `${at}/${key}`, range);
}

function vector(json: Json, key: string, at: string, length: number, range: Range = {}): void {
  const value = json[key];
  if (value === undefined) return;
  if (!Array.isArray(value) || value.length !== length) failGltf(`${at}/${key}`, `expected an array of ${length} numbers, got ${show(value)}`);
  value.forEach((x, i) => number(x, `${at}/${key}/${i}`, range));
}

function optionalInteger(json: Json, key: string, at: string, min = 0): void {
  const v = json[key];
  if (v !== undefined && (typeof v !== 'number' || !Number.isInteger(v) || v < min)) failGltf(`${at}/${key}`, `expected an integer >= ${min}, got ${show(v)}`);
}

function optionalBoolean(json: Json, key: string, at: string): void {
  if (json[key] !== undefined && typeof json[key] !== 'boolean') failGltf(`${at}/${key}`, `expected true or false, got ${show(json[key])}`);
}

function optionalString(json: Json, key: string, at: string): void {
  if (json[key] !== undefined && typeof json[key] !== 'string') failGltf(`${at}/${key}`, `expected a string, got ${show(json[key])}`);
}

function oneOf(json: Json, key: string, at: string, values: readonly unknown[]): void {
  if (json[key] !== undefined && !values.includes(json[key])) failGltf(`${at}/${key}`, `expected one of ${values.map((v) => JSON.stringify(v)).join(', ')}, got ${show(json[key])}`);
}

function child(json: Json, key: string, at: string): Json | undefined {
  const value = json[key];
  if (value === undefined) return undefined;
  if (!isObject(value)) failGltf(`${at}/${key}`, `expected an object, got ${show(value)}`);
  return value;
}

/** The extension objects a property carries (`extensions` an object of objects). */
function extensionsOf(json: Json, at: string): Json {
  const ext = child(json, 'extensions', at);
  if (ext === undefined) return {};
  for (const [name, value] of Object.entries(ext)) if (!isObject(value)) failGltf(`${at}/extensions/${name}`, `expected an object, got ${show(value)}`);
  return ext as Json;
}

/** A textureInfo (glTF 2.0 section 5.29; the index itself is checked with the references). */
function textureInfo(json: Json, key: string, at: string, extra?: { key: string; range: Range }): void {
  const info = child(json, key, at);
  if (info === undefined) return;
  const iat = `${at}/${key}`;
  optionalInteger(info, 'texCoord', iat);
  if (extra !== undefined) optionalNumber(info, extra.key, iat, extra.range);
  const transform = extensionsOf(info, iat).KHR_texture_transform as Json | undefined;
  if (transform !== undefined) {
    const tat = `${iat}/extensions/KHR_texture_transform`;
    vector(transform, 'offset', tat, 2);
    optionalNumber(transform, 'rotation', tat);
    vector(transform, 'scale', tat, 2);
    optionalInteger(transform, 'texCoord', tat);
  }
}

const UNIT: Range = { min: 0, max: 1 };
const NON_NEGATIVE: Range = { min: 0 };

function validateMaterial(material: Json, at: string): void {
  optionalString(material, 'name', at);
  const pbr = child(material, 'pbrMetallicRoughness', at);
  if (pbr !== undefined) {
    const pat = `${at}/pbrMetallicRoughness`;
    vector(pbr, 'baseColorFactor', pat, 4, UNIT);
    optionalNumber(pbr, 'metallicFactor', pat, UNIT);
    optionalNumber(pbr, 'roughnessFactor', pat, UNIT);
    textureInfo(pbr, 'baseColorTexture', pat);
    textureInfo(pbr, 'metallicRoughnessTexture', pat);
  }
  textureInfo(material, 'normalTexture', at, { key: 'scale', range: {} });
  textureInfo(material, 'occlusionTexture', at, { key: 'strength', range: UNIT });
  textureInfo(material, 'emissiveTexture', at);
  vector(material, 'emissiveFactor', at, 3, UNIT);
  oneOf(material, 'alphaMode', at, ['OPAQUE', 'MASK', 'BLEND']);
  optionalNumber(material, 'alphaCutoff', at, NON_NEGATIVE);
  optionalBoolean(material, 'doubleSided', at);

  const ext = extensionsOf(material, at);
  const e = (name: string): [Json | undefined, string] => [ext[name] as Json | undefined, `${at}/extensions/${name}`];
  let [x, xat] = e('KHR_materials_emissive_strength');
  // The factor is at most 1, so the strength bounds the emitted radiance (scene/limits.ts).
  if (x) optionalNumber(x, 'emissiveStrength', xat, { min: 0, max: maxRadiance });
  [x, xat] = e('KHR_materials_ior');
  if (x && x.ior !== undefined && x.ior !== 0) number(x.ior, `${xat}/ior`, { min: 1 });
  // The KHR BSDF extensions: ranges and texture slots from their registry entries.
  for (const spec of anyMaterialExtensions) {
    [x, xat] = e(spec.name);
    if (!x) continue;
    for (const f of spec.factors) {
      if (f.type === 'rgb') vector(x, f.key, xat, 3, f.range);
      else optionalNumber(x, f.key, xat, f.range);
    }
    for (const t of spec.textures) textureInfo(x, t.key, xat, t.scaleGetter === undefined ? undefined : { key: 'scale', range: {} });
  }
  [x, xat] = e('KHR_materials_pbrSpecularGlossiness');
  if (x) {
    vector(x, 'diffuseFactor', xat, 4, UNIT);
    vector(x, 'specularFactor', xat, 3, UNIT);
    optionalNumber(x, 'glossinessFactor', xat, UNIT);
    textureInfo(x, 'diffuseTexture', xat);
    textureInfo(x, 'specularGlossinessTexture', xat);
  }
}

const WRAP_MODES = [33071, 33648, 10497];
const MAG_FILTERS = [9728, 9729];
const MIN_FILTERS = [9728, 9729, 9984, 9985, 9986, 9987];

/**
 * The renderer's perspective camera takes a vertical field of view up to 179 degrees
 * (pathtracer/camera.ts); glTF allows anything below pi.
 */
const MAX_YFOV = (179 * Math.PI) / 180;

function validateCamera(camera: Json, at: string): void {
  const p = isObject(camera.perspective) ? camera.perspective : undefined;
  if (camera.type === 'perspective' && p !== undefined) {
    const pat = `${at}/perspective`;
    number(p.yfov, `${pat}/yfov`, { above: 0, max: MAX_YFOV });
    optionalNumber(p, 'aspectRatio', pat, { above: 0 });
    // znear and zfar are not used (a path tracer has no clip planes), only checked when present.
    if (p.znear !== undefined) number(p.znear, `${pat}/znear`, { above: 0 });
    if (p.zfar !== undefined) number(p.zfar, `${pat}/zfar`, { above: typeof p.znear === 'number' ? p.znear : 0 });
  }
  const o = isObject(camera.orthographic) ? camera.orthographic : undefined;
  if (camera.type === 'orthographic' && o !== undefined) {
    const oat = `${at}/orthographic`;
    if (o.xmag !== undefined) number(o.xmag, `${oat}/xmag`);
    number(o.ymag, `${oat}/ymag`);
    if (o.ymag === 0) failGltf(`${oat}/ymag`, 'must not be zero');
    if (o.znear !== undefined) number(o.znear, `${oat}/znear`, NON_NEGATIVE);
    if (o.zfar !== undefined) number(o.zfar, `${oat}/zfar`, { above: typeof o.znear === 'number' ? o.znear : 0 });
  }
}

function validateLight(light: Json, at: string): void {
  if (light.type !== 'directional' && light.type !== 'point' && light.type !== 'spot') failGltf(`${at}/type`, `expected "directional", "point" or "spot", got ${show(light.type)}`);
  optionalString(light, 'name', at);
  vector(light, 'color', at, 3, UNIT);
  optionalNumber(light, 'intensity', at, { min: 0, max: maxRadiance });
  optionalNumber(light, 'range', at, { above: 0 });
  if (light.type === 'spot') {
    const spot = child(light, 'spot', at);
    if (spot === undefined) failGltf(`${at}/spot`, 'a spot light needs its cone angles');
    const sat = `${at}/spot`;
    const outer = spot.outerConeAngle === undefined ? Math.PI / 4 : number(spot.outerConeAngle, `${sat}/outerConeAngle`, { above: 0, max: Math.PI / 2 });
    if (spot.innerConeAngle !== undefined) number(spot.innerConeAngle, `${sat}/innerConeAngle`, { min: 0, below: outer });
  }
}

function numbers(value: unknown, at: string): void {
  if (value === undefined) return;
  if (!Array.isArray(value)) failGltf(at, `expected an array of numbers, got ${show(value)}`);
  value.forEach((w, i) => number(w, `${at}/${i}`));
}

const list = (json: Json, key: string): Json[] => (Array.isArray(json[key]) ? (json[key] as Json[]) : []);

/**
 * Every `extensions` property is an object of objects (glTF 2.0 section 5.x "extension"): a
 * number there reaches @gltf-transform's extension readers as a TypeError. Walked with a stack
 * (the JSON's depth was bounded before parsing); `extras` hold application data and are skipped.
 */
function validateExtensionObjects(json: Json): void {
  const stack: Array<{ value: unknown; at: string }> = [{ value: json, at: '' }];
  while (stack.length > 0) {
    const { value, at } = stack.pop()!;
    if (Array.isArray(value)) {
      value.forEach((v, i) => stack.push({ value: v, at: `${at}/${i}` }));
      continue;
    }
    if (!isObject(value)) continue;
    for (const [key, v] of Object.entries(value)) {
      const kat = `${at}/${key.replaceAll('~', '~0').replaceAll('/', '~1')}`;
      if (key === 'extras') continue;
      if (key === 'extensions') {
        if (!isObject(v)) failGltf(kat, `expected an object of extensions, got ${show(v)}`);
        for (const [name, ext] of Object.entries(v)) if (!isObject(ext)) failGltf(`${kat}/${name}`, `expected an object, got ${show(ext)}`);
      }
      stack.push({ value: v, at: kat });
    }
  }
}

/**
 * Checks the properties above (the structure, references and accessors were checked by
 * json-validation.ts). `counts` are the lengths of the top-level arrays.
 */
export function validateGltfProperties(json: Json, counts: { nodes: number; accessors: number }): void {
  validateExtensionObjects(json);
  list(json, 'materials').forEach((m, i) => validateMaterial(m, pointer('materials', i)));
  list(json, 'samplers').forEach((entry, i) => {
    const at = pointer('samplers', i);
    if (!isObject(entry)) failGltf(at, `expected an object, got ${show(entry)}`);
    oneOf(entry, 'magFilter', at, MAG_FILTERS);
    oneOf(entry, 'minFilter', at, MIN_FILTERS);
    oneOf(entry, 'wrapS', at, WRAP_MODES);
    oneOf(entry, 'wrapT', at, WRAP_MODES);
  });
  list(json, 'cameras').forEach((c, i) => validateCamera(c, pointer('cameras', i)));
  list(json, 'images').forEach((image, i) => {
    const at = pointer('images', i);
    if (image.uri !== undefined && image.bufferView !== undefined) failGltf(at, 'an image has a uri or a bufferView, not both');
    if (image.uri !== undefined && typeof image.uri !== 'string') failGltf(`${at}/uri`, `expected a string, got ${show(image.uri)}`);
    optionalString(image, 'mimeType', at);
  });
  list(json, 'accessors').forEach((accessor, i) => {
    const at = pointer('accessors', i);
    optionalBoolean(accessor, 'normalized', at);
    numbers(accessor.min, `${at}/min`);
    numbers(accessor.max, `${at}/max`);
  });
  list(json, 'meshes').forEach((mesh, i) => numbers(mesh.weights, `${pointer('meshes', i)}/weights`));
  const rootExtensions = extensionsOf(json, '');
  const punctual = rootExtensions.KHR_lights_punctual as Json | undefined;
  const lights = punctual === undefined ? [] : Array.isArray(punctual.lights) ? (punctual.lights as unknown[]) : failGltf('/extensions/KHR_lights_punctual/lights', 'expected an array of lights');
  lights.forEach((light, i) => {
    const at = `/extensions/KHR_lights_punctual/lights/${i}`;
    if (!isObject(light)) failGltf(at, `expected an object, got ${show(light)}`);
    validateLight(light, at);
  });
  const variants = rootExtensions.KHR_materials_variants as Json | undefined;
  if (variants !== undefined) {
    if (!Array.isArray(variants.variants)) failGltf('/extensions/KHR_materials_variants/variants', 'expected an array of variants');
    variants.variants.forEach((v: unknown, i: number) => {
      const at = `/extensions/KHR_materials_variants/variants/${i}`;
      if (!isObject(v) || typeof v.name !== 'string') failGltf(at, 'expected { name }');
    });
  }
  list(json, 'nodes').forEach((node, i) => {
    const at = pointer('nodes', i);
    numbers(node.weights, `${at}/weights`);
    optionalString(node, 'name', at);
    const light = extensionsOf(node, at).KHR_lights_punctual as Json | undefined;
    if (light !== undefined) {
      const lat = `${at}/extensions/KHR_lights_punctual/light`;
      if (typeof light.light !== 'number' || !Number.isInteger(light.light) || light.light < 0 || light.light >= lights.length) failGltf(lat, `light index ${show(light.light)} is out of range (the asset has ${lights.length} lights)`);
    }
    if (isObject(node.extensions) && isObject(node.extensions.KHR_node_visibility)) optionalBoolean(node.extensions.KHR_node_visibility, 'visible', `${at}/extensions/KHR_node_visibility`);
  });
  list(json, 'animations').forEach((animation, a) => {
    const at = pointer('animations', a);
    const samplers = list(animation, 'samplers');
    samplers.forEach((s, k) => oneOf(s, 'interpolation', `${at}/samplers/${k}`, ['LINEAR', 'STEP', 'CUBICSPLINE']));
    if (!Array.isArray(animation.channels)) failGltf(`${at}/channels`, 'expected an array of channels');
    (animation.channels as unknown[]).forEach((c, k) => {
      const cat = `${at}/channels/${k}`;
      if (!isObject(c)) failGltf(cat, `expected an object, got ${show(c)}`);
      if (typeof c.sampler !== 'number' || !Number.isInteger(c.sampler) || c.sampler < 0 || c.sampler >= samplers.length) failGltf(`${cat}/sampler`, `sampler index ${show(c.sampler)} is out of range (the animation has ${samplers.length})`);
      if (!isObject(c.target)) failGltf(`${cat}/target`, 'expected { node, path }');
      const target = c.target;
      if (target.node !== undefined && (typeof target.node !== 'number' || !Number.isInteger(target.node) || target.node < 0 || target.node >= counts.nodes)) {
        failGltf(`${cat}/target/node`, `node index ${show(target.node)} is out of range (the asset has ${counts.nodes} nodes)`);
      }
      if (typeof target.path !== 'string') failGltf(`${cat}/target/path`, `expected a path, got ${show(target.path)}`);
    });
  });
  list(json, 'scenes').forEach((scene, i) => optionalString(scene, 'name', pointer('scenes', i)));
  for (const key of ['meshes', 'materials', 'textures', 'cameras', 'accessors', 'bufferViews', 'buffers', 'samplers', 'skins', 'animations'] as const) {
    list(json, key).forEach((entry, i) => {
      if (isObject(entry)) optionalString(entry, 'name', pointer(key, i));
    });
  }
}
