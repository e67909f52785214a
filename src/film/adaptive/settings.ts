/** Adaptive sampling's convergence test, resolved (Cycles' noise threshold and minimum samples). */
export interface WavefrontAdaptiveSettings {
  threshold: number;
  minimumSamplesPerPixel: number;
}

/** Most samples per pixel one renderFrame call takes, and the adaptive prediction's ceiling. */
export const maxSamplesPerFrame = 65536;
