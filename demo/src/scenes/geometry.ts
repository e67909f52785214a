// Mesh builders for the built-in scenes: surfaces of revolution (spheres, bottles, pedestals),
// quads and a cyclorama backdrop, with smooth normals and uvs, in the renderer's mesh input format
// (indexed vertex streams, counter-clockwise front faces).
import type { WavefrontMaterialInput, WavefrontMeshInput } from '@plasius/gpu-renderer';

type Vec3 = [number, number, number];

/** A profile point (radius, height) with an optional explicit profile normal (nr, ny). */
export interface ProfilePoint {
  r: number;
  y: number;
  normal?: [number, number];
}

/**
 * Revolves a profile (bottom to top, in the r-y half plane) about the y axis. A point repeated
 * twice makes a crease: each copy takes the normal of its own neighbouring segment only.
 */
export function lathe(id: string, profile: readonly ProfilePoint[], segments: number, material?: WavefrontMaterialInput | number): WavefrontMeshInput {
  const normals2 = profileNormals(profile);
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  const arc = [0];
  for (let i = 1; i < profile.length; i++) arc.push(arc[i - 1]! + Math.hypot(profile[i]!.r - profile[i - 1]!.r, profile[i]!.y - profile[i - 1]!.y));
  const total = arc[arc.length - 1] || 1;
  for (let i = 0; i < profile.length; i++) {
    const { r, y } = profile[i]!;
    const [nr, ny] = normals2[i]!;
    for (let j = 0; j <= segments; j++) {
      const theta = (2 * Math.PI * j) / segments;
      const c = Math.cos(theta);
      const s = Math.sin(theta);
      positions.push(r * c, y, r * s);
      normals.push(nr * c, ny, nr * s);
      uvs.push(j / segments, 1 - arc[i]! / total);
    }
  }
  const indices: number[] = [];
  const ring = segments + 1;
  for (let i = 0; i + 1 < profile.length; i++) {
    if (profile[i]!.r === profile[i + 1]!.r && profile[i]!.y === profile[i + 1]!.y) continue;
    for (let j = 0; j < segments; j++) {
      const a = i * ring + j;
      const b = a + 1;
      const d = a + ring;
      const c = d + 1;
      // (a, d, c) and (a, c, b) wind counter-clockwise seen from outside; a ring of radius 0
      // collapses one of them, which is left out.
      if (profile[i + 1]!.r > 0) indices.push(a, d, c);
      if (profile[i]!.r > 0) indices.push(a, c, b);
    }
  }
  return { id, positions, normals, uvs, indices, ...(material !== undefined ? { material } : {}) };
}

function profileNormals(profile: readonly ProfilePoint[]): [number, number][] {
  const segment = (i: number): [number, number] | null => {
    const a = profile[i];
    const b = profile[i + 1];
    if (!a || !b) return null;
    const dr = b.r - a.r;
    const dy = b.y - a.y;
    const len = Math.hypot(dr, dy);
    // Outward normal of a segment going up the profile.
    return len > 0 ? [dy / len, -dr / len] : null;
  };
  return profile.map((p, i) => {
    if (p.normal) {
      const len = Math.hypot(p.normal[0], p.normal[1]);
      return [p.normal[0] / len, p.normal[1] / len];
    }
    const prev = segment(i - 1);
    const next = segment(i);
    const sum: [number, number] = [(prev?.[0] ?? 0) + (next?.[0] ?? 0), (prev?.[1] ?? 0) + (next?.[1] ?? 0)];
    const len = Math.hypot(sum[0], sum[1]) || 1;
    return [sum[0] / len, sum[1] / len];
  });
}

/** A UV sphere of `radius` centred at the origin (exact normals). */
export function sphere(id: string, radius: number, segments: number, material?: WavefrontMaterialInput | number): WavefrontMeshInput {
  const rings = Math.max(4, Math.round(segments / 2));
  const profile: ProfilePoint[] = [];
  for (let i = 0; i <= rings; i++) {
    const phi = (Math.PI * i) / rings;
    const nr = Math.sin(phi);
    const ny = -Math.cos(phi);
    profile.push({ r: i === 0 || i === rings ? 0 : radius * nr, y: radius * ny, normal: [nr, ny] });
  }
  return lathe(id, profile, segments, material);
}

