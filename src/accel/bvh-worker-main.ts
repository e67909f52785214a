/**
 * The BVH worker's message loop. Like `createBvhKernels` it is self-contained (it uses nothing but its
 * arguments and globals): the inline worker's source is the text of both functions (see
 * bvh-worker-pool.ts), so it runs unchanged from the .ts sources, dist/esm, dist/cjs or a bundle.
 *
 * Requests carry an `id` that the reply echoes. Ops:
 * - `begin`: the shared slot buffers and settings of build `build`: either views of SharedArrayBuffers
 *   (JS loops) or a shared WebAssembly memory with the compiled module, the layout and this
 *   worker's scratch offset (WebAssembly loops);
 * - `boxes`: triangle AABBs of [from, to) (the prepass), replying their bounds;
 * - `split`: one node split (`mid` = -1 for a leaf), replying the children's bounds;
 * - `subtree`: a whole subtree in depth-first order into a fresh node buffer (transferred back);
 *   it stops early, replying `aborted`, once the build's shared abort flag is set;
 * - `end`: forget build `build`;
 * - `full`: the whole single-threaded build of copied positions (no shared memory needed), in a
 *   WebAssembly memory of its own when a module and layout come with it.
 */
import type { BvhBuildParams, BvhKernels, BvhWasmBackend, SlotBuffers } from './bvh-kernels.ts';

/** What the worker needs from its host: Node's `parentPort` or a browser worker's global scope. */
export interface BvhWorkerHost {
  onMessage(handler: (message: unknown) => void): void;
  post(message: unknown, transfer: Transferable[]): void;
}

export interface WorkerBuildMessage {
  op: string;
  id: number;
  build: number;
  [key: string]: unknown;
}

export function bvhWorkerMain(createKernels: () => BvhKernels, host: BvhWorkerHost): void {
  const k = createKernels();
  interface Layout { boxes: number; ids: number; pages: number }
  /** Views of a build's slots in WebAssembly memory, and the loops bound to it. */
  const wasmSlots = (memory: WebAssembly.Memory, module: WebAssembly.Module, layout: Layout, n: number, scratch: number): { slots: SlotBuffers; wasm: BvhWasmBackend } => {
    const instance = new WebAssembly.Instance(module, { env: { memory } });
    const buffer = memory.buffer;
    return {
      slots: { boxes: new Float32Array(buffer, layout.boxes, n * 8), ids: new Uint32Array(buffer, layout.ids, n) },
      wasm: { exports: instance.exports as unknown as BvhWasmBackend['exports'], buffer, scratch },
    };
  };
  interface Build {
    slots: SlotBuffers;
    wasm?: BvhWasmBackend;
    positions: Float32Array;
    params: BvhBuildParams;
    abort: Int32Array;
    split: ReturnType<BvhKernels['createSplitter']>;
  }
  const builds = new Map<number, Build>();
  // How long a subtree build runs between two looks at the abort flag.
  const ABORT_POLL_MS = 4;

  const handle = (m: WorkerBuildMessage): { reply: Record<string, unknown>; transfer: Transferable[] } => {
    if (m.op === 'begin') {
      const params = m.params as BvhBuildParams;
      const n = (m.positions as Float32Array).length / 9;
      const { slots, wasm } = m.memory
        ? wasmSlots(m.memory as WebAssembly.Memory, m.module as WebAssembly.Module, m.layout as Layout, n, m.scratch as number)
        : { slots: m.slots as SlotBuffers, wasm: undefined };
      builds.set(m.build, {
        slots,
        wasm,
        positions: m.positions as Float32Array,
        params,
        abort: m.abort as Int32Array,
        split: k.createSplitter(params, wasm),
      });
      return { reply: {}, transfer: [] };
    }
    if (m.op === 'end') {
      builds.delete(m.build);
      return { reply: {}, transfer: [] };
    }
    if (m.op === 'full') {
      const positions = m.positions as Float32Array;
      const params = m.params as BvhBuildParams;
      const n = positions.length / 9;
      const layout = m.layout as Layout | undefined;
      const { slots, wasm } = m.module && layout
        ? wasmSlots(new WebAssembly.Memory({ initial: layout.pages }), m.module as WebAssembly.Module, layout, n, 0)
        : { slots: { boxes: new Float32Array(n * 8), ids: new Uint32Array(n) }, wasm: undefined };
      const rootBounds = new Float64Array(12);
      k.emptyBounds(rootBounds, 0);
      k.computeBoxes(positions, slots.boxes, slots.ids, 0, n, rootBounds, 0);
      const nodes = new ArrayBuffer(Math.max(1, 2 * n - 1) * 32);
      const b = k.createSubtreeBuild({ ...slots, count: n, slotBase: 0, depth: 0, rootBounds, nodes, params, wasm });
      b.step(Infinity);
      const exact = nodes.slice(0, b.nodeCount() * 32);
      const order = wasm ? slots.ids.slice() : slots.ids;
      return {
        reply: { nodes: exact, nodeCount: b.nodeCount(), leafCount: b.leafCount(), depth: b.depthReached(), order },
        transfer: [exact, order.buffer as ArrayBuffer],
      };
    }
    const build = builds.get(m.build);
    if (!build) throw new Error(`bvh worker: unknown build ${m.build}`);
    if (m.op === 'boxes') {
      const bounds = new Float64Array(12);
      k.emptyBounds(bounds, 0);
      k.computeBoxes(build.positions, build.slots.boxes, build.slots.ids, m.from as number, m.to as number, bounds, 0);
      return { reply: { bounds }, transfer: [] };
    }
    const start = m.start as number;
    const count = m.count as number;
    const depth = m.depth as number;
    const bounds = m.bounds as Float64Array;
    if (m.op === 'split') {
      const out = new Float64Array(24);
      const mid = build.split(build.slots, start, count, depth, bounds, 0, bounds, 6, out);
      return { reply: { mid, out }, transfer: [] };
    }
    if (m.op === 'subtree') {
      const s = build.slots;
      const nodes = new ArrayBuffer((2 * count - 1) * 32);
      const b = k.createSubtreeBuild({
        boxes: s.boxes.subarray(start * 8, (start + count) * 8),
        ids: s.ids.subarray(start, start + count),
        count,
        slotBase: start,
        depth,
        rootBounds: bounds,
        nodes,
        params: build.params,
        wasm: build.wasm,
      });
      for (;;) {
        if (Atomics.load(build.abort, 0) !== 0) return { reply: { aborted: true }, transfer: [] };
        if (b.step(performance.now() + ABORT_POLL_MS)) break;
      }
      return {
        reply: { nodes, nodeCount: b.nodeCount(), leafCount: b.leafCount(), depth: b.depthReached() },
        transfer: [nodes],
      };
    }
    throw new Error(`bvh worker: unknown op ${m.op}`);
  };

  host.onMessage((data) => {
    const m = data as WorkerBuildMessage;
    try {
      const { reply, transfer } = handle(m);
      reply.id = m.id;
      host.post(reply, transfer);
    } catch (error) {
      host.post({ id: m.id, error: error instanceof Error ? `${error.message}\n${error.stack ?? ''}` : String(error) }, []);
    }
  });
}
