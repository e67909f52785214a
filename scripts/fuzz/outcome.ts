/** Case outcomes and the summary table. */
import type { CaseKind } from './cases.ts';

/**
 * - ok: loaded (or created) and accepted by the renderer's own validation
 * - typed: a GpuRendererError (code and field)
 * - wrapped: a GpuRendererError whose cause is a TypeError, RangeError or ReferenceError (an
 *   internal fault caught at the boundary: typed, but worth a look)
 * - aborted: the case aborted its signal and the load rejected with the AbortError
 * - late: loaded, then refused by the renderer's validation (a fault the loader should have named)
 * - limit: loaded, then over a renderer limit (SCENE_TOO_LARGE)
 * - untyped: anything thrown that is not a GpuRendererError
 * - polluted: Object.prototype gained a key
 * - hang, oom, crash: decided by the parent (time limit, memory limit, child death)
 * - escape: a canary file was read or a server was contacted without permission
 */
export type Status = 'ok' | 'typed' | 'wrapped' | 'aborted' | 'late' | 'limit' | 'untyped' | 'polluted' | 'hang' | 'oom' | 'crash' | 'escape';

export interface Outcome {
  kind: CaseKind;
  index: number;
  status: Status;
  ms: number;
  notes: string[];
  code?: string;
  field?: string;
  message?: string;
  errorName?: string;
  cause?: string;
  stack?: string;
  /** Origins the case's policy allowed (for the server check). */
  allowedOrigins?: string[];
  /** For escapes: what was touched. */
  escapes?: string[];
}

export const STATUSES: readonly Status[] = ['ok', 'typed', 'wrapped', 'aborted', 'late', 'limit', 'untyped', 'polluted', 'hang', 'oom', 'crash', 'escape'];

/** Outcomes that fail the run; `late` too (a loader must refuse what the renderer would, naming the asset's field). */
export function isFailure(outcome: Pick<Outcome, 'kind' | 'status'>): boolean {
  return outcome.status === 'late' || outcome.status === 'untyped' || outcome.status === 'polluted' || outcome.status === 'hang' || outcome.status === 'oom' || outcome.status === 'crash' || outcome.status === 'escape';
}

/** A short signature grouping outcomes that are the same fault. */
export function signature(o: Outcome): string {
  const message = (o.message ?? '').replace(/\d+(\.\d+)?(e[+-]?\d+)?/gi, 'N').replace(/"[^"]*"/g, '"…"').slice(0, 120);
  return `${o.kind} ${o.status} ${o.code ?? o.errorName ?? ''} ${o.status === 'typed' ? '' : message}`.trim();
}

export function summaryTable(outcomes: readonly Outcome[], kinds: readonly CaseKind[]): string {
  const header = ['kind', 'cases', ...STATUSES];
  const rows = kinds.map((kind) => {
    const mine = outcomes.filter((o) => o.kind === kind);
    return [kind, String(mine.length), ...STATUSES.map((s) => String(mine.filter((o) => o.status === s).length))];
  });
  rows.push(['all', String(outcomes.length), ...STATUSES.map((s) => String(outcomes.filter((o) => o.status === s).length))]);
  const widths = header.map((h, i) => Math.max(h.length, ...rows.map((r) => r[i]!.length)));
  const line = (cells: string[]): string => `| ${cells.map((c, i) => c.padStart(widths[i]!)).join(' | ')} |`;
  return [line(header), `|${widths.map((w) => '-'.repeat(w + 2)).join('|')}|`, ...rows.map(line)].join('\n');
}
