import { anyMaterialExtensions, type MaterialExtension } from '../../materials/extensions/index.ts';
import type { ShaderFeatures } from '../../shaders/features.ts';
import type { MaterialFeatureUses } from './pack-materials.ts';

type MaterialFeatureName = MaterialExtension['feature']['name'] | 'FEATURE_ENERGY_COMPENSATION';

/** The shader feature flags of the KHR material extensions a scene's materials use. */
export function materialFeatures(uses: MaterialFeatureUses): Pick<ShaderFeatures, MaterialFeatureName> {
  const features = Object.fromEntries(anyMaterialExtensions.map((e) => [e.feature.name, uses[e.key as MaterialExtension['key']]]));
  return { ...features, FEATURE_ENERGY_COMPENSATION: uses.energyCompensation } as Pick<ShaderFeatures, MaterialFeatureName>;
}
