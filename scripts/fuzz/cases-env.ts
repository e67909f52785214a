/**
 * Environment-map mutants: a seed with byte mutations aimed at the headers (resolution strings,
 * OpenEXR attributes, the offset table, chunk headers) and at the data, passed by path, file: URL
 * or bytes, or a hostile path instead of a file; plus loader option mutations.
 */
import type { EnvSeed } from './corpus-env.ts';
import type { Json } from './mutate-json.ts';
import type { Random } from './random.ts';
import { expandUri, HOSTILE_SOURCES, type UriContext } from './sandbox.ts';
import { fuzzPolicy, type LoaderCase } from './cases-gltf.ts';

const HDR_RESOLUTIONS = ['-Y 100000000000000000000 +X 8', '-Y 8 +X 100000000000000000000', '-Y 0 +X 8', '-Y 8192 +X 8193', '-Y 65536 +X 65536', '+X 8 -Y 4', '-Y -4 +X 8', '-Y 4 +X 8 junk', '-Y 4294967297 +X 1', '-Y 4096 +X 8192'];

function mutateHdr(bytes: Uint8Array, random: Random): { bytes: Uint8Array; note: string } {
  const text = new TextDecoder('latin1').decode(bytes);
  const match = /\n\n([^\n]*)\n/.exec(text);
  if (match === null || random.chance(0.3)) return mutateAny(bytes, random);
  const resolution = random.pick(HDR_RESOLUTIONS);
  const start = match.index + 2;
  const out = new Uint8Array([...bytes.subarray(0, start), ...new TextEncoder().encode(resolution), ...bytes.subarray(start + match[1]!.length)]);
  return { bytes: out, note: `resolution "${resolution}"` };
}

/** Offsets of OpenEXR header fields worth hitting: attribute sizes and values, the end of the header, the offset table and chunk headers. */
function exrTargets(bytes: Uint8Array): number[] {
  const targets: number[] = [4, 5];
  let pos = 8;
  while (pos < bytes.length && bytes[pos] !== 0) {
    const nameEnd = bytes.indexOf(0, pos);
    const typeEnd = bytes.indexOf(0, nameEnd + 1);
    if (nameEnd < 0 || typeEnd < 0 || typeEnd + 4 > bytes.length) break;
    const size = new DataView(bytes.buffer, bytes.byteOffset).getInt32(typeEnd + 1, true);
    targets.push(typeEnd + 1, typeEnd + 5, typeEnd + 9, typeEnd + 13);
    pos = typeEnd + 5 + Math.max(0, size);
  }
  targets.push(pos + 1, pos + 5, pos + 9);
  return targets.filter((t) => t + 4 <= bytes.length);
}

function mutateExr(bytes: Uint8Array, random: Random): { bytes: Uint8Array; note: string } {
  if (random.chance(0.3)) return mutateAny(bytes, random);
  const out = bytes.slice();
  const view = new DataView(out.buffer);
  const at = random.pick(exrTargets(bytes));
  const value = random.pick([0, 1, 2, 3, 4, 9, 10, 255, -1, 0x7fffffff, -0x80000000, 8192, 8193, 65536, out.length, view.getInt32(at, true) + 1, view.getInt32(at, true) - 1, view.getInt32(at, true) * 1000]);
  view.setInt32(at, value, true);
  return { bytes: out, note: `i32 at ${at} = ${value}` };
}

function mutateAny(bytes: Uint8Array, random: Random): { bytes: Uint8Array; note: string } {
  const op = random.int(5);
  if (op === 0) {
    const cut = random.int(bytes.length);
    return { bytes: bytes.subarray(0, cut), note: `truncated to ${cut}` };
  }
  if (op === 1) {
    const at = random.int(bytes.length);
    const length = 1 + random.int(64);
    const out = bytes.slice();
    out.fill(random.pick([0, 0xff, 0x80]), at, at + length);
    return { bytes: out, note: `${length} bytes filled at ${at}` };
  }
  if (op === 2) {
    const at = random.int(bytes.length);
    const insert = new Uint8Array(1 + random.int(16)).map(() => random.int(256));
    return { bytes: new Uint8Array([...bytes.subarray(0, at), ...insert, ...bytes.subarray(at)]), note: `${insert.length} bytes inserted at ${at}` };
  }
  const out = bytes.slice();
  const flips = 1 + random.int(16);
  // Flips land in the first 512 bytes (headers, tables) half of the time.
  for (let k = 0; k < flips; k++) out[random.chance(0.5) ? random.int(Math.min(512, out.length)) : random.int(out.length)] ^= 1 << random.int(8);
  return { bytes: out, note: `${flips} bit flips` };
}

export function makeEnvCase(corpus: readonly EnvSeed[], random: Random, context: UriContext): LoaderCase {
  const seed = random.pick(corpus);
  const notes = [seed.name];
  let bytes = seed.bytes;
  const rounds = 1 + (random.chance(0.6) ? 0 : random.int(3));
  for (let r = 0; r < rounds; r++) {
    const isHdr = bytes[0] === 0x23;
    const m = isHdr ? mutateHdr(bytes, random) : bytes[0] === 0x76 ? mutateExr(bytes, random) : mutateAny(bytes, random);
    bytes = m.bytes;
    notes.push(m.note);
  }
  const options: Record<string, Json> = { negativeTexels: 'zero', resourcePolicy: fuzzPolicy(random, context) };
  if (random.chance(0.1)) {
    const key = random.pick(['intensity', 'rotationRadians', 'negativeTexels', 'field', 'unknown', 'resourcePolicy', 'EXRLoader', 'onNegativeTexels']);
    const value = random.pick<Json>([-1, 0, 1e30, 1.5, 'zero', 'clamp', '', null, {}, [], true, { maxDecodedBytes: 1024 }, { maxResourceBytes: 10 }, { root: '/nonexistent' }]);
    options[key] = value;
    notes.push(`option ${key} = ${JSON.stringify(value)}`);
  }
  const file = bytes[0] === 0x76 ? 'map.exr' : 'map.hdr';
  const how = random.int(20);
  let source: LoaderCase['source'];
  if (how < 2) source = { kind: 'bytes', bytes };
  else if (how === 2) source = { kind: 'file-url', file };
  else if (how < 5) source = { kind: 'raw', value: expandUri(random.pick(HOSTILE_SOURCES), context) };
  else source = { kind: 'path', file };
  if (source.kind !== 'path') notes.push(`source ${source.kind === 'raw' ? source.value : source.kind}`);
  if (bytes[0] === 0x23 && random.chance(0.25)) {
    notes.push('decodeHdr');
    return { files: {}, source: { kind: 'bytes', bytes }, options: {}, abort: false, notes, decoder: 'decodeHdr' };
  }
  return { files: { [file]: bytes }, source, options, abort: random.chance(0.02), notes };
}
