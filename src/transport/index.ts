export { createMediumStack, isMediumStack, mediumStackLimit, noMediumId, type MediumStack, type MediumStackTransition } from './medium-stack.ts';
export { dielectricInterface, fresnelDielectric, type DielectricInterface } from './fresnel.ts';
export { createTransportBranches, type TransportBranch, type TransportBranches, type TransportBranchOptions } from './transport-branches.ts';
export {
  createSpectralSamples,
  dispersiveIor,
  abbeNumberFromDispersion,
  fraunhoferLinesNm,
  visibleWavelengthRangeNm,
  type SpectralSample,
  type SpectralSampleOptions,
} from './spectral-samples.ts';
export { beerLambertTransmittance } from './beer-lambert.ts';
