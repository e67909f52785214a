/**
 * Where compressed geometry is broken. @gltf-transform decodes every KHR_draco_mesh_compression
 * primitive and EXT_meshopt_compression buffer view while reading, and its errors do not say
 * which one failed; when reading fails, this decodes them one by one, the way the reader does, to
 * name the first bad one by its JSON pointer. It runs only on that error path, so valid assets are
 * decoded once.
 */
import { pointer } from './errors.ts';
import { isObject } from './json-validation.ts';

type Json = Record<string, unknown>;

export interface CompressionFault {
  field: string;
  message: string;
}

interface MeshoptDecoder {
  decodeGltfBuffer(target: Uint8Array, count: number, size: number, source: Uint8Array, mode: string, filter?: string): void;
}

/** The parts of the Draco decoder module (draco3dgltf) used here. */
interface DracoDecoderModule {
  Decoder: new () => DracoDecoder;
  DecoderBuffer: new () => { Init(data: Uint8Array, length: number): void };
  Mesh: new () => { ptr: number };
  TRIANGULAR_MESH: number;
  destroy(object: unknown): void;
}

interface DracoDecoder {
  GetEncodedGeometryType(buffer: unknown): number;
  DecodeBufferToMesh(buffer: unknown, mesh: unknown): { ok(): boolean; error_msg(): string };
}

function list(json: Json, key: string): Json[] {
  return Array.isArray(json[key]) ? (json[key] as Json[]) : [];
}

/** `item.extensions[name]` when it is an object. */
function extension(item: Json, name: string): Json | undefined {
  const ext = isObject(item.extensions) ? item.extensions[name] : undefined;
  return isObject(ext) ? ext : undefined;
}

function viewBytes(json: Json, buffers: ReadonlyArray<Uint8Array | undefined>, viewIndex: number): Uint8Array | undefined {
  const view = list(json, 'bufferViews')[viewIndex];
  const data = view === undefined ? undefined : buffers[view.buffer as number];
  if (view === undefined || data === undefined) return undefined;
  const offset = (view.byteOffset as number | undefined) ?? 0;
  return data.subarray(offset, offset + (view.byteLength as number));
}

function meshoptFault(json: Json, buffers: ReadonlyArray<Uint8Array | undefined>, decoder: MeshoptDecoder): CompressionFault | undefined {
  const views = list(json, 'bufferViews');
  for (let i = 0; i < views.length; i++) {
    const ext = extension(views[i], 'EXT_meshopt_compression');
    if (ext === undefined) continue;
    const source = buffers[ext.buffer as number];
    if (source === undefined) continue;
    const offset = (ext.byteOffset as number | undefined) ?? 0;
    const count = ext.count as number;
    const stride = ext.byteStride as number;
    try {
      decoder.decodeGltfBuffer(new Uint8Array(count * stride), count, stride, source.subarray(offset, offset + (ext.byteLength as number)), ext.mode as string, ext.filter as string | undefined);
    } catch (error) {
      return { field: pointer('bufferViews', i, 'extensions', 'EXT_meshopt_compression'), message: `the meshopt data does not decode: ${(error as Error).message}` };
    }
  }
  return undefined;
}

function dracoFault(json: Json, buffers: ReadonlyArray<Uint8Array | undefined>, module: DracoDecoderModule): CompressionFault | undefined {
  const meshes = list(json, 'meshes');
  for (let m = 0; m < meshes.length; m++) {
    const primitives = list(meshes[m], 'primitives');
    for (let p = 0; p < primitives.length; p++) {
      const ext = extension(primitives[p], 'KHR_draco_mesh_compression');
      if (ext === undefined) continue;
      const at = pointer('meshes', m, 'primitives', p, 'extensions', 'KHR_draco_mesh_compression');
      const data = viewBytes(json, buffers, ext.bufferView as number);
      if (data === undefined) continue;
      const decoder = new module.Decoder();
      const buffer = new module.DecoderBuffer();
      const mesh = new module.Mesh();
      try {
        buffer.Init(data, data.length);
        if (decoder.GetEncodedGeometryType(buffer) !== module.TRIANGULAR_MESH) return { field: at, message: 'the Draco data is not a triangle mesh' };
        const status = decoder.DecodeBufferToMesh(buffer, mesh);
        if (!status.ok() || mesh.ptr === 0) return { field: at, message: `the Draco data does not decode: ${status.error_msg()}` };
      } finally {
        module.destroy(mesh);
        module.destroy(buffer);
        module.destroy(decoder);
      }
    }
  }
  return undefined;
}

/**
 * The first compressed primitive or buffer view that does not decode, given the asset's JSON, its
 * buffers' bytes by index, and the decoders it was read with; undefined when all decode.
 */
export function locateCompressionFault(json: Json, buffers: ReadonlyArray<Uint8Array | undefined>, decoders: { draco?: unknown; meshopt?: unknown }): CompressionFault | undefined {
  try {
    return (
      (decoders.meshopt === undefined ? undefined : meshoptFault(json, buffers, decoders.meshopt as MeshoptDecoder)) ??
      (decoders.draco === undefined ? undefined : dracoFault(json, buffers, decoders.draco as DracoDecoderModule))
    );
  } catch {
    // A decoder module that is not what it should be: no better place to name than the reader's.
    return undefined;
  }
}
