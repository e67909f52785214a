// The BVH builds in a real browser (Debian's headless Chromium) from the built ESM package: inline
// Blob-URL workers start, and `buildBvhParallel` / `buildBvhAsync` give the tree `buildBvh` gives,
// on a cross-origin-isolated page (SharedArrayBuffer: workers share a WebAssembly memory) and on a
// plain one (no SharedArrayBuffer: one worker builds a copy).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createServer } from 'node:http';
import { readFile } from 'node:fs/promises';
import { join, normalize, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { builtPackageDir } from '../browser/built-package.ts';
import { chromiumPath, chromiumSkip } from '../browser/browser-session.ts';

const root = fileURLToPath(new URL('../..', import.meta.url));

const PAGE = `<!doctype html><html><head><meta charset="utf-8"></head><body><script type="module">
  const builder = await import('/pkg/accel/bvh-builder.js');
  const pool = await import('/pkg/accel/bvh-worker-pool.js');
  // A deterministic soup (mulberry32), large enough for split jobs and subtree jobs.
  const soup = (count, seed) => {
    let a = seed >>> 0;
    const r = () => { a = (a + 0x6d2b79f5) >>> 0; let t = a; t = Math.imul(t ^ (t >>> 15), t | 1); t ^= t + Math.imul(t ^ (t >>> 7), t | 61); return ((t ^ (t >>> 14)) >>> 0) / 4294967296; };
    const p = new Float32Array(count * 9);
    for (let i = 0; i < count; i++) { const cx = r() * 100, cy = r() * 100, cz = r() * 100; for (let v = 0; v < 9; v++) p[i * 9 + v] = [cx, cy, cz][v % 3] + r() - 0.5; }
    return p;
  };
  const same = (x, y) => {
    const a = new Uint8Array(x.nodes), b = new Uint8Array(y.nodes);
    if (a.length !== b.length || x.triangleOrder.length !== y.triangleOrder.length || x.sahCost !== y.sahCost) return false;
    for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return false;
    for (let i = 0; i < x.triangleOrder.length; i++) if (x.triangleOrder[i] !== y.triangleOrder[i]) return false;
    return true;
  };
  window.runBvh = async () => {
    const positions = soup(60000, 5);
    const serial = builder.buildBvh(positions);
    const workers = await pool.getBvhWorkerPool(2);
    const parallel = await builder.buildBvhParallel(positions, { workers: 2 });
    const viaAsync = await builder.buildBvhAsync(positions);
    const js = builder.buildBvh(positions, { wasm: false });
    return {
      isolated: globalThis.crossOriginIsolated === true,
      pool: workers !== null,
      sharedMemory: workers ? workers.sharedMemory : null,
      sameParallel: same(serial, parallel),
      sameAsync: same(serial, viaAsync),
      sameJs: same(serial, js),
      nodeCount: serial.nodeCount,
    };
  };
  window.ready = true;
</script></body></html>`;

async function withPage<T>(isolated: boolean, body: (url: string) => Promise<T>): Promise<T> {
  const built = builtPackageDir(root);
  const headers: Record<string, string> = isolated ? { 'cross-origin-opener-policy': 'same-origin', 'cross-origin-embedder-policy': 'require-corp' } : {};
  const server = createServer((req, res) => {
    void (async () => {
      const path = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
      if (path === '/') {
        res.writeHead(200, { ...headers, 'content-type': 'text/html' }).end(PAGE);
        return;
      }
      const file = path.startsWith('/pkg/') ? normalize(join(built.dir, path.slice(5))) : undefined;
      if (!file || !file.startsWith(built.dir + sep)) {
        res.writeHead(404).end();
        return;
      }
      try {
        res.writeHead(200, { ...headers, 'content-type': 'text/javascript' }).end(await readFile(file));
      } catch {
        res.writeHead(404).end();
      }
    })();
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const address = server.address();
  const port = typeof address === 'object' && address ? address.port : 0;
  try {
    return await body(`http://127.0.0.1:${port}/`);
  } finally {
    await new Promise<void>((resolve) => server.close(() => resolve()));
    built.cleanup();
  }
}

interface PageReport {
  isolated: boolean;
  pool: boolean;
  sharedMemory: boolean | null;
  sameParallel: boolean;
  sameAsync: boolean;
  sameJs: boolean;
  nodeCount: number;
}

test('Chromium: inline workers build the same BVH, with and without cross-origin isolation', { skip: chromiumSkip, timeout: 240_000 }, async () => {
  const { chromium } = await import('playwright-core');
  const browser = await chromium.launch({ executablePath: chromiumPath, headless: true, args: ['--no-sandbox', '--no-first-run', '--disable-background-networking'] });
  try {
    for (const isolated of [true, false]) {
      const report = await withPage(isolated, async (url) => {
        const tab = await browser.newPage();
        const errors: string[] = [];
        tab.on('pageerror', (e) => errors.push(e.message));
        await tab.goto(url);
        await tab.waitForFunction(() => (window as unknown as { ready?: boolean }).ready === true, undefined, { timeout: 30_000 });
        const result = await tab.evaluate(() => (window as unknown as { runBvh(): Promise<PageReport> }).runBvh());
        await tab.close();
        assert.deepEqual(errors, []);
        return result;
      });
      const label = isolated ? 'isolated page' : 'plain page';
      assert.equal(report.isolated, isolated, `${label}: crossOriginIsolated`);
      assert.equal(report.pool, true, `${label}: Blob-URL workers start`);
      assert.equal(report.sharedMemory, isolated, `${label}: shared memory exactly when isolated`);
      assert.ok(report.sameParallel, `${label}: buildBvhParallel gives the buildBvh tree`);
      assert.ok(report.sameAsync, `${label}: buildBvhAsync gives the buildBvh tree`);
      assert.ok(report.sameJs, `${label}: the JS loops give the WebAssembly tree`);
      assert.ok(report.nodeCount > 1);
    }
  } finally {
    await browser.close();
  }
});
