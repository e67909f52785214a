// Bad input at the public boundary: each case gets a typed error naming the field, raised before
// any GPU work, and the shared device stays healthy (nothing half-renders).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer, GpuRendererError, rendererWavefrontPrimitiveBytes } from '../../src/index.ts';
import { testDevice } from '../helpers/gpu.ts';

const tri = [0, 0, 0, 1, 0, 0, 0, 1, 0];

async function expectError(options: Record<string, unknown>, code: string, field: string | RegExp): Promise<void> {
  const device = await testDevice();
  await assert.rejects(
    createWavefrontPathTracingComputeRenderer({ device, width: 8, height: 8, ...options } as never),
    (error: unknown) => {
      assert.ok(error instanceof GpuRendererError, `expected GpuRendererError, got ${String(error)}`);
      assert.equal(error.code, code);
      if (typeof field === 'string') assert.equal(error.field, field);
      else assert.match(error.field ?? '', field);
      assert.ok(error.message.includes(error.field ?? ''), 'the message names the field');
      return true;
    },
  );
}

test('non-finite positions name the offending component', async () => {
  await expectError({ meshes: [{ positions: [0, 0, 0, 1, NaN, 0, 0, 1, 0] }] }, 'INVALID_MESH', 'meshes[0].positions[4]');
  await expectError({ meshes: [{ positions: tri }, { positions: [0, 0, Infinity, 1, 0, 0, 0, 1, 0] }] }, 'INVALID_MESH', 'meshes[1].positions[2]');
});

test('indices out of range, not a multiple of 3, or not integers', async () => {
  await expectError({ meshes: [{ positions: tri, indices: [0, 1, 3] }] }, 'INVALID_MESH', 'meshes[0].indices[2]');
  await expectError({ meshes: [{ positions: tri, indices: [0, 1, -1] }] }, 'INVALID_MESH', 'meshes[0].indices[2]');
  await expectError({ meshes: [{ positions: tri, indices: [0, 1, 2, 0] }] }, 'INVALID_MESH', 'meshes[0].indices');
  await expectError({ meshes: [{ positions: tri, indices: [0, 1.5, 2] }] }, 'INVALID_MESH', 'meshes[0].indices[1]');
});

test('empty meshes and mismatched attribute lengths', async () => {
  await expectError({ meshes: [{ positions: [] }] }, 'INVALID_MESH', 'meshes[0].positions');
  await expectError({ meshes: [{ positions: tri, indices: [] }] }, 'INVALID_MESH', 'meshes[0].indices');
  await expectError({ meshes: [{ positions: [0, 0, 0, 1] }] }, 'INVALID_MESH', 'meshes[0].positions');
  await expectError({ meshes: [{ positions: tri, normals: [0, 0, 1, 0, 0, 1] }] }, 'INVALID_MESH', 'meshes[0].normals');
  await expectError({ meshes: [{ positions: tri, uvs: [0, 0, 1, 0] }] }, 'INVALID_MESH', 'meshes[0].uvs');
  await expectError({ meshes: [{ positions: tri, material: { roughnessFactor: 2 } }] }, 'INVALID_MESH', 'meshes[0].material.roughnessFactor');
  await expectError({ meshes: [{ positions: tri, material: { ior: 0.5 } }] }, 'INVALID_MESH', 'meshes[0].material.ior');
});

test('maxDepth, size, samplesPerPixel and camera out of range', async () => {
  await expectError({ maxDepth: 0 }, 'INVALID_OPTION', 'maxDepth');
  await expectError({ maxDepth: 33 }, 'INVALID_OPTION', 'maxDepth');
  await expectError({ maxDepth: 2.5 }, 'INVALID_OPTION', 'maxDepth');
  await expectError({ width: 0 }, 'INVALID_OPTION', 'width');
  await expectError({ height: Number.NaN }, 'INVALID_OPTION', 'height');
  await expectError({ samplesPerPixel: 0 }, 'INVALID_OPTION', 'samplesPerPixel');
  await expectError({ camera: { position: [0, 0, 1], target: [0, 0, 1] } }, 'INVALID_OPTION', 'camera.target');
  await expectError({ camera: { position: [0, 0, 1], target: [0, 0, 0], up: [0, 0, 1] } }, 'INVALID_OPTION', 'camera.up');
  await expectError({ environment: { color: [1, -1, 0] } }, 'INVALID_OPTION', 'environment.color[1]');
  await expectError({ sceneObjects: [{ type: 'cone' }] }, 'INVALID_SCENE_OBJECT', 'sceneObjects[0].type');
  await expectError({ sceneObjects: [{ type: 'sphere', center: [0, 0, 0], radius: -1 }] }, 'INVALID_SCENE_OBJECT', 'sceneObjects[0].radius');
});

