// A tiny loopback static server for browser tests: one HTML page at `/` and folders mounted under
// URL prefixes (paths that leave a folder are 404).
import { createServer, type Server } from 'node:http';
import { readFile } from 'node:fs/promises';
import { extname, join, normalize, sep } from 'node:path';

const types: Record<string, string> = {
  '.js': 'text/javascript',
  '.mjs': 'text/javascript',
  '.map': 'application/json',
  '.json': 'application/json',
  '.wasm': 'application/wasm',
  '.html': 'text/html',
};

export interface StaticServer {
  url: string;
  close(): Promise<void>;
}

/** Serves `page` at `/` (and `/index.html`) and each mount's folder under its URL prefix (ending in `/`). */
export async function serveFiles(page: string, mounts: readonly { prefix: string; dir: string }[]): Promise<StaticServer> {
  const server: Server = createServer((req, res) => {
    void (async () => {
      const path = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
      if (path === '/' || path === '/index.html') {
        res.writeHead(200, { 'content-type': 'text/html' }).end(page);
        return;
      }
      const mount = mounts.find((m) => path.startsWith(m.prefix));
      const file = mount ? normalize(join(mount.dir, path.slice(mount.prefix.length))) : undefined;
      if (!mount || !file?.startsWith(normalize(mount.dir) + sep)) {
        res.writeHead(404).end();
        return;
      }
      try {
        const body = await readFile(file);
        res.writeHead(200, { 'content-type': types[extname(file)] ?? 'application/octet-stream' }).end(body);
      } catch {
        res.writeHead(404).end();
      }
    })();
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const address = server.address();
  const port = typeof address === 'object' && address ? address.port : 0;
  return { url: `http://127.0.0.1:${port}/`, close: () => new Promise<void>((resolve) => server.close(() => resolve())) };
}

/** Serves `/pkg/*` from `packageDir`, `/node_modules/*` from the repo, and `page` at `/`. */
export function startStaticServer(options: { root: string; packageDir: string; page: string }): Promise<StaticServer> {
  return serveFiles(options.page, [
    { prefix: '/pkg/', dir: options.packageDir },
    { prefix: '/node_modules/', dir: join(options.root, 'node_modules') },
  ]);
}
