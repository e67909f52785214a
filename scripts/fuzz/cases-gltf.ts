/**
 * glTF mutants: a seed of the corpus, one to four mutations at the JSON, resource, text or
 * container level, a packaging (.gltf with files, embedded .gltf, .glb), a way to pass it (path,
 * file: URL, bytes) and a resource policy. Everything is decided by the case's random stream, so
 * (seed, index) reproduces the case.
 */
import { packageGltf, type Packaging } from './container.ts';
import type { GltfSeed } from './corpus-gltf.ts';
import { getAt, jsonPaths, mutateJson, setAt, showPath, type Json, type JsonPath } from './mutate-json.ts';
import type { Random } from './random.ts';
import { expandUri, HOSTILE_SOURCES, HOSTILE_URIS, type UriContext } from './sandbox.ts';

export interface LoaderCase {
  /** Files written into the asset folder (relative names). */
  files: Record<string, Uint8Array>;
  /** The source: a file of the folder by path or file: URL, or bytes. */
  source: { kind: 'path' | 'file-url'; file: string } | { kind: 'bytes'; bytes: Uint8Array } | { kind: 'raw'; value: string };
  /** JSON-able loader options (`resourcePolicy` included); `abort` aborts a signal first. */
  options: Record<string, Json>;
  abort: boolean;
  notes: string[];
  /** Environment cases: decode with `decodeHdr` (the image-file API's errors and limits) instead of loadEnvironmentMap. */
  decoder?: 'decodeHdr';
}

type Doc = Record<string, Json>;

const REFERENCE_KEYS = new Set(['bufferView', 'buffer', 'source', 'index', 'mesh', 'material', 'sampler', 'camera', 'skin', 'node', 'scene', 'input', 'output', 'indices', 'POSITION', 'NORMAL', 'TEXCOORD_0', 'COLOR_0', 'light', 'inverseBindMatrices', 'skeleton']);

/** Data URI payloads are large and mutated by the byte-level mutators, not the JSON one. */
const skipDataUris = (doc: Json) => (path: JsonPath): boolean => {
  const v = getAt(doc, path);
  return typeof v === 'string' && v.startsWith('data:') && v.length > 200;
};

function list(doc: Doc, key: string): Array<Record<string, Json>> {
  return Array.isArray(doc[key]) ? (doc[key] as Array<Record<string, Json>>) : [];
}

function hostileUri(random: Random, context: UriContext): string {
  return expandUri(random.pick(HOSTILE_URIS), context);
}

/** Byte mutations of an image or buffer: header sizes, flips, truncation, extension. */
function mutateBytes(bytes: Uint8Array, random: Random): { bytes: Uint8Array; note: string } {
  const out = bytes.slice();
  const op = random.int(6);
  if (op === 0 && out.length >= 24 && out[0] === 0x89 && out[1] === 0x50) {
    // PNG IHDR width/height (big-endian at 16 and 20).
    const view = new DataView(out.buffer);
    const field = random.pick([16, 20]);
    const value = random.pick([0, 0x7fffffff, 0xffffffff, 65536, 16385, 100000, 1 << 24]);
    view.setUint32(field, value >>> 0);
    return { bytes: out, note: `PNG ${field === 16 ? 'width' : 'height'} = ${value}` };
  }
  if (op === 1 && out.length > 4 && out[0] === 0xff && out[1] === 0xd8) {
    for (let p = 2; p + 9 < out.length; p++) {
      if (out[p] === 0xff && out[p + 1]! >= 0xc0 && out[p + 1]! <= 0xc2) {
        const value = random.pick([0, 0xffff, 30000]);
        out[p + 5 + random.int(2) * 2] = value >> 8;
        out[p + 6] = value & 0xff;
        return { bytes: out, note: `JPEG SOF size ${value}` };
      }
    }
  }
  if (op === 2 && out.length > 0) {
    const cut = random.int(out.length);
    return { bytes: out.subarray(0, cut), note: `truncated to ${cut} of ${bytes.length} bytes` };
  }
  if (op === 3 && out.length > 30 && out[8] === 0x57) {
    // WebP: the VP8/VP8L/VP8X size fields.
    for (let k = 24; k < Math.min(34, out.length); k++) out[k] = 0xff;
    return { bytes: out, note: 'WebP size fields 0xff' };
  }
  const flips = 1 + random.int(8);
  for (let k = 0; k < flips && out.length > 0; k++) out[random.int(Math.min(out.length, random.chance(0.5) ? 64 : out.length))] ^= 1 << random.int(8);
  return { bytes: out, note: `${flips} bit flips` };
}

