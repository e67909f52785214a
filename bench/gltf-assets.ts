/**
 * Deterministic glTF assets for bench/gltf.ts, built with @gltf-transform/core:
 *
 * - `terrainGlb(triangles)`: a displaced terrain grid of at least `triangles` triangles (POSITION,
 *   NORMAL, TEXCOORD_0, uint32 indices) with a PNG base colour texture (1024 x 1024), as one .glb;
 *   what a large exported asset looks like to the loader (accessors, an image to decode).
 * - `texturedRoomDocument()`: a room to render: floor, walls and a few objects with base colour,
 *   metallic-roughness and normal textures (KHR_texture_transform on the floor), lit by an
 *   emissive ceiling panel, seen by a perspective camera.
 *
 * Every value is a function of the arguments (no randomness), so every run and every machine reads
 * the same bytes.
 */
import { Document, NodeIO, type Buffer as GltfBuffer, type Material, type Mesh, type TypedArray } from '@gltf-transform/core';
import { ALL_EXTENSIONS, KHRTextureTransform } from '@gltf-transform/extensions';
import { encode as encodePng } from 'fast-png';

function accessor(doc: Document, buffer: GltfBuffer, type: 'SCALAR' | 'VEC2' | 'VEC3', array: Float32Array | Uint32Array | Uint16Array) {
  return doc.createAccessor().setType(type).setArray(array as TypedArray).setBuffer(buffer);
}

/** RGBA8 PNG of `size`^2 texels with texel (x, y) = f(x, y). */
function png(size: number, f: (x: number, y: number) => [number, number, number]): Uint8Array {
  const data = new Uint8Array(size * size * 4);
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const [r, g, b] = f(x, y);
      data.set([r, g, b, 255], 4 * (y * size + x));
    }
  }
  return encodePng({ width: size, height: size, data, channels: 4 });
}

const byte = (v: number): number => Math.max(0, Math.min(255, Math.round(v * 255)));

/** Heights of the terrain: a few octaves of sines (smooth, with detail at every scale). */
function height(x: number, z: number): number {
  return 6 * Math.sin(x * 0.05) * Math.cos(z * 0.07) + 2 * Math.sin(x * 0.31 + z * 0.23) + 0.5 * Math.cos(x * 1.7 - z * 1.3);
}

/** A terrain grid of 2 n^2 >= `triangles` triangles over 100 x 100 units, as .glb bytes. */
export async function terrainGlb(triangles: number, options: { textureSize?: number } = {}): Promise<{ glb: Uint8Array; triangles: number; vertices: number }> {
  const textureSize = options.textureSize ?? 1024;
  const n = Math.ceil(Math.sqrt(triangles / 2));
  const size = 100;
  const verts = (n + 1) * (n + 1);
  const positions = new Float32Array(verts * 3);
  const normals = new Float32Array(verts * 3);
  const uvs = new Float32Array(verts * 2);
  const e = 1e-3;
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i <= n; i++) {
      const v = j * (n + 1) + i;
      const x = (i / n) * size;
      const z = (j / n) * size;
      const y = height(x, z);
      positions.set([x, y, z], 3 * v);
      // Normal of the height field: (-dh/dx, 1, -dh/dz), by central differences.
      const dx = (height(x + e, z) - height(x - e, z)) / (2 * e);
      const dz = (height(x, z + e) - height(x, z - e)) / (2 * e);
      const len = Math.hypot(dx, 1, dz);
      normals.set([-dx / len, 1 / len, -dz / len], 3 * v);
      uvs.set([i / n, j / n], 2 * v);
    }
  }
  const indices = new Uint32Array(n * n * 6);
  for (let j = 0, k = 0; j < n; j++) {
    for (let i = 0; i < n; i++, k += 6) {
      const a = j * (n + 1) + i;
      // Counter-clockwise seen from above (+y): a, a + n + 1, a + 1 and a + 1, a + n + 1, a + n + 2.
      indices.set([a, a + n + 1, a + 1, a + 1, a + n + 1, a + n + 2], k);
    }
  }
  const doc = new Document();
  const buffer = doc.createBuffer();
  const texture = doc.createTexture('terrain colour').setMimeType('image/png').setImage(png(textureSize, (x, y) => {
    const h = 0.5 + 0.5 * Math.sin(x * 0.05) * Math.cos(y * 0.07);
    return [byte(0.25 + 0.35 * h), byte(0.35 + 0.3 * h), byte(0.15 + 0.1 * Math.sin(x * 0.4 + y * 0.3))];
  }));
  const material = doc.createMaterial('terrain').setBaseColorTexture(texture).setMetallicFactor(0).setRoughnessFactor(0.9);
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', accessor(doc, buffer, 'VEC3', positions))
    .setAttribute('NORMAL', accessor(doc, buffer, 'VEC3', normals))
    .setAttribute('TEXCOORD_0', accessor(doc, buffer, 'VEC2', uvs))
    .setIndices(accessor(doc, buffer, 'SCALAR', indices))
    .setMaterial(material);
  doc.createScene().addChild(doc.createNode('terrain').setMesh(doc.createMesh('terrain').addPrimitive(primitive)));
  const glb = await new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(doc);
  return { glb, triangles: 2 * n * n, vertices: verts };
}

