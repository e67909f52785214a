/** The denoisers the renderer ships (registry.ts); below both the denoiser interface and its settings. */
export type WavefrontDenoiserName = 'oidn' | 'atrous';