/** A quad from four corners, counter-clockwise seen from its front; uvs span [0, 1] x `uvScale`. */
export function quad(id: string, corners: readonly [Vec3, Vec3, Vec3, Vec3], material?: WavefrontMaterialInput | number): WavefrontMeshInput {
  return {
    id,
    positions: corners.flat(),
    uvs: [0, 1, 1, 1, 1, 0, 0, 0],
    indices: [0, 1, 2, 0, 2, 3],
    ...(material !== undefined ? { material } : {}),
  };
}

/**
 * A photo-studio cyclorama: a floor of depth `depth` in front of z = 0 that curves up (radius
 * `radius`) into a back wall of height `height`, `width` wide, facing +z and +y.
 */
export function cyclorama(id: string, size: { width: number; depth: number; height: number; radius: number }, material?: WavefrontMaterialInput | number): WavefrontMeshInput {
  const { width, depth, height, radius } = size;
  // Cross-section (z, y, normal z, normal y) from the front edge of the floor to the top of the wall.
  const section: [number, number, number, number][] = [[depth, 0, 0, 1], [0, 0, 0, 1]];
  const steps = 12;
  for (let i = 1; i <= steps; i++) {
    const a = ((Math.PI / 2) * i) / steps;
    section.push([-radius * Math.sin(a), radius * (1 - Math.cos(a)), Math.sin(a), Math.cos(a)]);
  }
  section.push([-radius, height, 1, 0]);
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  for (let i = 0; i < section.length; i++) {
    const [z, y, nz, ny] = section[i]!;
    for (const x of [-width / 2, width / 2]) {
      positions.push(x, y, z);
      normals.push(0, ny, nz);
      uvs.push(x / width + 0.5, i / (section.length - 1));
    }
  }
  const indices: number[] = [];
  for (let i = 0; i + 1 < section.length; i++) {
    const a = 2 * i;
    // a = (left, i), a + 1 = (right, i), a + 2 / a + 3 the next row towards the wall top.
    indices.push(a, a + 1, a + 3, a, a + 3, a + 2);
  }
  return { id, positions, normals, uvs, indices, ...(material !== undefined ? { material } : {}) };
}

/** Column-major translation + uniform scale + rotation about y (glTF node matrix). */
export function placement(translation: Vec3, options: { scale?: number; yawDegrees?: number } = {}): number[] {
  const s = options.scale ?? 1;
  const a = ((options.yawDegrees ?? 0) * Math.PI) / 180;
  const c = Math.cos(a) * s;
  const n = Math.sin(a) * s;
  return [c, 0, -n, 0, 0, s, 0, 0, n, 0, c, 0, translation[0], translation[1], translation[2], 1];
}

/** A `width` x `height` quad centred at `center` whose front faces along `facing` (an area light or card). */
export function panel(id: string, center: Vec3, facing: Vec3, width: number, height: number, material?: WavefrontMaterialInput | number): WavefrontMeshInput {
  const n = normalize(facing);
  const reference: Vec3 = Math.abs(n[1]) > 0.99 ? [0, 0, 1] : [0, 1, 0];
  const right = normalize(cross(reference, n));
  const up = cross(n, right);
  const corner = (sx: number, sy: number): Vec3 => [0, 1, 2].map((i) => center[i]! + (sx * width * right[i]!) / 2 + (sy * height * up[i]!) / 2) as Vec3;
  return quad(id, [corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)], material);
}

function cross(a: Vec3, b: Vec3): Vec3 {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

function normalize(v: Vec3): Vec3 {
  const len = Math.hypot(v[0], v[1], v[2]);
  return [v[0] / len, v[1] / len, v[2] / len];
}
