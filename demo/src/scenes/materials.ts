// Materials the built-in scenes share. Each is a glTF metallic-roughness material as the renderer
// takes it, with KHR extension factors flattened under their glTF names where a material needs them.
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

/**
 * Solid glass (KHR_materials_transmission + _volume): smooth, ior 1.5, its tint from Beer-Lambert
 * absorption, `attenuationColor` being what is left after `attenuationDistance` (metres) inside.
 */
export const glass = (attenuationColor: Rgb, attenuationDistance: number): WavefrontMaterialInput => ({
  baseColorFactor: [1, 1, 1],
  metallicFactor: 0,
  roughnessFactor: 0,
  ior: 1.5,
  transmissionFactor: 1,
  thicknessFactor: 0.1,
  attenuationColor,
  attenuationDistance,
});
