// The demo's dev server never depends on a fixed port: port 0 takes a free port the system picks,
// even while the default port (5173) is held by another process, and two servers on port 0 run
// side by side; an explicit port that is taken is refused by name.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createServer, type Server } from 'node:http';
import { startDemoServer } from '../../scripts/demo-server.ts';

function hold(port: number): Promise<Server | null> {
  const s = createServer((_, res) => res.end('not the demo'));
  return new Promise((resolve) => {
    s.once('error', () => resolve(null)); // already held by someone else: held all the same
    s.listen(port, '127.0.0.1', () => resolve(s));
  });
}

test('demo server: port 0 picks a free port, with 5173 taken and two servers at once', { timeout: 60_000 }, async (t) => {
  const blocker = await hold(5173);
  t.after(() => blocker?.close());
  const a = await startDemoServer({ port: 0, quiet: true });
  t.after(() => a.close());
  const b = await startDemoServer({ port: 0, quiet: true });
  t.after(() => b.close());
  const ports = [a.url, b.url].map((u) => Number(new URL(u).port));
  assert.ok(ports.every((p) => p > 0 && p !== 5173), `free ports: ${ports.join(', ')}`);
  assert.notEqual(ports[0], ports[1]);
  for (const server of [a, b]) {
    const res = await fetch(server.url);
    assert.equal(res.status, 200);
    assert.match(await res.text(), /WebGPU path tracer demo/);
    // The page needs cross-origin isolation (SharedArrayBuffer for the parallel BVH build).
    assert.equal(res.headers.get('cross-origin-embedder-policy'), 'require-corp');
  }

  const taken = ports[1]!;
  await assert.rejects(startDemoServer({ port: taken, quiet: true }), new RegExp(`port ${taken} is already in use`));
});
