/**
 * The one interface every denoiser of the renderer implements. A denoiser works on a copy: it reads
 * the renderer's film (radiance sums and sample counts, the AOV sums, the moments) and writes
 * (rgb, 1) linear radiance per pixel to the renderer's `denoised` buffer, all on the GPU, encoded
 * into the renderer's own command encoder. A factory is prepared once per renderer (weights loaded,
 * pipelines compiled: the asynchronous part) and creates the denoiser once the renderer's buffers
 * exist. Implementations: 'oidn' (Open Image Denoise's U-Net, src/film/denoise/oidn) and 'atrous'
 * (the edge-avoiding à-trous preview, src/film/denoise/atrous-denoiser.ts).
 */

/** The denoisers the renderer ships. */
export type WavefrontDenoiserName = 'oidn' | 'atrous';

/** Counts the compute dispatches a denoiser encodes (the renderer's `gpuParallelism` statistics). */
export interface DenoiserDispatchTally {
  direct(workgroups: number, invocationsPerWorkgroup: number): void;
}

/** What a denoiser is created on: the renderer's device, image size and buffers by binding name. */
export interface WavefrontDenoiserTarget {
  device: GPUDevice;
  width: number;
  height: number;
  /**
   * The renderer's buffers by binding name; every denoiser may read `film` (vec4f: radiance sum,
   * sample count), `filmAovs` (3 vec4f per pixel: (albedo, depth), (normal, hits), (emission,
   * squared luminance) sums) and `filmMoments`, and writes `denoised` (vec4f: rgb, 1).
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
