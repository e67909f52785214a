import { dispatchArgSlots, dynamicUniformStride, rendererWavefrontComputeWorkgroupSize } from '../gpu-layout/constants.ts';
import type { KernelBindGroups } from './bind-groups.ts';
import type { DispatchTally } from './dispatch-tally.ts';
import type { WavefrontKernelName } from './pipelines.ts';
import type { Wave } from './tiling.ts';

/** Dynamic uniform offsets of the current wave and bounce. */
interface Offsets {
  wave: number;
  bounce: number;
}

/**
 * Encodes waves into a compute pass: per wave, camera rays, then per bounce (pbrt-v4's wavefront
 * stages) intersection -> material evaluation -> scatter (escaped rays included) -> shadow rays, all sized
 * by one indirect dispatch whose arguments the GPU writes from the ray queue's length (each stage
 * stops at its own queue's length; one sizing kernel per bounce keeps the dispatch count, which a
 * CPU driver pays for in synchronisation, low), then the accumulation. `waves[i]` uses
 * wave-uniform slot i; bounce d uses bounce slot d.
 */
export class WavefrontEncoder {
  private readonly kernels: Record<WavefrontKernelName, KernelBindGroups>;
  private readonly dispatchArgs: GPUBuffer;
  /** Upper bound of an indirect dispatch's workgroups: the queue capacity's. */
  private readonly indirectBound: number;
  /** Receives a count of every dispatch (frame diagnostics); replaced per frame. */
  tally: DispatchTally | null = null;

  constructor(kernels: Record<WavefrontKernelName, KernelBindGroups>, dispatchArgs: GPUBuffer, queueCapacity = 0) {
    this.kernels = kernels;
    this.dispatchArgs = dispatchArgs;
    this.indirectBound = Math.ceil(queueCapacity / rendererWavefrontComputeWorkgroupSize);
  }

  private dispatch(pass: GPUComputePassEncoder, name: WavefrontKernelName, offsets: Offsets, work: number | { indirect: number }): void {
    const k = this.kernels[name];
    pass.setPipeline(k.pipeline);
    k.groups.forEach((group, g) => pass.setBindGroup(g, group, k.dynamic[g]!.map((d) => offsets[d as keyof Offsets])));
    if (typeof work === 'number') {
      pass.dispatchWorkgroups(work);
      this.tally?.direct(work, name === 'prepareIntersect' ? 1 : rendererWavefrontComputeWorkgroupSize);
    } else {
      pass.dispatchWorkgroupsIndirect(this.dispatchArgs, work.indirect * 4);
      this.tally?.indirect(this.indirectBound);
    }
  }

  encode(pass: GPUComputePassEncoder, waves: readonly Wave[], maxDepth: number): void {
    const wg = rendererWavefrontComputeWorkgroupSize;
    waves.forEach((w, i) => {
      const pixels = w.tileSize[0] * w.tileSize[1];
      const o: Offsets = { wave: i * dynamicUniformStride, bounce: 0 };
      this.dispatch(pass, 'camera', o, Math.ceil(pixels / wg));
      for (let d = 0; d <= maxDepth; d++) {
        o.bounce = d * dynamicUniformStride;
        const rays = { indirect: dispatchArgSlots.intersect };
        this.dispatch(pass, 'prepareIntersect', o, 1);
        this.dispatch(pass, 'intersect', o, rays);
        this.dispatch(pass, 'evaluateMaterials', o, rays);
        this.dispatch(pass, 'scatter', o, rays);
        if (d < maxDepth) this.dispatch(pass, 'shadow', o, rays);
      }
      this.dispatch(pass, 'accumulate', o, Math.ceil(pixels / wg));
    });
  }
}
