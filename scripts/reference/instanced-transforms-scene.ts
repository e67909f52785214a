// The instanced-transforms comparison scene (issue 25), written from the one spec below:
//   - scene.glb: what the renderer loads (test/accel/instanced-transforms-scene.ts). Two shared
//     meshes, a smooth icosphere (vertex normals) and a chiral "L" prism (flat; its front cap a
//     primitive of its own colour, so a mirror image differs from every rotation of it), placed by
//     several nodes reusing them (rotations, non-uniform scales, a parent whose non-uniform scale
//     shears a rotated child, mirroring scales) and by two EXT_mesh_gpu_instancing nodes whose
//     TRANSLATION / ROTATION / SCALE instances include non-uniform and negative scales (one with
//     two negative factors: determinant positive); a diffuse ground quad, a one-sided emissive quad
//     light and the camera. Every material is single-sided (doubleSided false): camera rays cull
//     back faces, so a mirrored instance whose winding were not flipped would show its inside.
//   - mitsuba/*.ply: the same scene flattened to world-space triangles by this script itself (its
//     own TRS composition with wgpu-matrix, normals by the inverse transpose, winding reversed
//     under a negative determinant), one file per material, for
//     scripts/reference/instanced_transforms_mitsuba.py;
//   - scene.json: image size, blocks, depth, camera, environment, light and materials, and which
//     PLY carries which material.
//
//     node scripts/reference/instanced-transforms-scene.ts
//     python3 scripts/reference/instanced_transforms_mitsuba.py
import { mkdirSync, writeFileSync } from 'node:fs';
import { Document, NodeIO, type Buffer as GltfBuffer, type Material, type Node, type TypedArray } from '@gltf-transform/core';
import { EXTMeshGPUInstancing, KHRMaterialsEmissiveStrength, KHRMaterialsIOR } from '@gltf-transform/extensions';
import { mat3d, mat4d, quatd, vec3d } from 'wgpu-matrix';
import { icosphere } from '../../test/helpers/meshes.ts';

type Vec3 = [number, number, number];

/** A placement: translation, rotation (axis, degrees) and scale, as a glTF node or instance has them. */
interface Trs { t?: Vec3; axis?: Vec3; degrees?: number; s?: Vec3 }

interface NodeSpec extends Trs {
  name: string;
  mesh?: MeshName;
  /** EXT_mesh_gpu_instancing instances of `mesh` (placed by this node's world matrix). */
  instances?: Trs[];
  children?: NodeSpec[];
}

type MeshName = 'sphere' | 'ell';
type MaterialName = 'ground' | 'sphere' | 'ellBody' | 'ellCap';

const groundHalfSize = 20;

