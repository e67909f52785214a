/** Adaptive sampling's convergence test, resolved (Cycles' noise threshold and minimum samples). */
export interface WavefrontAdaptiveSettings {
  threshold: number;
  minimumSamplesPerPixel: number;
}
