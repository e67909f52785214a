/**
 * What a glTF asset will make the reader allocate, charged to the load's budget before
 * @gltf-transform or a decoder allocates it:
 * - every accessor becomes a dense typed array of count x element size, whether or not it has a
 *   bufferView (glTF 2.0 section 3.6.2.3: an accessor without one is zeros, plus sparse values), and
 *   several accessors may view the same bytes;
 * - an EXT_meshopt_compression view decodes to its declared byteLength;
 * - every image decodes to the texels its header claims (../image-headers.ts), checked against the
 *   policy's largest side.
 */
import { accessorElementSize, isObject } from './json-validation.ts';
import { pointer } from './errors.ts';
import { checkImageHeader } from '../image-headers.ts';
import type { DecodeBudget, ResolvedResourcePolicy } from '../resource-policy.ts';

type Json = Record<string, unknown>;

const list = (json: Json, key: string): Json[] => (Array.isArray(json[key]) ? (json[key] as Json[]) : []);

const COMPONENTS: Readonly<Record<string, number>> = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT2: 4, MAT3: 9, MAT4: 16 };

/**
 * Charges accessor arrays (the reader's array and the loader's float32 or uint32 copy) and meshopt
 * views (the JSON was validated: counts and types are sound).
 */
export function chargeGeometry(json: Json, budget: DecodeBudget): void {
  list(json, 'accessors').forEach((accessor, i) => {
    const count = accessor.count as number;
    const bytes = count * (accessorElementSize(accessor.componentType as number, accessor.type as string) + 4 * COMPONENTS[accessor.type as string]!);
    budget.charge(bytes, { code: 'INVALID_GLTF', field: pointer('accessors', i, 'count') }, `accessor ${i}'s ${count} ${String(accessor.type)} elements`);
  });
  list(json, 'bufferViews').forEach((view, i) => {
    const meshopt = isObject(view.extensions) ? view.extensions.EXT_meshopt_compression : undefined;
    if (!isObject(meshopt)) return;
    budget.charge(view.byteLength as number, { code: 'INVALID_GLTF', field: pointer('bufferViews', i, 'byteLength') }, `decompressing bufferView ${i}`);
  });
}

/**
 * Checks every image's header (side limits) and charges its texels; `buffers` are the buffers'
 * bytes by index and `external` the bytes of `uri` images by URI.
 */
export function chargeImages(json: Json, buffers: ReadonlyArray<Uint8Array | undefined>, external: Readonly<Record<string, Uint8Array>>, policy: ResolvedResourcePolicy, budget: DecodeBudget): void {
  const views = list(json, 'bufferViews');
  list(json, 'images').forEach((image, i) => {
    let bytes: Uint8Array | undefined;
    if (typeof image.bufferView === 'number') {
      const view = views[image.bufferView]!;
      const buffer = buffers[view.buffer as number];
      const offset = (view.byteOffset as number | undefined) ?? 0;
      if (buffer !== undefined) bytes = buffer.subarray(offset, offset + (view.byteLength as number));
    } else if (typeof image.uri === 'string') {
      bytes = external[image.uri];
    }
    if (bytes !== undefined) checkImageHeader(bytes, { code: 'INVALID_GLTF', field: pointer('images', i) }, policy, budget);
  });
}