test('scenes beyond the device limits are rejected before allocation, naming the field', async () => {
  const device = await testDevice();
  const limit = Math.min(device.limits.maxStorageBufferBindingSize, device.limits.maxBufferSize);
  // Enough triangles that the primitive records (one per triangle) overflow one storage binding.
  const triangles = Math.floor(limit / rendererWavefrontPrimitiveBytes) + 1;
  if (triangles > 6_000_000) return; // a device this large is not tested here
  const positions = new Float32Array(triangles * 9);
  for (let t = 0; t < triangles; t++) positions.set([t, 0, 0, t + 1, 0, 0, t, 1, 0], 9 * t);
  await expectError({ meshes: [{ positions }] }, 'SCENE_TOO_LARGE', 'meshes');
  // A frame too large for one accumulation binding.
  const side = Math.ceil(Math.sqrt(limit / 16)) + 1;
  if (side <= 16384) await expectError({ width: side, height: side }, 'SCENE_TOO_LARGE', 'width');
});

test('after rejected input the shared device still renders a valid scene', async () => {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: 8, height: 8, samplesPerPixel: 2,
    meshes: [{ positions: [-1, -1, 0, 1, -1, 0, 0, 1, 0], material: { emissiveFactor: [1, 1, 1], baseColorFactor: [0, 0, 0, 1] } }],
    camera: { position: [0, 0, 3], target: [0, 0, 0] },
  });
  const stats = await renderer.renderFrame();
  assert.equal(stats.samplesAccumulated, 2);
  const { data } = await renderer.readRadiance();
  // The centre pixel sees the emitter's front face: exactly its radiance.
  const centre = (4 * 8 + 4) * 4;
  assert.ok(Math.abs(data[centre]! - 1) < 1e-6);
  renderer.destroy();
  await assert.rejects(renderer.renderFrame(), (e: unknown) => e instanceof GpuRendererError && e.code === 'RENDERER_DESTROYED');
});

test('instances, shared materials and textures: typed errors naming the field', async () => {
  const quad = { positions: [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0], indices: [0, 1, 2, 0, 2, 3], uvs: [0, 0, 1, 0, 1, 1, 0, 1] };
  await expectError({ meshes: [quad], instances: [{ mesh: 1 }] }, 'INVALID_INSTANCE', 'instances[0].mesh');
  await expectError({ meshes: [quad], instances: [{ mesh: 0, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0] }] }, 'INVALID_INSTANCE', 'instances[0].transform');
  await expectError({ meshes: [quad], instances: [{ mesh: 0, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, NaN, 1] }] }, 'INVALID_INSTANCE', 'instances[0].transform[14]');
  await expectError({ meshes: [quad], instances: [{ mesh: 0, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1] }] }, 'INVALID_INSTANCE', 'instances[0].transform');
  await expectError({ meshes: [quad], instances: [{ mesh: 0, transform: [1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] }] }, 'INVALID_INSTANCE', 'instances[0].transform');
  await expectError({ meshes: [quad], instances: [{ mesh: 0, material: 0 }] }, 'INVALID_INSTANCE', 'instances[0].material');
  await expectError({ meshes: [{ ...quad, material: 2 }], materials: [{}] }, 'INVALID_MESH', 'meshes[0].material');
  await expectError({ meshes: [quad], materials: [{ roughnessFactor: -1 }] }, 'INVALID_MATERIAL', 'materials[0].roughnessFactor');
  await expectError({ meshes: [quad], materials: [{ baseColorTexture: { index: 0 } }] }, 'INVALID_MATERIAL', 'materials[0].baseColorTexture.index');
  await expectError({ meshes: [quad], materials: [{ shininess: 3 }] }, 'INVALID_MATERIAL', 'materials[0].shininess');
  await expectError({ meshes: [{ ...quad, material: { baseColorTexture: { index: 0, texCoord: 2 } } }], textures: [{ image: { width: 1, height: 1, data: new Uint8Array(4) } }] }, 'INVALID_MESH', 'meshes[0].material.baseColorTexture.texCoord');
  // KHR extension factors are validated against their extensions' ranges.
  await expectError({ meshes: [quad], materials: [{ transmissionFactor: 1.5 }] }, 'INVALID_MATERIAL', 'materials[0].transmissionFactor');
  const texture = (image: unknown) => ({ meshes: [{ ...quad, material: { baseColorTexture: { index: 0 } } }], textures: [{ image }] });
  await expectError(texture({ width: 2, height: 2, data: new Uint8Array(15) }), 'INVALID_TEXTURE', 'textures[0].image.data');
  await expectError(texture({ width: 0, height: 2, data: new Uint8Array(0) }), 'INVALID_TEXTURE', /textures\[0\]\.image\.width|images\[0\]\.width/);
  await expectError({ ...texture({ width: 1, height: 1, data: new Uint8Array(4) }), textures: [{ image: 3 }] }, 'INVALID_TEXTURE', /textures\[0\]\.image/);
  await expectError({ meshes: [{ ...quad, tangents: [1, 0, 0, 2, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1] }] }, 'INVALID_MESH', 'meshes[0].tangents[3]');
  await expectError({ meshes: [{ ...quad, colors: [1, 1, 1, 1, 1, 1] }] }, 'INVALID_MESH', 'meshes[0].colors');
});

