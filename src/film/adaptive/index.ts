export {
  adaptiveConvergedMask,
  adaptiveSamplingError,
  defaultAdaptiveSamplingParameters,
  type AdaptiveConvergenceOptions,
  type AdaptiveConvergenceResult,
} from './converged-mask.ts';
export {
  createWavefrontAdaptiveSamplingLevels,
  type WavefrontAdaptiveSamplingLevel,
  type WavefrontAdaptiveSamplingLevelConfig,
  type WavefrontAdaptiveSamplingLevelOptions,
} from './sampling-levels.ts';
