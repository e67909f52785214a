/**
 * What the film's GPU passes report of the compute work they encode: the renderer's dispatch tally
 * (the `gpuParallelism` diagnostics) implements it.
 */
export interface DispatchCounter {
  direct(workgroups: number, invocationsPerWorkgroup: number): void;
}
