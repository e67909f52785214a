/**
 * GLB container validation (glTF 2.0 specification, section 4.4 "Binary glTF Layout"): a 12-byte
 * header (magic "glTF", version 2, total length), then a JSON chunk, an optional BIN chunk and
 * chunks of unknown types, which readers must ignore. Faults name `glb:` paths.
 */
import { failGltf } from './errors.ts';

const GLB_MAGIC = 0x46546c67; // "glTF"
const CHUNK_JSON = 0x4e4f534a; // "JSON"
const CHUNK_BIN = 0x004e4942; // "BIN\0"

export interface GlbContents {
  /** The JSON chunk's text. */
  jsonText: string;
  /** The BIN chunk's payload, if there is one. */
  bin: Uint8Array | undefined;
}

export function isGlb(bytes: Uint8Array): boolean {
  return bytes.byteLength >= 4 && new DataView(bytes.buffer, bytes.byteOffset, 4).getUint32(0, true) === GLB_MAGIC;
}

export function parseGlb(bytes: Uint8Array): GlbContents {
  if (bytes.byteLength < 12) failGltf('glb:/header', `a GLB header is 12 bytes, the data has ${bytes.byteLength}`);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const magic = view.getUint32(0, true);
  if (magic !== GLB_MAGIC) failGltf('glb:/header/magic', `expected 0x46546c67 ("glTF"), got 0x${magic.toString(16).padStart(8, '0')}`);
  const version = view.getUint32(4, true);
  if (version !== 2) failGltf('glb:/header/version', `expected GLB version 2, got ${version}`);
  const length = view.getUint32(8, true);
  if (length !== bytes.byteLength) {
    failGltf('glb:/header/length', `the header says ${length} bytes, the data has ${bytes.byteLength}${length > bytes.byteLength ? ' (truncated file)' : ''}`);
  }
  let offset = 12;
  let jsonText: string | undefined;
  let bin: Uint8Array | undefined;
  for (let chunk = 0; offset < length; chunk++) {
    if (offset + 8 > length) failGltf(`glb:/chunks/${chunk}`, `a chunk header needs 8 bytes, ${length - offset} remain`);
    const chunkLength = view.getUint32(offset, true);
    const chunkType = view.getUint32(offset + 4, true);
    const start = offset + 8;
    if (start + chunkLength > length) {
      failGltf(`glb:/chunks/${chunk}/chunkLength`, `${chunkLength} bytes from byte ${start} run past the end of the ${length}-byte file`);
    }
    const payload = bytes.subarray(start, start + chunkLength);
    if (chunk === 0) {
      if (chunkType !== CHUNK_JSON) failGltf('glb:/chunks/0/chunkType', `the first chunk must be JSON (0x4e4f534a), got 0x${chunkType.toString(16)}`);
      try {
        jsonText = new TextDecoder('utf-8', { fatal: true }).decode(payload);
      } catch (error) {
        failGltf('glb:/chunks/0', 'the JSON chunk is not valid UTF-8', error);
      }
    } else if (chunkType === CHUNK_JSON) {
      failGltf(`glb:/chunks/${chunk}/chunkType`, 'only the first chunk may be JSON');
    } else if (chunkType === CHUNK_BIN) {
      if (chunk !== 1) failGltf(`glb:/chunks/${chunk}/chunkType`, 'the BIN chunk must directly follow the JSON chunk');
      bin = payload;
    }
    // Chunks of other types are skipped (section 4.4.3.1: clients must ignore unknown chunk types).
    offset = start + chunkLength;
    // Chunks start on 4-byte boundaries; writers pad the previous chunk, so tolerate a short tail.
    if (offset % 4 !== 0 && offset < length) failGltf(`glb:/chunks/${chunk}/chunkLength`, `chunk length ${chunkLength} leaves the next chunk unaligned`);
  }
  if (jsonText === undefined) failGltf('glb:/chunks/0', 'the GLB has no JSON chunk');
  return { jsonText, bin };
}
