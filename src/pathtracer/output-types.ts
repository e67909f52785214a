/**
 * Public types of the production-output surface: adaptive sampling, the denoiser,
 * presentation, progress events and the frame diagnostics hosts of the 0.2 API read.
 */
export type { WavefrontDenoiseOptions, WavefrontDenoiseSettings } from '../film/denoise/settings.ts';
export type { WavefrontAdaptiveSettings } from '../film/adaptive/settings.ts';
import type { WavefrontDenoiseSettings } from '../film/denoise/settings.ts';
import type { WavefrontAdaptiveSettings } from '../film/adaptive/settings.ts';
import type { TransportExperimentName, WavefrontFeatureFlagState, WavefrontTransportExperimentState } from './feature-flags.ts';

export type WavefrontPresentationOutput = 'tonemapped' | 'linear';

/** A progress event: after every group of sample passes of a frame, and at its end. */
export interface WavefrontRenderProgress {
  frame: number;
  /** Sample passes rendered in this frame so far (each gives every active pixel one sample). */
  samplesThisFrame: number;
  /** The frame's ceiling: samplesPerPixel of the call. */
  targetSamplesThisFrame: number;
  /** Most samples any pixel holds (every pixel without adaptive sampling). */
  samplesAccumulated: number;
  /** Pixels still sampling (all pixels without adaptive sampling). */
  activePixels: number;
  totalPixels: number;
  /** Milliseconds since renderFrame began. */
  elapsedMs: number;
  /**
   * Estimated milliseconds until the frame ends: the remaining passes at the measured pass time,
   * bounded by the frame budget; 0 when done.
   */
  estimatedRemainingMs: number;
  /** elapsedMs + estimatedRemainingMs. */
  estimatedTotalMs: number;
  /** Adaptive sampling: samples the active pixels still need by the 1/sqrt(n) error decay; null otherwise. */
  estimatedRemainingPixelSamples: number | null;
  done: boolean;
}

export type WavefrontProgressListener = (progress: WavefrontRenderProgress) => void;

export interface WavefrontAdaptiveFrameStats {
  threshold: number;
  minimumSamplesPerPixel: number;
  /** Pixels that still sample after this frame's last convergence test. */
  activePixels: number;
  convergedPixels: number;
  /** Pixel samples taken in this frame (camera paths). */
  pixelSamples: number;
  /** Mean samples per pixel in the accumulation. */
  meanSamplesPerPixel: number;
  /** Samples the active pixels still need by the 1/sqrt(n) decay of the error (see README). */
  estimatedRemainingPixelSamples: number;
}

/**
 * Where the frame's radiance came from, as mean luminance (Rec. 709) per pixel sample. Terminal
 * sources are emitter hits (camera and BSDF-sampled rays, MIS-weighted) and escaped paths (the
 * environment); next-event estimation is the rest. This renderer adds no ambient term, so the
 * ambient residual fields (kept for hosts of the 0.2 API) are always 0.
 */
export interface WavefrontTerminalRadiance {
  /** Every contribution: emitter + environment + directLight. */
  totalLuminance: number;
  emitterLuminance: number;
  environmentLuminance: number;
  /** Next-event estimation (shadow rays). */
  directLightLuminance: number;
  /** Always 0: no ambient term exists. */
  ambientResidualLuminance: 0;
  /** Always 0. */
  ambientResidualShare: 0;
  /** Pixel samples the means are over. */
  samples: number;
}

export interface WavefrontRadianceDiagnostics {
  /** Samples that lost at least one contribution as NaN, Inf or negative (counted once per sample). */
  invalidSamples: number;
  /** Contributions dropped as NaN, Inf or negative. */
  invalidContributions: number;
  /** Samples with a channel above 4: what the 0.2 API's legacy 4.0 clamp would have altered (nothing is clamped). */
  legacyClampEquivalentSamples: number;
}

export interface WavefrontGpuParallelism {
  adapterLimits: {
    maxComputeWorkgroupSizeX: number;
    maxComputeInvocationsPerWorkgroup: number;
    maxComputeWorkgroupsPerDimension: number;
    maxStorageBuffersPerShaderStage: number;
  };
  /** Invocations per workgroup of the 1-D wavefront kernels. */
  workgroupSize: number;
  /** WebGPU does not expose the GPU's core count. */
  physicalCoreCount: null;
  directDispatches: number;
  directWorkgroups: number;
  directInvocations: number;
  indirectDispatches: number;
  /** Upper bound: the queue capacity's workgroups per indirect dispatch (the GPU sizes them). */
  estimatedIndirectWorkgroups: number;
  largestDirectWorkgroupsPerDispatch: number;
  largestEstimatedIndirectWorkgroupsPerDispatch: number;
  exposesMultiWorkgroupParallelism: boolean;
}

export interface WavefrontTransportGuardrails {
  /** Waves (tile or list, one sample) rendered in the frame. */
  jobsPerFrame: number;
  jobsPerSecond: number;
  jobsPerSubmission: number;
  /** Command buffers submitted for the frame. */
  submissions: number;
  /** Always 0: every queue holds one entry per path of its wave, so none can overflow. */
  queueOverflow: number;
  radianceDiagnostics: WavefrontRadianceDiagnostics;
  trackedMemoryBytes: number;
  deviceLost: boolean;
}

/** Output state shared by frame stats and snapshots. */
export interface WavefrontOutputState {
  maxFramePassesPerSubmission: number;
  presentationOutput: WavefrontPresentationOutput;
  exposureEv: number;
  adaptiveSampling: WavefrontAdaptiveSettings | null;
  denoise: WavefrontDenoiseSettings | null;
  featureFlags: Readonly<Record<string, WavefrontFeatureFlagState>>;
  transportExperiments: Readonly<Record<TransportExperimentName, WavefrontTransportExperimentState>>;
  transportExperimentFlags: number;
  transportExperimentRequestedFlags: number;
}