const spec = {
  description: 'Instances of shared meshes (reused nodes, a sheared hierarchy, EXT_mesh_gpu_instancing) with rotations, non-uniform and mirroring scales, on a diffuse ground under a one-sided quad light and a constant environment. Written by scripts/reference/instanced-transforms-scene.ts; read by test/accel/instanced-transforms-scene.ts and scripts/reference/instanced_transforms_mitsuba.py.',
  width: 96,
  height: 96,
  block: 8,
  maxDepth: 5,
  camera: { position: [0, 6.2, 6.4] as Vec3, target: [0.2, 0.3, -0.45] as Vec3, up: [0, 1, 0] as Vec3, fovYDegrees: 40 },
  environment: [0.18, 0.2, 0.23] as Vec3,
  // Counter-clockwise seen from below: it emits downwards (off to the left, for slanted shadows).
  light: { corners: [[-3.5, 4.5, -1.2], [-2, 4.5, -1.2], [-2, 4.5, 0.3], [-3.5, 4.5, 0.3]] as Vec3[], radiance: [16, 15, 14] as Vec3 },
  materials: {
    ground: [0.55, 0.55, 0.5],
    sphere: [0.8, 0.22, 0.15],
    ellBody: [0.2, 0.62, 0.25],
    ellCap: [0.15, 0.3, 0.85],
  } satisfies Record<MaterialName, Vec3>,
  sphere: { radius: 0.5, subdivisions: 3 },
  // The L's cross-section in its xy plane (counter-clockwise), extruded over z in [-depth/2, depth/2].
  ell: { outline: [[0, 0], [1, 0], [1, 0.35], [0.35, 0.35], [0.35, 1], [0, 1]] as Array<[number, number]>, depth: 0.45 },
  // Standing L prisms are sunk 0.02 into the ground (no coplanar faces).
  nodes: [
    { name: 'sphere plain', mesh: 'sphere', t: [-2.1, 0.5, 1.4] },
    {
      name: 'shearing parent', t: [-0.6, 0, 1.5], axis: [0, 1, 0], degrees: 35, s: [1.6, 0.7, 0.9],
      children: [{ name: 'sphere sheared', mesh: 'sphere', t: [0, 0.42, 0], axis: [0, 0, 1], degrees: 40, s: [1, 0.6, 1] }],
    },
    { name: 'sphere mirrored', mesh: 'sphere', t: [0.9, 0.42, 1.75], axis: [1, 1, 0], degrees: 25, s: [-0.9, 0.8, 1.1] },
    {
      name: 'sphere instances', mesh: 'sphere', t: [2.1, 0, 0.3], axis: [0, 1, 0], degrees: 30, s: [1.2, 1, 0.8],
      instances: [
        { t: [0, 0.4, 0], s: [0.8, 0.8, 0.8] },
        { t: [-0.3, 0.3, 1.4], axis: [1, 0, 0], degrees: 60, s: [1.2, 0.5, 0.7] },
        { t: [-0.8, 0.4, -1.0], axis: [0, 1, 1], degrees: 45, s: [0.7, -0.9, 0.6] },
      ],
    },
    { name: 'ell plain', mesh: 'ell', t: [-2.7, -0.02, -0.9], axis: [0, 1, 0], degrees: 20 },
    { name: 'ell mirrored', mesh: 'ell', t: [-0.5, -0.02, -1.2], axis: [0, 1, 0], degrees: -15, s: [-1, 1.2, 0.8] },
    {
      name: 'ell instances', mesh: 'ell', t: [0.3, -0.02, -2.1], axis: [0, 1, 0], degrees: 10,
      instances: [
        { t: [0, 0, 0] },
        { t: [1.5, 0, -0.3], axis: [0, 1, 0], degrees: 70, s: [0.6, 1.4, 1] },
        { t: [2.9, 0, 0.2], s: [-0.8, 0.8, 0.8] },
        { t: [1.1, 0.27, 1.3], axis: [1, 0, 0], degrees: -90, s: [-0.7, -0.7, 0.7] },
      ],
    },
  ] satisfies NodeSpec[] as NodeSpec[],
};

interface MeshData { positions: number[]; normals?: number[]; primitives: Array<{ indices: number[]; material: MaterialName }> }

function sphereMesh(): MeshData {
  const { radius, subdivisions } = spec.sphere;
  const { positions, indices } = icosphere(radius, [0, 0, 0], subdivisions);
  return { positions, normals: positions.map((v) => v / radius), primitives: [{ indices, material: 'sphere' }] };
}

/** The L prism: the front cap (z = +depth/2, facing +z) one primitive, the back cap and sides another. */
function ellMesh(): MeshData {
  const { outline, depth } = spec.ell;
  const n = outline.length;
  const positions = [...outline.flatMap(([x, y]) => [x, y, depth / 2]), ...outline.flatMap(([x, y]) => [x, y, -depth / 2])];
  // The outline is star-shaped from its corner 0: a fan triangulates it counter-clockwise.
  const cap: number[] = [];
  const body: number[] = [];
  for (let i = 1; i < n - 1; i++) {
    cap.push(0, i, i + 1);
    body.push(n, n + i + 1, n + i); // the back cap, reversed
  }
  for (let i = 0; i < n; i++) {
    const j = (i + 1) % n;
    // Outward for a counter-clockwise outline: cross((j - i) back, j front - i back) = (dy, -dx, 0).
    body.push(n + i, n + j, j, n + i, j, i);
  }
  return { positions, primitives: [{ indices: body, material: 'ellBody' }, { indices: cap, material: 'ellCap' }] };
}

function quad(corners: Vec3[]): { positions: number[]; indices: number[] } {
  return { positions: corners.flat(), indices: [0, 1, 2, 0, 2, 3] };
}

const meshes: Record<MeshName, MeshData> = { sphere: sphereMesh(), ell: ellMesh() };

