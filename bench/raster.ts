/**
 * Raster renderer benchmark: frame time at 1920 x 1080 offscreen (4x MSAA, shadow map, prefiltered
 * environment) with 1 and 16 GPU-skinned characters, and skinning throughput (skinned vertices per
 * second) from frames whose output is 16 x 16 without shadows, where the skinning dispatches dominate. The character
 * is generated here: a textured tube of 48 x 160 vertices skinned to a chain of 8 joints (2
 * influences per vertex), bent every frame.
 */
import { mat4d } from 'wgpu-matrix';
import { acquireGpuDevice } from '../src/gpu/acquire-device.ts';
import { createRasterRenderer } from '../src/raster/index.ts';
import type { RasterRenderer, RasterSkinnedMeshInput } from '../src/raster/index.ts';

const SEGMENTS = 48;
const RINGS = 160;
const JOINTS = 8;
const HEIGHT = 1.8;

function benchCharacter(): RasterSkinnedMeshInput {
  const positions: number[] = [];
  const normals: number[] = [];
  const tangents: number[] = [];
  const uvs: number[] = [];
  const joints: number[] = [];
  const weights: number[] = [];
  const indices: number[] = [];
  for (let r = 0; r < RINGS; r++) {
    const y = (HEIGHT * r) / (RINGS - 1);
    const radius = 0.18 + 0.05 * Math.sin((Math.PI * r) / (RINGS - 1));
    const f = (y / HEIGHT) * (JOINTS - 1);
    const j0 = Math.min(JOINTS - 2, Math.floor(f));
    const w1 = f - j0;
    for (let s = 0; s < SEGMENTS; s++) {
      const a = (2 * Math.PI * s) / SEGMENTS;
      positions.push(radius * Math.sin(a), y, radius * Math.cos(a));
      normals.push(Math.sin(a), 0, Math.cos(a));
      tangents.push(Math.cos(a), 0, -Math.sin(a), 1);
      uvs.push(s / SEGMENTS, 1 - r / (RINGS - 1));
      joints.push(j0, j0 + 1, 0, 0);
      weights.push(1 - w1, w1, 0, 0);
    }
  }
  for (let r = 0; r + 1 < RINGS; r++) {
    for (let s = 0; s < SEGMENTS; s++) {
      const a = r * SEGMENTS + s;
      const b = r * SEGMENTS + ((s + 1) % SEGMENTS);
      indices.push(a, b, b + SEGMENTS, a, b + SEGMENTS, a + SEGMENTS);
    }
  }
  return { positions, normals, tangents, uvs, indices, influences: 4, joints, weights, jointCount: JOINTS, material: 0 };
}

/** Joint matrices of a chain bent by `phase`: joint j rotates about Z around its rest height. */
function bentChain(phase: number): Float32Array {
  const out = new Float32Array(16 * JOINTS);
  let parent = mat4d.identity();
  for (let j = 0; j < JOINTS; j++) {
    const y = (HEIGHT * j) / (JOINTS - 1);
    const local = mat4d.multiply(mat4d.translation([0, y, 0]), mat4d.multiply(mat4d.rotationZ(0.12 * Math.sin(phase + j)), mat4d.translation([0, -y, 0])));
    parent = mat4d.multiply(parent, local);
    out.set(parent, 16 * j);
  }
  return out;
}

function checker(size: number): Uint8Array {
  const data = new Uint8Array(size * size * 4);
  for (let y = 0; y < size; y++) for (let x = 0; x < size; x++) {
    const on = ((x >> 3) + (y >> 3)) % 2 === 0;
    data.set(on ? [200, 120, 60, 255] : [60, 90, 180, 255], 4 * (y * size + x));
  }
  return data;
}

function skyMap(width: number, height: number): { width: number; height: number; data: Float32Array } {
  const data = new Float32Array(width * height * 4);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) {
    const v = y / (height - 1);
    const sky = v < 0.5 ? [0.5 + v, 0.7 + 0.4 * v, 1.2] : [0.25, 0.22, 0.2];
    data.set([...sky, 1], 4 * (y * width + x));
  }
  return { width, height, data };
}

async function makeRenderer(device: GPUDevice, count: number, width: number, height: number, shadows: boolean): Promise<RasterRenderer> {
  const side = Math.ceil(Math.sqrt(count));
  return createRasterRenderer({
    device,
    width,
    height,
    msaa: 4,
    camera: { position: [0, 2.2, side * 1.2 + 2.5], target: [0, 0.9, 0], fovYDegrees: 45 },
    images: [{ width: 64, height: 64, data: checker(64) }],
    textures: [{ image: 0 }],
    materials: [{ baseColorTexture: { index: 0 }, metallicFactor: 0, roughnessFactor: 0.5 }, { baseColorFactor: [0.4, 0.45, 0.35, 1], metallicFactor: 0, roughnessFactor: 0.9 }],
    meshes: [{ positions: [-8, 0, 8, 8, 0, 8, 8, 0, -8, -8, 0, -8], normals: [0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0], indices: [0, 1, 2, 0, 2, 3], material: 1 }],
    skinnedMeshes: [benchCharacter()],
    skinnedInstances: Array.from({ length: count }, (_, i) => ({ mesh: 0, transform: Array.from(mat4d.translation([((i % side) - (side - 1) / 2) * 1.2, 0, (Math.floor(i / side) - (side - 1) / 2) * 1.2])) })),
    lights: [{ type: 'directional', direction: [-0.4, -1, -0.3], intensity: 3 }],
    environmentMap: skyMap(256, 128),
    shadow: shadows ? { mapSize: 2048 } : false,
  });
}

async function timeFrames(renderer: RasterRenderer, count: number, frames: number): Promise<number[]> {
  const times: number[] = [];
  for (let f = 0; f <= frames; f++) {
    for (let i = 0; i < count; i++) renderer.setSkinPose(i, bentChain(0.3 * f + i));
    const started = performance.now();
    await renderer.render();
    if (f > 0) times.push(performance.now() - started);
  }
  return times;
}

const median = (xs: number[]): number => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)]!;

export interface RasterBenchRow {
  characters: number;
  width: number;
  height: number;
  skinnedVertices: number;
  medianFrameMs: number;
  framesPerSecond: number;
  skinnedVerticesPerSecond: number;
}

export async function runRasterBenchmark(frames = Number(process.env.BENCH_RASTER_FRAMES ?? 3)): Promise<{ adapter: string; rows: RasterBenchRow[] }> {
  const acquired = await acquireGpuDevice();
  const rows: RasterBenchRow[] = [];
  // The 16 x 16 run has no shadow map either, so the skinning dispatches dominate its frame.
  for (const [count, width, height] of [[1, 1920, 1080], [16, 1920, 1080], [16, 16, 16]] as const) {
    const renderer = await makeRenderer(acquired.device, count, width, height, width > 16);
    const times = await timeFrames(renderer, count, frames);
    renderer.destroy();
    const ms = median(times);
    const vertices = count * SEGMENTS * RINGS;
    rows.push({ characters: count, width, height, skinnedVertices: vertices, medianFrameMs: ms, framesPerSecond: 1000 / ms, skinnedVerticesPerSecond: (vertices * 1000) / ms });
  }
  acquired.device.destroy();
  return { adapter: acquired.adapterDescription, rows };
}

if (import.meta.url === `file://${process.argv[1]}`) {
  const result = await runRasterBenchmark();
  console.log(result.adapter);
  console.table(result.rows);
}
