/**
 * How the primitive reader reports a fault in the asset: a JSON pointer (RFC 6901) into the asset's
 * JSON (`/meshes/2/primitives/0/attributes/NORMAL`) and a message, and the reporter throws. Each
 * caller keeps its own error contract: the path tracer's loader throws INVALID_GLTF with the
 * pointer, the animated-model reader INVALID_MODEL with the pointer as a dotted field.
 */
export type PrimitiveFault = (pointer: string, message: string) => never;

/** A JSON pointer as src/animation's dotted field: `/meshes/0/primitives/1/attributes/WEIGHTS_0/12` -> `meshes[0].primitives[1].attributes.WEIGHTS_0[12]`. */
export function pointerToDottedField(at: string): string {
  const segments = at.split('/').slice(1).map((s) => s.replaceAll('~1', '/').replaceAll('~0', '~'));
  return segments.reduce((out, s) => (/^\d+$/.test(s) ? `${out}[${s}]` : out === '' ? s : `${out}.${s}`), '');
}
