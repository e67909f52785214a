// The glTF loader poses skinned, morphed and animated assets at an animation's time: vertices
// against a hand computation of linear blend skinning, morph-target normals against the morph
// formula, animated cameras, animation choice by name and index, and typed errors.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadGltfScene } from '../../src/io/gltf/load-gltf-scene.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { bentVertex, createBendingTube, createMorphedPlane, PATCH_HALF, PATCH_NORMAL_DELTA, PATCH_RISE, tubeVertices } from './fixtures.ts';

function assertClose(actual: ArrayLike<number>, expected: ArrayLike<number>, tolerance: number, label: string): void {
  assert.equal(actual.length, expected.length, `${label}: length`);
  for (let i = 0; i < expected.length; i++) assert.ok(Math.abs(actual[i]! - expected[i]!) <= tolerance, `${label}[${i}]: ${actual[i]} vs ${expected[i]}`);
}

async function rejectsWith(promise: Promise<unknown>, code: string, field: string, message?: RegExp): Promise<void> {
  await assert.rejects(promise, (e: unknown) => {
    assert.ok(e instanceof GpuRendererError, `expected a GpuRendererError, got ${String(e)}`);
    assert.equal(e.code, code, e.message);
    assert.equal(e.field, field, e.message);
    if (message) assert.match(e.message, message);
    return true;
  });
}

function expectedTube(degrees: number): { positions: number[]; normals: number[] } {
  const bent = tubeVertices().map((v) => bentVertex(v, degrees));
  return { positions: bent.flatMap((v) => v.position), normals: bent.flatMap((v) => v.normal) };
}

test('a skinned mesh posed at t equals linear blend skinning computed by hand; the skinned node\'s own transform is ignored', async () => {
  const { document } = createBendingTube();
  for (const [time, degrees] of [[0.5, 45], [0.25, 22.5], [1, 90], [3, 90]] as const) {
    const scene = await loadGltfScene(document, { animation: 'Bend', time });
    assert.equal(scene.animation?.name, 'Bend');
    assert.equal(scene.time, time);
    assert.equal(scene.meshes.length, 1);
    assert.deepEqual(scene.instances.map((i) => Array.from(i.transform!)), [[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]]);
    const expected = expectedTube(degrees);
    assertClose(scene.meshes[0]!.positions, expected.positions, 1e-5, `positions at ${time} s`);
    assertClose(scene.meshes[0]!.normals!, expected.normals, 1e-5, `normals at ${time} s`);
    assert.deepEqual(scene.warnings, []);
  }
});

test('default pose: the first animation at 0 s; an animation by index; null poses none', async () => {
  const { document } = createBendingTube();
  const rest = expectedTube(0);
  const first = await loadGltfScene(document);
  assert.deepEqual(first.animations.map((a) => [a.index, a.name, a.durationS]), [[0, 'Bend', 1], [1, 'Sway', 0.5]]);
  assert.equal(first.animation?.name, 'Bend');
  assertClose(first.meshes[0]!.positions, rest.positions, 1e-6, 'rest positions');
  // Sway at 0.25 s moves Lower (and Upper, its child) by +0.5 in x.
  const swayed = await loadGltfScene(document, { animation: 1, time: 0.25 });
  assert.equal(swayed.animation?.name, 'Sway');
  assertClose(swayed.meshes[0]!.positions, rest.positions.map((v, i) => (i % 3 === 0 ? v + 0.5 : v)), 1e-6, 'swayed positions');
  const none = await loadGltfScene(document, { animation: null, time: 0.25 });
  assert.equal(none.animation, null);
  assertClose(none.meshes[0]!.positions, rest.positions, 1e-6, 'unanimated positions');
});

test('pose() reposes a loaded scene: materials shared, other times and animations, the same answer as loading anew', async () => {
  const { document } = createBendingTube();
  const scene = await loadGltfScene(document, { animation: 'Bend', time: 0 });
  const later = await scene.pose({ time: 0.5 });
  assert.equal(later.materials, scene.materials);
  assert.equal(later.animation?.name, 'Bend');
  assertClose(later.meshes[0]!.positions, expectedTube(45).positions, 1e-5, 'reposed');
  const swayed = await later.pose({ animation: 'Sway' });
  assert.equal(swayed.time, 0.5);
  assert.equal(swayed.animation?.name, 'Sway');
  assertClose(swayed.meshes[0]!.positions, expectedTube(0).positions.map((v, i) => (i % 3 === 0 ? v + 1 : v)), 1e-6, 'swayed at 0.5 s');
});

test('animated cameras move with the animation', async () => {
  const { document, nodes } = createBendingTube();
  const buffer = document.getRoot().listBuffers()[0]!;
  const dolly = document.createAnimation('Dolly');
  const sampler = document
    .createAnimationSampler()
    .setInput(document.createAccessor().setType('SCALAR').setArray(new Float32Array([0, 1])).setBuffer(buffer))
    .setOutput(document.createAccessor().setType('VEC3').setArray(new Float32Array([1, 1, 6, 1, 1, 10])).setBuffer(buffer))
    .setInterpolation('LINEAR');
  dolly.addSampler(sampler).addChannel(document.createAnimationChannel().setTargetNode(nodes.front).setTargetPath('translation').setSampler(sampler));
  const scene = await loadGltfScene(document, { animation: 'Dolly', time: 0.5, camera: 'Front' });
  assertClose(scene.camera.position!, [1, 1, 8], 1e-6, 'camera position');
  assertClose(scene.camera.target!, [1, 1, 7], 1e-6, 'camera target');
});

