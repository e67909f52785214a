import type { RendererWorkerProfileName } from './worker-constants.ts';

/** One adaptive budget level of a job, cheapest first; `config` is what the job applies at that level. */
export interface RendererJobBudgetLevel {
  readonly id: string;
  readonly estimatedCostMs: number;
  readonly config: Readonly<Record<string, string | number | boolean>>;
}

export type RendererJobImportance = 'critical' | 'high' | 'medium' | 'low';
/**
 * Who has the final say over the job's budget: `presentation` jobs are fixed by the display (they
 * cannot be degraded), `visual` jobs may be scaled by a frame-time governor.
 */
export type RendererJobAuthority = 'presentation' | 'visual';

export interface RendererWorkerJob {
  /** Globally unique job id: `renderer.<profile>.<key>`. */
  readonly id: string;
  readonly key: string;
  readonly label: string;
  readonly worker: {
    readonly jobType: string;
    readonly queueClass: string;
    /** Higher runs first among ready jobs. */
    readonly priority: number;
    /** Ids of the jobs that must finish first. */
    readonly dependencies: readonly string[];
    readonly schedulerMode: 'dag';
  };
  readonly performance: {
    readonly id: string;
    readonly domain: 'renderer';
    readonly authority: RendererJobAuthority;
    readonly importance: RendererJobImportance;
    readonly levels: readonly RendererJobBudgetLevel[];
  };
  readonly debug: {
    readonly owner: string;
    readonly tags: readonly string[];
    readonly allocationIds: readonly string[];
  };
}

export interface RendererWorkerManifest {
  readonly schemaVersion: 1;
  readonly profile: RendererWorkerProfileName;
  readonly owner: string;
  readonly queueClass: string;
  readonly schedulerMode: 'dag';
  readonly jobs: readonly RendererWorkerJob[];
  /** Jobs without dependencies (the DAG is multi-root). */
  readonly roots: readonly string[];
  /** Job ids ordered so that every job follows all of its dependencies. */
  readonly topologicalOrder: readonly string[];
}

export interface RendererWorkerProfile {
  readonly name: RendererWorkerProfileName;
  readonly label: string;
  readonly description: string;
  /** Job keys in publication order. */
  readonly stages: readonly string[];
}
