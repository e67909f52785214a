import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { RendererWorkerJob } from './worker-manifest-types.ts';

/**
 * Kahn's algorithm over the job DAG. Throws when an id repeats, a dependency does not resolve or a
 * cycle exists; otherwise returns an order in which every job follows its dependencies (ties keep
 * publication order, so the result is deterministic).
 */
export function topologicalJobOrder(jobs: readonly RendererWorkerJob[]): string[] {
  const ids = new Set<string>();
  for (const job of jobs) {
    if (ids.has(job.id)) throw new GpuRendererError('INVALID_STATE', `duplicate job id ${job.id}`, { field: 'jobs' });
    ids.add(job.id);
  }
  const remaining = new Map<string, number>();
  for (const job of jobs) {
    for (const dep of job.worker.dependencies) {
      if (!ids.has(dep)) throw new GpuRendererError('INVALID_STATE', `job ${job.id} depends on unknown job ${dep}`, { field: 'jobs' });
    }
    remaining.set(job.id, new Set(job.worker.dependencies).size);
  }
  const order: string[] = [];
  const done = new Set<string>();
  while (order.length < jobs.length) {
    const ready = jobs.find((job) => !done.has(job.id) && remaining.get(job.id) === 0);
    if (!ready) throw new GpuRendererError('INVALID_STATE', 'job dependencies form a cycle', { field: 'jobs' });
    done.add(ready.id);
    order.push(ready.id);
    for (const job of jobs) {
      if (!done.has(job.id) && job.worker.dependencies.includes(ready.id)) remaining.set(job.id, remaining.get(job.id)! - 1);
    }
  }
  return order;
}
