/**
 * The glTF loader's view of the resource policy (../resource-policy.ts): the asset's external
 * resources (glTF 2.0 section 3.1 "URIs": relative URIs resolve against the asset's own location;
 * data URIs carry their bytes inline) are read under the caller's policy, and faults are
 * INVALID_GLTF errors at the JSON pointer of the buffer or image that names them.
 */
import { readReference, type ResolvedResourcePolicy } from '../resource-policy.ts';

/** Reads a resource the asset at `base` names by `uri` (undefined `base`: the asset was bytes). */
export function readResource(uri: string, base: URL | undefined, field: string, policy: ResolvedResourcePolicy, signal: AbortSignal | undefined): Promise<Uint8Array> {
  return readReference(uri, base, policy, { code: 'INVALID_GLTF', field }, signal);
}
