/**
 * The OIDN weights the package ships (weights/oidn: Open Image Denoise's `RT` filter for HDR
 * colour, Apache-2.0), loaded on first use through a dynamic import, so bundles fetch them only when
 * the network runs; and user weights (any OIDN `.tza` of an HDR `RT` model, e.g. the large or
 * clean-auxiliary variants).
 */
import { GpuRendererError } from '../../../errors/gpu-renderer-error.ts';
import { parseTza } from './tza.ts';
import { oidnWeightParts } from './weight-modules.generated.ts';
import { unetFromTensors, type UNetModel } from './unet.ts';

/** Built-in weights: colour + albedo + normal (the default), or colour alone. */
export type OidnBuiltinWeights = 'rt_hdr_alb_nrm' | 'rt_hdr';

function decodeBase64(text: string): Uint8Array {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

const cache = new Map<OidnBuiltinWeights, Promise<UNetModel>>();

/** The network of built-in weights (parsed once per process). */
export function loadOidnModel(name: OidnBuiltinWeights): Promise<UNetModel> {
  let model = cache.get(name);
  if (!model) {
    // The modules sit in the package's weights/oidn, reached through its subpath imports
    // ("#oidn-weights/*" in package.json), which Node (ESM and CommonJS) and bundlers resolve
    // alike, from the sources and from every build: one copy in the package, in parts small
    // enough for bundlers' chunk-size limits.
    const parts = oidnWeightParts[name];
    if (!parts) return Promise.reject(new GpuRendererError('INVALID_OPTION', `unknown built-in OIDN weights ${JSON.stringify(name)} (${Object.keys(oidnWeightParts).join(', ')})`, { field: 'denoise.weights' }));
    model = Promise.all(parts.map((load) => load())).then((modules) => unetFromTensors(parseTza(decodeBase64(modules.map((m) => m.part).join('')), 'denoise.weights')));
    model.catch(() => cache.delete(name));
    cache.set(name, model);
  }
  return model;
}

/** The network of user weights: the bytes of an OIDN `.tza` file. */
export function oidnModelFromBytes(bytes: ArrayBuffer | ArrayBufferView, field = 'denoise.weights'): UNetModel {
  return unetFromTensors(parseTza(bytes, field), field);
}
