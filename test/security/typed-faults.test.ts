// Faults that used to escape as TypeError, RangeError, DOMException or a WebAssembly trap, or were
// accepted, or were refused only later by the renderer under its own field names: each is now a
// GpuRendererError naming the field (a JSON pointer for glTF) at load, or loads where it is legal.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { createCornellBoxScene, createWavefrontPathTracingComputeRenderer, loadEnvironmentMap, loadGltfScene, loadSceneFile } from '../../src/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { assetFolder, refused, triangleDataUri, triangleGltf } from './helpers.ts';
import { encodeExr } from '../io/images/environment-encoders.ts';

const bytes = (json: unknown): Uint8Array => new TextEncoder().encode(typeof json === 'string' ? json : JSON.stringify(json));

/** The triangle with one material (and whatever else `extra` sets). */
const withMaterial = (material: unknown, extra: Record<string, unknown> = {}): Record<string, unknown> =>
  triangleGltf(triangleDataUri, { materials: [material], meshes: [{ primitives: [{ attributes: { POSITION: 0 }, material: 0 }] }], ...extra });

test('data URIs of a bad base64 length are INVALID_GLTF (was a DOMException from atob)', async () => {
  for (const uri of ['data:application/octet-stream;base64,A', 'data:application/octet-stream;base64,AAAAA', 'data:;base64,AA=A', 'data:,%ZZ']) {
    await refused(loadGltfScene(bytes(triangleGltf(uri))), 'INVALID_GLTF', '/buffers/0', /malformed data URI/);
  }
});

test('factors of the wrong type or range are refused at load with the JSON pointer', async () => {
  for (const value of [3, { r: 1 }, null, true, [1, 1, 1], [2, 2, 2, 1], [-1, 0, 0, 1]]) {
    await refused(loadGltfScene(bytes(withMaterial({ pbrMetallicRoughness: { baseColorFactor: value } }))), 'INVALID_GLTF', /^\/materials\/0\/pbrMetallicRoughness\/baseColorFactor(\/\d)?$/);
  }
  for (const value of [3, { r: 1 }, null, true, [1, 1, 1, 1], [2, 2, 2], [-1, 0, 0]]) {
    await refused(loadGltfScene(bytes(withMaterial({ emissiveFactor: value }))), 'INVALID_GLTF', /^\/materials\/0\/emissiveFactor(\/\d)?$/);
  }
  await refused(loadGltfScene(bytes(withMaterial({ extensions: { KHR_materials_ior: { ior: '1.5' } } }, { extensionsUsed: ['KHR_materials_ior'] }))), 'INVALID_GLTF', '/materials/0/extensions/KHR_materials_ior/ior');
  await refused(loadGltfScene(bytes(withMaterial({ extensions: { KHR_materials_ior: { ior: 0.5 } } }, { extensionsUsed: ['KHR_materials_ior'] }))), 'INVALID_GLTF', '/materials/0/extensions/KHR_materials_ior/ior', /must be >= 1/);
  // 1e999 in JSON text parses to Infinity.
  const rotation = JSON.stringify(
    withMaterial(
      { pbrMetallicRoughness: { baseColorTexture: { index: 0, extensions: { KHR_texture_transform: { rotation: 12345 } } } } },
      { images: [{ uri: 'data:image/png;base64,' }], textures: [{ source: 0 }], extensionsUsed: ['KHR_texture_transform'] },
    ),
  ).replace('12345', '1e999');
  await refused(loadGltfScene(bytes(rotation)), 'INVALID_GLTF', '/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/rotation', /finite/);
  await refused(loadGltfScene(bytes(triangleGltf(triangleDataUri, { samplers: [{ wrapS: 7 }] }))), 'INVALID_GLTF', '/samplers/0/wrapS');
  const light = { extensionsUsed: ['KHR_lights_punctual'], extensions: { KHR_lights_punctual: { lights: [{ type: 'spot', intensity: -1, spot: {} }] } } };
  await refused(loadGltfScene(bytes(triangleGltf(triangleDataUri, light))), 'INVALID_GLTF', '/extensions/KHR_lights_punctual/lights/0/intensity');
});

