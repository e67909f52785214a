/**
 * The declarative description of one KHR material extension: the single place its glTF properties,
 * their ranges and defaults, its texture slots, when it changes the material, its GPU heap block
 * and how it is packed, its shader feature constant and flag bit, and whether the raster renderer
 * draws it are written down. Everything that handles material extensions (the glTF mapper and
 * validator, scene-file keys, material normalization, the heap packer, the generated WGSL, the
 * raster renderer) reads these entries instead of naming extensions itself.
 *
 * This module and the entries import only `errors/` and `gpu-layout/struct-layout.ts`: they are the
 * material schema, read by the scene and GPU-layout layers below the materials' physics.
 */
import type { StructLayout } from '../../gpu-layout/struct-layout.ts';
import type { NormalizedTextureRef } from '../../scene/texture-refs.ts';

/** A numeric range from the extension's JSON schema (exclusive bounds as `above`). */
export interface ValueRange {
  readonly min?: number;
  readonly max?: number;
  readonly above?: number;
}

/** One factor of the extension: a glTF property, equally the material input and scene-file key. */
export interface FactorSpec {
  /** The glTF property name in the extension object (also the WavefrontMaterialInput key). */
  readonly key: string;
  /** Its field in the normalized block. */
  readonly field: string;
  readonly type: 'number' | 'rgb';
  readonly default: number | readonly [number, number, number];
  /** The schema's range, checked on glTF files and on materials alike (every channel for rgb). */
  readonly range: ValueRange;
  /** Infinity is accepted as a value (the material input's "none", e.g. no absorption). */
  readonly infinity?: boolean;
  /** The @gltf-transform getter when it is not `get<Key>` (e.g. getIridescenceIOR). */
  readonly getter?: string;
  /** What the factor means, for the documentation. */
  readonly doc: string;
}

/** One texture slot of the extension (a glTF textureInfo property). */
export interface TextureSpec {
  /** The glTF property name (also the WavefrontMaterialInput key). */
  readonly key: string;
  /** Its field in the normalized block. */
  readonly field: string;
  /** Whether its RGB is sRGB colour (the extension's specification). */
  readonly srgb: boolean;
  /** A normal map's `scale` (its @gltf-transform getter), kept in the texture reference. */
  readonly scaleGetter?: string;
}

/** The precomputed tables of the materials heap (see pathtracer/scene/pack-materials.ts). */
export type MaterialTableName = 'ggx' | 'dielectric' | 'dielectricTransmission' | 'clearcoat' | 'sheen' | 'media' | 'spectral';

/** Binds a texture reference into the heap (TextureBinding offset or INDEX_NONE). */
export type BindTexture = (ref: NormalizedTextureRef | undefined, srgb: boolean) => number;

/** What the packer knows beyond one material's block. */
export interface PackContext {
  /** 1-based medium id of a refractive solid (KHR_materials_volume), if the material has one. */
  readonly medium: number | undefined;
}

/** The extension's GPU heap block: a record a MaterialCore points to. */
export interface BlockSpec<Block> {
  /** Its layout; `package::layout::heaps` gets `load_<snake name>(offset)` for it. */
  readonly layout: StructLayout;
  /** The block's field values for a material (texture slots bound through `bind`). */
  readonly pack: (block: Block, bind: BindTexture, context: PackContext) => Record<string, number | ArrayLike<number>>;
}

/**
 * A KHR material extension. `Block` is the normalized block the factors and textures make (see
 * NormalizedExtension).
 */