/**
 * An axis-aligned box [min, max] with per-face normals and uvs, facing out (or in, for a room);
 * `omit` names faces to leave out ('x-', 'z+', ...).
 */
function box(doc: Document, buffer: GltfBuffer, min: number[], max: number[], material: Material, options: { inward?: boolean; omit?: string[] } = {}): Mesh {
  const inward = options.inward ?? false;
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  const indices: number[] = [];
  for (let axis = 0; axis < 3; axis++) {
    for (const side of [-1, 1]) {
      if (options.omit?.includes(`${'xyz'[axis]}${side < 0 ? '-' : '+'}`)) continue;
      const u = (axis + 1) % 3;
      const v = (axis + 2) % 3;
      const base = positions.length / 3;
      for (const [a, b] of [[0, 0], [1, 0], [1, 1], [0, 1]] as const) {
        const p = [0, 0, 0];
        p[axis] = side < 0 ? min[axis]! : max[axis]!;
        p[u] = a ? max[u]! : min[u]!;
        p[v] = b ? max[v]! : min[v]!;
        positions.push(...p);
        const n = [0, 0, 0];
        n[axis] = inward ? -side : side;
        normals.push(...n);
        uvs.push(a, 1 - b);
      }
      // (u, v) corners go counter-clockwise around +axis: keep that for outward +side faces.
      const outwardCcw = side > 0 !== inward;
      indices.push(...(outwardCcw ? [0, 1, 2, 0, 2, 3] : [0, 2, 1, 0, 3, 2]).map((i) => base + i));
    }
  }
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array(positions)))
    .setAttribute('NORMAL', accessor(doc, buffer, 'VEC3', new Float32Array(normals)))
    .setAttribute('TEXCOORD_0', accessor(doc, buffer, 'VEC2', new Float32Array(uvs)))
    .setIndices(accessor(doc, buffer, 'SCALAR', new Uint16Array(indices)))
    .setMaterial(material);
  return doc.createMesh().addPrimitive(primitive);
}

/** A UV sphere of `segments` x `segments / 2` quads with normals and uvs. */
function sphere(doc: Document, buffer: GltfBuffer, radius: number, segments: number, material: Material): Mesh {
  const rings = segments / 2;
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  for (let r = 0; r <= rings; r++) {
    const theta = (r / rings) * Math.PI;
    for (let s = 0; s <= segments; s++) {
      const phi = (s / segments) * 2 * Math.PI;
      const n = [Math.sin(theta) * Math.cos(phi), Math.cos(theta), -Math.sin(theta) * Math.sin(phi)];
      positions.push(...n.map((c) => c * radius));
      normals.push(...n);
      uvs.push(s / segments, r / rings);
    }
  }
  const indices: number[] = [];
  for (let r = 0; r < rings; r++) {
    for (let s = 0; s < segments; s++) {
      const a = r * (segments + 1) + s;
      const b = a + segments + 1;
      indices.push(a, b, a + 1, a + 1, b, b + 1);
    }
  }
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array(positions)))
    .setAttribute('NORMAL', accessor(doc, buffer, 'VEC3', new Float32Array(normals)))
    .setAttribute('TEXCOORD_0', accessor(doc, buffer, 'VEC2', new Float32Array(uvs)))
    .setIndices(accessor(doc, buffer, 'SCALAR', new Uint32Array(indices)))
    .setMaterial(material);
  return doc.createMesh().addPrimitive(primitive);
}