test('positions beyond the renderer range and vertex colours above 1 are refused at load, not by the renderer', async () => {
  const distant = new Float32Array([0, 0, 0, 1e19, 0, 0, 0, 1, 0]);
  const farUri = `data:application/octet-stream;base64,${Buffer.from(distant.buffer).toString('base64')}`;
  await refused(loadGltfScene(bytes(triangleGltf(farUri))), 'INVALID_GLTF', '/meshes/0/primitives/0/attributes/POSITION', /exceeds the largest supported coordinate/);
  const data = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 1, 1, 1]);
  const uri = `data:application/octet-stream;base64,${Buffer.from(data.buffer).toString('base64')}`;
  const colors = triangleGltf(uri, {
    buffers: [{ uri, byteLength: 72 }],
    bufferViews: [{ buffer: 0, byteLength: 36 }, { buffer: 0, byteOffset: 36, byteLength: 36 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3' }, { bufferView: 1, componentType: 5126, count: 3, type: 'VEC3' }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, COLOR_0: 1 } }] }],
  });
  await refused(loadGltfScene(bytes(colors)), 'INVALID_GLTF', '/meshes/0/primitives/0/attributes/COLOR_0', /vertex colours are in \[0, 1\]/);
  // Found by the fuzzer: a light placed beyond the coordinate range by its node.
  const far = triangleGltf(triangleDataUri, {
    extensionsUsed: ['KHR_lights_punctual'],
    extensions: { KHR_lights_punctual: { lights: [{ type: 'point', intensity: 1 }] } },
    nodes: [{ mesh: 0 }, { translation: [1e300, 0, 0], extensions: { KHR_lights_punctual: { light: 0 } } }],
    scenes: [{ nodes: [0, 1] }],
  });
  await refused(loadGltfScene(bytes(far)), 'INVALID_GLTF', '/nodes/1/extensions/KHR_lights_punctual', /lights\[0\]\.position/);
});

test('what @gltf-transform crashed on is refused with the pointer: no texture source, non-object extensions, meshopt fallbacks', async () => {
  const textured = withMaterial({ pbrMetallicRoughness: { baseColorTexture: { index: 0 } } }, { images: [{ uri: 'data:image/png;base64,' }], textures: [{}] });
  await refused(loadGltfScene(bytes(textured)), 'INVALID_GLTF', '/textures/0', /no source image/);
  // An extension's source counts only when the extension is in extensionsUsed (else it is not read).
  const unlisted = { ...textured, textures: [{ extensions: { EXT_texture_avif: { source: 0 } } }] };
  await refused(loadGltfScene(bytes(unlisted)), 'INVALID_GLTF', '/textures/0', /no source image/);
  const sourceless = { ...textured, extensionsUsed: ['KHR_texture_basisu'], textures: [{ source: 0, extensions: { KHR_texture_basisu: { value: { source: 0 } } } }] };
  await refused(loadGltfScene(bytes(sourceless)), 'INVALID_GLTF', '/textures/0/extensions/KHR_texture_basisu/source', /expected an integer/);
  await refused(loadGltfScene(bytes(triangleGltf(triangleDataUri, { bufferViews: [{ buffer: 0, byteLength: 36, extensions: 1e300 }] }))), 'INVALID_GLTF', '/bufferViews/0/extensions');
  await refused(loadGltfScene(bytes(withMaterial({ extensions: { KHR_materials_ior: 1 } }))), 'INVALID_GLTF', '/materials/0/extensions/KHR_materials_ior');
  await refused(loadGltfScene(bytes(triangleGltf(triangleDataUri, { extensionsUsed: 'perspective' }))), 'INVALID_GLTF', '/extensionsUsed');
  await refused(loadGltfScene(bytes(triangleGltf(triangleDataUri, { extensionsRequired: ['KHR_materials_ior'] }))), 'INVALID_GLTF', '/extensionsRequired/0', /not listed in extensionsUsed/);
  const fallback = triangleGltf(triangleDataUri, {
    extensionsUsed: ['EXT_meshopt_compression'],
    buffers: [{ byteLength: 36, extensions: { EXT_meshopt_compression: { fallback: true } } }],
  });
  await refused(loadGltfScene(bytes(fallback)), 'INVALID_GLTF', '/bufferViews/0/buffer', /fallback/);
  const draco = triangleGltf(triangleDataUri, {
    extensionsUsed: ['KHR_draco_mesh_compression'],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, extensions: { KHR_draco_mesh_compression: { bufferView: 0, attributes: { POSITION: 0, scale: 1 } } } }] }],
  });
  await refused(loadGltfScene(bytes(draco)), 'INVALID_GLTF', '/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression/attributes/scale', /no scale attribute/);
});

