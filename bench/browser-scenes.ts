/**
 * The browser bench's scenes (bench/browser.ts), as plain data that both renderers are built from
 * in the page (bench/browser-page.ts): the same triangles, camera, materials, rectangle light and
 * uniform environment for ours and for three-gpu-pathtracer, so their converged images can agree.
 *
 * Materials are restricted to what both models share: a Lambertian base (metallic 0, ior 1: no
 * dielectric specular layer) or a GGX conductor (metallic 1, glTF base colour as F0).
 */
import { createCornellBoxScene } from '../src/scene/cornell-box.ts';

export type V3 = [number, number, number];

export interface BenchMaterial {
  baseColor: V3;
  metallic: 0 | 1;
  roughness: number;
}

export interface BenchMesh {
  name: string;
  positions: number[];
  indices: number[];
  /** Per-vertex shading normals; omitted means flat (geometric) normals in both renderers. */
  normals?: number[];
  material: BenchMaterial;
}

/** A one-sided rectangle light: emits `radiance` towards cross(edgeU, edgeV) (our convention). */
export interface BenchRectLight {
  center: V3;
  edgeU: V3;
  edgeV: V3;
  radiance: V3;
}

export interface BenchScene {
  name: string;
  camera: { position: V3; target: V3; fovYDegrees: number };
  meshes: BenchMesh[];
  rectLights: BenchRectLight[];
  /** Uniform environment radiance (also the background camera rays see); null is black. */
  environment: V3 | null;
  /** Scattering events per path (pbrt-v4 maxDepth; three-gpu-pathtracer's maxBounces counts the same). */
  maxDepth: number;
  /** The analytic converged value of every pixel the sphere covers and of the rest, where known (the furnace). */
  analytic?: { sphere: { center: V3; radius: number; value: V3 }; background: V3 };
}

const lambert = (c: V3): BenchMaterial => ({ baseColor: c, metallic: 0, roughness: 1 });

/** A UV sphere (latitude-longitude tessellation), counter-clockwise seen from outside. */
export function uvSphere(center: V3, radius: number, segments: number, rings: number, smooth: boolean): Omit<BenchMesh, 'name' | 'material'> {
  const positions: number[] = [];
  const normals: number[] = [];
  for (let r = 0; r <= rings; r++) {
    const theta = (r / rings) * Math.PI;
    for (let s = 0; s <= segments; s++) {
      const phi = (s / segments) * 2 * Math.PI;
      const n: V3 = [Math.sin(theta) * Math.cos(phi), Math.cos(theta), -Math.sin(theta) * Math.sin(phi)];
      positions.push(center[0] + radius * n[0], center[1] + radius * n[1], center[2] + radius * n[2]);
      normals.push(...n);
    }
  }
  const indices: number[] = [];
  const row = segments + 1;
  for (let r = 0; r < rings; r++) {
    for (let s = 0; s < segments; s++) {
      const a = r * row + s;
      const b = a + row;
      // Skip the degenerate triangles at the poles.
      if (r !== 0) indices.push(a, b, a + 1);
      if (r !== rings - 1) indices.push(a + 1, b, b + 1);
    }
  }
  return smooth ? { positions, indices, normals } : { positions, indices };
}

function quad(name: string, corners: [V3, V3, V3, V3], material: BenchMaterial): BenchMesh {
  return { name, positions: corners.flat(), indices: [0, 1, 2, 0, 2, 3], material };
}

/** The Cornell box's walls and blocks (src/scene/cornell-box.ts) lit by a rectangle light in place of its emissive quad. */
function cornellRect(): BenchScene {
  const cornell = createCornellBoxScene();
  const meshes = (cornell.meshes ?? [])
    .filter((m) => m.id !== 'light')
    .map((m): BenchMesh => {
      const material = m.material as { baseColorFactor: number[] };
      return {
        name: String(m.id),
        positions: Array.from(m.positions),
        indices: Array.from(m.indices ?? []),
        material: lambert(material.baseColorFactor.slice(0, 3) as V3),
      };
    });
  const camera = cornell.camera!;
  return {
    name: 'cornell-rect',
    camera: { position: [...camera.position] as V3, target: [...camera.target] as V3, fovYDegrees: camera.fovYDegrees! },
    meshes,
    // The Cornell light's 130 x 105 mm (0.47 x 0.38 here), just below the ceiling, facing -y.
    rectLights: [{ center: [0, 0.99, 0], edgeU: [0.47, 0, 0], edgeV: [0, 0, 0.38], radiance: [17, 12, 4] }],
    environment: null,
    maxDepth: 8,
  };
}

