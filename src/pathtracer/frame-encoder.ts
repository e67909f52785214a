import { dynamicUniformStride, indirectDispatchBytes, rendererWavefrontComputeWorkgroupSize } from '../gpu-layout/constants.ts';
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
 * closest hits and the previous bounce's shadow rays), a one-invocation dispatch that sizes the
 * shading dispatch from the queue lengths the traversal left, and the shading dispatch (material
 * evaluation and scatter) itself, indirect, one invocation per queued entry (bounce 0 shades every
 * path of the wave, directly); then the accumulation: 3 maxDepth + 4 dispatches per wave. Nothing waits on a CPU readback. The
 * traversal is a direct dispatch of at most `gridLimit` workgroups looping over its queues (a
 * persistent grid sized to the device, so it needs no sizing pass); shading cannot loop (its body
 * is too large for a loop: see shade.wesl), so its dispatch is sized to the live entries: a dispatch
 * covering the wave launched a wave of invocations for every bounce, which a CPU implementation
 * pays for in full. `waves[i]` uses wave-uniform slot i; bounce d uses bounce slot d and indirect
 * record d.
 *
 * The megakernel integrator encodes two dispatches per wave instead: one invocation per path runs
 * all its bounces (kernels/megakernel.wesl), then the same accumulation.
 */
export class WavefrontEncoder {
  private kernels: IntegratorKernelSet<KernelBindGroups>;
  private readonly gridLimit: number;
  private readonly integrator: PathTracingIntegrator;
  private readonly pixels: number;
  /** Indirect arguments of each bounce's shading dispatch (written by the shadingSize kernel). */
  private readonly shadingDispatch: GPUBuffer | null;
  /** Receives a count of every dispatch (frame diagnostics); replaced per frame. */
  tally: DispatchTally | null = null;

  /**
   * @param gridLimit most workgroups of a grid-stride dispatch (device-sized: enough to fill the
   *   GPU, few on a CPU adapter, whose every workgroup costs a task).
   */
  constructor(
    kernels: IntegratorKernelSet<KernelBindGroups>,
    options: { pixels: number; gridLimit: number; integrator: PathTracingIntegrator; shadingDispatch: GPUBuffer | null },
  ) {
    const { pixels, gridLimit, integrator, shadingDispatch } = options;
    if (integrator === 'wavefront' && !shadingDispatch) throw new Error('the wavefront integrator needs the shading dispatch buffer');
    this.shadingDispatch = shadingDispatch;
    this.kernels = kernels;
    this.integrator = integrator;
    this.pixels = pixels;
    this.gridLimit = gridLimit;
  }

  /** New bind groups (the queue buffers were reallocated). */
  rebind(kernels: IntegratorKernelSet<KernelBindGroups>): void {
    this.kernels = kernels;
  }

  private bind(pass: GPUComputePassEncoder, name: WavefrontKernelName, offsets: Offsets): void {
    const k = this.kernels[name];
    if (!k) throw new Error(`kernel ${name} was not compiled for the ${this.integrator} integrator`);
    pass.setPipeline(k.pipeline);
    k.groups.forEach((group, g) => pass.setBindGroup(g, group, k.dynamic[g]!.map((d) => offsets[d as keyof Offsets])));
  }

  private dispatch(pass: GPUComputePassEncoder, name: WavefrontKernelName, offsets: Offsets, workgroups: number, invocationsPerWorkgroup = rendererWavefrontComputeWorkgroupSize): void {
    this.bind(pass, name, offsets);
    pass.dispatchWorkgroups(workgroups);
    this.tally?.direct(workgroups, invocationsPerWorkgroup);
  }

  /** An indirect dispatch of `name` with the arguments of record `record`; `upperBound` workgroups at most. */
  private dispatchIndirect(pass: GPUComputePassEncoder, name: WavefrontKernelName, offsets: Offsets, record: number, upperBound: number): void {
    this.bind(pass, name, offsets);
    pass.dispatchWorkgroupsIndirect(this.shadingDispatch!, record * indirectDispatchBytes);
    this.tally?.indirect(upperBound);
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
      if (d === 0) {
        // Every camera ray hits or escapes: bounce 0 shades the whole wave, no sizing needed.
        this.dispatch(pass, 'shade', o, WavefrontEncoder.cover(paths));
      } else {
        this.dispatch(pass, 'shadingSize', o, 1, 1);
        this.dispatchIndirect(pass, 'shade', o, d, WavefrontEncoder.cover(paths));
      }
    }
  }
}