test('morph targets move positions and normals at the animated weight (glTF 2.0 section 3.7.2.2)', async () => {
  const scene = await loadGltfScene(createMorphedPlane(), { time: 0.5 });
  const mesh = scene.meshes[0]!;
  const w = 0.5;
  const len = Math.hypot(w * PATCH_NORMAL_DELTA[0], 1, 0);
  let inside = 0;
  for (let v = 0; v < mesh.positions.length / 3; v++) {
    const x = mesh.positions[3 * v]!;
    const z = mesh.positions[3 * v + 2]!;
    const patch = Math.abs(x) <= PATCH_HALF + 1e-6 && Math.abs(z) <= PATCH_HALF + 1e-6;
    if (patch) inside++;
    assertClose([mesh.positions[3 * v + 1]!], [patch ? w * PATCH_RISE : 0], 1e-6, `y of vertex ${v}`);
    assertClose(Array.from(mesh.normals!).slice(3 * v, 3 * v + 3), patch ? [(w * PATCH_NORMAL_DELTA[0]) / len, 1 / len, 0] : [0, 1, 0], 1e-6, `normal of vertex ${v}`);
  }
  assert.equal(inside, 25);
});

test('bad animation options and data are typed errors naming the option or the JSON pointer', async () => {
  const { document } = createBendingTube();
  await rejectsWith(loadGltfScene(document, { animation: 'Walk' }), 'INVALID_OPTION', 'animation', /"Walk".*0 "Bend", 1 "Sway"/);
  await rejectsWith(loadGltfScene(document, { animation: 2 }), 'INVALID_OPTION', 'animation', /out of range/);
  await rejectsWith(loadGltfScene(document, { time: -1 }), 'INVALID_OPTION', 'time');
  await rejectsWith(loadGltfScene(document, { time: Number.NaN }), 'INVALID_OPTION', 'time');
  const scene = await loadGltfScene(document);
  await rejectsWith(scene.pose({ animation: 'Walk' }), 'INVALID_OPTION', 'animation');
  await rejectsWith(loadGltfScene(createBendingTube().document, { animation: 'x', scene: 0 }), 'INVALID_OPTION', 'animation');

  const unanimated = createMorphedPlane();
  unanimated.getRoot().listAnimations()[0]!.dispose();
  await rejectsWith(loadGltfScene(unanimated, { animation: 'Raise' }), 'INVALID_OPTION', 'animation', /no animations/);

  const backwards = createBendingTube().document;
  backwards.getRoot().listAnimations()[0]!.listSamplers()[0]!.getInput()!.setArray(new Float32Array([1, 0]));
  await rejectsWith(loadGltfScene(backwards), 'INVALID_GLTF', '/animations/0/samplers/0/input/1', /strictly increase/);

  const badJoint = createBendingTube().document;
  const joints = badJoint.getRoot().listMeshes()[0]!.listPrimitives()[0]!.getAttribute('JOINTS_0')!;
  // Vertex 6 (ring y = 1.5) has all its weight on the second influence.
  joints.setElement(6, [0, 7, 0, 0]);
  await rejectsWith(loadGltfScene(badJoint), 'INVALID_GLTF', '/meshes/0/primitives/0/attributes/JOINTS_0/6', /joint index 7 is out of range for a skin of 2 joints/);

  const noJoints = createBendingTube().document;
  const primitive = noJoints.getRoot().listMeshes()[0]!.listPrimitives()[0]!;
  primitive.setAttribute('JOINTS_0', null).setAttribute('WEIGHTS_0', null);
  await rejectsWith(loadGltfScene(noJoints), 'INVALID_GLTF', '/meshes/0/primitives/0/attributes/JOINTS_0', /needs JOINTS_0/);
});

test('scene JSON: a glTF reference poses its asset with "animation" and "time"', async (t) => {
  const { mkdtemp, rm, writeFile } = await import('node:fs/promises');
  const { tmpdir } = await import('node:os');
  const { join } = await import('node:path');
  const { NodeIO } = await import('@gltf-transform/core');
  const { loadSceneFile } = await import('../../src/io/scene-file-loader.ts');
  const { parseGltfReferences } = await import('../../src/scene/gltf-references.ts');
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-pose-'));
  t.after(() => rm(dir, { recursive: true, force: true }));
  await writeFile(join(dir, 'tube.glb'), await new NodeIO().writeBinary(createBendingTube().document));
  await writeFile(join(dir, 'scene.json'), JSON.stringify({ gltf: [{ src: 'tube.glb', animation: 'Bend', time: 0.5 }] }));
  const { scene } = await loadSceneFile(join(dir, 'scene.json'));
  assertClose(scene.meshes![0]!.positions, expectedTube(45).positions, 1e-5, 'referenced asset posed');
  assert.throws(() => parseGltfReferences([{ src: 'a.glb', time: -2 }]), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_SCENE_FILE' && e.field === 'gltf[0].time');
  assert.throws(() => parseGltfReferences([{ src: 'a.glb', animation: 1.5 }]), (e: unknown) => e instanceof GpuRendererError && e.field === 'gltf[0].animation');
});
