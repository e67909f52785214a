/**
 * The CPU reference of a KHR extension that is a layer over the glTF base BSDF: its layer.wesl in
 * double precision. The composed BSDF's reference (gltf-bsdf-reference.ts) stacks the registry's
 * layers in order (material-layers.generated.ts) by albedo scaling:
 * f = sum_k (prod_{j<k} s_j) f_k + (prod_j s_j) f_base.
 */
import type { Vec3 } from './reference/vector.ts';

/** The layer's physics, as its layer.wesl has it. `P`: its parameters at a hit. */
export interface MaterialLayerPhysics<P> {
  /** Its estimated albedo at wo in [0, 1]: its share of the lobe selection (1 - it goes below). */
  reflectance(p: P, wo: Vec3): number;
  /** Its lobe: f without the cosine, and the pdf of its own sampling. */
  evalPdf(p: P, wo: Vec3, wi: Vec3): { f: Vec3; pdf: number };
  /** The albedo scaling (>= 0) of everything below it. */
  scale(p: P, wo: Vec3, wi: Vec3): number;
  /** Its two vec4s of PackedLobeParams.layers (what its layer.wesl `unpack_params` reads). */
  pack(p: P): readonly number[];
  /** Parameters the composed-BSDF harness tests it with (test/materials/lobes.ts). */
  readonly examples: readonly { readonly name: string; readonly value: P }[];
}

export interface MaterialLayerReference<Key extends string, P> extends MaterialLayerPhysics<P> {
  /** The registry key: also the GltfBsdfMaterial field holding its parameters. */
  readonly key: Key;
  /** Its MATERIAL_FLAG_* value. */
  readonly flag: number;
  /** Its FEATURE_* override. */
  readonly feature: string;
}

/** The parameters of a layer reference. */
export type LayerParams<L> = L extends MaterialLayerReference<string, infer P> ? P : never;

/** A layer reference for the registry entry it belongs to. */
export function defineLayerReference<const Key extends string, P>(
  extension: { readonly key: Key; readonly flag: { readonly bit: number }; readonly feature: { readonly name: string } },
  physics: MaterialLayerPhysics<P>,
): MaterialLayerReference<Key, P> {
  return { ...physics, key: extension.key, flag: 1 << extension.flag.bit, feature: extension.feature.name };
}
