// Scenes that flattening refused (issue 25), through the glTF loader: 10,000 EXT_mesh_gpu_instancing
// instances of a 20,480-triangle sphere (205 M placed triangles; flattened, the primitive buffer
// alone would be 9.8 GB) and 4,000 nodes reusing 8 such meshes, on lavapipe (128 MiB per binding),
// looked at from above with an orthographic camera so every placement is in view.
// - Visible: unlit black spheres under a white environment: each pixel is the fraction of its
//   area no sphere covers. The expected coverage comes from the placements themselves (discs of
//   the instance scale x radius about the instance translations, 8 x 8 points per pixel), not from
//   the renderer.
// - Lit right: white diffuse spheres in a white furnace (radiance 1, albedo 1): every path carries
//   throughput 1 until it escapes, so every pixel's expectation is 1 (up to the paths still
//   bouncing at maxDepth, a vanishing fraction for spheres this far apart).
import { test, type TestContext } from 'node:test';
import assert from 'node:assert/strict';
import { Document, type Material } from '@gltf-transform/core';
import { EXTMeshGPUInstancing, KHRMaterialsUnlit } from '@gltf-transform/extensions';
import type { GltfScene } from '../../src/io/index.ts';
import { icosphere } from '../helpers/meshes.ts';
import { floatAccessor, renderScene, roundTrip } from './gltf-scenes.ts';

const SIZE = 64;
const RADIUS = 0.3;
const GRID = 100;

interface Placement { x: number; z: number; yaw: number; scale: number; mesh: number }

/** A 100 x 100 grid (spacing 1) of placements with a yaw and a scale each, deterministic. */
function placements(count: number, meshes: number): Placement[] {
  const out: Placement[] = [];
  let state = 12345;
  const random = (): number => ((state = (state * 1103515245 + 12345) >>> 0) / 2 ** 32);
  for (let i = 0; i < count; i++) {
    out.push({ x: (i % GRID) - GRID / 2 + 0.5, z: Math.floor(i / GRID) - GRID / 2 + 0.5, yaw: 2 * Math.PI * random(), scale: 0.8 + 0.4 * random(), mesh: i % meshes });
  }
  return out;
}

function material(doc: Document, kind: 'black-unlit' | 'white'): Material {
  const m = doc.createMaterial().setMetallicFactor(0).setRoughnessFactor(1);
  if (kind === 'white') return m.setBaseColorFactor([1, 1, 1, 1]);
  const unlit = doc.createExtension(KHRMaterialsUnlit).setRequired(true);
  return m.setBaseColorFactor([0, 0, 0, 1]).setExtension('KHR_materials_unlit', unlit.createUnlit());
}

/** `meshes` spheres of 20,480 triangles (radii RADIUS x (1 + k / 16)), placed by EXT_mesh_gpu_instancing or by one node each. */
async function forest(how: 'instancing' | 'nodes', count: number, meshes: number, kind: 'black-unlit' | 'white'): Promise<{ scene: GltfScene; placed: Placement[] }> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const mat = material(doc, kind);
  const sphere = icosphere(1, [0, 0, 0], 5);
  const gltfMeshes = Array.from({ length: meshes }, (_, k) => {
    const r = RADIUS * (1 + k / 16);
    const primitive = doc
      .createPrimitive()
      .setAttribute('POSITION', floatAccessor(doc, buffer, 'VEC3', sphere.positions.map((v) => v * r)))
      .setAttribute('NORMAL', floatAccessor(doc, buffer, 'VEC3', sphere.positions))
      .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint32Array(sphere.indices)).setBuffer(buffer))
      .setMaterial(mat);
    return doc.createMesh(`sphere ${k}`).addPrimitive(primitive);
  });
  const placed = placements(count, meshes);
  const root = doc.createScene();
  const rotation = (p: Placement): [number, number, number, number] => [0, Math.sin(p.yaw / 2), 0, Math.cos(p.yaw / 2)];
  if (how === 'instancing') {
    const ext = doc.createExtension(EXTMeshGPUInstancing).setRequired(true);
    const batch = ext
      .createInstancedMesh()
      .setAttribute('TRANSLATION', floatAccessor(doc, buffer, 'VEC3', placed.flatMap((p) => [p.x, 0, p.z])))
      .setAttribute('ROTATION', floatAccessor(doc, buffer, 'VEC4', placed.flatMap(rotation)))
      .setAttribute('SCALE', floatAccessor(doc, buffer, 'VEC3', placed.flatMap((p) => [p.scale, p.scale, p.scale])));
    root.addChild(doc.createNode('forest').setMesh(gltfMeshes[0]!).setExtension('EXT_mesh_gpu_instancing', batch));
  } else {
    placed.forEach((p, i) => root.addChild(doc.createNode(`tree ${i}`).setMesh(gltfMeshes[p.mesh]!).setTranslation([p.x, 0, p.z]).setRotation(rotation(p)).setScale([p.scale, p.scale, p.scale])));
  }
  return { scene: await roundTrip(doc), placed };
}

