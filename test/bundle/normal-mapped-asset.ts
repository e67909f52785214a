// A small normal-mapped glTF asset without TANGENT attributes, made with @gltf-transform/core, for
// the bundle tests: the loader must generate MikkTSpace tangents for it (glTF 2.0 section
// 3.7.2.1), in the browser as in Node.
// - `panel`: a quad filling [-1, 1]^2 in the z = 0 plane, facing +z, black metal (reflects
//   nothing), emissive through a 2 x 2 texture (nearest filtering): seen head-on with a camera that
//   frames it exactly, each quarter of the image shows one texel's colour and nothing else.
// - `patch`: a curved, sheared-uv surface behind that camera (never seen, never lit: no light
//   reaches it) whose tangents vary from vertex to vertex, so they test MikkTSpace properly.
import { Document, NodeIO, type Buffer as GltfBuffer, type Material, type Mesh } from '@gltf-transform/core';
import { encode as encodePng } from 'fast-png';

/** The emissive texture's texels (sRGB bytes), row by row from the top: [top-left, top-right, bottom-left, bottom-right]. */
export const panelTexels: ReadonlyArray<readonly [number, number, number]> = [
  [230, 40, 40],
  [40, 200, 60],
  [50, 80, 220],
  [240, 220, 60],
];

/** A camera (renderer input) at distance 2 whose vertical field of view spans the panel exactly (square images). */
export const panelCamera = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovYDegrees: (2 * Math.atan(0.5) * 180) / Math.PI };

const NEAREST = 9728;

function rgbaPng(width: number, height: number, pixels: ReadonlyArray<readonly number[]>): Uint8Array {
  const data = new Uint8Array(width * height * 4);
  pixels.forEach((p, i) => data.set([p[0]!, p[1]!, p[2]!, p[3] ?? 255], i * 4));
  return encodePng({ width, height, data, channels: 4 });
}

function mesh(doc: Document, buffer: GltfBuffer, name: string, material: Material, positions: number[], normals: number[], uvs: number[], indices: number[]): Mesh {
  const accessor = (type: 'SCALAR' | 'VEC2' | 'VEC3', array: Float32Array<ArrayBuffer> | Uint16Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', accessor('VEC3', new Float32Array(positions)))
    .setAttribute('NORMAL', accessor('VEC3', new Float32Array(normals)))
    .setAttribute('TEXCOORD_0', accessor('VEC2', new Float32Array(uvs)))
    .setIndices(accessor('SCALAR', new Uint16Array(indices)))
    .setMaterial(material);
  return doc.createMesh(name).addPrimitive(primitive);
}

/** The asset as .glb bytes. */
export async function createNormalMappedGlb(): Promise<Uint8Array> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  // Normals tilted a different way in each texel (tangent-space xyz mapped to bytes).
  const normalMap = doc.createTexture('normals').setMimeType('image/png').setImage(rgbaPng(2, 2, [[180, 128, 230], [128, 90, 235], [90, 160, 230], [150, 150, 240]]));
  const emissive = doc.createTexture('emissive').setMimeType('image/png').setImage(rgbaPng(2, 2, panelTexels));
  const panelMaterial = doc.createMaterial('panel').setBaseColorFactor([0, 0, 0, 1]).setMetallicFactor(1).setEmissiveFactor([1, 1, 1]).setEmissiveTexture(emissive).setNormalTexture(normalMap);
  for (const info of [panelMaterial.getEmissiveTextureInfo()!, panelMaterial.getNormalTextureInfo()!]) info.setMagFilter(NEAREST).setMinFilter(NEAREST);
  const patchMaterial = doc.createMaterial('patch').setBaseColorFactor([0.5, 0.5, 0.5, 1]).setMetallicFactor(0).setNormalTexture(normalMap).setNormalScale(0.7);

  // uv (0, 0) is the image's top-left texel: v grows downwards, y upwards.
  const panel = mesh(doc, buffer, 'panel', panelMaterial, [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0], [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1], [0, 1, 1, 1, 1, 0, 0, 0], [0, 1, 2, 0, 2, 3]);

  const n = 5;
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  const indices: number[] = [];
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i <= n; i++) {
      const a = (i / n) * (Math.PI / 2);
      positions.push(Math.sin(a), j / n, Math.cos(a));
      normals.push(Math.sin(a), 0, Math.cos(a));
      uvs.push(i / n + 0.3 * (j / n) * (j / n), 1 - j / n);
    }
  }
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i;
      indices.push(a, a + 1, a + n + 2, a, a + n + 2, a + n + 1);
    }
  }
  const patch = mesh(doc, buffer, 'patch', patchMaterial, positions, normals, uvs, indices);

  doc
    .createScene()
    .addChild(doc.createNode('panel').setMesh(panel))
    .addChild(doc.createNode('patch').setMesh(patch).setTranslation([0, 0, 6]));
  return new NodeIO().writeBinary(doc);
}

/** What the bundle tests compare between Node and the browser: every mesh's vertex streams. */
export interface MeshStreams {
  positions: number[];
  normals: number[];
  uvs: number[];
  tangents: number[];
  indices: number[];
}

/** The streams of a loaded scene's meshes as plain arrays (what a page can return). */
export function meshStreams(meshes: ReadonlyArray<{ positions: ArrayLike<number>; normals?: ArrayLike<number>; uvs?: ArrayLike<number>; tangents?: ArrayLike<number>; indices?: ArrayLike<number> }>): MeshStreams[] {
  return meshes.map((m) => ({
    positions: Array.from(m.positions),
    normals: Array.from(m.normals ?? []),
    uvs: Array.from(m.uvs ?? []),
    tangents: Array.from(m.tangents ?? []),
    indices: Array.from(m.indices ?? []),
  }));
}
