/**
 * `node bench/kernel-times.ts`: GPU time per kernel of a 1-spp Cornell box frame (256x256 unless
 * SIZE, maxDepth 8 unless MAXDEPTH; FRAMES (5) frames after one warm-up), in Node on Dawn, on
 * SwiftShader (ADAPTER=swiftshader, the default: Chromium's own libvk_swiftshader, the CPU
 * implementation browsers without a GPU use) or lavapipe (ADAPTER=lavapipe).
 *
 * Why: Chromium's frame time is one number. This harness replays every compute pass of a frame
 * one dispatch per pass, with timestamp queries around each, and sums the time per entry point,
 * which says where a browser frame goes. It wraps only the device's encoder and pipeline
 * factories, not the renderer, so it measures any version: ENTRY names the module that exports
 * createCornellBoxScene and createWavefrontPathTracingComputeRenderer (default this checkout's
 * src/index.ts; for an older commit, a worktree's). Replaying each dispatch as its own pass adds a
 * pass boundary per dispatch, so the total is a little above the frame's.
 */
import { existsSync } from 'node:fs';
import { fileURLToPath, pathToFileURL } from 'node:url';

const adapterKind = process.env.ADAPTER ?? 'swiftshader';
const swiftshaderIcd = '/usr/lib/chromium/vk_swiftshader_icd.json';
if (adapterKind === 'swiftshader') {
  if (!existsSync(swiftshaderIcd)) throw new Error(`kernel-times: ${swiftshaderIcd} is missing (Debian's chromium package ships it; scripts/setup.sh installs chromium)`);
  // Read by the Vulkan loader when Dawn creates its instance, below.
  process.env.VK_ICD_FILENAMES = swiftshaderIcd;
} else if (adapterKind !== 'lavapipe') {
  throw new Error(`kernel-times: ADAPTER must be swiftshader or lavapipe, got ${adapterKind}`);
}

const { create, globals } = await import('webgpu');
Object.assign(globalThis, globals);
// Held for the whole run: a collected GPU object takes Dawn's instance (and the device) with it.
const gpu = create([]);
const adapter = await gpu.requestAdapter();
if (!adapter) throw new Error('kernel-times: no WebGPU adapter');
const limits = adapter.limits;
const device = await adapter.requestDevice({
  requiredFeatures: ['timestamp-query'],
  requiredLimits: { maxStorageBuffersPerShaderStage: limits.maxStorageBuffersPerShaderStage, maxStorageBufferBindingSize: limits.maxStorageBufferBindingSize, maxBufferSize: limits.maxBufferSize },
});

type Pass = GPUComputePassEncoder;
const entryPoints = new WeakMap<GPUComputePipeline, string>();
const deviceHooks = device as unknown as Record<string, (descriptor: GPUComputePipelineDescriptor) => unknown>;
for (const name of ['createComputePipeline', 'createComputePipelineAsync']) {
  const original = deviceHooks[name]!.bind(device);
  deviceHooks[name] = (descriptor) => {
    const name = (p: GPUComputePipeline): GPUComputePipeline => (entryPoints.set(p, descriptor.compute.entryPoint ?? descriptor.label ?? '?'), p);
    const made = original(descriptor) as GPUComputePipeline | Promise<GPUComputePipeline>;
    return made instanceof Promise ? made.then(name) : name(made);
  };
}

