import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document } from '@gltf-transform/core';
import { encode as encodePng } from 'fast-png';
import { loadGltfScene } from '../../../src/io/index.ts';
import { accessor, toGlb } from './helpers.ts';

/** A curved, normal-mapped surface without TANGENT: a cylinder patch with a skewed uv layout. */
function normalMappedPatch(doc: Document, withNormals: boolean): void {
  const buffer = doc.createBuffer();
  const n = 6;
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i <= n; i++) {
      const a = (i / n) * (Math.PI / 2);
      positions.push(Math.sin(a), j / n, Math.cos(a));
      normals.push(Math.sin(a), 0, Math.cos(a));
      // u grows with the angle, v with height (downwards in image space) plus a shear.
      uvs.push(i / n + 0.2 * (j / n), 1 - j / n);
    }
  }
  const indices: number[] = [];
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i;
      indices.push(a, a + 1, a + n + 2, a, a + n + 2, a + n + 1);
    }
  }
  const normalMap = doc.createTexture('normal').setMimeType('image/png').setImage(encodePng({ width: 1, height: 1, data: new Uint8Array([128, 128, 255, 255]), channels: 4 }));
  const material = doc.createMaterial('bumpy').setNormalTexture(normalMap).setNormalScale(0.5);
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array(positions)))
    .setAttribute('TEXCOORD_0', accessor(doc, buffer, 'VEC2', new Float32Array(uvs)))
    .setIndices(accessor(doc, buffer, 'SCALAR', new Uint16Array(indices)))
    .setMaterial(material);
  if (withNormals) primitive.setAttribute('NORMAL', accessor(doc, buffer, 'VEC3', new Float32Array(normals)));
  doc.createScene().addChild(doc.createNode('patch').setMesh(doc.createMesh().addPrimitive(primitive)));
}

function vec(a: ArrayLike<number>, i: number, size: number): number[] {
  return Array.from({ length: size }, (_, k) => a[i * size + k]);
}

const dot = (a: number[], b: number[]): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const sub = (a: number[], b: number[]): number[] => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross = (a: number[], b: number[]): number[] => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];

/**
 * Checks MikkTSpace output: unit, orthogonal to the normal, w = +-1, the tangent along +du per
 * triangle and the bitangent along -dv (glTF's uv origin is the top left and normal maps' +Y is up).
 */
function checkTangents(mesh: { positions: ArrayLike<number>; normals?: ArrayLike<number>; uvs?: ArrayLike<number>; tangents?: ArrayLike<number>; indices?: ArrayLike<number> }): void {
  const { positions, normals, uvs, tangents, indices } = mesh;
  assert.ok(tangents && normals && uvs && indices);
  assert.equal(tangents.length / 4, positions.length / 3);
  for (let v = 0; v < tangents.length / 4; v++) {
    const t = vec(tangents, v, 4);
    const nrm = vec(normals, v, 3);
    assert.ok(Math.abs(Math.hypot(t[0], t[1], t[2]) - 1) < 1e-4, `tangent ${v} not unit: ${t}`);
    assert.ok(Math.abs(dot(t, nrm)) < 1e-4, `tangent ${v} not orthogonal to its normal`);
    assert.ok(t[3] === 1 || t[3] === -1, `w = ${t[3]}`);
  }
  // Per triangle, the uv gradient dP/du (solved from the edge equations) points along the tangent
  // and dP/dv against w * (n x t) (glTF: bitangent = cross(normal, tangent.xyz) * w, towards
  // decreasing v; every triangle of Khronos's NormalTangentMirrorTest, authored in Blender, agrees).
  for (let f = 0; f < indices.length; f += 3) {
    const [a, b, c] = [indices[f], indices[f + 1], indices[f + 2]];
    const [pa, pb, pc] = [a, b, c].map((i) => vec(positions, i, 3));
    const [ta, tb, tc] = [a, b, c].map((i) => vec(uvs, i, 2));
    const e1 = sub(pb, pa);
    const e2 = sub(pc, pa);
    const [du1, dv1, du2, dv2] = [tb[0] - ta[0], tb[1] - ta[1], tc[0] - ta[0], tc[1] - ta[1]];
    const r = 1 / (du1 * dv2 - du2 * dv1);
    const dPdu = [0, 1, 2].map((k) => (e1[k] * dv2 - e2[k] * dv1) * r);
    const dPdv = [0, 1, 2].map((k) => (e2[k] * du1 - e1[k] * du2) * r);
    for (const i of [a, b, c]) {
      const t = vec(tangents, i, 4);
      assert.ok(dot(t, dPdu) > 0, `triangle ${f / 3}: tangent opposes dP/du`);
      const bitangent = cross(vec(normals, i, 3), t).map((x) => x * t[3]);
      assert.ok(dot(bitangent, dPdv) < 0, `triangle ${f / 3}: bitangent along +dP/dv (image down)`);
    }
  }
}

test('a normal-mapped mesh without TANGENT gets MikkTSpace tangents', async () => {
  const doc = new Document();
  normalMappedPatch(doc, true);
  const scene = await loadGltfScene(await toGlb(doc));
  const mesh = scene.meshes[0];
  checkTangents(mesh);
  // Welding back: a smooth patch with continuous uvs needs no more vertices than the input.
  assert.equal(mesh.positions.length / 3, 49);
  assert.equal(mesh.indices!.length, 6 * 6 * 6);
  assert.deepEqual(scene.materials[0].normalTexture, { index: 0, texCoord: 0, scale: 0.5 });
});

