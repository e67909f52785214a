/**
 * Primitive meshes for `props` whose kind has no glTF asset: boxes, cylinders, spheres, cones,
 * built with their base at y = 0 so a prop placed at its ground anchor stands on the terrain.
 */
import type { WavefrontMaterialInput, WavefrontMeshInput } from '../../scene/types.ts';

type Geometry = { positions: number[]; normals: number[]; uvs: number[]; indices: number[] };

function box(w: number, h: number, d: number): Geometry {
  const g: Geometry = { positions: [], normals: [], uvs: [], indices: [] };
  const faces: [number[], number[], number[]][] = [
    [[1, 0, 0], [0, 0, -1], [0, 1, 0]],
    [[-1, 0, 0], [0, 0, 1], [0, 1, 0]],
    [[0, 1, 0], [1, 0, 0], [0, 0, -1]],
    [[0, -1, 0], [1, 0, 0], [0, 0, 1]],
    [[0, 0, 1], [1, 0, 0], [0, 1, 0]],
    [[0, 0, -1], [-1, 0, 0], [0, 1, 0]],
  ];
  const half = [w / 2, h / 2, d / 2];
  for (const [n, u, v] of faces) {
    const base = g.positions.length / 3;
    for (const [su, sv] of [[-1, -1], [1, -1], [1, 1], [-1, 1]] as const) {
      const p = [0, 1, 2].map((k) => (n[k]! + su * u[k]! + sv * v[k]!) * half[k]! + (k === 1 ? h / 2 : 0));
      g.positions.push(...p);
      g.normals.push(...n);
      g.uvs.push((su + 1) / 2, (1 - sv) / 2);
    }
    g.indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
  }
  return g;
}

/** A closed cylinder (radiusTop 0 gives a cone) of `segments` sides. */
function cylinder(radiusBottom: number, radiusTop: number, height: number, segments: number, y0 = 0): Geometry {
  const g: Geometry = { positions: [], normals: [], uvs: [], indices: [] };
  const slope = (radiusBottom - radiusTop) / height;
  for (let s = 0; s <= segments; s++) {
    const a = (2 * Math.PI * s) / segments;
    const c = Math.cos(a);
    const sn = Math.sin(a);
    const len = Math.hypot(1, slope);
    for (const [r, y] of [[radiusBottom, y0], [radiusTop, y0 + height]] as const) {
      g.positions.push(r * sn, y, r * c);
      g.normals.push(sn / len, slope / len, c / len);
      g.uvs.push(s / segments, y === y0 ? 1 : 0);
    }
  }
  for (let s = 0; s < segments; s++) {
    const a = 2 * s;
    g.indices.push(a, a + 2, a + 1, a + 1, a + 2, a + 3);
  }
  for (const [r, y, ny] of [[radiusBottom, y0, -1], [radiusTop, y0 + height, 1]] as const) {
    if (r === 0) continue;
    const center = g.positions.length / 3;
    g.positions.push(0, y, 0);
    g.normals.push(0, ny, 0);
    g.uvs.push(0.5, 0.5);
    for (let s = 0; s <= segments; s++) {
      const a = (2 * Math.PI * s) / segments;
      g.positions.push(r * Math.sin(a), y, r * Math.cos(a));
      g.normals.push(0, ny, 0);
      g.uvs.push(0.5 + 0.5 * Math.sin(a), 0.5 + 0.5 * Math.cos(a));
    }
    for (let s = 0; s < segments; s++) {
      if (ny > 0) g.indices.push(center, center + 1 + s, center + 2 + s);
      else g.indices.push(center, center + 2 + s, center + 1 + s);
    }
  }
  return g;
}

function sphere(radius: number, segments: number, rings: number): Geometry {
  const g: Geometry = { positions: [], normals: [], uvs: [], indices: [] };
  for (let r = 0; r <= rings; r++) {
    const t = (Math.PI * r) / rings;
    for (let s = 0; s <= segments; s++) {
      const p = (2 * Math.PI * s) / segments;
      const n = [Math.sin(t) * Math.sin(p), Math.cos(t), Math.sin(t) * Math.cos(p)];
      g.normals.push(...n);
      g.positions.push(n[0]! * radius, n[1]! * radius + radius, n[2]! * radius);
      g.uvs.push(s / segments, r / rings);
    }
  }
  const row = segments + 1;
  for (let r = 0; r < rings; r++) for (let s = 0; s < segments; s++) {
    const a = r * row + s;
    g.indices.push(a, a + row, a + 1, a + 1, a + row, a + row + 1);
  }
  return g;
}

function lift(g: Geometry, dy: number): Geometry {
  return { ...g, positions: g.positions.map((v, i) => (i % 3 === 1 ? v + dy : v)) };
}

function merge(parts: Geometry[]): Geometry {
  const out: Geometry = { positions: [], normals: [], uvs: [], indices: [] };
  for (const p of parts) {
    const base = out.positions.length / 3;
    out.positions.push(...p.positions);
    out.normals.push(...p.normals);
    out.uvs.push(...p.uvs);
    out.indices.push(...p.indices.map((i) => i + base));
  }
  return out;
}

const shapes: Record<string, { geometry: () => Geometry; material: WavefrontMaterialInput }> = {
  box: { geometry: () => box(0.8, 0.8, 0.8), material: { baseColorFactor: [0.55, 0.38, 0.2, 1], metallicFactor: 0, roughnessFactor: 0.8 } },
  barrel: { geometry: () => cylinder(0.35, 0.35, 0.9, 20), material: { baseColorFactor: [0.45, 0.25, 0.12, 1], metallicFactor: 0, roughnessFactor: 0.6 } },
  rock: { geometry: () => sphere(0.4, 12, 8), material: { baseColorFactor: [0.4, 0.4, 0.42, 1], metallicFactor: 0, roughnessFactor: 0.95 } },
  tree: { geometry: () => merge([cylinder(0.12, 0.1, 1, 10), cylinder(0.7, 0, 1.8, 14, 0.9)]), material: { baseColorFactor: [0.15, 0.4, 0.15, 1], metallicFactor: 0, roughnessFactor: 0.9 } },
  lamp: { geometry: () => merge([cylinder(0.06, 0.05, 2.2, 8), lift(sphere(0.15, 10, 6), 2.2)]), material: { baseColorFactor: [0.2, 0.2, 0.22, 1], metallicFactor: 1, roughnessFactor: 0.4 } },
};
const aliases: Record<string, string> = { crate: 'box', cube: 'box', chest: 'box', cylinder: 'barrel', post: 'lamp', lantern: 'lamp', sphere: 'rock', boulder: 'rock', stone: 'rock', bush: 'rock', cone: 'tree', pine: 'tree' };

/** Names of the built-in prop shapes (plus their aliases). */
export const builtInPropKinds: readonly string[] = [...Object.keys(shapes), ...Object.keys(aliases)];

/** The primitive mesh of a prop kind (unknown kinds are boxes), with its default material inline. */
export function primitivePropMesh(kind: string): WavefrontMeshInput {
  const shape = shapes[kind] ?? shapes[aliases[kind] ?? 'box']!;
  return { ...shape.geometry(), material: shape.material };
}
