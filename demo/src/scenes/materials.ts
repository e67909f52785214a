// Materials the built-in scenes share. Each is a glTF metallic-roughness material as the renderer
// takes it. `glass` is where KHR_materials_transmission goes once the path tracer renders it (it
// refuses transmission today rather than fake it): until then it is a polished dark dielectric,
// which shows glass's Fresnel reflections but not what lies behind it.
import type { WavefrontMaterialInput } from '@plasius/gpu-renderer';

type Rgb = [number, number, number];

export const emitter = (rgb: Rgb, strength: number): WavefrontMaterialInput => ({
  baseColorFactor: [0, 0, 0],
  metallicFactor: 0,
  roughnessFactor: 1,
  emissiveFactor: rgb,
  emissiveStrength: strength,
});

export const diffuse = (rgb: Rgb): WavefrontMaterialInput => ({ baseColorFactor: rgb, metallicFactor: 0, roughnessFactor: 1, ior: 1 });

/** A dielectric with a GGX specular layer (plastic, lacquer, ceramics). */
export const dielectric = (rgb: Rgb, roughness: number, ior = 1.5): WavefrontMaterialInput => ({ baseColorFactor: rgb, metallicFactor: 0, roughnessFactor: roughness, ior });

/** A conductor; `rgb` is its F0 (linear reflectance at normal incidence). */
export const metal = (rgb: Rgb, roughness: number): WavefrontMaterialInput => ({ baseColorFactor: rgb, metallicFactor: 1, roughnessFactor: roughness });

/** Linear F0 of common metals (approximations after Hoffman, "Physics and Math of Shading", 2015). */
export const metalF0 = {
  gold: [1.0, 0.766, 0.336] as Rgb,
  copper: [0.955, 0.638, 0.538] as Rgb,
  aluminium: [0.913, 0.922, 0.924] as Rgb,
  silver: [0.972, 0.96, 0.915] as Rgb,
};

/** Clear glass: a polished dielectric today (see above); gains transmissionFactor when it lands. */
export const glass = (tint: Rgb): WavefrontMaterialInput => dielectric(tint, 0.02, 1.5);
