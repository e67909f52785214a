import { dynamicUniformStride, rendererWavefrontComputeWorkgroupSize } from '../gpu-layout/constants.ts';
import type { KernelBindGroups } from './bind-groups.ts';
import type { DispatchTally } from './dispatch-tally.ts';
import type { IntegratorKernelSet, WavefrontKernelName } from './pipelines.ts';
import type { PathTracingIntegrator } from './types.ts';
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
 *
 * The megakernel integrator encodes two dispatches per wave instead: one invocation per path runs
 * all its bounces (kernels/megakernel.wesl), then the same accumulation.
 */
export class WavefrontEncoder {
  private kernels: IntegratorKernelSet<KernelBindGroups>;
  private readonly gridLimit: number;
  private readonly integrator: PathTracingIntegrator;
  private readonly pixels: number;
  /** Receives a count of every dispatch (frame diagnostics); replaced per frame. */
  tally: DispatchTally | null = null;

  /**
   * @param gridLimit most workgroups of a grid-stride dispatch (device-sized: enough to fill the
   *   GPU, few on a CPU adapter, whose every workgroup costs a task).
   */
  constructor(kernels: IntegratorKernelSet<KernelBindGroups>, pixels: number, gridLimit: number, integrator: PathTracingIntegrator = 'wavefront') {
    this.kernels = kernels;
    this.integrator = integrator;
    this.pixels = pixels;
    this.gridLimit = gridLimit;
  }

  /** New bind groups (the queue buffers were reallocated). */
  rebind(kernels: IntegratorKernelSet<KernelBindGroups>): void {
    this.kernels = kernels;
  }

  private dispatch(pass: GPUComputePassEncoder, name: WavefrontKernelName, offsets: Offsets, workgroups: number): void {
    const k = this.kernels[name];
    if (!k) throw new Error(`kernel ${name} was not compiled for the ${this.integrator} integrator`);
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
      if (this.integrator === 'megakernel') {
        this.dispatch(pass, 'megakernel', o, WavefrontEncoder.cover(paths));
      } else {
        this.encodeBounces(pass, o, paths, maxDepth);
      }
      this.dispatch(pass, 'accumulate', o, WavefrontEncoder.cover(w.list ? paths : Math.min(paths, this.pixels)));
    });
  }

  /** The wavefront's camera rays and bounces of one wave. */
  private encodeBounces(pass: GPUComputePassEncoder, o: Offsets, paths: number, maxDepth: number): void {
    this.dispatch(pass, 'camera', o, WavefrontEncoder.cover(paths));
    for (let d = 0; d <= maxDepth; d++) {
      o.bounce = d * dynamicUniformStride;
      // Each path queues at most one ray and one shadow ray per bounce.
      this.dispatch(pass, 'trace', o, this.grid(d === 0 ? paths : 2 * paths));
      this.dispatch(pass, 'shade', o, WavefrontEncoder.cover(paths));
    }
  }
}
