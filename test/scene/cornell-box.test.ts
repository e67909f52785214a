import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import type { WavefrontMaterialInput, WavefrontMeshInput } from '../../src/scene/types.ts';

type V3 = [number, number, number];
const sub = (a: V3, b: V3): V3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a: V3, b: V3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a: V3, b: V3): V3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a: V3): V3 => {
  const l = Math.hypot(...a);
  return [a[0] / l, a[1] / l, a[2] / l];
};

interface Tri {
  v: [V3, V3, V3];
  n: V3;
  centroid: V3;
}

function triangles(mesh: WavefrontMeshInput): Tri[] {
  const p = Array.from(mesh.positions);
  const idx = Array.from(mesh.indices ?? p.map((_, i) => i).slice(0, p.length / 3));
  const vert = (i: number): V3 => [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
  const out: Tri[] = [];
  for (let t = 0; t < idx.length; t += 3) {
    const v: [V3, V3, V3] = [vert(idx[t]), vert(idx[t + 1]), vert(idx[t + 2])];
    out.push({
      v,
      n: normalize(cross(sub(v[1], v[0]), sub(v[2], v[0]))),
      centroid: [0, 1, 2].map((k) => (v[0][k] + v[1][k] + v[2][k]) / 3) as V3,
    });
  }
  return out;
}

const scene = createCornellBoxScene();
const meshes = new Map((scene.meshes ?? []).map((m) => [String(m.id), m]));

test('every mesh is a valid triangle list with finite positions inside [-1, 1]^3', () => {
  assert.deepEqual([...meshes.keys()].sort(), ['back-wall', 'ceiling', 'floor', 'left-wall', 'light', 'right-wall', 'short-block', 'tall-block']);
  for (const [id, mesh] of meshes) {
    const positions = Array.from(mesh.positions);
    assert.equal(positions.length % 3, 0, id);
    assert.ok(positions.every((x) => Number.isFinite(x) && Math.abs(x) <= 1 + 1e-12), id);
    const indices = Array.from(mesh.indices ?? []);
    assert.ok(indices.length > 0 && indices.length % 3 === 0, id);
    assert.ok(indices.every((i) => Number.isInteger(i) && i >= 0 && i < positions.length / 3), id);
    for (const t of triangles(mesh)) assert.ok(Math.hypot(...cross(sub(t.v[1], t.v[0]), sub(t.v[2], t.v[0]))) > 1e-3, `${id}: degenerate triangle`);
  }
});

test('walls face into the box', () => {
  const expected: Record<string, V3> = {
    floor: [0, 1, 0],
    ceiling: [0, -1, 0],
    'back-wall': [0, 0, 1],
    'left-wall': [1, 0, 0],
    'right-wall': [-1, 0, 0],
  };
  for (const [id, normal] of Object.entries(expected)) {
    for (const t of triangles(meshes.get(id)!)) {
      assert.ok(dot(t.n, normal) > 1 - 1e-12, `${id}: normal ${t.n}`);
      // Pointing towards the box centre.
      assert.ok(dot(t.n, sub([0, 0, 0], t.centroid)) > 0, id);
    }
  }
});

test('the blocks are closed boxes on the floor whose faces point out of the block (into the room)', () => {
  for (const id of ['short-block', 'tall-block']) {
    const mesh = meshes.get(id)!;
    const tris = triangles(mesh);
    assert.equal(tris.length, 12);
    const positions = Array.from(mesh.positions);
    const n = positions.length / 3;
    const centre = [0, 1, 2].map((k) => positions.filter((_, i) => i % 3 === k).reduce((a, b) => a + b, 0) / n) as V3;
    for (const t of tris) assert.ok(dot(t.n, sub(t.centroid, centre)) > 0, `${id}: inward face ${t.n}`);
    // Closed and consistently oriented: every directed edge appears once and its reverse once.
    const edges = new Map<string, number>();
    const idx = Array.from(mesh.indices!);
    for (let t = 0; t < idx.length; t += 3) {
      for (let e = 0; e < 3; e++) {
        const key = `${idx[t + e]}>${idx[t + ((e + 1) % 3)]}`;
        edges.set(key, (edges.get(key) ?? 0) + 1);
      }
    }
    for (const [key, count] of edges) {
      const [a, b] = key.split('>');
      assert.equal(count, 1, `${id}: edge ${key} used ${count} times`);
      assert.equal(edges.get(`${b}>${a}`), 1, `${id}: edge ${key} has no twin`);
    }
    const ys = positions.filter((_, i) => i % 3 === 1);
    assert.equal(Math.min(...ys), -1);
  }
  const height = (id: string) => Math.max(...Array.from(meshes.get(id)!.positions).filter((_, i) => i % 3 === 1)) + 1;
  assert.ok(Math.abs(height('tall-block') - 2 * height('short-block')) < 1e-12);
});

/** The Cornell box's meshes carry their materials inline. */
function materialOf(mesh: WavefrontMeshInput): WavefrontMaterialInput {
  assert.equal(typeof mesh.material, 'object', 'an inline material');
  return mesh.material as WavefrontMaterialInput;
}

test('the light is an emitter just below the ceiling facing down', () => {
  const light = meshes.get('light')!;
  for (const t of triangles(light)) {
    assert.ok(dot(t.n, [0, -1, 0]) > 1 - 1e-12, `light normal ${t.n}`);
    assert.ok(t.centroid[1] < 1 && t.centroid[1] > 0.95);
  }
  const m = materialOf(light);
  const e = Array.from(m.emissiveFactor!).map((x) => x * m.emissiveStrength!);
  assert.deepEqual(e.map((x) => Math.round(x * 1e9) / 1e9), [17, 12, 4]);
  assert.ok(Math.max(...Array.from(m.emissiveFactor!)) <= 1);
  assert.notEqual(m.doubleSided, true);
  // No other mesh emits.
  for (const [id, mesh] of meshes) {
    if (id === 'light') continue;
    const material = materialOf(mesh);
    assert.ok(!material.emissiveFactor || Array.from(material.emissiveFactor).every((x) => x === 0), id);
    assert.equal(mesh.emission, undefined);
  }
});

test('materials are Lambertian with the classic albedos; black environment; camera looks in through the open side', () => {
  const albedo = (id: string) => Array.from(materialOf(meshes.get(id)!).baseColorFactor!);
  assert.deepEqual(albedo('left-wall'), [0.63, 0.065, 0.05]);
  assert.deepEqual(albedo('right-wall'), [0.14, 0.45, 0.091]);
  for (const id of ['floor', 'ceiling', 'back-wall', 'short-block', 'tall-block']) assert.deepEqual(albedo(id), [0.73, 0.73, 0.73]);
  for (const mesh of meshes.values()) {
    assert.equal(materialOf(mesh).metallicFactor, 0);
    assert.equal(materialOf(mesh).roughnessFactor, 1);
    assert.equal(materialOf(mesh).ior, 1);
  }
  assert.deepEqual(Array.from(scene.environment!.color), [0, 0, 0]);
  const cam = scene.camera!;
  assert.ok(cam.position[2] > 1, 'camera outside the open side');
  assert.deepEqual(Array.from(cam.target), [0, 0, 0]);
  // The whole open side (z = 1 square) fits in the vertical field of view.
  const half = Math.atan(1 / (cam.position[2] - 1)) * (180 / Math.PI);
  assert.ok(cam.fovYDegrees! > 30 && cam.fovYDegrees! < 45 && cam.fovYDegrees! / 2 >= half - 1);
  // Every object is in front of the camera.
  for (const mesh of meshes.values()) assert.ok(Array.from(mesh.positions).filter((_, i) => i % 3 === 2).every((z) => z < cam.position[2]));
});