/** The TRS values as the .glb stores them (float32), so the flattening uses exactly what the loader reads. */
function storedTrs(p: Trs): { t: Vec3; r: [number, number, number, number]; s: Vec3 } {
  const q = p.degrees ? quatd.fromAxisAngle(vec3d.normalize(p.axis ?? [0, 1, 0]), (p.degrees * Math.PI) / 180) : [0, 0, 0, 1];
  const f = (v: ArrayLike<number>): number[] => Array.from(v, Math.fround);
  return { t: f(p.t ?? [0, 0, 0]) as Vec3, r: f(q) as [number, number, number, number], s: f(p.s ?? [1, 1, 1]) as Vec3 };
}

function trsMatrix(p: Trs): Float64Array {
  const { t, r, s } = storedTrs(p);
  return mat4d.multiply(mat4d.multiply(mat4d.translation(t), mat4d.fromQuat(r)), mat4d.scaling(s));
}

// ---- the flattened scene (for Mitsuba) ----

interface Bucket { positions: number[]; normals: number[]; indices: number[] }
const buckets = new Map<MaterialName, Bucket>();
const placements: string[] = [];
const boxes: Array<{ name: string; min: number[]; max: number[] }> = [];

function flatten(mesh: MeshData, world: Float64Array, name: string): void {
  const det = mat4d.determinant(world);
  // Normals by the inverse transpose of the linear part; the winding reverses under a mirror.
  const normalMatrix = mat3d.transpose(mat3d.inverse(mat3d.fromMat4(world)));
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < mesh.positions.length / 3; v++) {
    const p = vec3d.transformMat4(mesh.positions.slice(3 * v, 3 * v + 3), world);
    for (let c = 0; c < 3; c++) { min[c] = Math.min(min[c]!, p[c]!); max[c] = Math.max(max[c]!, p[c]!); }
  }
  const clash = boxes.find((b) => b.min.every((m, c) => m < max[c]! && min[c]! < b.max[c]!));
  if (clash) throw new Error(`the bounds of ${name} and ${clash.name} overlap`);
  boxes.push({ name, min, max });
  const f = (v: number[]): string => v.map((c) => c.toFixed(2)).join(', ');
  placements.push(`${name}: determinant ${det.toFixed(3)}, bounds (${f(min)}) to (${f(max)})`);
  for (const primitive of mesh.primitives) {
    const bucket = buckets.get(primitive.material) ?? { positions: [], normals: [], indices: [] };
    buckets.set(primitive.material, bucket);
    const base = bucket.positions.length / 3;
    for (let v = 0; v < mesh.positions.length / 3; v++) {
      bucket.positions.push(...vec3d.transformMat4(mesh.positions.slice(3 * v, 3 * v + 3), world));
      if (mesh.normals) bucket.normals.push(...vec3d.normalize(vec3d.transformMat3(mesh.normals.slice(3 * v, 3 * v + 3), normalMatrix)));
    }
    for (let k = 0; k < primitive.indices.length; k += 3) {
      const [a, b, c] = primitive.indices.slice(k, k + 3) as [number, number, number];
      bucket.indices.push(...(det < 0 ? [a, c, b] : [a, b, c]).map((i) => base + i));
    }
  }
}

function walk(node: NodeSpec, parent: Float64Array): void {
  const world = mat4d.multiply(parent, trsMatrix(node));
  if (node.mesh && node.instances) node.instances.forEach((instance, i) => flatten(meshes[node.mesh!], mat4d.multiply(world, trsMatrix(instance)), `${node.name} #${i}`));
  else if (node.mesh) flatten(meshes[node.mesh], world, node.name);
  for (const child of node.children ?? []) walk(child, world);
}

for (const node of spec.nodes) walk(node, mat4d.identity());

/** Binary little-endian PLY: float positions (and normals), uchar-int triangle lists. */
function ply(positions: number[], indices: number[], normals?: number[]): Uint8Array {
  const vertices = positions.length / 3, faces = indices.length / 3, stride = normals ? 24 : 12;
  const header = `ply\nformat binary_little_endian 1.0\nelement vertex ${vertices}\nproperty float x\nproperty float y\nproperty float z\n`
    + (normals ? 'property float nx\nproperty float ny\nproperty float nz\n' : '')
    + `element face ${faces}\nproperty list uchar int vertex_indices\nend_header\n`;
  const head = new TextEncoder().encode(header);
  const out = new Uint8Array(head.length + vertices * stride + faces * 13);
  out.set(head);
  const view = new DataView(out.buffer, head.length);
  for (let v = 0; v < vertices; v++) {
    for (let c = 0; c < 3; c++) view.setFloat32(v * stride + 4 * c, positions[3 * v + c]!, true);
    if (normals) for (let c = 0; c < 3; c++) view.setFloat32(v * stride + 12 + 4 * c, normals[3 * v + c]!, true);
  }
  for (let f = 0; f < faces; f++) {
    const o = vertices * stride + 13 * f;
    view.setUint8(o, 3);
    for (let c = 0; c < 3; c++) view.setInt32(o + 1 + 4 * c, indices[3 * f + c]!, true);
  }
  return out;
}

