/**
 * Sparse accessor indices (glTF 2.0 section 3.6.2.3): every index must be below the accessor's
 * count and the indices must strictly increase. Readers write the substituted values at those
 * indices, so an index out of range would be dropped silently (a typed array ignores the write)
 * and the accessor would keep values the asset meant to replace; this check needs the buffers'
 * bytes, so it runs once they are loaded. Indices in meshopt-compressed buffer views are left to
 * the decoder.
 */
import { failGltf, pointer } from './errors.ts';
import { isObject } from './json-validation.ts';

type Json = Record<string, unknown>;

const READERS: Readonly<Record<number, { size: number; read: (view: DataView, at: number) => number }>> = {
  5121: { size: 1, read: (v, at) => v.getUint8(at) },
  5123: { size: 2, read: (v, at) => v.getUint16(at, true) },
  5125: { size: 4, read: (v, at) => v.getUint32(at, true) },
};

export function validateSparseIndices(json: Json, buffers: ReadonlyArray<Uint8Array | undefined>): void {
  const accessors = Array.isArray(json.accessors) ? (json.accessors as Json[]) : [];
  const views = Array.isArray(json.bufferViews) ? (json.bufferViews as Json[]) : [];
  accessors.forEach((accessor, a) => {
    if (!isObject(accessor.sparse)) return;
    const sparse = accessor.sparse;
    const indices = sparse.indices as Json;
    const view = views[indices.bufferView as number];
    if (isObject(view.extensions) && view.extensions.EXT_meshopt_compression !== undefined) return;
    const data = buffers[view.buffer as number];
    if (data === undefined) return;
    const reader = READERS[indices.componentType as number];
    const start = data.byteOffset + ((view.byteOffset as number | undefined) ?? 0) + ((indices.byteOffset as number | undefined) ?? 0);
    const bytes = new DataView(data.buffer, start, (sparse.count as number) * reader.size);
    const count = accessor.count as number;
    let previous = -1;
    for (let i = 0; i < (sparse.count as number); i++) {
      const index = reader.read(bytes, i * reader.size);
      const at = pointer('accessors', a, 'sparse', 'indices');
      if (index >= count) failGltf(at, `sparse index ${i} is ${index}, the accessor has ${count} elements`);
      if (index <= previous) failGltf(at, `sparse index ${i} is ${index}, after ${previous}: sparse indices must strictly increase`);
      previous = index;
    }
  });
}
