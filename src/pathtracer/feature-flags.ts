/**
 * `featureFlags`: the rollout flags of the 0.2 API, accepted by their names so hosts written for
 * it keep working, and reported honestly. This renderer's transport is physically based and
 * unbiased by construction, so a flag asking for that is reported as requested and effective; a
 * flag that would turn it off (and add bias) is refused with `BIASED_TRANSPORT_REFUSED`; the Product
 * Studio transport experiments are either what this renderer always does (effective whatever was
 * requested) or no-ops (never effective), each with the reason. `transportExperimentFlags` packs the
 * effective experiments into a bitfield (bit i = the i-th entry of `transportExperimentNames`).
 */
import { fail } from '../errors/validate.ts';

/** The Product Studio transport experiments, in bit order. */
export const transportExperimentNames = Object.freeze({
  stableSampleRouting: 'renderer.transport.stableSampleRouting.enabled',
  strictZeroOverflow: 'renderer.transport.strictZeroOverflow.enabled',
  deferLowSppRussianRoulette: 'renderer.transport.deferLowSppRussianRoulette.enabled',
  deterministicDirectLighting: 'renderer.transport.deterministicDirectLighting.enabled',
  sourceStableDirectLighting: 'renderer.transport.sourceStableDirectLighting.enabled',
  deterministicLowSppIndirect: 'renderer.transport.deterministicLowSppIndirect.enabled',
  productStudioImportance: 'renderer.environment.productStudioImportance.enabled',
  productTransportTelemetry: 'renderer.diagnostics.productTransportTelemetry.enabled',
} as const);

export type TransportExperimentName = keyof typeof transportExperimentNames;

/** What each experiment is here: `always` (effective whatever is requested) or `noop` (never effective). */
export const transportExperimentBehaviour: Readonly<Record<TransportExperimentName, { kind: 'always' | 'noop'; reason: string }>> = Object.freeze({
  stableSampleRouting: { kind: 'always', reason: 'every sample dimension is keyed by (seed, pixel, sample index, dimension), independent of tiles, waves and frames' },
  strictZeroOverflow: { kind: 'always', reason: 'every queue holds one entry per path of the wave, so no queue can overflow' },
  deferLowSppRussianRoulette: { kind: 'noop', reason: 'Russian roulette starts at a fixed depth; it reweights survivors, so it adds no bias at any spp' },
  deterministicDirectLighting: { kind: 'noop', reason: 'direct light is estimated by stochastic next-event estimation with MIS; a deterministic estimator is not implemented' },
  sourceStableDirectLighting: { kind: 'noop', reason: 'depends on deterministic direct lighting, which is not implemented' },
  deterministicLowSppIndirect: { kind: 'noop', reason: 'would inject cached indirect radiance (bias); indirect light comes from BSDF continuation only' },
  productStudioImportance: { kind: 'noop', reason: 'environment importance sampling belongs to the lighting subsystem, not to this flag' },
  productTransportTelemetry: { kind: 'always', reason: 'terminal radiance, radiance diagnostics and termination counters are always reported' },
});

/** Flags asking for the physically based transport itself; `false` would mean a biased fallback. */
export const physicalTransportFlagNames = Object.freeze([
  'renderer.transport.physicalEstimator',
  'renderer.transport.strictPhysicalLowSppLighting',
] as const);

/** Denoising is only ever the explicit `denoise` option; `readRadiance()` always returns the raw estimate. */
export const denoiseIndependenceFlagName = 'renderer.denoise.highSppIndependence';

export interface WavefrontFeatureFlagState {
  /** The value passed, or null when the flag was not given. */
  requested: boolean | null;
  effective: boolean;
  reason: string;
}

export interface WavefrontTransportExperimentState {
  requested: boolean;
  effective: boolean;
}

export interface WavefrontFeatureFlagResolution {
  /** Every known flag by its 0.2 API name. */
  featureFlags: Readonly<Record<string, WavefrontFeatureFlagState>>;
  transportExperiments: Readonly<Record<TransportExperimentName, WavefrontTransportExperimentState>>;
  /** Effective experiments, bit i = entry i of transportExperimentNames. */
  transportExperimentFlags: number;
  /** Requested experiments, same bit order. */
  transportExperimentRequestedFlags: number;
}

/** Every flag name `featureFlags` accepts. */
export const featureFlagNames: readonly string[] = Object.freeze([...physicalTransportFlagNames, denoiseIndependenceFlagName, ...Object.values(transportExperimentNames)]);

/** Validates `featureFlags` (an object of booleans by 0.2 API name) and resolves every flag's state. */
export function resolveFeatureFlags(input: unknown): WavefrontFeatureFlagResolution {
  const given: Record<string, boolean> = {};
  if (input !== undefined) {
    if (typeof input !== 'object' || input === null || Array.isArray(input)) fail('INVALID_OPTION', 'featureFlags', 'expected an object of boolean flags by name');
    for (const [name, value] of Object.entries(input)) {
      const field = `featureFlags[${JSON.stringify(name)}]`;
      if (!featureFlagNames.includes(name)) fail('INVALID_OPTION', field, `unknown feature flag (expected one of ${featureFlagNames.join(', ')})`);
      if (typeof value !== 'boolean') fail('INVALID_OPTION', field, 'expected a boolean');
      if (value === false && (physicalTransportFlagNames as readonly string[]).includes(name)) {
        fail('BIASED_TRANSPORT_REFUSED', field, 'this renderer only has the physically based, unbiased transport; turning it off would add bias');
      }
      given[name] = value;
    }
  }
  const featureFlags: Record<string, WavefrontFeatureFlagState> = {};
  for (const name of physicalTransportFlagNames) {
    featureFlags[name] = { requested: given[name] ?? null, effective: true, reason: 'the transport is always physically based: MIS next-event estimation, no ambient, rescue or clamp terms' };
  }
  featureFlags[denoiseIndependenceFlagName] = {
    requested: given[denoiseIndependenceFlagName] ?? null,
    effective: true,
    reason: 'denoising runs only with the denoise option, on a copy; readRadiance() is always the raw estimate',
  };
  const transportExperiments = {} as Record<TransportExperimentName, WavefrontTransportExperimentState>;
  let transportExperimentFlags = 0;
  let transportExperimentRequestedFlags = 0;
  (Object.keys(transportExperimentNames) as TransportExperimentName[]).forEach((key, bit) => {
    const name = transportExperimentNames[key];
    const behaviour = transportExperimentBehaviour[key];
    const requested = given[name] ?? false;
    const effective = behaviour.kind === 'always';
    transportExperiments[key] = Object.freeze({ requested, effective });
    featureFlags[name] = { requested: given[name] ?? null, effective, reason: behaviour.reason };
    if (effective) transportExperimentFlags |= 1 << bit;
    if (requested) transportExperimentRequestedFlags |= 1 << bit;
  });
  for (const state of Object.values(featureFlags)) Object.freeze(state);
  return Object.freeze({
    featureFlags: Object.freeze(featureFlags),
    transportExperiments: Object.freeze(transportExperiments),
    transportExperimentFlags,
    transportExperimentRequestedFlags,
  });
}