const maxDispatches = 1024;
const querySet = device.createQuerySet({ type: 'timestamp', count: 2 * maxDispatches });
const timed: string[] = [];
let recording = false;
const createEncoder = device.createCommandEncoder.bind(device);
device.createCommandEncoder = (descriptor?: GPUCommandEncoderDescriptor): GPUCommandEncoder => {
  const encoder = createEncoder(descriptor);
  if (!recording) return encoder;
  const beginPass = encoder.beginComputePass.bind(encoder);
  // A stand-in pass that records each dispatch with the state it was issued in, and on end()
  // replays them one per timed pass.
  encoder.beginComputePass = (): Pass => {
    const replays: ((pass: Pass) => void)[] = [];
    let pipeline: GPUComputePipeline | null = null;
    const groups: [GPUBindGroup, Iterable<number>][] = [];
    const issue = (kind: string, dispatch: (pass: Pass) => void): void => {
      const p = pipeline!;
      const bound = groups.slice();
      replays.push((pass) => {
        pass.setPipeline(p);
        bound.forEach((g, i) => g && pass.setBindGroup(i, g[0], g[1]));
        dispatch(pass);
        timed.push((entryPoints.get(p) ?? '?') + kind);
      });
    };
    const stand: Partial<Pass> = {
      setPipeline: (p: GPUComputePipeline) => void (pipeline = p),
      setBindGroup: ((index: number, group: GPUBindGroup, offsets: Iterable<number> = []) => void (groups[index] = [group, offsets])) as Pass['setBindGroup'],
      dispatchWorkgroups: ((x: number, y = 1, z = 1) => issue('', (pass) => pass.dispatchWorkgroups(x, y, z))) as Pass['dispatchWorkgroups'],
      dispatchWorkgroupsIndirect: ((buffer: GPUBuffer, offset: number) => issue(' (indirect)', (pass) => pass.dispatchWorkgroupsIndirect(buffer, offset))) as Pass['dispatchWorkgroupsIndirect'],
      pushDebugGroup: () => undefined,
      popDebugGroup: () => undefined,
      insertDebugMarker: () => undefined,
      end: () => {
        for (const replay of replays) {
          const k = timed.length;
          if (k >= maxDispatches) throw new Error(`kernel-times: more than ${maxDispatches} dispatches in a frame`);
          const pass = beginPass({ timestampWrites: { querySet, beginningOfPassWriteIndex: 2 * k, endOfPassWriteIndex: 2 * k + 1 } });
          replay(pass);
          pass.end();
        }
      },
    };
    return stand as Pass;
  };
  return encoder;
};

interface Package {
  createCornellBoxScene(): object;
  createWavefrontPathTracingComputeRenderer(options: object): Promise<{ renderFrame(): Promise<unknown>; destroy(): void }>;
}
const entry = process.env.ENTRY ?? fileURLToPath(new URL('../src/index.ts', import.meta.url));
const pkg = (await import(pathToFileURL(entry).href)) as Package;
const size = Number(process.env.SIZE ?? 256);
const frames = Number(process.env.FRAMES ?? 5);
const renderer = await pkg.createWavefrontPathTracingComputeRenderer({ ...pkg.createCornellBoxScene(), device, width: size, height: size, samplesPerPixel: 1, maxDepth: Number(process.env.MAXDEPTH ?? 8) });
await renderer.renderFrame();

const totals = new Map<string, { ms: number; dispatches: number }>();
for (let f = 0; f < frames; f++) {
  timed.length = 0;
  recording = true;
  await renderer.renderFrame();
  recording = false;
  const k = timed.length;
  const resolve = device.createBuffer({ size: 16 * k, usage: GPUBufferUsage.QUERY_RESOLVE | GPUBufferUsage.COPY_SRC });
  const read = device.createBuffer({ size: 16 * k, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  const encoder = createEncoder();
  encoder.resolveQuerySet(querySet, 0, 2 * k, resolve, 0);
  encoder.copyBufferToBuffer(resolve, 0, read, 0, 16 * k);
  device.queue.submit([encoder.finish()]);
  await read.mapAsync(GPUMapMode.READ);
  const t = new BigUint64Array(read.getMappedRange().slice(0));
  read.unmap();
  timed.forEach((name, i) => {
    const row = totals.get(name) ?? { ms: 0, dispatches: 0 };
    row.ms += Number(t[2 * i + 1]! - t[2 * i]!) / 1e6 / frames;
    row.dispatches += 1 / frames;
    totals.set(name, row);
  });
}
renderer.destroy();
void gpu;
const sum = [...totals.values()].reduce((s, r) => s + r.ms, 0);
console.log(`${adapter.info.description || adapterKind}: ${size}x${size}, 1 spp, means of ${frames} frames, ${sum.toFixed(0)} ms of GPU time per frame`);
console.table([...totals].map(([kernel, r]) => ({ kernel, 'ms per frame': Number(r.ms.toFixed(1)), share: `${((100 * r.ms) / sum).toFixed(0)} %`, dispatches: Math.round(r.dispatches) })));
process.exit(0);
