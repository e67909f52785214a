/**
 * Source -> @gltf-transform `Document`: reads the bytes (file, URL, memory), validates the GLB
 * container and the JSON with exact pointers, fetches every external resource, then lets
 * @gltf-transform build the document with all Khronos extensions registered, plus the Draco and
 * meshopt decoders they need.
 */
import type { Document} from '@gltf-transform/core';
import { GLB_BUFFER, WebIO, type ILogger, type JSONDocument } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { locateCompressionFault } from './compression-faults.ts';
import { failGltf, gltfError, pointer } from './errors.ts';
import { SUPPORTED_EXTENSIONS } from './extensions.ts';
import { isGlb, parseGlb } from './glb-container.ts';
import { isMeshoptFallback, validateGltfJson } from './json-validation.ts';
import { budgetOf, derivePolicy, readByteSource, type DecodeBudget, type ResolvedResourcePolicy } from '../resource-policy.ts';
import { JSON_BYTES_PER_VALUE, MAX_JSON_DEPTH, scanJson } from '../json-scan.ts';
import { chargeGeometry, chargeImages } from './decode-budget.ts';
import { nodeModule } from '../platform.ts';
import { readResource } from './resources.ts';
import { validateSparseIndices } from './sparse-indices.ts';

/** What `loadGltfScene` accepts. */
export type GltfSource = string | URL | ArrayBuffer | Uint8Array | Document;

/**
 * Decoder modules for compressed geometry; loaded on demand in Node (`draco3dgltf`, `meshoptimizer`).
 * Browser applications whose bundler does not include those packages pass their own here.
 */
export interface GltfDecoderModules {
  /** An initialised Draco decoder module (`await draco3d.createDecoderModule()`). */
  'draco3d.decoder'?: unknown;
  /** meshoptimizer's `MeshoptDecoder` (after `await MeshoptDecoder.ready`). */
  'meshopt.decoder'?: unknown;
}

export interface ReadDocumentResult {
  document: Document;
  /** The asset's JSON, or undefined when a Document was passed in. */
  json: Record<string, unknown> | undefined;
}

let dracoDecoder: Promise<unknown> | undefined;
let meshoptDecoder: Promise<unknown> | undefined;

async function loadDraco(): Promise<unknown> {
  // Node-oriented: browser builds pass their own decoder.
  const draco3d = (await nodeModule<{ default: { createDecoderModule: () => Promise<unknown> } }>('draco3dgltf')).default;
  return draco3d.createDecoderModule();
}

async function loadMeshopt(): Promise<unknown> {
  const { MeshoptDecoder } = await import('meshoptimizer');
  await MeshoptDecoder.ready;
  return MeshoptDecoder;
}

function captureLogger(warnings: string[]): ILogger {
  const warn = (text: string): void => {
    // Unregistered optional extensions are reported by readGltfDocument itself (supported or not).
    if (/^Missing optional extension/.test(text)) return;
    warnings.push(`glTF reader: ${text}`);
  };
  return { debug: () => {}, info: () => {}, warn, error: warn };
}

async function sourceBytes(source: Exclude<GltfSource, Document>, policy: ResolvedResourcePolicy, signal: AbortSignal | undefined): Promise<{ bytes: Uint8Array; base: URL | undefined }> {
  if (!(source instanceof Uint8Array || source instanceof ArrayBuffer || typeof source === 'string' || source instanceof URL)) {
    failGltf('', `expected a path, a URL, an ArrayBuffer, a Uint8Array or a Document, got ${source === null ? 'null' : typeof source}`);
  }
  const { bytes, url } = await readByteSource(source, policy, { code: 'INVALID_GLTF', field: '' }, signal);
  return { bytes, base: url };
}

