// Watches the event loop while something runs: a ticker that needs one event-loop turn per tick, so
// the longest gap between ticks is the longest stretch the main thread stayed blocked.
import { setImmediate as immediate } from 'node:timers';

export function watchEventLoop(): { stop: () => { turns: number; longestGapMs: number } } {
  let turns = 0;
  let running = true;
  let last = performance.now();
  let longestGapMs = 0;
  const tick = (): void => {
    const now = performance.now();
    longestGapMs = Math.max(longestGapMs, now - last);
    last = now;
    turns++;
    if (running) immediate(tick);
  };
  immediate(tick);
  return { stop: () => ((running = false), { turns, longestGapMs }) };
}