/** A flat-shaded Lambertian sphere of albedo 0.8 in a uniform white environment: convex, so every covered pixel converges to 0.8. */
function furnace(): BenchScene {
  const albedo = 0.8;
  return {
    name: 'furnace',
    camera: { position: [0, 0, 4], target: [0, 0, 0], fovYDegrees: 40 },
    meshes: [{ name: 'sphere', ...uvSphere([0, 0, 0], 1, 64, 32, false), material: lambert([albedo, albedo, albedo]) }],
    rectLights: [],
    environment: [1, 1, 1],
    maxDepth: 8,
    analytic: { sphere: { center: [0, 0, 0], radius: 1, value: [albedo, albedo, albedo] }, background: [1, 1, 1] },
  };
}

/** Three GGX conductor spheres (roughness 0.1, 0.3, 0.6) on a grey floor, a rectangle light above, a dim uniform environment. */
function glossySpheres(): BenchScene {
  const spheres: { x: number; roughness: number; color: V3 }[] = [
    { x: -1.3, roughness: 0.1, color: [0.95, 0.64, 0.54] },
    { x: 0, roughness: 0.3, color: [0.91, 0.92, 0.92] },
    { x: 1.3, roughness: 0.6, color: [1.0, 0.78, 0.34] },
  ];
  return {
    name: 'glossy-spheres',
    camera: { position: [0, 0.8, 4.5], target: [0, -0.3, 0], fovYDegrees: 40 },
    meshes: [
      quad('floor', [[-4, -1, 4], [4, -1, 4], [4, -1, -4], [-4, -1, -4]], lambert([0.5, 0.5, 0.5])),
      ...spheres.map((s, i): BenchMesh => ({
        name: `sphere-${i}`,
        ...uvSphere([s.x, -0.4, 0], 0.6, 48, 24, true),
        material: { baseColor: s.color, metallic: 1, roughness: s.roughness },
      })),
    ],
    rectLights: [{ center: [0, 2.5, 0.5], edgeU: [1.2, 0, 0], edgeV: [0, 0, 0.8], radiance: [12, 12, 12] }],
    environment: [0.25, 0.25, 0.25],
    maxDepth: 8,
  };
}

export function browserBenchScenes(): BenchScene[] {
  return [cornellRect(), furnace(), glossySpheres()];
}

/** Our renderer's options for a bench scene (plain data, so the page can take it as it is). */
export function ourSceneOptions(scene: BenchScene): Record<string, unknown> {
  return {
    camera: { position: scene.camera.position, target: scene.camera.target, up: [0, 1, 0], fovYDegrees: scene.camera.fovYDegrees },
    environment: { color: scene.environment ?? [0, 0, 0] },
    meshes: scene.meshes.map((m) => ({
      id: m.name,
      positions: m.positions,
      indices: m.indices,
      ...(m.normals ? { normals: m.normals } : {}),
      // ior 1 on the Lambertian materials: no dielectric specular layer (as in createCornellBoxScene).
      material: { baseColorFactor: [...m.material.baseColor, 1], metallicFactor: m.material.metallic, roughnessFactor: m.material.roughness, ...(m.material.metallic === 0 ? { ior: 1 } : {}) },
    })),
    lights: scene.rectLights.map((l) => ({ type: 'rectangle', center: l.center, edgeU: l.edgeU, edgeV: l.edgeV, emission: l.radiance })),
    maxDepth: scene.maxDepth,
  };
}

/**
 * The pinhole camera's ray through image point (x, y) in pixels (y down; not normalised): the
 * convention of both renderers (vertical fov, square pixels, up = +y).
 */
export function pinholeRay(camera: BenchScene['camera'], width: number, height: number): (x: number, y: number) => number[] {
  const { position: eye, target, fovYDegrees } = camera;
  const forward = normalize(target.map((t, i) => t - eye[i]!));
  const right = normalize(cross(forward, [0, 1, 0]));
  const up = cross(right, forward);
  const tanY = Math.tan((fovYDegrees * Math.PI) / 360);
  const tanX = tanY * (width / height);
  return (x, y) => {
    const u = (2 * x) / width - 1;
    const v = 1 - (2 * y) / height;
    return forward.map((f, k) => f + u * tanX * right[k]! + v * tanY * up[k]!);
  };
}

function normalize(p: number[]): number[] {
  const l = Math.hypot(...p);
  return p.map((v) => v / l);
}

function cross(p: number[], q: number[]): number[] {
  return [p[1]! * q[2]! - p[2]! * q[1]!, p[2]! * q[0]! - p[0]! * q[2]!, p[0]! * q[1]! - p[1]! * q[0]!];
}