test('a normal-mapped primitive whose triangles all have zero area loads (the mikktspace wasm trapped)', async () => {
  const zero = `data:application/octet-stream;base64,${Buffer.from(new Float32Array(15).buffer).toString('base64')}`;
  const png = 'iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8DwHwAFBQIAX8jx0gAAAABJRU5ErkJggg==';
  const json = {
    asset: { version: '2.0' },
    buffers: [{ uri: zero, byteLength: 60 }],
    bufferViews: [{ buffer: 0, byteLength: 36 }, { buffer: 0, byteOffset: 36, byteLength: 24 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3' }, { bufferView: 1, componentType: 5126, count: 3, type: 'VEC2' }],
    images: [{ uri: `data:image/png;base64,${png}` }],
    textures: [{ source: 0 }],
    materials: [{ normalTexture: { index: 0 } }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, TEXCOORD_0: 1 }, material: 0 }] }],
    nodes: [{ mesh: 0 }],
    scenes: [{ nodes: [0] }],
  };
  for (let k = 0; k < 2; k++) {
    const scene = await loadGltfScene(bytes(json));
    const t = scene.meshes[0]!.tangents!;
    assert.equal(t.length, 4 * (scene.meshes[0]!.positions.length / 3));
    for (let v = 0; v < t.length; v += 4) assert.ok(Math.abs(Math.hypot(t[v]!, t[v + 1]!, t[v + 2]!) - 1) < 1e-6 && Math.abs(t[v + 3]!) === 1, `tangent ${v / 4}`);
  }
});

test('renderer options: device {}, powerPreference "x", materials [null], camera at 1e19 and baseColorFactor [2, 2, 2] are typed errors', async () => {
  const base = { ...createCornellBoxScene(), width: 4, height: 4 };
  await refused(createWavefrontPathTracingComputeRenderer({ ...base, device: {} as GPUDevice }), 'INVALID_OPTION', 'device', /expected a GPUDevice/);
  await refused(createWavefrontPathTracingComputeRenderer({ ...base, device: null as unknown as GPUDevice }), 'INVALID_OPTION', 'device');
  await refused(createWavefrontPathTracingComputeRenderer({ ...base, powerPreference: 'x' as GPUPowerPreference }), 'INVALID_OPTION', 'powerPreference');
  await refused(createWavefrontPathTracingComputeRenderer({ ...base, materials: [null as never] }), 'INVALID_MATERIAL', 'materials[0]', /got null/);
  await refused(createWavefrontPathTracingComputeRenderer({ ...base, camera: { position: [1e19, 0, 0], target: [0, 0, 0] } }), 'INVALID_OPTION', 'camera.position[0]', /beyond the supported coordinate range/);
  await refused(createWavefrontPathTracingComputeRenderer({ ...base, camera: null as never }), 'INVALID_OPTION', 'camera', /got null/);
  await refused(createWavefrontPathTracingComputeRenderer({ ...base, materials: [{ baseColorFactor: [2, 2, 2] }] }), 'INVALID_MATERIAL', 'materials[0].baseColorFactor[0]', /<= 1/);
});

