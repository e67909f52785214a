/**
 * The one interface every denoiser of the renderer implements. A denoiser works on a copy: it reads
 * the renderer's film (radiance sums and sample counts, the AOV sums, the moments) and writes
 * (rgb, 1) linear radiance per pixel to the renderer's `denoised` buffer, all on the GPU, encoded
 * into the renderer's own command encoder. A factory is prepared once per renderer (weights loaded,
 * pipelines compiled: the asynchronous part) and creates the denoiser once the renderer's buffers
 * exist. Implementations (registry.ts): 'oidn' (Open Image Denoise's U-Net, oidn-denoiser.ts) and
 * 'atrous' (the edge-avoiding à-trous preview, atrous-denoiser.ts).
 */
import type { ShaderFeatures } from '../../shaders/features.ts';
import type { DispatchCounter } from '../dispatch-counter.ts';
import type { WavefrontDenoiserName } from './denoiser-name.ts';
import type { WavefrontDenoiseOptions, WavefrontDenoiseSettings } from './settings.ts';

export type { WavefrontDenoiserName } from './denoiser-name.ts';

/** Counts the compute dispatches a denoiser encodes (the renderer's `gpuParallelism` statistics). */
export type DenoiserDispatchTally = DispatchCounter;

/** What a denoiser is created on: the renderer's device, image size and buffers by binding name. */
export interface WavefrontDenoiserTarget {
  device: GPUDevice;
  width: number;
  height: number;
  /**
   * The renderer's buffers by binding name; every denoiser may read `film`, `filmAovs` and
   * `filmMoments` (the FilmPixel, FilmAovPixel and FilmMoments records of gpu-layout/records.ts:
   * sums over each pixel's samples) and writes `denoised` (vec4f: rgb, 1).
   */
  resources: Readonly<Record<string, GPUBuffer | GPUTextureView>>;
  /** Allocates a buffer the renderer tracks (memory statistics) and releases on destroy. */
  createBuffer(label: string, size: number, usage: number): GPUBuffer;
}

export interface WavefrontDenoiser {
  readonly name: WavefrontDenoiserName;
  /** Encodes the denoise of the film as it is now into `encoder`. */
  encode(encoder: GPUCommandEncoder, tally: DenoiserDispatchTally | null): void;
  /** Releases what it allocated outside the target's createBuffer. */
  destroy(): void;
}

export interface WavefrontDenoiserFactory {
  readonly name: WavefrontDenoiserName;
  create(target: WavefrontDenoiserTarget): WavefrontDenoiser;
}

/** What the renderer knows of a denoiser before it runs: a row of the registry (registry.ts). */
export interface WavefrontDenoiserEntry {
  readonly name: WavefrontDenoiserName;
  /** The `denoise` options only this denoiser reads (giving one under 'auto' chooses it). */
  readonly optionNames: readonly (keyof WavefrontDenoiseOptions)[];
  /**
   * The film records it reads besides FilmPixel (FilmAovPixel: aovs, FilmMoments: moments); the
   * accumulation writes only what some reader needs.
   */
  readonly reads: { readonly aovs: boolean; readonly moments: boolean };
  /** Whether this device's limits run it ('auto' picks the first registry entry that does). */
  runsOn(device: GPUDevice): boolean;
  /**
   * The asynchronous part, once per renderer: loads and compiles what it needs and returns its
   * factory; may update `settings` to what runs (e.g. a precision of 'auto' becomes 'f16' or 'f32').
   */
  prepare(device: GPUDevice, settings: WavefrontDenoiseSettings, customWeights: Uint8Array | null, features: ShaderFeatures): Promise<WavefrontDenoiserFactory>;
}
