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

/** Checks MikkTSpace output: unit, orthogonal to the normal, w = +-1, and along +du per triangle. */
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
  // and dP/dv along w * (n x t) (glTF: bitangent = cross(normal, tangent.xyz) * w).
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
      assert.ok(dot(bitangent, dPdv) > 0, `triangle ${f / 3}: bitangent sign disagrees with dP/dv`);
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