function mutateText(text: string, random: Random): { text: string; note: string } {
  const op = random.int(5);
  if (op === 0) {
    const numbers = [...text.matchAll(/-?\d+(\.\d+)?(e[+-]?\d+)?/gi)];
    if (numbers.length > 0) {
      const m = random.pick(numbers);
      const value = random.pick(['1e999', '-1e999', '1e400', '-0', '1e-400', '123456789012345678901234567890', '0.0000000000000000000000001']);
      return { text: text.slice(0, m.index) + value + text.slice(m.index! + m[0].length), note: `number at ${m.index} = ${value}` };
    }
  }
  if (op === 1) {
    const cut = random.int(text.length);
    return { text: text.slice(0, cut), note: `JSON text truncated at ${cut}` };
  }
  if (op === 2) return { text: `\uFEFF${text}`, note: 'byte order mark' };
  if (op === 3) {
    const at = random.int(text.length);
    return { text: text.slice(0, at) + random.pick(['\uD800', '\u0000', '"', '}', ']', ',', '\\']) + text.slice(at), note: `character inserted at ${at}` };
  }
  const at = text.indexOf('{', 1);
  const depth = random.pick([300, 5000, 100000]);
  if (at > 0) return { text: `${text.slice(0, at)}${'['.repeat(depth)}${']'.repeat(depth)},${text.slice(at)}`, note: `array nested ${depth} deep` };
  return { text, note: 'unchanged text' };
}

function mutateGlb(glb: Uint8Array, random: Random): { bytes: Uint8Array; note: string } {
  const out = glb.slice();
  const view = new DataView(out.buffer);
  const field = random.pick([4, 8, 12, 16, 20 + view.getUint32(12, true), 24 + view.getUint32(12, true)]);
  if (field + 4 > out.length) return { bytes: out.subarray(0, random.int(out.length)), note: 'GLB truncated' };
  const value = random.pick([0, 1, 3, 0xffffffff, 0x7fffffff, out.length, out.length + 4, view.getUint32(field, true) + 4, view.getUint32(field, true) - 4]);
  view.setUint32(field, value >>> 0, true);
  return { bytes: out, note: `GLB u32 at ${field} = ${value}` };
}

/**
 * The policy a case loads under: a 256 MiB budget (so that a legal but large decode stays far below
 * the worker's memory limit) and time limits under the case's deadline; sometimes the allowed
 * server's origin.
 */
export function fuzzPolicy(random: Random, context: UriContext): Record<string, Json> {
  const policy: Record<string, Json> = { maxDecodedBytes: 256 * 2 ** 20, fetchTimeoutMs: random.pick([1000, 3000]), decodeTimeoutMs: 5000 };
  if (random.chance(0.15)) policy.allowedOrigins = [context.servers.allowed];
  return policy;
}