/**
 * The room: 4 x 3 x 4 units, its walls, floor and objects textured (512^2 base colour, 256^2
 * metallic-roughness and normal maps, the floor's repeated 4 times by KHR_texture_transform), an
 * emissive panel under the ceiling, a perspective camera at the open front.
 */
export function texturedRoomDocument(): Document {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const transform = doc.createExtension(KHRTextureTransform);
  const tile = doc.createTexture('tiles').setMimeType('image/png').setImage(png(512, (x, y) => {
    const edge = x % 64 < 3 || y % 64 < 3;
    const shade = 0.55 + 0.25 * Math.sin(Math.floor(x / 64) * 1.7 + Math.floor(y / 64) * 2.3);
    return edge ? [byte(0.2), byte(0.2), byte(0.22)] : [byte(shade), byte(shade * 0.85), byte(shade * 0.7)];
  }));
  const plaster = doc.createTexture('plaster').setMimeType('image/png').setImage(png(512, (x, y) => {
    const s = 0.7 + 0.08 * Math.sin(x * 0.21) * Math.sin(y * 0.17) + 0.04 * Math.sin(x * 1.3 + y * 0.7);
    return [byte(s), byte(s * 0.97), byte(s * 0.9)];
  }));
  const orm = doc.createTexture('orm').setMimeType('image/png').setImage(png(256, (x, y) => [255, byte(0.3 + 0.5 * (0.5 + 0.5 * Math.sin(x * 0.1) * Math.cos(y * 0.13))), byte(((x >> 5) + (y >> 5)) % 2)]));
  const bumps = doc.createTexture('bumps').setMimeType('image/png').setImage(png(256, (x, y) => {
    const dx = 0.25 * Math.cos(x * 0.2) * Math.sin(y * 0.15);
    const dy = 0.25 * Math.sin(x * 0.2) * Math.cos(y * 0.15);
    const dz = Math.sqrt(1 - dx * dx - dy * dy);
    return [byte(0.5 + 0.5 * dx), byte(0.5 + 0.5 * dy), byte(0.5 + 0.5 * dz)];
  }));
  const floor = doc.createMaterial('floor').setBaseColorTexture(tile).setMetallicFactor(0).setRoughnessFactor(0.6).setNormalTexture(bumps);
  floor.getBaseColorTextureInfo()!.setExtension('KHR_texture_transform', transform.createTransform().setScale([4, 4]));
  const walls = doc.createMaterial('walls').setBaseColorTexture(plaster).setMetallicFactor(0).setRoughnessFactor(1).setNormalTexture(bumps).setNormalScale(0.5);
  const metal = doc.createMaterial('metal').setBaseColorFactor([0.95, 0.8, 0.55, 1]).setMetallicFactor(1).setRoughnessFactor(1).setMetallicRoughnessTexture(orm);
  const clay = doc.createMaterial('clay').setBaseColorTexture(tile).setMetallicFactor(0).setRoughnessFactor(1).setMetallicRoughnessTexture(orm).setNormalTexture(bumps);
  const lamp = doc.createMaterial('lamp').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 0.92, 0.8]);
  const scene = doc.createScene();
  const add = (name: string, mesh: Mesh, t: [number, number, number] = [0, 0, 0]) => scene.addChild(doc.createNode(name).setMesh(mesh).setTranslation(t));
  // The room's inside faces: ceiling y = 3, walls x = +-2 and z = -2; open towards +z; the floor
  // is a slab of its own.
  add('room', box(doc, buffer, [-2, 0, -2], [2, 3, 2], walls, { inward: true, omit: ['y-', 'z+'] }));
  add('floor', box(doc, buffer, [-2, -0.05, -2], [2, 0, 2], floor));
  add('lamp', box(doc, buffer, [-0.6, 2.9, -0.6], [0.6, 2.95, 0.6], lamp));
  add('sphere', sphere(doc, buffer, 0.6, 96, metal), [-0.8, 0.6, -0.5]);
  add('block', box(doc, buffer, [-0.5, 0, -0.5], [0.5, 1.4, 0.5], clay), [0.9, 0, -0.8]);
  const camera = doc.createCamera('view').setType('perspective').setYFov(0.9).setZNear(0.05);
  scene.addChild(doc.createNode('camera').setCamera(camera).setTranslation([0, 1.5, 5.2]).setRotation([-Math.sin(0.05), 0, 0, Math.cos(0.05)]));
  return doc;
}
