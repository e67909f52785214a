// The glass-sphere comparison scene (fixtures/glass-sphere/scene.json, which
// scripts/reference/glass_sphere_mitsuba.py renders in Mitsuba 3) as the renderer's input, rendered
// to per-block statistics: used by glass-sphere-reference.test.ts, and by anyone measuring it at
// more samples.
import { readFileSync } from 'node:fs';
import type { WavefrontMeshInput } from '../../src/scene/types.ts';
import { renderBlockStats, type BlockStats, type Vec3 } from '../helpers/block-reference.ts';
import { icosphere } from '../helpers/meshes.ts';

export type { Vec3 } from '../helpers/block-reference.ts';

export interface GlassSphereSpec {
  width: number; height: number; block: number; maxDepth: number;
  camera: { position: Vec3; target: Vec3; up: Vec3; fovYDegrees: number };
  sphere: { center: Vec3; radius: number; subdivisions: number; ior: number };
  plane: { halfSize: number; reflectance: Vec3 };
  light: { corners: Vec3[]; radiance: Vec3 };
}

const fixtures = new URL('./fixtures/glass-sphere/', import.meta.url);

export function readFixture<T>(name: string): T {
  return JSON.parse(readFileSync(new URL(name, fixtures), 'utf8')) as T;
}

export const glassSphereSpec = readFixture<GlassSphereSpec>('scene.json');

/** Two counter-clockwise triangles over four corners in order (the script's `quad`). */
function quad(corners: Vec3[], material: WavefrontMeshInput['material']): WavefrontMeshInput {
  return { positions: corners.flat(), indices: [0, 1, 2, 0, 2, 3], material };
}

export function glassSphereMeshes(spec: GlassSphereSpec): WavefrontMeshInput[] {
  const { center, radius, subdivisions, ior } = spec.sphere;
  const sphere = icosphere(radius, center, subdivisions);
  const normals = sphere.positions.map((v, i) => (v - center[i % 3]!) / radius);
  const h = spec.plane.halfSize;
  const radiance = spec.light.radiance;
  const strength = Math.max(...radiance);
  return [
    // Transmission 1 with a volume: a refractive solid, Fresnel-weighted reflection and refraction.
    { positions: sphere.positions, indices: sphere.indices, normals, material: { baseColorFactor: [1, 1, 1], metallicFactor: 0, roughnessFactor: 0, ior, transmissionFactor: 1, thicknessFactor: 2 * radius } },
    // ior 1: the exact Fresnel term vanishes, so the glTF BSDF is Lambertian (Mitsuba's `diffuse`).
    quad([[-h, 0, h], [h, 0, h], [h, 0, -h], [-h, 0, -h]], { baseColorFactor: spec.plane.reflectance, metallicFactor: 0, roughnessFactor: 1, ior: 1 }),
    // One-sided: it emits downwards, along the normal of its counter-clockwise winding.
    quad(spec.light.corners, { baseColorFactor: [0, 0, 0], metallicFactor: 0, roughnessFactor: 1, ior: 1, emissiveFactor: radiance.map((v) => v / strength) as Vec3, emissiveStrength: strength }),
  ];
}

/** Renders the scene at `maxDepth` (default the spec's) and returns its block statistics. */
export async function renderGlassSphere(device: GPUDevice, spec: GlassSphereSpec, spp: number, seed: number, maxDepth = spec.maxDepth): Promise<BlockStats & { invalidSamples: number }> {
  const c = spec.camera;
  return renderBlockStats(spec, {
    device, maxDepth, samplesPerPixel: spp, seed,
    camera: { type: 'perspective', position: c.position, target: c.target, up: c.up, fovYDegrees: c.fovYDegrees },
    meshes: glassSphereMeshes(spec),
  });
}
