// The renderer's WGSL camera (camera_ray_direction) and closest-hit traversal (trace_closest), run on
// the GPU for random pixels and jitters, agree with the JS reference helpers' brute-force hits.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { composeShader } from '../../src/shaders/modules.ts';
import { createWavefrontMeshAcceleration, createWavefrontPathTracingComputeConfig, createWavefrontReferenceRay, traceWavefrontReferenceTriangles } from '../../src/pathtracer/index.ts';
import { frameUniformsLayout, PRIMITIVE_NONE } from '../../src/gpu-layout/records.ts';
import { writeStruct } from '../../src/gpu-layout/struct-layout.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import { createShaderChecked, readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { rng } from '../helpers/meshes.ts';

const kernel = `
@group(3) @binding(0) var<storage, read> queries: array<vec4f>;
@group(3) @binding(1) var<storage, read_write> results: array<vec4f>;
@compute @workgroup_size(64)
fn primary_hits(@builtin(global_invocation_id) gid: vec3u) {
  if (gid.x >= arrayLength(&queries)) { return; }
  let q = queries[gid.x];
  let direction = camera_ray_direction(q.xy + q.zw);
  let hit = trace_closest(frame.cameraPosition, direction, F32_INF);
  results[gid.x] = vec4f(bitcast<f32>(hit.primitive), hit.t, hit.u, hit.v);
}`;

test('GPU primary hits equal the JS reference helpers on random rays (ids and distances)', async () => {
  const device = await testDevice();
  const random = rng(1234);
  const width = 320, height = 240;
  const camera = { position: [0.3, 0.2, 6], target: [0, 0, 0], up: [0, 1, 0], fovYDegrees: 50 };
  const config = createWavefrontPathTracingComputeConfig({ width, height, camera });
  // A random triangle soup in front of the camera.
  const triangles = Array.from({ length: 400 }, () => {
    const c = [random() * 6 - 3, random() * 4 - 2, random() * 4 - 2];
    const v = () => c.map((x) => x + (random() - 0.5) * 1.2);
    return { v0: v(), v1: v(), v2: v() };
  });
  const positions = triangles.flatMap((t) => [...t.v0, ...t.v1, ...t.v2]);
  const accel = createWavefrontMeshAcceleration([{ positions }]);
  const frame = new ArrayBuffer(frameUniformsLayout.size);
  writeStruct(frameUniformsLayout, new DataView(frame), 0, {
    cameraPosition: config.camera.position, tanHalfFovY: config.camera.tanHalfFovY, cameraRight: config.camera.right,
    aspect: width / height, cameraUp: config.camera.trueUp, cameraForward: config.camera.forward, imageSize: [width, height],
    triangleCount: accel.triangleCount, sceneObjectCount: 0,
  });
  const n = 4096;
  const queries = new Float32Array(n * 4);
  for (let i = 0; i < n; i++) queries.set([Math.floor(random() * width), Math.floor(random() * height), random(), random()], 4 * i);
  const module = await createShaderChecked(device, composeShader(['camera', 'bvh-traversal']) + kernel);
  const pipeline = device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint: 'primary_hits' } });
  const frameBuffer = uploadBuffer(device, frame, BufferUsage.UNIFORM);
  const results = device.createBuffer({ size: n * 16, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
  const group = (g: number, entries: GPUBindGroupEntry[]) => device.createBindGroup({ layout: pipeline.getBindGroupLayout(g), entries });
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipeline);
  pass.setBindGroup(0, group(0, [
    { binding: 0, resource: { buffer: frameBuffer } },
    { binding: 1, resource: { buffer: uploadBuffer(device, accel.triangles) } },
    { binding: 3, resource: { buffer: uploadBuffer(device, accel.nodes) } },
    { binding: 5, resource: { buffer: uploadBuffer(device, new ArrayBuffer(32)) } },
  ]));
  pass.setBindGroup(1, group(1, []));
  pass.setBindGroup(2, group(2, []));
  pass.setBindGroup(3, group(3, [{ binding: 0, resource: { buffer: uploadBuffer(device, queries) } }, { binding: 1, resource: { buffer: results } }]));
  pass.dispatchWorkgroups(Math.ceil(n / 64));
  pass.end();
  device.queue.submit([encoder.finish()]);
  const out = await readBuffer(device, results);
  const ids = new Uint32Array(out);
  const values = new Float32Array(out);
  let hits = 0, compared = 0;
  for (let i = 0; i < n; i++) {
    const ray = createWavefrontReferenceRay(config, { pixel: [queries[4 * i]!, queries[4 * i + 1]!], jitter: [queries[4 * i + 2]!, queries[4 * i + 3]!] });
    const ref = traceWavefrontReferenceTriangles(config, ray, triangles);
    const gpuId = ids[4 * i]!;
    // Rays grazing an edge (barycentric margin < 1e-4) may legitimately flip between neighbours in f32.
    const nearEdge = ref.hit && Math.min(ref.u, ref.v, 1 - ref.u - ref.v) < 1e-4;
    if (nearEdge) continue;
    compared++;
    if (!ref.hit) {
      assert.equal(gpuId, PRIMITIVE_NONE, `ray ${i}: reference misses, GPU hit`);
      continue;
    }
    hits++;
    assert.notEqual(gpuId, PRIMITIVE_NONE, `ray ${i}: reference hits triangle ${ref.triangle}, GPU misses`);
    const source = accel.triangleOrder[gpuId & 0x3fffffff]!;
    assert.equal(source, ref.triangle, `ray ${i}: triangle id`);
    assert.ok(Math.abs(values[4 * i + 1]! - ref.t) <= 1e-5 * ref.t, `ray ${i}: t ${values[4 * i + 1]} vs ${ref.t}`);
  }
  assert.ok(compared > 4000 && hits > 1000, `compared ${compared}, hits ${hits}`);
});
