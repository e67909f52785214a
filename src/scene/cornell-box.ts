import type { WavefrontMaterialInput, WavefrontMeshInput, WavefrontSceneDescription } from './types.ts';

/**
 * The Cornell box (Cornell University Program of Computer Graphics, "The Cornell Box",
 * https://www.graphics.cornell.edu/online/box/data.html), rescaled from its 556 x 548.8 x 559.2 mm
 * extent to the cube [-1, 1]^3 with y up and the open side facing +z (towards the camera).
 *
 * - Walls are quads whose counter-clockwise winding makes their normals point into the box; the
 *   blocks are closed boxes with outward normals; the light is a quad just below the ceiling whose
 *   front face (counter-clockwise as seen from below) points down.
 * - Albedos are the usual linear-RGB approximations of the measured spectral reflectances
 *   (white 0.73, red (0.63, 0.065, 0.05), green (0.14, 0.45, 0.091)), and the light emits
 *   (17, 12, 4), as in pbrt-v4's and Mitsuba's RGB Cornell boxes.
 * - Surfaces are Lambertian: metallic 0, roughness 1 and ior 1 (no Fresnel-weighted specular
 *   layer), so the scene matches the classic diffuse-only reference.
 */
export function createCornellBoxScene(): WavefrontSceneDescription {
  const white = lambertian([0.73, 0.73, 0.73]);
  const red = lambertian([0.63, 0.065, 0.05]);
  const green = lambertian([0.14, 0.45, 0.091]);
  const emission = [17, 12, 4];
  const strength = Math.max(...emission);
  const light: WavefrontMaterialInput = {
    ...lambertian([0.78, 0.78, 0.78]),
    emissiveFactor: emission.map((e) => e / strength),
    emissiveStrength: strength,
  };

  // Quads are given as four corners in counter-clockwise order seen from the side they face.
  const meshes: WavefrontMeshInput[] = [
    quadMesh('floor', [[-1, -1, 1], [1, -1, 1], [1, -1, -1], [-1, -1, -1]], white),
    quadMesh('ceiling', [[-1, 1, 1], [-1, 1, -1], [1, 1, -1], [1, 1, 1]], white),
    quadMesh('back-wall', [[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1]], white),
    quadMesh('left-wall', [[-1, -1, 1], [-1, -1, -1], [-1, 1, -1], [-1, 1, 1]], red),
    quadMesh('right-wall', [[1, -1, -1], [1, -1, 1], [1, 1, 1], [1, 1, -1]], green),
    // Cornell data: short block centred at (185.5, 169) mm, tall block at (368.5, 351.25) mm,
    // 165 and 330 mm high, footprints ~166 mm rotated ~17 degrees.
    boxMesh('short-block', { center: [0.333, 0.396], halfSize: 0.3, height: 0.6, yawDegrees: -16.7 }, white),
    boxMesh('tall-block', { center: [-0.326, -0.256], halfSize: 0.3, height: 1.2, yawDegrees: 17.2 }, white),
    // The 130 x 105 mm light, centred, 1 mm-equivalent below the ceiling; faces -y.
    quadMesh('light', [[-0.235, 0.99, -0.19], [0.235, 0.99, -0.19], [0.235, 0.99, 0.19], [-0.235, 0.99, 0.19]], light),
  ];

  return {
    // Cornell camera: (278, 273, -800) mm looking at +z, 35 mm focal length, 25 mm film:
    // fovY = 2 atan(12.5 / 35) = 39.3 degrees.
    camera: { position: [0, 0, 3.86], target: [0, 0, 0], up: [0, 1, 0], fovYDegrees: 39.3 },
    environment: { color: [0, 0, 0] },
    meshes,
  };
}

function lambertian(baseColor: [number, number, number]): WavefrontMaterialInput {
  return { baseColorFactor: baseColor, metallicFactor: 0, roughnessFactor: 1, ior: 1 };
}

type V3 = [number, number, number];

function quadMesh(id: string, corners: [V3, V3, V3, V3], material: WavefrontMaterialInput): WavefrontMeshInput {
  return { id, positions: corners.flat(), indices: [0, 1, 2, 0, 2, 3], material };
}

/** A closed box standing on the floor (y = -1), rotated about +y, with outward-facing triangles. */
function boxMesh(
  id: string,
  box: { center: [number, number]; halfSize: number; height: number; yawDegrees: number },
  material: WavefrontMaterialInput,
): WavefrontMeshInput {
  const phi = (box.yawDegrees * Math.PI) / 180;
  const c = Math.cos(phi);
  const s = Math.sin(phi);
  const h = box.halfSize;
  const positions: number[] = [];
  // Corner k: bit 0 -> +x, bit 1 -> +y, bit 2 -> +z (local), rotated by phi about +y.
  for (let k = 0; k < 8; k++) {
    const lx = k & 1 ? h : -h;
    const lz = k & 4 ? h : -h;
    const y = k & 2 ? -1 + box.height : -1;
    positions.push(box.center[0] + c * lx + s * lz, y, box.center[1] - s * lx + c * lz);
  }
  // Each face as four corner indices counter-clockwise seen from outside.
  const faces = [
    [1, 3, 7, 5], // +x
    [0, 4, 6, 2], // -x
    [2, 6, 7, 3], // +y
    [0, 1, 5, 4], // -y
    [4, 5, 7, 6], // +z
    [0, 2, 3, 1], // -z
  ];
  const indices = faces.flatMap(([a, b, c2, d]) => [a, b, c2, a, c2, d]);
  return { id, positions, indices, material };
}
