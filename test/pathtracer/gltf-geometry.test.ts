// glTF geometry end to end on the GPU: normals placed by the inverse transpose of a non-uniformly
// scaled node, flat shading of a primitive without NORMAL, front faces kept under mirroring node
// transforms (glTF 2.0 section 3.7.4), and EXT_mesh_gpu_instancing rendering like the same
// placements written as nodes. Expected normals come from the world-space triangles themselves
// (cross products), not from the renderer's matrices.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document, type Buffer as GltfBuffer, type Material, type Mesh } from '@gltf-transform/core';
import { EXTMeshGPUInstancing, KHRMaterialsIOR } from '@gltf-transform/extensions';
import { floatAccessor, orthographicCameraNode, quad, renderScene, roundTrip } from './gltf-scenes.ts';

function normalize(v: readonly number[]): number[] {
  const len = Math.hypot(...v);
  return v.map((x) => x / len);
}

function cross(a: readonly number[], b: readonly number[]): number[] {
  return [a[1]! * b[2]! - a[2]! * b[1]!, a[2]! * b[0]! - a[0]! * b[2]!, a[0]! * b[1]! - a[1]! * b[0]!];
}

function mesh(doc: Document, buffer: GltfBuffer, positions: number[], indices: number[], material: Material | null, normals?: number[]): Mesh {
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', floatAccessor(doc, buffer, 'VEC3', positions))
    .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint16Array(indices)).setBuffer(buffer));
  if (normals) primitive.setAttribute('NORMAL', floatAccessor(doc, buffer, 'VEC3', normals));
  if (material) primitive.setMaterial(material);
  return doc.createMesh().addPrimitive(primitive);
}

function assertNormal(normal: Float32Array, pixel: number, want: readonly number[], what: string): void {
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(normal[4 * pixel + c]! - want[c]!) < 1e-4, `${what}, pixel ${pixel} channel ${c}: ${normal[4 * pixel + c]} vs ${want[c]}`);
}

test('a non-uniformly scaled node: authored normals map by the inverse transpose (the world face normal)', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  // A quad spanned by e1 = (1, 0, -1) and e2 = (0, 1, 0) in object space, front normal (1, 0, 1) / sqrt 2.
  const e1 = [1, 0, -1];
  const e2 = [0, 1, 0];
  const corner = (i: number, j: number): number[] => [0, 1, 2].map((k) => 0.5 * i * e1[k]! + 1.5 * j * e2[k]!);
  const positions = [...corner(-1, -1), ...corner(1, -1), ...corner(1, 1), ...corner(-1, 1)];
  const n = normalize([1, 0, 1]);
  const slanted = mesh(doc, buffer, positions, [0, 1, 2, 0, 2, 3], null, [...n, ...n, ...n, ...n]);
  doc.createScene().addChild(orthographicCameraNode(doc, 2)).addChild(doc.createNode('stretched').setMesh(slanted).setScale([3, 1, 1]));
  const scene = await roundTrip(doc);
  const { normal } = await renderScene(scene, { width: 8, height: 8, aovs: true, environment: { color: [1, 1, 1] } }, 2);
  // World corners: x scaled by 3; the world face normal is cross((3, 0, -1), e2) = (1, 0, 3) / sqrt 10,
  // where the matrix itself would give normalize(3, 0, 1).
  const scaled = (p: number[]): number[] => [3 * p[0]!, p[1]!, p[2]!];
  const want = normalize(cross(scaled(e1), e2));
  for (let i = 0; i < 64; i++) assertNormal(normal!, i, want, 'inverse transpose');
});

test('a primitive without NORMAL is flat shaded: each facet of a ridge shows its own geometric normal', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  // A roof over [-1.5, 1.5]^2: ridge along y at x = 0, height 0.5, eaves at z = 0; 6 shared vertices.
  const positions = [-1.5, -1.5, 0, 0, -1.5, 0.5, 1.5, -1.5, 0, -1.5, 1.5, 0, 0, 1.5, 0.5, 1.5, 1.5, 0];
  const roof = mesh(doc, buffer, positions, [0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4], null);
  doc.createScene().addChild(orthographicCameraNode(doc, 2)).addChild(doc.createNode('roof').setMesh(roof));
  const scene = await roundTrip(doc);
  assert.equal(scene.meshes[0]!.normals, undefined);
  const { normal } = await renderScene(scene, { width: 16, height: 16, aovs: true, environment: { color: [1, 1, 1] } }, 2);
  const p = (i: number): number[] => positions.slice(3 * i, 3 * i + 3);
  const sub = (a: number[], b: number[]): number[] => a.map((v, k) => v - b[k]!);
  const left = normalize(cross(sub(p(1), p(0)), sub(p(4), p(0))));
  const right = normalize(cross(sub(p(2), p(1)), sub(p(5), p(1))));
  assert.ok(left[0]! < 0 && right[0]! > 0 && left[2]! > 0);
  // Pixel columns 0..7 cover x in [-1, 0] (left facet), 8..15 x in [0, 1]: no pixel straddles the ridge.
  for (let i = 0; i < 256; i++) assertNormal(normal!, i, i % 16 < 8 ? left : right, i % 16 < 8 ? 'left facet' : 'right facet');
});