export function makeGltfCase(corpus: readonly GltfSeed[], random: Random, context: UriContext & { hasFifo: boolean }): LoaderCase {
  const seed = random.pick(corpus);
  let doc = structuredClone(seed.json) as Doc;
  const resources: Record<string, Uint8Array> = { ...seed.resources };
  const notes = [seed.name];
  const options: Record<string, Json> = {};
  let abort = false;
  let textMutation: ((t: string) => string) | undefined;
  let glbMutation = false;
  const count = 1 + (random.chance(0.5) ? 0 : random.int(3));
  for (let m = 0; m < count; m++) {
    const kind = random.int(100);
    if (kind < 38) {
      const r = mutateJson(doc, random, { skip: skipDataUris(doc) });
      doc = r.value as Doc;
      notes.push(r.note);
    } else if (kind < 50) {
      const holders = [...list(doc, 'buffers').map((b, i) => ['buffers', i, b] as const), ...list(doc, 'images').map((b, i) => ['images', i, b] as const)];
      if (holders.length === 0) continue;
      const [key, i] = random.pick(holders);
      const uri = hostileUri(random, context);
      doc = setAt(doc, [key, i, 'uri'], uri) as Doc;
      if (key === 'images') doc = setAt(doc, [key, i, 'bufferView'], undefined) as Doc;
      notes.push(`/${key}/${i}/uri = ${JSON.stringify(uri).slice(0, 80)}`);
    } else if (kind < 58) {
      const refs = jsonPaths(doc).filter((p) => REFERENCE_KEYS.has(String(p[p.length - 1])) && typeof getAt(doc, p) === 'number');
      if (refs.length === 0) continue;
      const path = random.pick(refs);
      const value = random.pick([-1, 0, 1, 2, 3, 7, 100, 2 ** 31, 1.5]);
      doc = setAt(doc, path, value) as Doc;
      notes.push(`${showPath(path)} = ${value}`);
    } else if (kind < 62) {
      const accessors = list(doc, 'accessors');
      if (accessors.length === 0) continue;
      const i = random.int(accessors.length);
      const value = random.pick([2 ** 20, 2 ** 24, 2 ** 26, 2 ** 28, 2 ** 30, 2 ** 32, 2 ** 40]);
      doc = setAt(doc, ['accessors', i, 'count'], value) as Doc;
      doc = setAt(doc, ['accessors', i, 'bufferView'], undefined) as Doc;
      doc = setAt(doc, ['accessors', i, 'byteOffset'], undefined) as Doc;
      notes.push(`/accessors/${i}: no bufferView, count ${value}`);
    } else if (kind < 64) {
      const depth = random.pick([200, 5000, 20000]);
      const nodes = list(doc, 'nodes').slice();
      const first = nodes.length;
      for (let k = 0; k < depth; k++) nodes.push(k + 1 < depth ? { children: [first + k + 1] } : { mesh: 0 });
      doc = { ...doc, nodes };
      const scenes = list(doc, 'scenes');
      if (scenes.length > 0) doc = setAt(doc, ['scenes', 0, 'nodes'], [...((scenes[0]!.nodes as Json[]) ?? []), first]) as Doc;
      notes.push(`node chain ${depth} deep`);
    } else if (kind < 66) {
      const depth = random.pick([100, 300, 1000]);
      let nested: Json = 1;
      for (let k = 0; k < depth; k++) nested = random.chance(0.5) ? [nested] : { a: nested };
      const targets = jsonPaths(doc).filter((p) => getAt(doc, p) !== null && typeof getAt(doc, p) === 'object' && !Array.isArray(getAt(doc, p)));
      if (targets.length === 0) continue;
      const path = random.pick(targets);
      doc = setAt(doc, [...path, random.pick(['extras', 'extensions', 'KHR_texture_transform'])], random.chance(0.5) ? nested : { KHR_materials_ior: nested }) as Doc;
      notes.push(`${showPath(path)} nested ${depth} deep`);
    } else if (kind < 78) {
      const names = Object.keys(resources);
      if (names.length === 0) continue;
      const name = random.pick(names);
      const r = mutateBytes(resources[name]!, random);
      resources[name] = r.bytes;
      notes.push(`${name}: ${r.note}`);
    } else if (kind < 84) {
      textMutation = (t) => {
        const r = mutateText(t, random);
        notes.push(r.note);
        return r.text;
      };
    } else if (kind < 88) {
      glbMutation = true;
    } else if (kind < 90) {
      const accessors = list(doc, 'accessors');
      const views = list(doc, 'bufferViews');
      if (accessors.length === 0 || views.length === 0) continue;
      const template = accessors.find((a) => a.bufferView !== undefined) ?? accessors[0]!;
      const copies = random.pick([100, 2000, 20000]);
      doc = { ...doc, accessors: [...accessors, ...Array.from({ length: copies }, () => template)] };
      notes.push(`${copies} accessors aliasing one view`);
    } else if (kind < 93) {
      const buffers = list(doc, 'buffers');
      if (buffers.length === 0) continue;
      const uri = random.pick(['data:application/octet-stream;base64,A', 'data:application/octet-stream;base64,AAAAA', 'data:application/octet-stream;base64,AA=A', `data:application/octet-stream;base64,${'A'.repeat(4097)}`, 'data:text/plain,%E0%A4%A', 'data:application/octet-stream;base64,' + '/'.repeat(64)]);
      doc = setAt(doc, ['buffers', random.int(buffers.length), 'uri'], uri) as Doc;
      notes.push(`buffer data URI ${uri.slice(0, 50)}`);
    } else if (kind < 97) {
      const key = random.pick(['camera', 'variant', 'scene', 'unknownOption', 'resourcePolicy', 'decoders', 'signal']);
      const value = random.pick([-1, 0, 1, 1.5, 'Camera', 'Night', 'Day', 'nope', '', null, {}, [], true, 2 ** 40]);
      options[key] = value;
      notes.push(`option ${key} = ${JSON.stringify(value)}`);
    } else {
      abort = true;
      notes.push('aborted signal');
    }
  }
  // The resource policy: mostly the default; sometimes the allowed server, a short timeout, a small budget.
  const policy = fuzzPolicy(random, context);
  if (random.chance(0.05)) policy.maxDecodedBytes = random.pick([1024, 65536]);
  if (random.chance(0.03)) policy.maxImageDimension = random.pick([1, 2, 3]);
  if (options.resourcePolicy === undefined) options.resourcePolicy = policy;
  const packaging = random.pick<Packaging>(['gltf-files', 'gltf-files', 'gltf-embedded', 'glb', 'glb']);
  notes.push(packaging);
  const packaged = packageGltf(doc, resources, packaging, textMutation);
  if (glbMutation && packaging === 'glb') {
    const r = mutateGlb(packaged.files['asset.glb']!, random);
    packaged.files['asset.glb'] = r.bytes;
    notes.push(r.note);
  }
  const how = random.int(20);
  let source: LoaderCase['source'];
  if (how === 0) source = { kind: 'bytes', bytes: packaged.files[packaged.entry]! };
  else if (how === 1) source = { kind: 'file-url', file: packaged.entry };
  else if (how === 2) source = { kind: 'raw', value: expandUri(random.pick(HOSTILE_SOURCES), context) };
  else source = { kind: 'path', file: packaged.entry };
  if (source.kind !== 'path') notes.push(`source ${source.kind}`);
  return { files: packaged.files, source, options, abort, notes };
}
