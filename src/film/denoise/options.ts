/**
 * The `denoise` option: its defaults and its parser. Which options exist, and which denoiser each
 * belongs to, comes from the registry (registry.ts).
 */
import { fail, requireFiniteNumber, requireInteger, requireNumberInRange } from '../../errors/validate.ts';
import type { WavefrontDenoiserName } from './denoiser.ts';
import { wavefrontDenoisers } from './registry.ts';
import type { WavefrontDenoiseSettings } from './settings.ts';

function isDenoiserName(value: string): value is WavefrontDenoiserName {
  return Object.hasOwn(wavefrontDenoisers, value);
}

export const defaultDenoiseSettings: Readonly<WavefrontDenoiseSettings> = Object.freeze({
  denoiser: 'auto',
  present: 'denoised',
  iterations: 5,
  // SVGF uses 4 with temporally accumulated 1-spp variance; with every sample's moments in the film,
  // 2 measured better from 16 spp up and the same at 4 spp (README, Performance).
  sigmaLuminance: 2,
  sigmaNormal: 128,
  sigmaDepth: 1,
  auxiliary: true,
  precision: 'auto',
  emission: 'exact',
  maxMemoryMB: 1024,
  weights: 'rt_hdr_alb_nrm',
});

/**
 * Parses the renderer's `denoise` option (true, false, a denoiser's name or an options object) into
 * settings with every default; the bytes of user weights come back apart. An option that only one
 * denoiser reads (its registry entry's optionNames) picks that denoiser under 'auto'; options of two
 * denoisers together are an error.
 */
export function parseDenoiseOptions(value: unknown): { settings: WavefrontDenoiseSettings; weights: Uint8Array | null } | null {
  if (value === undefined || value === false) return null;
  const d = defaultDenoiseSettings;
  if (value === true) return { settings: { ...d }, weights: null };
  const entries = Object.values(wavefrontDenoisers);
  const quoted = entries.map((e) => `'${e.name}'`).join(', ');
  if (typeof value === 'string' && isDenoiserName(value)) return { settings: { ...d, denoiser: value }, weights: null };
  if (typeof value !== 'object' || value === null || Array.isArray(value)) fail('INVALID_OPTION', 'denoise', `expected true, false, ${quoted} or an options object, got ${JSON.stringify(value)}`);
  const o = value as Record<string, unknown>;
  const known: string[] = ['denoiser', 'present', ...entries.flatMap((e) => e.optionNames)];
  for (const key of Object.keys(o)) if (!known.includes(key)) fail('INVALID_OPTION', `denoise.${key}`, `unknown denoise option (expected ${known.join(', ')})`);
  const given = (names: readonly string[]) => names.filter((k) => o[k] !== undefined);
  const asking = entries.map((e) => ({ name: e.name, given: given(e.optionNames) })).filter((e) => e.given.length > 0);
  const denoiserValue = o.denoiser ?? d.denoiser;
  if (denoiserValue !== 'auto' && !(typeof denoiserValue === 'string' && isDenoiserName(denoiserValue))) fail('INVALID_OPTION', 'denoise.denoiser', `expected ${quoted} or 'auto', got ${JSON.stringify(denoiserValue)}`);
  let denoiser: WavefrontDenoiseSettings['denoiser'] = denoiserValue;
  const [first, second] = asking;
  if (first && second) fail('INVALID_OPTION', `denoise.${first.given[0]}`, `applies to the '${first.name}' denoiser, but ${second.given[0]} asks for '${second.name}'`);
  if (denoiser === 'auto' && first) denoiser = first.name;
  const wrong = denoiser === 'auto' ? [] : asking.filter((e) => e.name !== denoiser).flatMap((e) => e.given);
  if (wrong.length > 0) fail('INVALID_OPTION', `denoise.${wrong[0]}`, `does not apply to the '${String(denoiser)}' denoiser`);
  const present = o.present ?? d.present;
  if (present !== 'denoised' && present !== 'raw') fail('INVALID_OPTION', 'denoise.present', `expected 'denoised' or 'raw', got ${JSON.stringify(present)}`);
  const positive = (key: string, fallback: number): number => {
    const v = o[key] === undefined ? fallback : requireFiniteNumber(o[key], `denoise.${key}`);
    if (!(v > 0)) fail('INVALID_OPTION', `denoise.${key}`, `must be > 0, got ${v}`);
    return v;
  };
  if (o.auxiliary !== undefined && typeof o.auxiliary !== 'boolean') fail('INVALID_OPTION', 'denoise.auxiliary', `expected a boolean, got ${JSON.stringify(o.auxiliary)}`);
  const precision = o.precision ?? d.precision;
  if (precision !== 'auto' && precision !== 'f16' && precision !== 'f32') fail('INVALID_OPTION', 'denoise.precision', `expected 'auto', 'f16' or 'f32', got ${JSON.stringify(precision)}`);
  const emission = o.emission ?? d.emission;
  if (emission !== 'exact' && emission !== 'network') fail('INVALID_OPTION', 'denoise.emission', `expected 'exact' or 'network', got ${JSON.stringify(emission)}`);
  let weights: Uint8Array | null = null;
  if (o.weights !== undefined) {
    if (o.weights instanceof ArrayBuffer) weights = new Uint8Array(o.weights.slice(0));
    else if (ArrayBuffer.isView(o.weights)) weights = new Uint8Array(o.weights.buffer.slice(o.weights.byteOffset, o.weights.byteOffset + o.weights.byteLength));
    else fail('INVALID_OPTION', 'denoise.weights', 'expected the bytes of an OIDN .tza file (ArrayBuffer or typed array)');
    if (o.auxiliary !== undefined) fail('INVALID_OPTION', 'denoise.auxiliary', 'the weights decide the inputs: give either weights or auxiliary');
  }
  const auxiliary = (o.auxiliary as boolean | undefined) ?? d.auxiliary;
  return {
    settings: {
      denoiser,
      present,
      iterations: o.iterations === undefined ? d.iterations : requireInteger(o.iterations, 'denoise.iterations', { min: 1, max: 8 }),
      sigmaLuminance: positive('sigmaLuminance', d.sigmaLuminance),
      sigmaNormal: o.sigmaNormal === undefined ? d.sigmaNormal : requireNumberInRange(o.sigmaNormal, 'denoise.sigmaNormal', { min: 0, max: 1024 }),
      sigmaDepth: positive('sigmaDepth', d.sigmaDepth),
      auxiliary,
      precision,
      emission,
      maxMemoryMB: o.maxMemoryMB === undefined ? d.maxMemoryMB : requireNumberInRange(o.maxMemoryMB, 'denoise.maxMemoryMB', { min: 16, max: 1 << 20 }),
      weights: weights ? 'custom' : auxiliary ? 'rt_hdr_alb_nrm' : 'rt_hdr',
    },
    weights,
  };
}
