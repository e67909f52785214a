import { dynamicUniformStride, rendererWavefrontComputeWorkgroupSize } from '../gpu-layout/constants.ts';
import type { KernelBindGroups } from './bind-groups.ts';
import type { DispatchTally } from './dispatch-tally.ts';
import type { WavefrontKernelName } from './pipelines.ts';
import type { Wave } from './waves.ts';

/** Dynamic uniform offsets of the current wave and bounce. */
interface Offsets {
  wave: number;
  bounce: number;
}

/**
 * Encodes waves into a compute pass: per wave, camera rays, then per bounce (pbrt-v4's wavefront
 * stages, fused where no global barrier separates them) one traversal dispatch (this bounce's
 * closest hits and the previous bounce's shadow rays) and one shading dispatch (material
 * evaluation and scatter), then the accumulation: 2 (maxDepth + 1) + 2 dispatches per wave. All
 * are direct dispatches sized on the CPU, and the kernels stop at their queues' GPU-side lengths:
 * nothing waits on a CPU readback, and no indirect dispatch pays Dawn's validation pass. The
 * traversal loops over its queues with a grid of at most `gridLimit` workgroups; shading covers
 * the wave (one entry per invocation). `waves[i]` uses wave-uniform slot i; bounce d uses bounce
 * slot d.
 */
export class WavefrontEncoder {
  private kernels: Record<WavefrontKernelName, KernelBindGroups>;
  private readonly gridLimit: number;
  private readonly pixels: number;
  /** Receives a count of every dispatch (frame diagnostics); replaced per frame. */
  tally: DispatchTally | null = null;

  /**
   * @param gridLimit most workgroups of a grid-stride dispatch (device-sized: enough to fill the
   *   GPU, few on a CPU adapter, whose every workgroup costs a task).
   */
  constructor(kernels: Record<WavefrontKernelName, KernelBindGroups>, pixels: number, gridLimit: number) {
    this.kernels = kernels;
    this.pixels = pixels;
    this.gridLimit = gridLimit;
  }

  /** New bind groups (the queue buffers were reallocated). */
  rebind(kernels: Record<WavefrontKernelName, KernelBindGroups>): void {
    this.kernels = kernels;
  }

  private dispatch(pass: GPUComputePassEncoder, name: WavefrontKernelName, offsets: Offsets, workgroups: number): void {
    const k = this.kernels[name];
    pass.setPipeline(k.pipeline);
    k.groups.forEach((group, g) => pass.setBindGroup(g, group, k.dynamic[g]!.map((d) => offsets[d as keyof Offsets])));
    pass.dispatchWorkgroups(workgroups);
    this.tally?.direct(workgroups, rendererWavefrontComputeWorkgroupSize);
  }

  /** Workgroups covering `items` invocations, one each. */
  private static cover(items: number): number {
    return Math.max(1, Math.ceil(items / rendererWavefrontComputeWorkgroupSize));
  }

  /** Workgroups of a grid-stride loop over at most `items` queue entries. */
  private grid(items: number): number {
    return Math.min(WavefrontEncoder.cover(items), this.gridLimit);
  }

  encode(pass: GPUComputePassEncoder, waves: readonly Wave[], maxDepth: number): void {
    waves.forEach((w, i) => {
      const paths = w.pathCount;
      const o: Offsets = { wave: i * dynamicUniformStride, bounce: 0 };
      this.dispatch(pass, 'camera', o, WavefrontEncoder.cover(paths));
      for (let d = 0; d <= maxDepth; d++) {
        o.bounce = d * dynamicUniformStride;
        // Each path queues at most one ray and one shadow ray per bounce.
        this.dispatch(pass, 'trace', o, this.grid(d === 0 ? paths : 2 * paths));
        this.dispatch(pass, 'shade', o, WavefrontEncoder.cover(paths));
      }
      this.dispatch(pass, 'accumulate', o, WavefrontEncoder.cover(w.list ? paths : Math.min(paths, this.pixels)));
    });
  }
}
