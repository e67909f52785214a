// A product shot: a perfume bottle (glass body, polished metal cap) and a chrome ball on a
// lacquered pedestal, in a photo studio's cyclorama lit by a key soft box, a rim strip and a top
// light.
import { cyclorama, lathe, panel, placement, sphere, type ProfilePoint } from './geometry.ts';
import { dielectric, diffuse, emitter, glass, metal, metalF0 } from './materials.ts';
import type { BuiltInScene } from './types.ts';

/** A cylinder of radius r and height h whose top and bottom edges are rounded by `bevel`. */
function roundedCylinder(r: number, h: number, bevel: number, steps = 4): ProfilePoint[] {
  const points: ProfilePoint[] = [{ r: 0, y: 0, normal: [0, -1] }];
  for (let i = 0; i <= steps; i++) {
    const a = (Math.PI / 2) * (i / steps);
    points.push({ r: r - bevel + bevel * Math.sin(a), y: bevel - bevel * Math.cos(a), normal: [Math.sin(a), -Math.cos(a)] });
  }
  for (let i = 0; i <= steps; i++) {
    const a = (Math.PI / 2) * (i / steps);
    points.push({ r: r - bevel + bevel * Math.cos(a), y: h - bevel + bevel * Math.sin(a), normal: [Math.cos(a), Math.sin(a)] });
  }
  points.push({ r: 0, y: h, normal: [0, 1] });
  return points;
}

/** The bottle: a body with a rounded foot, an elliptical shoulder and a short neck. */
function bottleProfile(): ProfilePoint[] {
  // Bottom centre and the foot's bevel (the first six points of a rounded cylinder).
  const points = roundedCylinder(0.34, 0.62, 0.08).slice(0, 6);
  points.push({ r: 0.34, y: 0.6 });
  for (let i = 1; i <= 8; i++) {
    const a = (Math.PI / 2) * (i / 8);
    points.push({ r: 0.12 + 0.22 * Math.cos(a), y: 0.6 + 0.12 * Math.sin(a) });
  }
  points.push({ r: 0.12, y: 0.8 }, { r: 0.12, y: 0.8 }, { r: 0, y: 0.8, normal: [0, 1] });
  return points;
}

export const productShot: BuiltInScene = {
  id: 'product',
  label: 'Glass and metal product shot',
  create() {
    const meshes = [
      cyclorama('cyclorama', { width: 9, depth: 5, height: 4, radius: 1.4 }, diffuse([0.78, 0.78, 0.8])),
      lathe('pedestal', roundedCylinder(0.75, 0.3, 0.04), 64, dielectric([0.05, 0.05, 0.055], 0.25)),
      lathe('bottle', bottleProfile(), 64, glass([0.72, 0.88, 0.84], 0.5)),
      lathe('cap', roundedCylinder(0.13, 0.3, 0.025), 48, metal(metalF0.gold, 0.18)),
      sphere('ball', 0.14, 48, metal(metalF0.silver, 0.04)),
      panel('key-light', [-2.2, 2.2, 2], [1.1, -0.6, -1], 1.6, 2, emitter([1, 0.97, 0.92], 9)),
      panel('rim-light', [2.4, 1.4, -0.6], [-1, -0.1, 0.4], 0.5, 2.4, emitter([0.9, 0.95, 1], 12)),
      panel('top-light', [0, 3.4, 0.3], [0, -1, 0], 2, 1.2, emitter([1, 1, 1], 4)),
    ];
    return {
      name: 'product-shot',
      description: {
        camera: { position: [0, 1.15, 3.4], target: [0, 0.62, 0], fovYDegrees: 30 },
        meshes,
        instances: [
          { mesh: 0, transform: placement([0, 0, -1.2]) },
          { mesh: 1 },
          { mesh: 2, transform: placement([-0.12, 0.3, 0]) },
          { mesh: 3, transform: placement([-0.12, 1.1, 0]) },
          { mesh: 4, transform: placement([0.38, 0.44, 0.3]) },
          { mesh: 5 },
          { mesh: 6 },
          { mesh: 7 },
        ],
      },
      suggestedEnvironment: [0.02, 0.02, 0.025],
      notes: [],
    };
  },
};
