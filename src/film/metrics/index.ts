export { meanSquaredError, rootMeanSquaredError, peakSignalToNoiseRatio, relativeMeanSquaredError } from './image-error.ts';
export { structuralSimilarity, ssimMap, ssimRgba8, rgba8Luma, ssimWindowSize, ssimWindowSigma, type GrayImage, type SsimOptions } from './ssim.ts';
export { displayPeakSignalToNoiseRatio, displayStructuralSimilarity } from './display.ts';
