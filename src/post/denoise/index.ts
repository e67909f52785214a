export { denoiseAtrousReference, demodulationMinAlbedo, unknownVariance, type AtrousDenoiseInput, type AtrousDenoiseSettings } from './atrous-reference.ts';
