/** A one-line progress bar for stderr; plain, throttled lines where stderr is not a terminal. */

export interface ProgressStream {
  write(text: string): unknown;
  isTTY?: boolean;
  columns?: number;
}

/**
 * What the caller knows better than done / total: with a time limit or a noise target the render
 * may end before `total` samples. `fraction` replaces done / total for the bar, `remainingSeconds`
 * the extrapolated time left, `note` adds a short status (e.g. the share of pixels still sampling).
 */
export interface ProgressEstimate {
  fraction?: number;
  remainingSeconds?: number;
  note?: string;
}

export interface ProgressBar {
  update(done: number, total: number, estimate?: ProgressEstimate): void;
  /** Ends the bar's line (TTY) so later output starts on a new line. */
  finish(): void;
}

export function formatDuration(seconds: number): string {
  if (!Number.isFinite(seconds) || seconds < 0) return '?';
  if (seconds < 60) return `${seconds.toFixed(1)}s`;
  const m = Math.floor(seconds / 60);
  return `${m}m${String(Math.round(seconds - 60 * m)).padStart(2, '0')}s`;
}

export function createProgressBar(stream: ProgressStream, label = 'render', now: () => number = () => performance.now()): ProgressBar {
  const start = now();
  let lastDecile = -1;
  let open = false;
  return {
    update(done: number, total: number, estimate: ProgressEstimate = {}): void {
      const fraction = Math.min(Math.max(estimate.fraction ?? (total > 0 ? done / total : 1), 0), 1);
      const elapsed = (now() - start) / 1000;
      const eta = estimate.remainingSeconds ?? (fraction > 0 ? (elapsed * (1 - fraction)) / fraction : Number.NaN);
      const note = estimate.note ? `  ${estimate.note}` : '';
      const stats = `${done}/${total} spp ${(100 * fraction).toFixed(0).padStart(3)}%  ${formatDuration(elapsed)} elapsed, ${fraction < 1 ? `~${formatDuration(eta)} left` : 'done'}${note}`;
      if (stream.isTTY) {
        const width = Math.max(10, Math.min(40, (stream.columns ?? 80) - stats.length - label.length - 6));
        const filled = Math.round(fraction * width);
        // \r returns to the line start and ESC[K clears what a longer previous line left behind.
        stream.write(`\r${label} [${'#'.repeat(filled)}${'-'.repeat(width - filled)}] ${stats}\x1b[K`);
        open = true;
      } else {
        // Logs and CI capture: one line per 10 % step (the last is 100 %).
        const decile = Math.floor(fraction * 10);
        if (decile !== lastDecile) {
          lastDecile = decile;
          stream.write(`${label}: ${stats}\n`);
        }
      }
    },
    finish(): void {
      if (open) stream.write('\n');
      open = false;
    },
  };
}