/** Refuses JSON nested deeper than MAX_JSON_DEPTH and charges its parsed size before parsing. */
function checkJsonShape(text: Uint8Array | string, field: string, budget: DecodeBudget): void {
  const shape = scanJson(text);
  if (shape.depth > MAX_JSON_DEPTH) failGltf(field, `the JSON nests ${shape.depth} levels deep; the loader reads at most ${MAX_JSON_DEPTH}`);
  budget.charge(shape.values * JSON_BYTES_PER_VALUE, { code: 'INVALID_GLTF', field }, `parsing the JSON's ${shape.values} values`);
}

function parseJsonText(bytes: Uint8Array, field: string): unknown {
  let text: string;
  try {
    text = new TextDecoder('utf-8', { fatal: true, ignoreBOM: false }).decode(bytes);
  } catch (error) {
    failGltf(field, 'the glTF JSON is not valid UTF-8', error);
  }
  try {
    return JSON.parse(text);
  } catch (error) {
    failGltf(field, `the glTF JSON does not parse: ${(error as Error).message}`, error);
  }
}

interface LoadedResources {
  /** By URI (GLB_BUFFER for the BIN chunk), as @gltf-transform's readJSON takes them. */
  resources: JSONDocument['resources'];
  /** Each buffer's bytes by index; undefined for meshopt fallback buffers, which are never read. */
  buffers: Array<Uint8Array | undefined>;
}

async function loadResources(
  json: Record<string, unknown>,
  bufferByteLengths: number[],
  bin: Uint8Array | undefined,
  base: URL | undefined,
  policy: ResolvedResourcePolicy,
  signal: AbortSignal | undefined,
): Promise<LoadedResources> {
  const resources: Record<string, Uint8Array> = {};
  const bufferDefs = (Array.isArray(json.buffers) ? json.buffers : []) as Array<Record<string, unknown>>;
  const buffers = await Promise.all(
    bufferDefs.map(async (buffer, i): Promise<Uint8Array | undefined> => {
      const at = pointer('buffers', i);
      const meshoptFallback = isMeshoptFallback(json, buffer);
      let data: Uint8Array;
      if (typeof buffer.uri === 'string') {
        if (meshoptFallback && !buffer.uri.startsWith('data:')) return undefined; // never read: meshopt decodes instead
        data = await readResource(buffer.uri, base, at, policy, signal);
        resources[buffer.uri] = data;
      } else if (meshoptFallback) {
        return undefined;
      } else if (i === 0 && bin !== undefined) {
        data = bin;
        resources[GLB_BUFFER] = bin;
      } else {
        failGltf(at, i === 0 ? 'the buffer has no uri and the file has no GLB BIN chunk' : 'only the first buffer may omit its uri (GLB BIN chunk)');
      }
      if (data.byteLength < bufferByteLengths[i]) failGltf(pointer('buffers', i, 'byteLength'), `declared ${bufferByteLengths[i]} bytes, the data has ${data.byteLength} (truncated)`);
      return data;
    }),
  );
  const images = (Array.isArray(json.images) ? json.images : []) as Array<Record<string, unknown>>;
  await Promise.all(
    images.map(async (image, i) => {
      if (image.bufferView !== undefined || typeof image.uri !== 'string') return;
      resources[image.uri] = await readResource(image.uri, base, pointer('images', i), policy, signal);
    }),
  );
  return { resources: resources as JSONDocument['resources'], buffers };
}

/**
 * A gltf-transform Document, recognised by shape rather than `instanceof`: the browser build
 * carries its own copy of @gltf-transform/core, so an application's Document comes from another
 * class object.
 */
function isDocument(source: GltfSource): source is Document {
  return typeof source === 'object' && source !== null && !(source instanceof URL) && !ArrayBuffer.isView(source) && !(source instanceof ArrayBuffer) && typeof (source as Document).getRoot === 'function';
}