// ---- the .glb ----

const doc = new Document();
const buffer = doc.createBuffer();
const ior = doc.createExtension(KHRMaterialsIOR);
const emissiveStrength = doc.createExtension(KHRMaterialsEmissiveStrength);
const instancing = doc.createExtension(EXTMeshGPUInstancing).setRequired(true);
const accessor = (type: 'SCALAR' | 'VEC3' | 'VEC4', values: readonly number[], buf: GltfBuffer = buffer) =>
  doc.createAccessor().setType(type).setBuffer(buf).setArray((type === 'SCALAR' ? new Uint16Array(values) : new Float32Array(values)) as TypedArray);

// ior 1: the glTF dielectric's specular layer vanishes, the BSDF is Lambertian (Mitsuba's `diffuse`).
function diffuse(name: MaterialName): Material {
  return doc.createMaterial(name).setBaseColorFactor([...spec.materials[name], 1]).setMetallicFactor(0).setRoughnessFactor(1).setDoubleSided(false)
    .setExtension('KHR_materials_ior', ior.createIOR().setIOR(1));
}
const materials = Object.fromEntries((Object.keys(spec.materials) as MaterialName[]).map((name) => [name, diffuse(name)])) as Record<MaterialName, Material>;

const gltfMeshes = Object.fromEntries((Object.keys(meshes) as MeshName[]).map((name) => {
  const data = meshes[name];
  const position = accessor('VEC3', data.positions);
  const normal = data.normals ? accessor('VEC3', data.normals) : undefined;
  const mesh = doc.createMesh(name);
  for (const p of data.primitives) {
    const primitive = doc.createPrimitive().setAttribute('POSITION', position).setIndices(accessor('SCALAR', p.indices)).setMaterial(materials[p.material]);
    if (normal) primitive.setAttribute('NORMAL', normal);
    mesh.addPrimitive(primitive);
  }
  return [name, mesh];
})) as Record<MeshName, ReturnType<Document['createMesh']>>;

function gltfNode(n: NodeSpec): Node {
  const { t, r, s } = storedTrs(n);
  const node = doc.createNode(n.name).setTranslation(t).setRotation(r).setScale(s);
  if (n.mesh) node.setMesh(gltfMeshes[n.mesh]);
  if (n.instances) {
    const stored = n.instances.map(storedTrs);
    node.setExtension('EXT_mesh_gpu_instancing', instancing.createInstancedMesh()
      .setAttribute('TRANSLATION', accessor('VEC3', stored.flatMap((i) => i.t)))
      .setAttribute('ROTATION', accessor('VEC4', stored.flatMap((i) => i.r)))
      .setAttribute('SCALE', accessor('VEC3', stored.flatMap((i) => i.s))));
  }
  for (const child of n.children ?? []) node.addChild(gltfNode(child));
  return node;
}

function quadNode(name: string, corners: Vec3[], material: Material): Node {
  const q = quad(corners);
  const primitive = doc.createPrimitive().setAttribute('POSITION', accessor('VEC3', q.positions)).setIndices(accessor('SCALAR', q.indices)).setMaterial(material);
  return doc.createNode(name).setMesh(doc.createMesh(name).addPrimitive(primitive));
}

const h = groundHalfSize;
const groundCorners: Vec3[] = [[-h, 0, h], [h, 0, h], [h, 0, -h], [-h, 0, -h]]; // counter-clockwise from above
const radiance = spec.light.radiance, strength = Math.max(...radiance);
const lightMaterial = doc.createMaterial('light').setBaseColorFactor([0, 0, 0, 1]).setMetallicFactor(0).setRoughnessFactor(1).setDoubleSided(false)
  .setEmissiveFactor(radiance.map((v) => v / strength) as Vec3)
  .setExtension('KHR_materials_emissive_strength', emissiveStrength.createEmissiveStrength().setEmissiveStrength(strength));

