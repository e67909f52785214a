// Runs the package's WESL BVH traversal (trace_closest and trace_any) on real WebGPU for a batch of
// rays over packed primitives, nodes and parent links: the shared plumbing of the traversal tests.
import { BufferUsage, TextureUsage } from '../../src/gpu/webgpu-constants.ts';
import { readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { runTestProgram } from '../helpers/wgsl.ts';

const kernel = `
import package::accel::bvh_traversal::{make_trace_ray, trace_closest, trace_any};
import package::layout::constants::INDEX_NONE;
@group(3) @binding(20) var<storage, read> testRays: array<vec4f>;
@group(3) @binding(21) var<storage, read_write> testResults: array<vec4u>;

// One ray per invocation: trace_closest over (0, rays[2i].w), trace_any over (0, rays[2i + 1].w).
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= arrayLength(&testResults)) { return; }
  let a = testRays[2u * i];
  let b = testRays[2u * i + 1u];
  let ray = make_trace_ray(a.xyz, b.xyz, 0u);
  let closest = trace_closest(ray, a.w);
  let any = trace_any(ray, b.w);
  let fallbacks = select(0u, 1u, closest.fallback) | select(0u, 2u, any.fallback);
  testResults[i] = vec4u(bitcast<u32>(closest.t), closest.slot, select(0u, 1u, any.slot != INDEX_NONE), fallbacks);
}
`;

export interface GpuTraceResult {
  t: Float32Array;
  slot: Uint32Array;
  occluded: Uint8Array;
  /** Bit 0: the closest-hit query fell back to stackless traversal; bit 1: the any-hit query did. */
  fallbacks: Uint8Array;
}

/** `rays[k]` = origin, direction, closest-hit tMax, any-hit tMax. */
export async function traceOnGpu(
  scene: { primitives: ArrayBuffer; nodes: ArrayBuffer; parents: Uint32Array },
  rays: readonly { origin: ArrayLike<number>; direction: ArrayLike<number>; tMax: number; anyTMax: number }[],
): Promise<GpuTraceResult> {
  const device = await testDevice();
  const count = rays.length;
  const rayData = new Float32Array(count * 8);
  rays.forEach((r, k) => rayData.set([r.origin[0]!, r.origin[1]!, r.origin[2]!, r.tMax, r.direction[0]!, r.direction[1]!, r.direction[2]!, r.anyTMax], k * 8));
  const results = device.createBuffer({ size: count * 16, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
  const atlas = device.createTexture({ size: [1, 1, 1], format: 'rgba8unorm', usage: TextureUsage.TEXTURE_BINDING });
  const buffers = {
    primitives: uploadBuffer(device, scene.primitives),
    bvhNodes: uploadBuffer(device, scene.nodes),
    bvhParents: uploadBuffer(device, scene.parents),
    alphaPrimitives: uploadBuffer(device, new ArrayBuffer(64)),
    materials: uploadBuffer(device, new ArrayBuffer(64)),
    testRays: uploadBuffer(device, rayData),
    testResults: results,
  };
  try {
    await runTestProgram(device, {
      source: kernel,
      resources: { ...buffers, textureAtlas: atlas.createView({ dimension: '2d-array' }) },
      workgroups: Math.ceil(count / 64),
      constants: { FEATURE_ANALYTIC_SHAPES: 0, FEATURE_ALPHA_TEST: 0, FEATURE_TEXTURES: 0 },
    });
    const out = await readBuffer(device, results);
    const f = new Float32Array(out);
    const u = new Uint32Array(out);
    const r: GpuTraceResult = { t: new Float32Array(count), slot: new Uint32Array(count), occluded: new Uint8Array(count), fallbacks: new Uint8Array(count) };
    for (let k = 0; k < count; k++) {
      r.t[k] = f[4 * k]!;
      r.slot[k] = u[4 * k + 1]!;
      r.occluded[k] = u[4 * k + 2]!;
      r.fallbacks[k] = u[4 * k + 3]!;
    }
    return r;
  } finally {
    for (const b of Object.values(buffers)) b.destroy();
    atlas.destroy();
  }
}
