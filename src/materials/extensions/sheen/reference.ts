/**
 * KHR_materials_sheen's CPU reference: the Charlie lobe (sheen-charlie.ts, re-exported) and the
 * sheen layer over the base (layer.wesl).
 */
import { lookupSheenAlbedo } from '../../energy/table-lookup.ts';
import { defineLayerReference } from '../../material-layer.ts';
import { add, maxComponent, normalize, scale, type Vec3 } from '../../reference/vector.ts';
import { sheen } from './extension.ts';
import { sheenBrdf } from './sheen-charlie.ts';

export { charlieD, charlieLambda, sheenAlpha, sheenBrdf, sheenCharlie, sheenMinRoughness } from './sheen-charlie.ts';

export interface SheenLayerParams {
  color: Vec3;
  roughness: number;
}

/**
 * The sheen layer (layer.wesl): the Charlie lobe times the sheen colour, divided by max(1, E(wo)),
 * over the layers below scaled by min(1 - max(color) E(wo), 1 - max(color) E(wi)).
 */
export const layerReference = defineLayerReference(sheen, {
  reflectance: (p: SheenLayerParams, wo: Vec3) => maxComponent(p.color) * Math.min(lookupSheenAlbedo(wo[2], p.roughness), 1),
  scale: (p: SheenLayerParams, wo: Vec3, wi: Vec3) => {
    const s = maxComponent(p.color);
    return Math.max(0, Math.min(1 - s * lookupSheenAlbedo(wo[2], p.roughness), 1 - s * lookupSheenAlbedo(Math.abs(wi[2]), p.roughness)));
  },
  evalPdf: (p: SheenLayerParams, wo: Vec3, wi: Vec3) => {
    if (wi[2] <= 0) return { f: [0, 0, 0], pdf: 0 };
    const h = normalize(add(wo, wi));
    const e = lookupSheenAlbedo(wo[2], p.roughness);
    return { f: scale(p.color, sheenBrdf(wo[2], wi[2], h[2], p.roughness) / Math.max(1, e)), pdf: wi[2] / Math.PI };
  },
  pack: (p: SheenLayerParams) => [...p.color, p.roughness, 0, 0, 0, 0],
  examples: [{ name: 'velvet sheen', value: { color: [0.9, 0.4, 0.6], roughness: 0.5 } }],
});
