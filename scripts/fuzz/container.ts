/** Packaging of a (mutated) glTF JSON and its resources as files or bytes: .gltf, embedded .gltf, .glb. */
import type { Json } from './mutate-json.ts';

export type Packaging = 'gltf-files' | 'gltf-embedded' | 'glb';

/** A GLB (glTF 2.0 section 4.4): 12-byte header, JSON chunk padded with spaces, BIN chunk padded with zeros. */
export function writeGlb(jsonText: string, bin: Uint8Array | undefined): Uint8Array {
  const json = new TextEncoder().encode(jsonText);
  const jsonPadded = Math.ceil(json.length / 4) * 4;
  const binPadded = bin === undefined ? 0 : Math.ceil(bin.length / 4) * 4;
  const total = 12 + 8 + jsonPadded + (bin === undefined ? 0 : 8 + binPadded);
  const out = new Uint8Array(total);
  const view = new DataView(out.buffer);
  view.setUint32(0, 0x46546c67, true);
  view.setUint32(4, 2, true);
  view.setUint32(8, total, true);
  view.setUint32(12, jsonPadded, true);
  view.setUint32(16, 0x4e4f534a, true);
  out.set(json, 20);
  out.fill(0x20, 20 + json.length, 20 + jsonPadded);
  if (bin !== undefined) {
    const at = 20 + jsonPadded;
    view.setUint32(at, binPadded, true);
    view.setUint32(at + 4, 0x004e4942, true);
    out.set(bin, at + 8);
  }
  return out;
}

const dataUri = (bytes: Uint8Array): string => `data:application/octet-stream;base64,${Buffer.from(bytes).toString('base64')}`;

/** A relative file name for a resource URI the seed asset wrote (never anything that leaves the folder). */
function safeFile(uri: string): string | undefined {
  let path: string;
  try {
    path = decodeURIComponent(uri);
  } catch {
    return undefined;
  }
  if (path === '' || path.startsWith('/') || path.includes('..') || path.includes('\\') || path.includes('\0') || /^[a-z][a-z0-9+.-]*:/i.test(path)) return undefined;
  return path;
}

/**
 * Files to write into the asset folder and the entry file's name. `mutateText` may change the JSON
 * text (number overflows, truncation) before it is packaged.
 */
export function packageGltf(json: Json, resources: Record<string, Uint8Array>, packaging: Packaging, mutateText: (text: string) => string = (t) => t): { files: Record<string, Uint8Array>; entry: string } {
  const files: Record<string, Uint8Array> = {};
  const doc = structuredClone(json) as Record<string, Json>;
  const buffers = Array.isArray(doc.buffers) ? (doc.buffers as Array<Record<string, Json>>) : [];
  const images = Array.isArray(doc.images) ? (doc.images as Array<Record<string, Json>>) : [];
  let bin: Uint8Array | undefined;
  if (packaging === 'glb' && buffers[0] && typeof buffers[0].uri === 'string' && resources[buffers[0].uri] !== undefined) {
    bin = resources[buffers[0].uri];
    delete buffers[0].uri;
  }
  for (const item of [...buffers, ...images]) {
    if (item === null || typeof item !== 'object' || typeof item.uri !== 'string') continue;
    const bytes = resources[item.uri];
    if (bytes === undefined) continue;
    if (packaging === 'gltf-embedded') item.uri = dataUri(bytes);
  }
  if (packaging !== 'gltf-embedded') {
    for (const [uri, bytes] of Object.entries(resources)) {
      const file = safeFile(uri);
      if (file !== undefined) files[file] = bytes;
    }
  }
  const text = mutateText(JSON.stringify(doc));
  if (packaging === 'glb') {
    files['asset.glb'] = writeGlb(text, bin);
    return { files, entry: 'asset.glb' };
  }
  files['asset.gltf'] = new TextEncoder().encode(text);
  return { files, entry: 'asset.gltf' };
}
