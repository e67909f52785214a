/**
 * Pipeline specialisation: WGSL `override` constants (generated into `package::layout::features`).
 * A scene without a feature compiles its kernels with the feature off, so the shader compiler
 * removes that code and the scene does not pay for it; the output is identical either way (tests
 * render with features forced on and off).
 */
import { materialExtensions, type MaterialExtension } from '../materials/extensions/index.ts';

export const shaderFeatures = {
  FEATURE_ANALYTIC_SHAPES: { default: true, doc: 'spheres and boxes among the primitives' },
  FEATURE_INSTANCING: { default: true, doc: 'placements of shared meshes in the top level: traversal enters their bottom-level trees in object space' },
  FEATURE_ALPHA_TEST: { default: true, doc: 'MASK or BLEND primitives: traversal alpha-tests candidate hits' },
  FEATURE_TEXTURES: { default: true, doc: 'materials sample the texture atlas' },
  FEATURE_EMISSIVE_LIGHTS: { default: true, doc: 'emissive triangles are sampled by next-event estimation' },
  FEATURE_ENVIRONMENT: { default: true, doc: 'a non-black environment lights the scene' },
  FEATURE_AOVS: { default: true, doc: 'the first non-specular hit writes albedo, normal, depth and ids' },
  FEATURE_FILM_MOMENTS: { default: true, doc: 'the film accumulates the half-sample sum and second moments (adaptive sampling, variance, denoising)' },
  FEATURE_ADAPTIVE_SAMPLING: { default: true, doc: 'waves take their pixels from the active-pixel list of adaptive sampling' },
  // Lighting: which emitter kinds and samplers the scene needs.
  FEATURE_ENVIRONMENT_MAP: { default: true, doc: 'the environment is an importance-sampled map (environmentMap, environmentLighting)' },
  FEATURE_SUN: { default: true, doc: 'a sun disc (environmentLighting) is cone-sampled and seen by escaped rays' },
  FEATURE_PORTALS: { default: true, doc: 'environment portals steer environment sampling' },
  FEATURE_PUNCTUAL_LIGHTS: { default: true, doc: 'point, spot or directional lights are sampled by next-event estimation' },
  FEATURE_AREA_LIGHTS: { default: true, doc: 'rectangle, disk or sphere lights are sampled, hit by rays and block rays' },
  FEATURE_LIGHT_TREE: { default: true, doc: 'bounded lights are chosen by the light hierarchy instead of the power alias table' },
  // KHR material extensions (materials/extensions/): each compiles in when a material uses it.
  ...extensionFeatures(),
  FEATURE_ENERGY_COMPENSATION: { default: true, doc: 'multiple-scattering energy compensation of rough microfacet lobes' },
  // The device, not the scene: how kernels reduce per-frame statistics.
  FEATURE_WORKGROUP_TALLIES: {
    default: true,
    doc: 'frame diagnostics are summed per workgroup (one barrier, then one set of global atomics per workgroup), as suits a GPU; off on a CPU adapter, where each invocation adds its own (a barrier there costs more than the atomics: 4x on SwiftShader)',
  },
} as const;

type ExtensionFeatureName = MaterialExtension['feature']['name'];

function extensionFeatures(): Record<ExtensionFeatureName, { default: true; doc: string }> {
  return Object.fromEntries(materialExtensions.map((e) => [e.feature.name, { default: true, doc: e.feature.doc }])) as Record<ExtensionFeatureName, { default: true; doc: string }>;
}

export type ShaderFeatureName = keyof typeof shaderFeatures;
export type ShaderFeatures = Record<ShaderFeatureName, boolean>;

export const allShaderFeatures: ShaderFeatures = Object.fromEntries(Object.keys(shaderFeatures).map((k) => [k, true])) as ShaderFeatures;