const cam = spec.camera;
const aim = mat4d.cameraAim(cam.position, cam.target, cam.up); // columns: x, y, z = away from the target
const cameraNode = doc.createNode('camera').setTranslation(cam.position).setRotation(Array.from(quatd.fromMat(aim), Math.fround) as [number, number, number, number])
  .setCamera(doc.createCamera('camera').setType('perspective').setYFov((cam.fovYDegrees * Math.PI) / 180).setAspectRatio(spec.width / spec.height).setZNear(0.05).setZFar(100));

const scene = doc.createScene('instanced transforms');
for (const n of spec.nodes) scene.addChild(gltfNode(n));
scene.addChild(quadNode('ground', groundCorners, materials.ground)).addChild(quadNode('light', spec.light.corners, lightMaterial)).addChild(cameraNode);
doc.getRoot().setDefaultScene(scene);

// ---- checks of the setup itself: the view sees only the ground (no sky, no light) ----

{
  const tanHalf = Math.tan((cam.fovYDegrees * Math.PI) / 360), aspect = spec.width / spec.height;
  const forward = vec3d.negate(aim.slice(8, 11)), right = aim.slice(0, 3), up = aim.slice(4, 7);
  for (const [sx, sy] of [[-1, -1], [1, -1], [1, 1], [-1, 1]] as const) {
    const d = vec3d.add(forward, vec3d.add(vec3d.scale(right, sx * tanHalf * aspect), vec3d.scale(up, sy * tanHalf)));
    const along = -cam.position[1] / d[1]!;
    const hit = vec3d.add(cam.position, vec3d.scale(d, along));
    if (!(along > 0) || Math.abs(hit[0]!) >= h || Math.abs(hit[2]!) >= h) throw new Error(`the corner ray (${sx}, ${sy}) leaves the ground (${hit[0]!.toFixed(2)}, ${hit[2]!.toFixed(2)})`);
  }
  for (const corner of spec.light.corners) {
    const v = vec3d.subtract(corner, cam.position);
    const z = vec3d.dot(v, forward);
    if (z > 0 && Math.abs(vec3d.dot(v, up) / z) < tanHalf && Math.abs(vec3d.dot(v, right) / z) < tanHalf * aspect) throw new Error('the light is in view');
  }
}

// ---- output ----

const folder = new URL('../../test/accel/fixtures/instanced-transforms/', import.meta.url);
mkdirSync(new URL('mitsuba/', folder), { recursive: true });
const glb = await new NodeIO().registerExtensions([KHRMaterialsIOR, KHRMaterialsEmissiveStrength, EXTMeshGPUInstancing]).writeBinary(doc);
writeFileSync(new URL('scene.glb', folder), glb);

const shapes: Array<{ ply: string; material: string; smooth: boolean }> = [];
const writePly = (name: string, bytes: Uint8Array): void => writeFileSync(new URL(`mitsuba/${name}`, folder), bytes);
for (const [material, b] of buckets) {
  const smooth = b.normals.length > 0;
  writePly(`${material}.ply`, ply(b.positions, b.indices, smooth ? b.normals : undefined));
  shapes.push({ ply: `mitsuba/${material}.ply`, material, smooth });
}
writePly('ground.ply', ply(groundCorners.flat(), quad(groundCorners).indices));
writePly('light.ply', ply(spec.light.corners.flat(), quad(spec.light.corners).indices));
shapes.push({ ply: 'mitsuba/ground.ply', material: 'ground', smooth: false });

const { nodes: _nodes, sphere: _sphere, ell: _ell, ...json } = spec;
// Two-space JSON with every array of numbers on one line.
const text = JSON.stringify({ ...json, light: { ...spec.light, ply: 'mitsuba/light.ply' }, shapes, placements }, null, 2)
  .replace(/\[\s+(-?[\d.e-]+(?:,\s+-?[\d.e-]+)*)\s+\]/g, (_, inner: string) => `[${inner.split(/,\s+/).join(', ')}]`);
writeFileSync(new URL('scene.json', folder), `${text}\n`);
console.log(`wrote scene.glb (${glb.byteLength} bytes), scene.json and ${shapes.length + 1} PLY files (${[...buckets.values()].reduce((n, b) => n + b.indices.length / 3, 0)} object triangles) in ${folder.pathname}`);
for (const line of placements) console.log(`  ${line}`);
