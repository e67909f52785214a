/**
 * Typed errors of the glTF loader: code `INVALID_GLTF`, `field` a JSON pointer (RFC 6901) into the
 * asset's JSON (`/meshes/3/primitives/0/attributes/POSITION`), or `glb:` followed by a pointer-like
 * path into the GLB container (`glb:/header/magic`, `glb:/chunks/1/chunkType`) for container faults,
 * or `''` (the whole document) where no narrower place exists.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';

export function gltfError(field: string, message: string, cause?: unknown): GpuRendererError {
  return new GpuRendererError('INVALID_GLTF', message, cause === undefined ? { field } : { field, cause });
}

export function failGltf(field: string, message: string, cause?: unknown): never {
  throw gltfError(field, message, cause);
}

/** Joins JSON pointer segments, escaping `~` and `/` as RFC 6901 section 3 requires. */
export function pointer(...segments: ReadonlyArray<string | number>): string {
  return segments.map((s) => `/${String(s).replaceAll('~', '~0').replaceAll('/', '~1')}`).join('');
}

/**
 * src/animation's dotted fields as JSON pointers: `meshes[0].primitives[1].attributes.JOINTS_0[12]`
 * -> `/meshes/0/primitives/1/attributes/JOINTS_0/12` (the other way: primitive/primitive-fault.ts).
 */
export function dottedFieldToPointer(field: string): string {
  const segments = field.replace(/\[(\d+)\]/g, '.$1').split('.').filter((s) => s !== '');
  return pointer(...segments);
}