test('mirroring node transforms keep the object-space front face: a one-sided emitter stays visible', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const lamp = doc.createMaterial('lamp').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 0.5, 0.25])
    .setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1));
  // The quad faces +z in object space. Left: mirrored in x (determinant -1), still facing +z.
  // Right: turned half a turn about y (determinant +1), facing -z: its back is towards the camera.
  const panel = quad(doc, buffer, lamp, { x0: -0.5, y0: -1, x1: 0.5, y1: 1 });
  doc.createScene()
    .addChild(orthographicCameraNode(doc, 2))
    .addChild(doc.createNode('mirrored').setMesh(panel).setScale([-1, 1, 1]).setTranslation([-0.5, 0, 0]))
    .addChild(doc.createNode('turned').setMesh(panel).setRotation([0, 1, 0, 0]).setTranslation([0.5, 0, 0]));
  const scene = await roundTrip(doc);
  assert.equal(scene.meshes.length, 1, 'one mesh, two instances');
  const { radiance } = await renderScene(scene, { width: 16, height: 16, environment: { color: [0, 0, 0] } }, 2);
  for (let i = 0; i < 256; i++) {
    const want = i % 16 < 8 ? [1, 0.5, 0.25] : [0, 0, 0];
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(radiance[4 * i + c]! - want[c]!) < 1e-6, `pixel ${i} channel ${c}: ${radiance[4 * i + c]} vs ${want[c]}`);
  }
});

test('EXT_mesh_gpu_instancing renders like the same placements written as nodes', async () => {
  const placements = [
    { t: [-0.6, 0.5, 0], r: [0, 0, Math.sin(0.3), Math.cos(0.3)], s: [0.3, 0.3, 0.3] },
    { t: [0.5, 0.4, 0.2], r: [Math.sin(0.4), 0, 0, Math.cos(0.4)], s: [0.4, 0.2, 0.4] },
    { t: [0, -0.5, -0.1], r: [0, Math.sin(0.2), 0, Math.cos(0.2)], s: [-0.35, 0.35, 0.35] },
  ];
  const build = (instanced: boolean): Document => {
    const doc = new Document();
    const buffer = doc.createBuffer();
    const material = doc.createMaterial('clay').setBaseColorFactor([0.7, 0.6, 0.5, 1]).setMetallicFactor(0);
    // A tetrahedron, counter-clockwise seen from outside.
    const tetra = mesh(doc, buffer, [1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1], [0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2], material);
    const floor = quad(doc, buffer, material, { x0: -2, y0: -2, x1: 2, y1: 2, z: -1, normals: true });
    const root = doc.createScene().addChild(orthographicCameraNode(doc, 2, [0, 0, 3])).addChild(doc.createNode('floor').setMesh(floor));
    if (instanced) {
      const ext = doc.createExtension(EXTMeshGPUInstancing).setRequired(true);
      const batch = ext
        .createInstancedMesh()
        .setAttribute('TRANSLATION', floatAccessor(doc, buffer, 'VEC3', placements.flatMap((p) => p.t)))
        .setAttribute('ROTATION', floatAccessor(doc, buffer, 'VEC4', placements.flatMap((p) => p.r)))
        .setAttribute('SCALE', floatAccessor(doc, buffer, 'VEC3', placements.flatMap((p) => p.s)));
      root.addChild(doc.createNode('batch').setMesh(tetra).setExtension('EXT_mesh_gpu_instancing', batch));
    } else {
      placements.forEach((p, i) => root.addChild(doc.createNode(`tetra ${i}`).setMesh(tetra).setTranslation(p.t as [number, number, number]).setRotation(p.r as [number, number, number, number]).setScale(p.s as [number, number, number])));
    }
    return doc;
  };
  const instanced = await roundTrip(build(true));
  const nodes = await roundTrip(build(false));
  assert.equal(instanced.meshes.length, 2, 'the tetrahedron once, not copied per instance');
  assert.equal(instanced.instances.length, 4);
  const options = { width: 24, height: 24, environment: { color: [0.8, 0.9, 1] } };
  const a = await renderScene(instanced, options, 8);
  const b = await renderScene(nodes, options, 8);
  // The same world geometry and samples; float32 instance matrices composed two ways can differ in
  // the last bit, which may move a rare grazing path.
  let same = 0;
  for (let i = 0; i < a.radiance.length; i += 4) if ([0, 1, 2].every((c) => Math.abs(a.radiance[i + c]! - b.radiance[i + c]!) <= 1e-4)) same++;
  assert.ok(same >= 0.98 * (a.radiance.length / 4), `${same} of ${a.radiance.length / 4} pixels agree`);
});
