// `npm run demo`: the demo page (demo/) on a Vite dev server. Everything it serves comes from this
// repository and its node_modules; nothing is fetched from the network.
//   npm run demo [-- --port 5173] [-- --host 0.0.0.0]
import { createServer as createHttpServer, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { parseArgs } from 'node:util';
import { createServer, type ViteDevServer } from 'vite';
import { demoViteConfig } from '../demo/vite.config.ts';

export interface DemoServer {
  url: string;
  server: ViteDevServer;
  close(): Promise<void>;
}

const defaultPort = 5173;

/** Listens on `port` (0: a free one the system picks); `walk`: on EADDRINUSE try the next ports. */
function listen(http: Server, port: number, host: string, walk: boolean): Promise<number> {
  return new Promise((resolve, reject) => {
    const onError = (error: NodeJS.ErrnoException): void => {
      if (error.code === 'EADDRINUSE' && walk && port < 65535) {
        http.listen(++port, host);
        return;
      }
      http.off('error', onError);
      reject(error.code === 'EADDRINUSE' ? new Error(`demo: port ${port} is already in use`) : error);
    };
    http.on('error', onError);
    http.listen(port, host, () => {
      http.off('error', onError);
      resolve((http.address() as AddressInfo).port);
    });
  });
}

/**
 * Starts the demo's Vite dev server. `port` 0 takes a free port the system picks (what tests use:
 * they never depend on a fixed port); another port is taken strictly; without one, 5173 or the
 * next free port above it. Vite runs in middleware mode on an HTTP server of ours, with its HMR
 * socket on that server, because Vite's own listen treats port 0 as "unset" (5173).
 */
export async function startDemoServer(options: { port?: number; host?: string; quiet?: boolean } = {}): Promise<DemoServer> {
  const host = options.host ?? '127.0.0.1';
  const http = createHttpServer();
  const server = await createServer({
    ...demoViteConfig,
    configFile: false,
    logLevel: options.quiet ? 'error' : 'info',
    server: { ...demoViteConfig.server, host, middlewareMode: true, hmr: { server: http } },
  });
  http.on('request', server.middlewares);
  let port: number;
  try {
    port = await listen(http, options.port ?? defaultPort, host, options.port === undefined);
  } catch (error) {
    await server.close();
    throw error;
  }
  const close = async (): Promise<void> => {
    await server.close();
    http.closeAllConnections();
    await new Promise<void>((resolve, reject) => http.close((error) => (error ? reject(error) : resolve())));
  };
  const shown = host.includes(':') ? `[${host}]` : host;
  return { url: `http://${shown === '0.0.0.0' ? 'localhost' : shown}:${port}/`, server, close };
}

if (import.meta.main) {
  const { values } = parseArgs({ options: { port: { type: 'string' }, host: { type: 'string' } } });
  const port = values.port === undefined ? undefined : Number(values.port);
  if (port !== undefined && !(Number.isInteger(port) && port >= 0 && port < 65536)) {
    console.error(`demo: --port expects a port number, got ${values.port}`);
    process.exit(1);
  }
  const demo = await startDemoServer({ ...(port !== undefined ? { port } : {}), ...(values.host ? { host: values.host } : {}) });
  console.log(`demo: ${demo.url}`);
  console.log('demo: WebGPU needs a recent Chrome or Edge (or Firefox/Safari with WebGPU enabled). Ctrl-C stops the server.');
}
