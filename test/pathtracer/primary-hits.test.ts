// The renderer's WGSL camera (camera_ray) and closest-hit traversal (trace_closest), run on the GPU
// for random pixels and jitters, agree with the JS reference helpers' brute-force hits, for a
// perspective and an orthographic camera.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontMeshAcceleration, createWavefrontPathTracingComputeConfig, createWavefrontReferenceRay, traceWavefrontReferenceTriangles } from '../../src/pathtracer/index.ts';
import { CAMERA_ORTHOGRAPHIC, CAMERA_PERSPECTIVE, INDEX_NONE } from '../../src/gpu-layout/constants.ts';
import { frameUniformsLayout, primitiveLayout } from '../../src/gpu-layout/records.ts';
import { writeStruct } from '../../src/gpu-layout/struct-layout.ts';
import { BufferUsage, TextureUsage } from '../../src/gpu/webgpu-constants.ts';
import type { WavefrontCameraInput } from '../../src/scene/types.ts';
import { readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { rng } from '../helpers/meshes.ts';
import { runTestProgram } from '../helpers/wgsl.ts';

const kernel = `
import package::layout::bindings::frame;
import package::pathtracer::camera::camera_ray;
import package::accel::bvh_traversal::{make_trace_ray, trace_closest};
import package::shaders::lib::math::F32_INF;
@group(3) @binding(20) var<storage, read> queries: array<vec4f>;
@group(3) @binding(21) var<storage, read_write> results: array<vec4f>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3u) {
  if (gid.x >= arrayLength(&queries)) { return; }
  let q = queries[gid.x];
  let ray = camera_ray(frame, q.xy + q.zw);
  let hit = trace_closest(make_trace_ray(ray.origin, ray.direction, 0u), F32_INF);
  results[gid.x] = vec4f(bitcast<f32>(hit.slot), hit.t, hit.u, hit.v);
}`;

async function primaryHits(camera: WavefrontCameraInput): Promise<void> {
  const device = await testDevice();
  const random = rng(1234);
  const width = 320, height = 240;
  const config = createWavefrontPathTracingComputeConfig({ width, height, camera });
  // A random triangle soup in front of the camera.
  const triangles = Array.from({ length: 400 }, () => {
    const c = [random() * 6 - 3, random() * 4 - 2, random() * 4 - 2];
    const v = () => c.map((x) => x + (random() - 0.5) * 1.2);
    return { v0: v(), v1: v(), v2: v() };
  });
  const positions = triangles.flatMap((t) => [...t.v0, ...t.v1, ...t.v2]);
  const accel = await createWavefrontMeshAcceleration([{ positions }]);
  const frame = new ArrayBuffer(frameUniformsLayout.size);
  writeStruct(frameUniformsLayout, new DataView(frame), 0, {
    cameraPosition: config.camera.position, tanHalfFovY: config.camera.tanHalfFovY, cameraRight: config.camera.right,
    aspect: width / height, cameraUp: config.camera.trueUp, cameraForward: config.camera.forward, imageSize: [width, height],
    cameraKind: config.camera.kind === 'orthographic' ? CAMERA_ORTHOGRAPHIC : CAMERA_PERSPECTIVE,
    orthographicHalfHeight: config.camera.orthographicHalfHeight,
  });
  const n = 4096;
  const queries = new Float32Array(n * 4);
  for (let i = 0; i < n; i++) queries.set([Math.floor(random() * width), Math.floor(random() * height), random(), random()], 4 * i);
  const results = device.createBuffer({ size: n * 16, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
  const atlas = device.createTexture({ size: [1, 1, 1], format: 'rgba8unorm', usage: TextureUsage.TEXTURE_BINDING });
  await runTestProgram(device, {
    source: kernel,
    resources: {
      frame: uploadBuffer(device, frame, BufferUsage.UNIFORM),
      primitives: uploadBuffer(device, accel.primitives),
      bvhNodes: uploadBuffer(device, accel.bvhNodes),
      bvhParents: uploadBuffer(device, accel.bvhParents),
      alphaPrimitives: uploadBuffer(device, accel.alphaPrimitives),
      materials: uploadBuffer(device, accel.materials),
      textureAtlas: atlas.createView({ dimension: '2d-array' }),
      queries: uploadBuffer(device, queries),
      results,
    },
    workgroups: Math.ceil(n / 64),
  });
  const out = await readBuffer(device, results);
  const ids = new Uint32Array(out);
  const values = new Float32Array(out);
  const primitive = new Uint32Array(accel.primitives);
  let hits = 0, compared = 0;
  for (let i = 0; i < n; i++) {
    const ray = createWavefrontReferenceRay(config, { pixel: [queries[4 * i]!, queries[4 * i + 1]!], jitter: [queries[4 * i + 2]!, queries[4 * i + 3]!] });
    const ref = traceWavefrontReferenceTriangles(config, ray, triangles);
    const slot = ids[4 * i]!;
    // Rays grazing an edge (barycentric margin < 1e-4) may legitimately flip between neighbours in f32.
    const nearEdge = ref.hit && Math.min(ref.u, ref.v, 1 - ref.u - ref.v) < 1e-4;
    if (nearEdge) continue;
    compared++;
    if (!ref.hit) {
      assert.equal(slot, INDEX_NONE, `ray ${i}: reference misses, GPU hit`);
      continue;
    }
    hits++;
    assert.notEqual(slot, INDEX_NONE, `ray ${i}: reference hits triangle ${ref.triangle}, GPU misses`);
    // The primitive record's `primitive` field is the triangle's index in its (only) mesh.
    assert.equal(primitive[slot * (primitiveLayout.size / 4) + 7], ref.triangle, `ray ${i}: triangle id`);
    assert.ok(Math.abs(values[4 * i + 1]! - ref.t) <= 1e-5 * ref.t, `ray ${i}: t ${values[4 * i + 1]} vs ${ref.t}`);
  }
  assert.ok(compared > 4000 && hits > 1000, `compared ${compared}, hits ${hits}`);
  atlas.destroy();
}

test('GPU primary hits equal the JS reference helpers on random rays (ids and distances): perspective camera', async () => {
  await primaryHits({ position: [0.3, 0.2, 6], target: [0, 0, 0], up: [0, 1, 0], fovYDegrees: 50 });
});

test('GPU primary hits equal the JS reference helpers on random rays: orthographic camera', async () => {
  await primaryHits({ type: 'orthographic', position: [0.3, 0.2, 6], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 5 });
});
