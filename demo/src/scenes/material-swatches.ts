// Material swatches: one shared sphere mesh placed 10 times (instances), a row of gold spheres and
// a row of blue lacquer spheres with roughness rising from 0.05 to 1, and two textured spheres
// (a checker base colour; roughness bands from a metallicRoughness texture), on a checker floor
// under a soft box.
import type { WavefrontInstanceInput, WavefrontMaterialInput } from '@plasius/gpu-renderer';
import { panel, placement, quad, sphere } from './geometry.ts';
import { dielectric, diffuse, emitter, metal, metalF0 } from './materials.ts';
import { checkerImage, roughnessBandsImage } from './textures.ts';
import type { BuiltInScene } from './types.ts';

const roughnesses = [0.05, 0.25, 0.45, 0.7, 1];

export const materialSwatches: BuiltInScene = {
  id: 'swatches',
  label: 'Material swatches',
  create() {
    const materials: WavefrontMaterialInput[] = [
      ...roughnesses.map((r) => metal(metalF0.gold, r)),
      ...roughnesses.map((r) => dielectric([0.05, 0.18, 0.6], r)),
      { ...diffuse([1, 1, 1]), baseColorTexture: { index: 1 } },
      { ...metal(metalF0.aluminium, 1), metallicRoughnessTexture: { index: 2 } },
      { ...diffuse([1, 1, 1]), roughnessFactor: 0.8, baseColorTexture: { index: 0, transform: { scale: [8, 8] } } },
    ];
    const ball = sphere('ball', 0.32, 48);
    const meshes = [ball, quad('floor', [[-6, 0, 6], [6, 0, 6], [6, 0, -6], [-6, 0, -6]]), panel('soft-box', [0, 4, 1], [0, -1, 0], 4, 2, emitter([1, 0.96, 0.9], 6))];
    const instances: WavefrontInstanceInput[] = [];
    roughnesses.forEach((_, i) => {
      const x = (i - 2) * 0.8;
      instances.push({ id: `gold-${i}`, mesh: 0, material: i, transform: placement([x, 0.32, -0.45]) });
      instances.push({ id: `lacquer-${i}`, mesh: 0, material: 5 + i, transform: placement([x, 0.32, 0.45]) });
    });
    instances.push({ id: 'checker-ball', mesh: 0, material: 10, transform: placement([-0.9, 0.55, -1.6], { scale: 1.7 }) });
    instances.push({ id: 'bands-ball', mesh: 0, material: 11, transform: placement([0.9, 0.55, -1.6], { scale: 1.7, yawDegrees: 30 }) });
    instances.push({ id: 'floor', mesh: 1, material: 12 });
    instances.push({ id: 'soft-box', mesh: 2 });
    return {
      name: 'material-swatches',
      description: {
        camera: { position: [0, 2.3, 4.6], target: [0, 0.35, -0.3], fovYDegrees: 38 },
        meshes,
        instances,
        materials,
        textures: [
          { name: 'floor-checker', image: checkerImage(64, 2, [200, 200, 200], [120, 120, 120]), sampler: { wrapS: 'repeat', wrapT: 'repeat' } },
          { name: 'ball-checker', image: checkerImage(256, 8, [230, 120, 40], [235, 235, 225]), sampler: { magFilter: 'nearest' } },
          { name: 'roughness-bands', image: roughnessBandsImage(64, 6, 0.05, 0.9, 1) },
        ],
      },
      suggestedEnvironment: [0.16, 0.18, 0.22],
      notes: [],
    };
  },
};
