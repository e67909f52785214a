/**
 * `node bench/browser-frame.ts`: the time of one 1-spp frame of the Cornell box
 * (createCornellBoxScene, 256x256 unless SIZE, maxDepth unless MAXDEPTH, integrator unless
 * INTEGRATOR) in Chromium on SwiftShader, FRAMES (4) frames after one warm-up: wall clock, GPU time
 * and the CPU time of Chromium's processes (Linux /proc; less disturbed by other load), medians.
 * It uses only APIs every version since November has (renderFrame, the built package through
 * test/browser/browser-session.ts), so the same file copied into a worktree of an older commit
 * (e.g. ca1bff9) measures that version on the same machine: that is how the issue-27 table was
 * compared.
 */
import { readFileSync, readdirSync } from 'node:fs';
import { openPackagePage } from '../test/browser/browser-session.ts';

const size = Number(process.env.SIZE ?? 256);
const frames = Number(process.env.FRAMES ?? 4);
const maxDepth = process.env.MAXDEPTH ? Number(process.env.MAXDEPTH) : null;
const integrator = process.env.INTEGRATOR ?? null;

/** CPU milliseconds Chromium's processes have used so far (utime + stime, 10 ms ticks). */
function chromiumCpuMs(): number {
  let ticks = 0;
  for (const pid of readdirSync('/proc')) {
    if (!/^\d+$/.test(pid)) continue;
    try {
      if (!readFileSync(`/proc/${pid}/cmdline`, 'utf8').includes('chromium')) continue;
      const fields = readFileSync(`/proc/${pid}/stat`, 'utf8').split(') ')[1]!.split(' ');
      ticks += Number(fields[11]) + Number(fields[12]);
    } catch {
      // The process ended between the listing and the read.
    }
  }
  return ticks * 10;
}

interface FrameRenderer {
  renderFrame(): Promise<{ gpuTimeMs: number | null; gpuParallelism?: { directDispatches: number; indirectDispatches: number } }>;
  getSnapshot?(): { integrator?: string; warnings?: string[] };
}
interface PageWindow {
  pkg: { createCornellBoxScene(): object; createWavefrontPathTracingComputeRenderer(options: object): Promise<FrameRenderer> };
  renderer: FrameRenderer;
}

const { tab, pageErrors, close } = await openPackagePage({ style: '', body: '', viewport: { width: 100, height: 100 } });
try {
  const setup = await tab.evaluate(async ({ size, maxDepth, integrator }) => {
    const w = window as unknown as PageWindow;
    const options = { ...w.pkg.createCornellBoxScene(), width: size, height: size, samplesPerPixel: 1, ...(maxDepth !== null ? { maxDepth } : {}), ...(integrator ? { integrator } : {}) };
    w.renderer = await w.pkg.createWavefrontPathTracingComputeRenderer(options);
    await w.renderer.renderFrame();
    const snapshot = w.renderer.getSnapshot?.();
    return { integrator: snapshot?.integrator ?? null, warnings: snapshot?.warnings ?? [] };
  }, { size, maxDepth, integrator });
  const out: { wallMs: number; cpuMs: number; gpuMs: number | null; direct?: number; indirect?: number }[] = [];
  for (let i = 0; i < frames; i++) {
    const cpu = chromiumCpuMs();
    const started = performance.now();
    const stats = await tab.evaluate(async () => {
      const s = await (window as unknown as PageWindow).renderer.renderFrame();
      return { gpuMs: s.gpuTimeMs, direct: s.gpuParallelism?.directDispatches, indirect: s.gpuParallelism?.indirectDispatches };
    });
    out.push({ wallMs: Math.round(performance.now() - started), cpuMs: chromiumCpuMs() - cpu, ...stats });
  }
  const median = (values: number[]): number => values.sort((a, b) => a - b)[values.length >> 1]!;
  console.log(JSON.stringify({ size, ...setup, wallMedianMs: median(out.map((o) => o.wallMs)), cpuMedianMs: median(out.map((o) => o.cpuMs)), frames: out }));
  if (pageErrors.length > 0) console.log('page errors:', pageErrors.join('; '));
} finally {
  await close();
}
