/**
 * Public types of the production-output surface: adaptive sampling, the denoiser,
 * presentation, progress events and the frame diagnostics hosts of the 0.2 API read.
 */
import type { WavefrontDenoiserName } from '../post/denoise/denoiser.ts';
import type { TransportExperimentName, WavefrontFeatureFlagState, WavefrontTransportExperimentState } from './feature-flags.ts';

/**
 * Options of the denoiser (`denoise: true`, `'oidn'` or `'atrous'` take every default). The
 * à-trous options imply `denoiser: 'atrous'`, the OIDN options `denoiser: 'oidn'`; mixing them is
 * an error.
 */
export interface WavefrontDenoiseOptions {
  /**
   * 'oidn': Open Image Denoise's U-Net on the GPU (production quality); 'atrous': the edge-avoiding
   * à-trous filter (a fast preview); 'auto' (default): the better one the device runs ('oidn' on any
   * WebGPU device that meets the core limits).
   */
  denoiser?: WavefrontDenoiserName | 'auto';
  /** What readPixels and the canvas show: 'denoised' (default) or 'raw'. */
  present?: 'denoised' | 'raw';
  /** A-trous passes, taps 1, 2, 4, ... pixels apart; 1..8, default 5 (a 125-pixel footprint). */
  iterations?: number;
  /** Luminance edge-stopping in standard deviations of the pixel noise (SVGF sigma_l); > 0, default 2. */
  sigmaLuminance?: number;
  /** Normal edge-stopping exponent (SVGF sigma_n); >= 0, default 128. */
  sigmaNormal?: number;
  /** Depth edge-stopping in depth-gradient units (SVGF sigma_z); > 0, default 1. */
  sigmaDepth?: number;
  /** OIDN: guide the network with the albedo and normal AOVs (weights rt_hdr_alb_nrm; default true) or not (rt_hdr). */
  auxiliary?: boolean;
  /** OIDN: 'f16' (needs the device feature shader-f16), 'f32', or 'auto' (default: f16 where the device has it). */
  precision?: 'auto' | 'f16' | 'f32';
  /**
   * OIDN: 'exact' (default): the emission seen at the first non-specular hit (emitters seen directly
   * or through mirrors: exact, noise-free but for anti-aliasing) bypasses the network and is added
   * back unchanged, so the network neither blurs nor brightens bright emitters' edges; 'network':
   * the network denoises the whole beauty, as OIDN's own API does.
   */
  emission?: 'exact' | 'network';
  /** OIDN: memory budget of the network's tensors in MiB (tiles shrink to fit); default 1024. */
  maxMemoryMB?: number;
  /** OIDN: your own weights, the bytes of an OIDN `.tza` of an HDR `RT` model (e.g. rt_hdr_calb_cnrm_large). */
  weights?: ArrayBuffer | ArrayBufferView;
}

/** The denoiser a renderer runs, with every option resolved ('auto' only before the renderer exists). */
export interface WavefrontDenoiseSettings {
  denoiser: WavefrontDenoiserName | 'auto';
  present: 'denoised' | 'raw';
  /** A-trous settings (used when denoiser is 'atrous'). */
  iterations: number;
  sigmaLuminance: number;
  sigmaNormal: number;
  sigmaDepth: number;
  /** OIDN settings (used when denoiser is 'oidn'). */
  auxiliary: boolean;
  precision: 'auto' | 'f16' | 'f32';
  emission: 'exact' | 'network';
  maxMemoryMB: number;
  /** The OIDN weights: 'rt_hdr_alb_nrm', 'rt_hdr' or 'custom' (given as `weights`). */
  weights: string;
}

export interface WavefrontAdaptiveSettings {
  threshold: number;
  minimumSamplesPerPixel: number;
}

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
