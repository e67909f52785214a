/**
 * The GPU radix sort of (key, value) pairs used by the LBVH build (radix-sort.wesl): recorded into a
 * DispatchList, and runnable on its own (`sortPairsOnGpu`) for other users and the tests.
 */
import { BufferUsage } from '../../gpu/webgpu-constants.ts';
import { bvhBuildConstants } from '../../gpu-layout/constants.ts';
import { DispatchList, runPass, scanSumsWords, type Resources } from './dispatch-plan.ts';
import { bvhBuildPipelines } from './pipelines.ts';

const C = bvhBuildConstants;

export interface RadixSortBuffers {
  /** Input and output keys (keyWords per pair, low word first), and the other half of the ping-pong. */
  keys: GPUBuffer;
  keysScratch: GPUBuffer;
  values: GPUBuffer;
  valuesScratch: GPUBuffer;
  /** BVH_SORT_RADIX words per block of BVH_SORT_BLOCK pairs. */
  histogram: GPUBuffer;
  /** Scan sums per level (radixSortScratchWords). */
  sums: readonly GPUBuffer[];
}

/** Sizes of the sort's scratch in words: histogram, then the scan sums per level. */
export function radixSortScratchWords(count: number): { histogram: number; sums: number[] } {
  const histogram = C.BVH_SORT_RADIX * Math.ceil(count / C.BVH_SORT_BLOCK);
  return { histogram, sums: scanSumsWords([histogram]) };
}

/**
 * Records a stable sort of `count` pairs by their keys (`keyWords` u32 words, 30 bits used per word:
 * 8 passes of 4 bits per word), in place: the sorted pairs end in `keys` and `values` (the pass
 * count is even).
 */
export function recordRadixSort(list: DispatchList, b: RadixSortBuffers, count: number, keyWords: 1 | 2, base: Record<string, number>): void {
  const blocks = Math.ceil(count / C.BVH_SORT_BLOCK);
  const passes = 8 * keyWords;
  for (let pass = 0; pass < passes; pass++) {
    const even = pass % 2 === 0;
    const io: Resources = {
      sortKeysIn: even ? b.keys : b.keysScratch,
      sortValuesIn: even ? b.values : b.valuesScratch,
      sortKeysOut: even ? b.keysScratch : b.keys,
      sortValuesOut: even ? b.valuesScratch : b.values,
      sortHistogram: b.histogram,
    };
    const offset = list.slot({ ...base, primitiveCount: count, keyWords, digitShift: 4 * (pass % 8), digitWord: Math.floor(pass / 8), blockCount: blocks });
    list.add('sortCount', io, offset, list.blocks(blocks), `sort count ${pass}`);
    list.scan(b.histogram, C.BVH_SORT_RADIX * blocks, b.sums, base, `sort ${pass}`);
    list.add('sortScatter', io, offset, list.blocks(blocks), `sort scatter ${pass}`);
  }
}

/**
 * Sorts (key, value) pairs on the GPU and reads them back: keys of `keyWords` words (low word
 * first, at most 30 significant bits per word; 60-bit keys as two words), stable.
 */
export async function sortPairsOnGpu(device: GPUDevice, keys: Uint32Array, values: Uint32Array, keyWords: 1 | 2 = 1): Promise<{ keys: Uint32Array; values: Uint32Array }> {
  const count = values.length;
  if (keys.length !== count * keyWords) throw new RangeError(`sortPairsOnGpu: ${keys.length} key words for ${count} values of ${keyWords} words`);
  if (count === 0) return { keys: new Uint32Array(0), values: new Uint32Array(0) };
  const usage = BufferUsage.STORAGE | BufferUsage.COPY_DST | BufferUsage.COPY_SRC;
  const buffer = (words: number): GPUBuffer => device.createBuffer({ size: Math.max(16, words * 4), usage });
  const scratch = radixSortScratchWords(count);
  const b: RadixSortBuffers = {
    keys: buffer(keys.length), keysScratch: buffer(keys.length), values: buffer(count), valuesScratch: buffer(count),
    histogram: buffer(scratch.histogram), sums: scratch.sums.map(buffer),
  };
  const all = [b.keys, b.keysScratch, b.values, b.valuesScratch, b.histogram, ...b.sums];
  try {
    device.queue.writeBuffer(b.keys, 0, keys);
    device.queue.writeBuffer(b.values, 0, values);
    const pipelines = await bvhBuildPipelines(device);
    const list = new DispatchList(device, pipelines, {});
    recordRadixSort(list, b, count, keyWords, {});
    const { uniforms, dispatches } = list.finish();
    all.push(uniforms);
    const readKeys = device.createBuffer({ size: keys.byteLength, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
    const readValues = device.createBuffer({ size: values.byteLength, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
    all.push(readKeys, readValues);
    await runPass(device, pipelines, dispatches, () => undefined, (encoder) => {
      encoder.copyBufferToBuffer(b.keys, 0, readKeys, 0, keys.byteLength);
      encoder.copyBufferToBuffer(b.values, 0, readValues, 0, values.byteLength);
    }, null, 'radix sort');
    await Promise.all([readKeys.mapAsync(1), readValues.mapAsync(1)]);
    return { keys: new Uint32Array(readKeys.getMappedRange().slice(0)), values: new Uint32Array(readValues.getMappedRange().slice(0)) };
  } finally {
    for (const x of all) x.destroy();
  }
}