export interface MaterialExtensionSpec<Block = never> {
  /** The glTF extension name. */
  readonly name: string;
  /**
   * The NormalizedMaterial key of its block; also the MaterialCore field holding the block's heap
   * offset and the MaterialFeatureUses key.
   */
  readonly key: string;
  readonly factors: readonly FactorSpec[];
  readonly textures: readonly TextureSpec[];
  /** 'scalar': the normalized value is the one factor itself, not a block (KHR_materials_dispersion). */
  readonly normalized?: 'scalar';
  /**
   * Whether the validated block changes the material, so it is kept (absent blocks are simply not
   * there). `material` holds the extensions normalized before it, in registry order.
   */
  readonly present: (block: Block, material: Readonly<Record<string, unknown>>) => boolean;
  /** The factor that turns the extension on (named in errors that refuse the extension). */
  readonly enabledBy: string;
  /** The WGSL `override` constant compiling its code in (off when no material of a scene uses it). */
  readonly feature: { readonly name: `FEATURE_${string}`; readonly doc: string };
  /** Its MaterialCore.flags / SurfaceRecord.flags bit (`MATERIAL_FLAG_<flag>`), set when present. */
  readonly flag: { readonly name: `MATERIAL_FLAG_${string}`; readonly bit: number };
  /** Its heap block; none for an extension stored in MaterialCore itself (dispersion). */
  readonly block?: BlockSpec<Block>;
  /**
   * Whether a present extension reaches the GPU (its flag and block) in this context; default
   * always (volume and dispersion: only a solid with a medium).
   */
  readonly packed?: (context: PackContext) => boolean;
  /**
   * It adds or changes a rough microfacet lobe, so multiple-scattering energy compensation applies
   * to a material that has it.
   */
  readonly compensable: boolean;
  /** The material tables (MaterialTables entries) a scene using it needs. */
  readonly tables?: readonly MaterialTableName[];
  /** Whether the raster renderer draws it (as the Khronos sample viewer does) or refuses it. */
  readonly raster: 'drawn' | 'refused';
  /**
   * A layer over the base BSDF (as clearcoat and sheen are): its physics is `<folder>/layer.wesl`
   * (the material-layer interface) and `<folder>/reference.ts`'s `layerReference`. Layers stack in
   * registry order, outermost first; the composed BSDF's layering, the material stage's reads, the
   * surface record's words and the CPU reference's stack are generated from the entries
   * (scripts/shader-build/material-layers.ts).
   */
  readonly layer?: { readonly folder: string };
}

/** The data part of an extension (what its literal types are inferred from). */
type ExtensionShape = Omit<MaterialExtensionSpec<never>, 'present' | 'block' | 'packed'>;
/** The behaviour part, typed by the data part's normalized block. */
type ExtensionBehaviour<Block> = Pick<MaterialExtensionSpec<Block>, 'present' | 'block' | 'packed'>;

/**
 * Declares an extension: its data (literal types kept, so the material types follow from it), then
 * its behaviour, typed by the normalized block the data makes.
 */
export function defineMaterialExtension<const Spec extends ExtensionShape>(
  data: Spec,
  behaviour: ExtensionBehaviour<NormalizedExtension<Spec>>,
): Spec & ExtensionBehaviour<NormalizedExtension<Spec>> {
  return { ...data, ...behaviour };
}

type FactorValue<F> = F extends { type: 'rgb' } ? [number, number, number] : number;
type FactorInput<F> = F extends { type: 'rgb' } ? readonly [number, number, number] | readonly number[] : number;

/** The normalized block of an extension: its factors (defaults applied) and its bound textures. */
export type NormalizedExtension<Spec> = Spec extends { normalized: 'scalar'; factors: readonly [infer F] }
  ? FactorValue<F>
  : Spec extends { factors: readonly (infer F)[]; textures: readonly (infer T)[] }
    ? { [P in F as P extends { field: infer K extends string } ? K : never]: FactorValue<P> } & {
        [P in T as P extends { field: infer K extends string } ? K : never]?: NormalizedTextureRef;
      }
    : never;

/** The material input keys of an extension: its factors and textures under their glTF names. */
export type ExtensionInput<Spec, TextureRefInput> = Spec extends { factors: readonly (infer F)[]; textures: readonly (infer T)[] }
  ? { [P in F as P extends { key: infer K extends string } ? K : never]?: FactorInput<P> } & {
      [P in T as P extends { key: infer K extends string } ? K : never]?: TextureRefInput;
    }
  : never;
