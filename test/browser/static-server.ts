// A tiny static server for the browser test: the built package, node_modules and one HTML page.
import { createServer, type Server } from 'node:http';
import { readFile } from 'node:fs/promises';
import { extname, join, normalize, sep } from 'node:path';

const types: Record<string, string> = { '.js': 'text/javascript', '.mjs': 'text/javascript', '.map': 'application/json', '.json': 'application/json', '.html': 'text/html' };

/** Serves `/pkg/*` from `packageDir`, `/node_modules/*` from the repo, and `page` at `/`. */
export async function startStaticServer(options: { root: string; packageDir: string; page: string }): Promise<{ url: string; close(): Promise<void> }> {
  const server: Server = createServer((req, res) => {
    void (async () => {
      const path = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
      if (path === '/' || path === '/index.html') {
        res.writeHead(200, { 'content-type': 'text/html' }).end(options.page);
        return;
      }
      let file: string | undefined;
      if (path.startsWith('/pkg/')) file = normalize(join(options.packageDir, path.slice(5)));
      else if (path.startsWith('/node_modules/')) file = normalize(join(options.root, path));
      const allowed = [options.packageDir, join(options.root, 'node_modules')].some((dir) => file?.startsWith(dir + sep));
      if (!file || !allowed) {
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
  return {
    url: `http://127.0.0.1:${port}/`,
    close: () => new Promise<void>((resolve) => server.close(() => resolve())),
  };
}