const camera = { type: 'orthographic' as const, position: [0, 10, 0], target: [0, 0, 0], up: [0, 0, -1], orthographicHeight: GRID };

/** Per pixel: the fraction of 8 x 8 points inside some placement's disc (image up is -z, right is +x). */
function expectedCoverage(placed: readonly Placement[], meshes: number): Float64Array {
  const coverage = new Float64Array(SIZE * SIZE);
  const pixel = GRID / SIZE;
  for (const p of placed) {
    const r = RADIUS * (1 + (p.mesh % meshes) / 16) * p.scale;
    const x0 = Math.max(0, Math.floor((p.x - r + GRID / 2) / pixel));
    const x1 = Math.min(SIZE - 1, Math.floor((p.x + r + GRID / 2) / pixel));
    const y0 = Math.max(0, Math.floor((p.z - r + GRID / 2) / pixel));
    const y1 = Math.min(SIZE - 1, Math.floor((p.z + r + GRID / 2) / pixel));
    for (let py = y0; py <= y1; py++) {
      for (let px = x0; px <= x1; px++) {
        let inside = 0;
        for (let j = 0; j < 8; j++) {
          for (let i = 0; i < 8; i++) {
            const x = (px + (i + 0.5) / 8) * pixel - GRID / 2;
            const z = (py + (j + 0.5) / 8) * pixel - GRID / 2;
            if ((x - p.x) ** 2 + (z - p.z) ** 2 < r * r) inside++;
          }
        }
        // Placements are 1 apart and at most 0.66 across: their discs never overlap.
        coverage[py * SIZE + px]! += inside / 64;
      }
    }
  }
  return coverage;
}

async function assertVisible(t: TestContext, how: 'instancing' | 'nodes', count: number, meshes: number): Promise<void> {
  const { scene, placed } = await forest(how, count, meshes, 'black-unlit');
  assert.equal(scene.meshes.length, meshes, 'each sphere once, not copied per placement');
  assert.equal(scene.instances.length, count);
  const spp = 32;
  const { radiance, stats } = await renderScene(scene, { width: SIZE, height: SIZE, camera, maxDepth: 1, environment: { color: [1, 1, 1] } }, spp);
  assert.equal(stats.invalidSamples, 0);
  const want = expectedCoverage(placed, meshes);
  let got = 0, expected = 0, far = 0;
  for (let p = 0; p < SIZE * SIZE; p++) {
    const covered = 1 - radiance[4 * p]!;
    got += covered;
    expected += want[p]!;
    // A pixel's covered fraction from `spp` jittered rays: binomial, sd <= 0.5 / sqrt(spp) = 0.09.
    if (Math.abs(covered - want[p]!) > 0.4) far++;
  }
  const pixels = SIZE * SIZE;
  t.diagnostic(`${how}: covered ${(got / pixels).toFixed(4)} expected ${(expected / pixels).toFixed(4)}, far ${far}, rss ${(process.memoryUsage().rss / 2 ** 30).toFixed(2)} GiB`);
  // The image mean of `spp` x pixels jittered rays: sd < 0.5 / sqrt(spp x pixels) = 0.0014.
  assert.ok(Math.abs(got - expected) / pixels < 0.007, `covered fraction ${(got / pixels).toFixed(4)}, expected ${(expected / pixels).toFixed(4)}`);
  assert.ok(far <= 2, `${far} pixels differ from their expected coverage by more than 0.4`);
  const rss = process.memoryUsage().rss;
  assert.ok(rss < 3 * 2 ** 30, `process memory ${(rss / 2 ** 30).toFixed(2)} GiB`);
}

test('10,000 EXT_mesh_gpu_instancing instances of a 20,480-triangle sphere render on lavapipe, each where it belongs', async (t) => {
  await assertVisible(t, 'instancing', 10_000, 1);
});

test('4,000 nodes reusing 8 meshes of 20,480 triangles render on lavapipe, each where it belongs', async (t) => {
  await assertVisible(t, 'nodes', 4_000, 8);
});

test('10,000 instanced white spheres in a white furnace: every pixel is 1 in expectation', async (t) => {
  const { scene } = await forest('instancing', 10_000, 1, 'white');
  const { radiance, stats } = await renderScene(scene, { width: 32, height: 32, camera, maxDepth: 24, environment: { color: [1, 1, 1] } }, 16);
  assert.equal(stats.invalidSamples, 0);
  let sum = 0, min = Infinity;
  for (let p = 0; p < 32 * 32; p++) {
    sum += radiance[4 * p + 1]!;
    min = Math.min(min, radiance[4 * p + 1]!);
  }
  const mean = sum / (32 * 32);
  t.diagnostic(`furnace mean ${mean.toFixed(4)} min ${min.toFixed(3)}`);
  assert.ok(Math.abs(mean - 1) < 0.01, `furnace mean ${mean.toFixed(4)}`);
  assert.ok(min > 0.8, `darkest pixel ${min.toFixed(3)}`);
});
