/**
 * glTF sampler state (glTF 2.0 section 5.26, named instead of GL enums) resolved to the
 * TextureInfo.sampler bit fields that texture-sampling.wesl reads.
 */
import { fail } from '../../errors/validate.ts';
import {
  SAMPLER_MAG_LINEAR,
  SAMPLER_MIN_LINEAR,
  SAMPLER_MIP_LINEAR,
  SAMPLER_MIPMAPS,
  SAMPLER_WRAP_CLAMP,
  SAMPLER_WRAP_MIRROR,
  SAMPLER_WRAP_REPEAT,
  SAMPLER_WRAP_S_SHIFT,
  SAMPLER_WRAP_T_SHIFT,
} from '../../gpu-layout/constants.ts';
import type { WavefrontMagFilter, WavefrontMinFilter, WavefrontSamplerInput, WavefrontWrapMode } from '../../scene/types.ts';

export interface ResolvedSampler {
  readonly wrapS: WavefrontWrapMode;
  readonly wrapT: WavefrontWrapMode;
  readonly magFilter: WavefrontMagFilter;
  readonly minFilter: WavefrontMinFilter;
}

const wrapBits: Readonly<Record<WavefrontWrapMode, number>> = {
  repeat: SAMPLER_WRAP_REPEAT,
  'clamp-to-edge': SAMPLER_WRAP_CLAMP,
  'mirrored-repeat': SAMPLER_WRAP_MIRROR,
};

const magBits: Readonly<Record<WavefrontMagFilter, number>> = { nearest: 0, linear: SAMPLER_MAG_LINEAR };

/** 'nearest' and 'linear' minify from level 0 only (GL semantics); the mipmap modes name the filter within a level, then across levels. */
const minBits: Readonly<Record<WavefrontMinFilter, number>> = {
  nearest: 0,
  linear: SAMPLER_MIN_LINEAR,
  'nearest-mipmap-nearest': SAMPLER_MIPMAPS,
  'linear-mipmap-nearest': SAMPLER_MIN_LINEAR | SAMPLER_MIPMAPS,
  'nearest-mipmap-linear': SAMPLER_MIPMAPS | SAMPLER_MIP_LINEAR,
  'linear-mipmap-linear': SAMPLER_MIN_LINEAR | SAMPLER_MIPMAPS | SAMPLER_MIP_LINEAR,
};

/** The glTF defaults the scene types document: repeat, linear magnification, trilinear minification. */
export const defaultSampler: ResolvedSampler = Object.freeze({
  wrapS: 'repeat',
  wrapT: 'repeat',
  magFilter: 'linear',
  minFilter: 'linear-mipmap-linear',
});

function pick<T extends string>(value: unknown, names: Readonly<Record<T, number>>, fallback: T, field: string): T {
  if (value === undefined) return fallback;
  if (typeof value === 'string' && Object.hasOwn(names, value)) return value as T;
  const allowed = Object.keys(names).map((n) => `'${n}'`).join(', ');
  return fail('INVALID_TEXTURE', field, `expected one of ${allowed}, got ${JSON.stringify(value) ?? String(value)}`);
}

/** Validates a sampler (undefined fields take the glTF defaults); `field` names it in errors. */
export function resolveSampler(input: WavefrontSamplerInput | undefined, field: string): ResolvedSampler {
  if (input === undefined) return defaultSampler;
  if (input === null || typeof input !== 'object') fail('INVALID_TEXTURE', field, 'expected a sampler object');
  return {
    wrapS: pick(input.wrapS, wrapBits, defaultSampler.wrapS, `${field}.wrapS`),
    wrapT: pick(input.wrapT, wrapBits, defaultSampler.wrapT, `${field}.wrapT`),
    magFilter: pick(input.magFilter, magBits, defaultSampler.magFilter, `${field}.magFilter`),
    minFilter: pick(input.minFilter, minBits, defaultSampler.minFilter, `${field}.minFilter`),
  };
}

/** The TextureInfo.sampler word of a resolved sampler. */
export function samplerBits(s: ResolvedSampler): number {
  return (wrapBits[s.wrapS] << SAMPLER_WRAP_S_SHIFT) | (wrapBits[s.wrapT] << SAMPLER_WRAP_T_SHIFT) | magBits[s.magFilter] | minBits[s.minFilter];
}

/** Whether minification reads mip levels at all (so the texture's block needs its mip chain). */
export function samplerUsesMipmaps(s: ResolvedSampler): boolean {
  return (minBits[s.minFilter] & SAMPLER_MIPMAPS) !== 0;
}
