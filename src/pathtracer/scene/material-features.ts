import type { ShaderFeatures } from '../../shaders/features.ts';
import type { MaterialFeatureUses } from './pack-materials.ts';

type MaterialFeatureName =
  | 'FEATURE_SPECULAR' | 'FEATURE_TRANSMISSION' | 'FEATURE_VOLUME' | 'FEATURE_CLEARCOAT' | 'FEATURE_SHEEN' | 'FEATURE_IRIDESCENCE'
  | 'FEATURE_ANISOTROPY' | 'FEATURE_DIFFUSE_TRANSMISSION' | 'FEATURE_DISPERSION' | 'FEATURE_ENERGY_COMPENSATION';

/** The shader feature flags of the KHR material extensions a scene's materials use. */
export function materialFeatures(uses: MaterialFeatureUses): Pick<ShaderFeatures, MaterialFeatureName> {
  return {
    FEATURE_SPECULAR: uses.specular,
    FEATURE_TRANSMISSION: uses.transmission,
    FEATURE_VOLUME: uses.volume,
    FEATURE_CLEARCOAT: uses.clearcoat,
    FEATURE_SHEEN: uses.sheen,
    FEATURE_IRIDESCENCE: uses.iridescence,
    FEATURE_ANISOTROPY: uses.anisotropy,
    FEATURE_DIFFUSE_TRANSMISSION: uses.diffuseTransmission,
    FEATURE_DISPERSION: uses.dispersion,
    FEATURE_ENERGY_COMPENSATION: uses.energyCompensation,
  };
}