test('without NORMAL, flat normals are computed first (for that case only), with a warning', async () => {
  const doc = new Document();
  normalMappedPatch(doc, false);
  const scene = await loadGltfScene(await toGlb(doc));
  const mesh = scene.meshes[0];
  checkTangents(mesh);
  assert.ok(scene.warnings.some((w) => /flat normals/.test(w)));
  // Flat normals equal each triangle's geometric normal (counter-clockwise front).
  const idx = mesh.indices!;
  for (let f = 0; f < idx.length; f += 3) {
    const [pa, pb, pc] = [idx[f], idx[f + 1], idx[f + 2]].map((i) => vec(mesh.positions, i, 3));
    const g = cross(sub(pb, pa), sub(pc, pa));
    const len = Math.hypot(...g);
    for (const i of [idx[f], idx[f + 1], idx[f + 2]]) {
      const nrm = vec(mesh.normals!, i, 3);
      assert.ok(dot(nrm, g) / len > 1 - 1e-5, `triangle ${f / 3}`);
    }
  }
});

/** The eight uv layouts of a square (rotations by k quarter turns about its centre, optionally mirrored). */
function uvLayouts(): { name: string; uv: (u: number, v: number) => [number, number] }[] {
  const out: { name: string; uv: (u: number, v: number) => [number, number] }[] = [];
  for (const mirrored of [false, true]) {
    for (let k = 0; k < 4; k++) {
      out.push({
        name: `${mirrored ? 'mirrored, ' : ''}rotated ${90 * k} degrees`,
        uv: (u0, v0) => {
          let [u, v] = [mirrored ? 1 - u0 : u0, v0];
          for (let r = 0; r < k; r++) [u, v] = [1 - v, u];
          return [u, v];
        },
      });
    }
  }
  return out;
}

/**
 * A normal-mapped square (facing +z, four vertices) with its uvs laid out by `uv`; with `authored`
 * it carries TANGENT as glTF defines it: T = dP/du, and w such that cross(N, T) w points towards
 * decreasing v (the image's up).
 */
function layoutSquare(uv: (u: number, v: number) => [number, number], authored: boolean): Document {
  const doc = new Document();
  const buffer = doc.createBuffer();
  // Corners bottom left, bottom right, top right, top left; (u, v) = (0, 1) at the bottom left.
  const positions = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0];
  const uvs = [uv(0, 1), uv(1, 1), uv(1, 0), uv(0, 0)];
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array(positions)))
    .setAttribute('NORMAL', accessor(doc, buffer, 'VEC3', new Float32Array([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1])))
    .setAttribute('TEXCOORD_0', accessor(doc, buffer, 'VEC2', new Float32Array(uvs.flat())))
    .setIndices(accessor(doc, buffer, 'SCALAR', new Uint16Array([0, 1, 2, 0, 2, 3])));
  if (authored) {
    // dP/du and dP/dv of the (affine) layout from two edges: P = p0 + x (1, 0, 0) + y (0, 1, 0).
    const [a, b, d] = [uvs[0]!, uvs[1]!, uvs[3]!];
    const dudx = b[0] - a[0];
    const dvdx = b[1] - a[1];
    const dudy = d[0] - a[0];
    const dvdy = d[1] - a[1];
    const det = dudx * dvdy - dudy * dvdx;
    const dPdu = [dvdy / det, -dvdx / det, 0];
    const dPdv = [-dudy / det, dudx / det, 0];
    const t = dPdu.map((x) => x / Math.hypot(...dPdu));
    const w = dot(cross([0, 0, 1], t), dPdv) < 0 ? 1 : -1;
    primitive.setAttribute('TANGENT', accessor(doc, buffer, 'VEC4', new Float32Array([0, 1, 2, 3].flatMap(() => [...t, w]))));
  }
  const normalMap = doc.createTexture('normal').setMimeType('image/png').setImage(encodePng({ width: 1, height: 1, data: new Uint8Array([200, 90, 230, 255]), channels: 4 }));
  primitive.setMaterial(doc.createMaterial('bumpy').setNormalTexture(normalMap));
  doc.createScene().addChild(doc.createNode('square').setMesh(doc.createMesh().addPrimitive(primitive)));
  return doc;
}

/** Shading normal per vertex position (glTF 2.0 section 3.9.3: normalize(T m.x + B m.y + N m.z), B = cross(N, T) w). */
function shadingNormals(mesh: { positions: ArrayLike<number>; normals?: ArrayLike<number>; tangents?: ArrayLike<number> }, m: number[]): Map<string, number[]> {
  const out = new Map<string, number[]>();
  for (let v = 0; v < mesh.positions.length / 3; v++) {
    const nrm = vec(mesh.normals!, v, 3);
    const t = vec(mesh.tangents!, v, 4);
    const b = cross(nrm, t).map((x) => x * t[3]);
    const s = [0, 1, 2].map((k) => t[k] * m[0] + b[k] * m[1] + nrm[k] * m[2]);
    const len = Math.hypot(...s);
    out.set(vec(mesh.positions, v, 3).join(','), s.map((x) => x / len));
  }
  return out;
}

test('generated tangents shade a normal map exactly as authored TANGENTs do, for every rotated and mirrored uv layout', async () => {
  const m = [200 / 255, 90 / 255, 230 / 255].map((x) => x * 2 - 1);
  for (const layout of uvLayouts()) {
    const authored = (await loadGltfScene(await toGlb(layoutSquare(layout.uv, true)))).meshes[0];
    const generated = (await loadGltfScene(await toGlb(layoutSquare(layout.uv, false)))).meshes[0];
    const want = shadingNormals(authored, m);
    const got = shadingNormals(generated, m);
    assert.equal(got.size, 4, layout.name);
    for (const [corner, n] of got) {
      const w = want.get(corner)!;
      for (let k = 0; k < 3; k++) assert.ok(Math.abs(n[k] - w[k]) < 1e-5, `${layout.name}, corner ${corner}: shading normal ${n} vs authored ${w}`);
    }
    checkTangents(generated);
  }
});