test('finite inputs whose products overflow get typed errors, never RangeErrors or non-finite pixels', async () => {
  // An emissive factor of 3.4e38 would make the light's power infinite in the alias table.
  await expectError({ meshes: [{ positions: tri, material: { emissiveFactor: [3.4e38, 0, 0] } }] }, 'INVALID_MESH', 'meshes[0].material.emissiveFactor');
  await expectError({ meshes: [{ positions: tri, material: { emissiveFactor: [1e10, 0, 0], emissiveStrength: 1e15 } }] }, 'INVALID_MESH', 'meshes[0].material.emissiveFactor');
  await expectError({ meshes: [{ positions: tri, emission: [1, 1, 1, 3e38] }] }, 'INVALID_MESH', 'meshes[0].emission');
  await expectError({ sceneObjects: [{ type: 'sphere', center: [0, 0, 0], radius: 1, emission: [1, 1, 1, 1e30] }] }, 'INVALID_SCENE_OBJECT', 'sceneObjects[0].emission');
  await expectError({ environment: { color: [1e30, 0, 0] } }, 'INVALID_OPTION', 'environment.color[0]');
  // Coordinates whose squares overflow float32.
  await expectError({ meshes: [{ positions: [0, 0, 0, 1e20, 0, 0, 0, 1, 0] }] }, 'INVALID_MESH', 'meshes[0].positions[3]');
  // A light whose emission is finite but whose area times radiance overflows.
  await expectError({ meshes: [{ positions: [0, 0, 0, 1e17, 0, 0, 0, 1e17, 0], material: { emissiveFactor: [1, 1, 1], emissiveStrength: 1e19 } }] }, 'SCENE_TOO_LARGE', 'meshes[0].material');
});

test('options the renderer does not know are typed errors naming them', async () => {
  await expectError({ environmentCubeMap: { width: 1, height: 1, data: new Float32Array(4) } }, 'INVALID_OPTION', 'environmentCubeMap');
  await expectError({ denoiser: true }, 'INVALID_OPTION', 'denoiser');
  await expectError({ camera: { position: [0, 0, 1], target: [0, 0, 0], fov: 40 } }, 'INVALID_OPTION', 'camera.fov');
  await expectError({ environment: { color: [1, 1, 1], intensity: 2 } }, 'INVALID_OPTION', 'environment.intensity');
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: 8, height: 8 });
  await assert.rejects(renderer.renderFrame({ samplesPerPixel: 1, readStats: true } as never), (e: unknown) => e instanceof GpuRendererError && e.field === 'readStats');
  renderer.destroy();
});
