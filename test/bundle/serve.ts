// A loopback static server for a bundle's output folder plus one HTML page at `/`.
import { serveFiles, type StaticServer } from '../browser/static-server.ts';

export function serveDirectory(dir: string, page: string): Promise<StaticServer> {
  return serveFiles(page, [{ prefix: '/', dir }]);
}