export async function readGltfDocument(
  source: GltfSource,
  warnings: string[],
  options: { signal?: AbortSignal; decoders?: GltfDecoderModules; policy: ResolvedResourcePolicy },
): Promise<ReadDocumentResult> {
  const { signal } = options;
  if (isDocument(source)) return { document: source, json: undefined };
  // One budget for everything this asset reads and decodes (shared with a scene file loading it).
  const policy = options.policy.budget === undefined ? derivePolicy(options.policy, { budget: budgetOf(options.policy) }) : options.policy;
  const budget = policy.budget!;
  const { bytes, base } = await sourceBytes(source, policy, signal);
  signal?.throwIfAborted();
  let rawJson: unknown;
  let bin: Uint8Array | undefined;
  if (isGlb(bytes)) {
    const glb = parseGlb(bytes);
    bin = glb.bin;
    checkJsonShape(glb.jsonText, 'glb:/chunks/0', budget);
    try {
      rawJson = JSON.parse(glb.jsonText);
    } catch (error) {
      failGltf('glb:/chunks/0', `the JSON chunk does not parse: ${(error as Error).message}`, error);
    }
  } else {
    // glTF JSON starts with '{' (after optional whitespace and a UTF-8 BOM); anything else is taken
    // for a GLB whose magic is wrong.
    const first = bytes.findIndex((b, i) => !(b === 0x20 || b === 0x09 || b === 0x0a || b === 0x0d || (i < 3 && (b === 0xef || b === 0xbb || b === 0xbf))));
    if (first < 0 || bytes[first] !== 0x7b) {
      const magic = bytes.byteLength >= 4 ? new DataView(bytes.buffer, bytes.byteOffset, 4).getUint32(0, true) : 0;
      failGltf('glb:/header/magic', `neither glTF JSON nor a GLB: expected magic 0x46546c67 ("glTF"), got 0x${magic.toString(16).padStart(8, '0')}`);
    }
    checkJsonShape(bytes, '', budget);
    rawJson = parseJsonText(bytes, '');
  }
  const { json, bufferByteLengths } = validateGltfJson(rawJson);
  chargeGeometry(json, budget);
  const used = Array.isArray(json.extensionsUsed) ? (json.extensionsUsed as unknown[]).filter((e): e is string => typeof e === 'string') : [];
  // A required one the renderer cannot express was refused during validation.
  for (const name of used) if (!SUPPORTED_EXTENSIONS.has(name)) warnings.push(`${name}: not supported; the asset is drawn without it`);
  const { resources, buffers } = await loadResources(json, bufferByteLengths, bin, base, policy, signal);
  signal?.throwIfAborted();
  chargeImages(json, buffers, resources as Record<string, Uint8Array>, policy, budget);
  validateSparseIndices(json, buffers);

  const dependencies: Record<string, unknown> = {};
  if (used.includes('KHR_draco_mesh_compression')) {
    dependencies['draco3d.decoder'] = options.decoders?.['draco3d.decoder'] ?? (await (dracoDecoder ??= loadDraco()));
  }
  if (used.includes('EXT_meshopt_compression')) {
    dependencies['meshopt.decoder'] = options.decoders?.['meshopt.decoder'] ?? (await (meshoptDecoder ??= loadMeshopt()));
  }
  const io = new WebIO().registerExtensions(ALL_EXTENSIONS).registerDependencies(dependencies).setLogger(captureLogger(warnings));
  try {
    const document = await io.readJSON({ json: json as unknown as JSONDocument['json'], resources });
    return { document, json };
  } catch (error) {
    if (error instanceof GpuRendererError) throw error;
    const fault = locateCompressionFault(json, buffers, { draco: dependencies['draco3d.decoder'], meshopt: dependencies['meshopt.decoder'] });
    if (fault !== undefined) throw gltfError(fault.field, fault.message, error);
    throw gltfError(readerErrorPointer(error, used), `the glTF reader rejected the asset: ${(error as Error).message}`, error);
  }
}

/** Best pointer for an error raised inside @gltf-transform: the extension it names, else the root. */
function readerErrorPointer(error: unknown, used: readonly string[]): string {
  const message = error instanceof Error ? error.message : String(error);
  const index = used.findIndex((name) => message.includes(name));
  return index >= 0 ? pointer('extensionsUsed', index) : '';
}
