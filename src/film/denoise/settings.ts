import type { WavefrontDenoiserName } from './denoiser-name.ts';

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
