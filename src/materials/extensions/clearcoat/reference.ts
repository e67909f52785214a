/**
 * KHR_materials_clearcoat's layer in double precision (the CPU reference of layer.wesl): a
 * dielectric GGX coat of ior 1.5 about its own normal, scaling the layers below by
 * 1 - clearcoat E_coat(wo).
 */
import { lookupClearcoatAlbedo } from '../../energy/table-lookup.ts';
import { defineLayerReference } from '../../material-layer.ts';
import { fresnelDielectric } from '../../reference/fresnel.ts';
import { ggxDAniso, ggxG2, ggxVisibleNormalPdf } from '../../reference/microfacet.ts';
import { add, dot, frameAround, normalize, toLocal, type Vec3 } from '../../reference/vector.ts';
import { clearcoat } from './extension.ts';

export interface ClearcoatLayerParams {
  factor: number;
  roughness: number;
  /** In the local shading frame (default +z). */
  normal?: Vec3;
}

const clearcoatIor = 1.5;
/** Below this alpha the coat is a mirror (layer.wesl CLEARCOAT_DELTA_ALPHA). */
const clearcoatDeltaAlpha = 1e-3;
const up: Vec3 = [0, 0, 1];

const tilted = (x: number, y: number): Vec3 => normalize([x, y, 1]);

export const layerReference = defineLayerReference(clearcoat, {
  reflectance: (p: ClearcoatLayerParams, wo: Vec3) => {
    const cosC = dot(wo, p.normal ?? up);
    return cosC > 0 ? p.factor * fresnelDielectric(cosC, clearcoatIor) : 0;
  },
  scale: (p: ClearcoatLayerParams, wo: Vec3) => {
    const woC = toLocal(frameAround(p.normal ?? up), wo);
    return woC[2] > 0 ? 1 - p.factor * lookupClearcoatAlbedo(woC[2], p.roughness) : 1;
  },
  evalPdf: (p: ClearcoatLayerParams, wo: Vec3, wi: Vec3) => {
    const frame = frameAround(p.normal ?? up);
    const woC = toLocal(frame, wo);
    const wiC = toLocal(frame, wi);
    const alpha = p.roughness * p.roughness;
    if (!(woC[2] > 0 && wiC[2] > 0 && wi[2] > 0 && alpha >= clearcoatDeltaAlpha)) return { f: [0, 0, 0], pdf: 0 };
    const h = normalize(add(woC, wiC));
    const a = { x: alpha, y: alpha };
    const v = (p.factor * fresnelDielectric(dot(woC, h), clearcoatIor) * ggxDAniso(h, a) * ggxG2(woC, wiC, a)) / (4 * woC[2] * wiC[2]);
    return { f: [v, v, v], pdf: ggxVisibleNormalPdf(woC, h, a) / (4 * dot(woC, h)) };
  },
  pack: (p: ClearcoatLayerParams) => [...(p.normal ?? up), p.factor, p.roughness, 0, 0, 0],
  examples: [
    { name: 'rough coat, tilted normal', value: { factor: 0.8, roughness: 0.3, normal: tilted(0.2, -0.1) } },
    { name: 'smooth coat', value: { factor: 1, roughness: 0 } },
  ],
});