test('updateCamera(null) and updateCamera(undefined) are typed errors and keep the camera', async () => {
  const renderer = await createWavefrontPathTracingComputeRenderer({ ...createCornellBoxScene(), width: 4, height: 4, device: await testDevice() });
  try {
    const before = await renderer.renderFrame();
    assert.equal(before.samplesAdded, 1);
    assert.throws(() => renderer.updateCamera(null as never), (e: Error & { code?: string; field?: string }) => e.code === 'INVALID_OPTION' && e.field === 'camera');
    assert.throws(() => renderer.updateCamera(undefined as never), (e: Error & { code?: string; field?: string }) => e.code === 'INVALID_OPTION' && e.field === 'camera');
    assert.throws(() => renderer.updateCamera({ position: [0, 0, 1e19], target: [0, 0, 0] }), (e: Error & { field?: string }) => e.field === 'camera.position[2]');
    // Nothing was reset by the refused calls: the accumulation continues.
    assert.equal((await renderer.renderFrame()).samplesAccumulated, 2);
  } finally {
    renderer.destroy();
  }
});

test('scene files are refused at load by the renderer validation, and references may not place assets out of range', async () => {
  const f = assetFolder();
  try {
    const path = join(f.asset, 'scene.json');
    writeFileSync(path, JSON.stringify({ meshes: [{ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], indices: [0, 1, 2, 0, 1] }] }));
    await refused(loadSceneFile(path), 'INVALID_SCENE_FILE', 'meshes[0].indices', /multiple of 3/);
    writeFileSync(join(f.asset, 'tri.gltf'), JSON.stringify(triangleGltf(triangleDataUri)));
    writeFileSync(path, JSON.stringify({ gltf: [{ src: 'tri.gltf', transform: [3.5e38, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] }] }));
    await refused(loadSceneFile(path), 'INVALID_SCENE_FILE', 'gltf[0].transform[0]', /largest supported coordinate/);
    writeFileSync(path, JSON.stringify({ gltf: [{ src: 'tri.gltf', transform: [1e18, 0, 0, 0, 0, 1e18, 0, 0, 0, 0, 1e18, 0, 1e18, 0, 0, 1] }] }));
    await refused(loadSceneFile(path), 'INVALID_SCENE_FILE', 'gltf[0].transform', /places the asset/);
    // Found by the fuzzer: a texture naming an image the file does not have, and a map intensity
    // whose product with the brightest texel the renderer cannot hold (1e20).
    writeFileSync(path, JSON.stringify({ textures: [{ image: 0 }] }));
    await refused(loadSceneFile(path), 'INVALID_SCENE_FILE', 'textures[0].image', /index into images/);
    writeFileSync(join(f.asset, 'sky.hdr'), new TextEncoder().encode('#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n\x80\x80\x80\x81'));
    writeFileSync(path, JSON.stringify({ environment: { map: 'sky.hdr', intensity: 1e21 } }));
    await refused(loadSceneFile(path), 'INVALID_SCENE_FILE', 'environment.intensity', /exceeds the supported/);
  } finally {
    f.cleanup();
  }
});

test("negativeTexels: 'zero' zeroes negative texels also without an onNegativeTexels callback", async () => {
  const exr = encodeExr(2, 1, new Float64Array([1, 1, 1, -0.5, 2, 3]), 'float', 'none');
  await refused(loadEnvironmentMap(exr), 'INVALID_ENVIRONMENT', 'source.data[4]', /must be finite and >= 0/);
  const map = await loadEnvironmentMap(exr, { negativeTexels: 'zero' });
  assert.deepEqual([...map.data], [1, 1, 1, 1, 0, 2, 3, 1]);
});
