/**
 * The KHR material extensions the renderer implements, in the order they are normalized (an
 * extension may depend on those before it: volume on transmission, dispersion on volume). Adding
 * one is adding its folder and a line here; docs/material-extensions.md has the checklist.
 */
import type { WavefrontTextureRefInput } from '../../scene/texture-refs.ts';
import { anisotropy } from './anisotropy/extension.ts';
import { clearcoat } from './clearcoat/extension.ts';
import { diffuseTransmission } from './diffuse-transmission/extension.ts';
import { dispersion } from './dispersion/extension.ts';
import { iridescence } from './iridescence/extension.ts';
import type { ExtensionInput, MaterialExtensionSpec, NormalizedExtension } from './material-extension.ts';
import { sheen } from './sheen/extension.ts';
import { specular } from './specular/extension.ts';
import { transmission } from './transmission/extension.ts';
import { volume } from './volume/extension.ts';

export const materialExtensions = [specular, transmission, diffuseTransmission, volume, dispersion, clearcoat, sheen, iridescence, anisotropy] as const;

export type MaterialExtension = (typeof materialExtensions)[number];
export type MaterialExtensionKey = MaterialExtension['key'];

/** Every extension, loosely typed, for code that handles them all alike. */
export const anyMaterialExtensions: readonly MaterialExtensionSpec<never>[] = materialExtensions as readonly MaterialExtensionSpec<never>[];

/** The normalized extension blocks of a material (NormalizedMaterial's extension keys). */
export type NormalizedMaterialExtensions = { [E in MaterialExtension as E['key']]?: NormalizedExtension<E> };

/** The material input keys of every extension (WavefrontMaterialInput's extension keys). */
export type MaterialExtensionInputs = UnionToIntersection<ExtensionInput<MaterialExtension, WavefrontTextureRefInput>>;

type UnionToIntersection<U> = (U extends unknown ? (x: U) => void : never) extends (x: infer I) => void ? I : never;

export { absorptionCoefficient } from './volume/absorption.ts';
export type { BindTexture, FactorSpec, MaterialExtensionSpec, NormalizedExtension, PackContext, TextureSpec, ValueRange } from './material-extension.ts';
export { anisotropy, clearcoat, diffuseTransmission, dispersion, iridescence, sheen, specular, transmission, volume };
