import type { WavefrontGpuParallelism } from './output-types.ts';

/**
 * Counts the compute work a frame encodes, for the `gpuParallelism` diagnostics: direct dispatches
 * with their workgroups, and indirect dispatches with the upper bound of theirs (the GPU sizes them
 * from queue lengths it never reports back).
 */
export class DispatchTally {
  directDispatches = 0;
  directWorkgroups = 0;
  directInvocations = 0;
  indirectDispatches = 0;
  estimatedIndirectWorkgroups = 0;
  largestDirect = 0;
  largestIndirect = 0;

  direct(workgroups: number, invocationsPerWorkgroup: number): void {
    this.directDispatches += 1;
    this.directWorkgroups += workgroups;
    this.directInvocations += workgroups * invocationsPerWorkgroup;
    this.largestDirect = Math.max(this.largestDirect, workgroups);
  }

  indirect(upperBoundWorkgroups: number): void {
    this.indirectDispatches += 1;
    this.estimatedIndirectWorkgroups += upperBoundWorkgroups;
    this.largestIndirect = Math.max(this.largestIndirect, upperBoundWorkgroups);
  }

  report(limits: GPUSupportedLimits, workgroupSize: number): WavefrontGpuParallelism {
    return {
      adapterLimits: {
        maxComputeWorkgroupSizeX: limits.maxComputeWorkgroupSizeX,
        maxComputeInvocationsPerWorkgroup: limits.maxComputeInvocationsPerWorkgroup,
        maxComputeWorkgroupsPerDimension: limits.maxComputeWorkgroupsPerDimension,
        maxStorageBuffersPerShaderStage: limits.maxStorageBuffersPerShaderStage,
      },
      workgroupSize,
      physicalCoreCount: null,
      directDispatches: this.directDispatches,
      directWorkgroups: this.directWorkgroups,
      directInvocations: this.directInvocations,
      indirectDispatches: this.indirectDispatches,
      estimatedIndirectWorkgroups: this.estimatedIndirectWorkgroups,
      largestDirectWorkgroupsPerDispatch: this.largestDirect,
      largestEstimatedIndirectWorkgroupsPerDispatch: this.largestIndirect,
      exposesMultiWorkgroupParallelism: Math.max(this.largestDirect, this.largestIndirect) > 1,
    };
  }
}
