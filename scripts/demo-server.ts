// `npm run demo`: the demo page (demo/) on a Vite dev server. Everything it serves comes from this
// repository and its node_modules; nothing is fetched from the network.
//   npm run demo [-- --port 5173] [-- --host 0.0.0.0]
import { parseArgs } from 'node:util';
import { createServer, type ViteDevServer } from 'vite';
import { demoViteConfig } from '../demo/vite.config.ts';

export interface DemoServer {
  url: string;
  server: ViteDevServer;
  close(): Promise<void>;
}

/** Starts the demo's Vite dev server; port 0 picks a free port. */
export async function startDemoServer(options: { port?: number; host?: string; quiet?: boolean } = {}): Promise<DemoServer> {
  const server = await createServer({
    ...demoViteConfig,
    configFile: false,
    logLevel: options.quiet ? 'error' : 'info',
    server: { ...demoViteConfig.server, port: options.port ?? 5173, strictPort: options.port !== undefined, host: options.host ?? '127.0.0.1' },
  });
  await server.listen();
  const url = server.resolvedUrls?.local[0];
  if (!url) {
    await server.close();
    throw new Error('the demo server did not report a URL');
  }
  return { url, server, close: () => server.close() };
}

if (import.meta.main) {
  const { values } = parseArgs({ options: { port: { type: 'string' }, host: { type: 'string' } } });
  const port = values.port === undefined ? undefined : Number(values.port);
  if (port !== undefined && !(Number.isInteger(port) && port >= 0 && port < 65536)) {
    console.error(`demo: --port expects a port number, got ${values.port}`);
    process.exit(1);
  }
  const demo = await startDemoServer({ ...(port !== undefined ? { port } : {}), ...(values.host ? { host: values.host } : {}) });
  demo.server.printUrls();
  console.log('demo: WebGPU needs a recent Chrome or Edge (or Firefox/Safari with WebGPU enabled). Ctrl-C stops the server.');
}
