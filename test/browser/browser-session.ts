// One headless Chromium session for browser tests: Debian's chromium with SwiftShader WebGPU (the
// flags DEVELOPERS.md names), a loopback static server for the built package, and a page that has
// imported the package as `window.pkg`.
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import type { Browser, Page } from 'playwright-core';
import { builtPackageDir } from './built-package.ts';
import { createImportMap } from './import-map.ts';
import { startStaticServer } from './static-server.ts';

export const chromiumPath = '/usr/bin/chromium';
export const chromiumSkip: false | string = existsSync(chromiumPath) ? false : `${chromiumPath} is not installed`;

const root = fileURLToPath(new URL('../..', import.meta.url));

export const chromiumWebGpuArgs = [
  '--enable-unsafe-webgpu',
  '--enable-features=Vulkan',
  '--use-vulkan=swiftshader',
  '--use-webgpu-adapter=swiftshader',
  '--use-angle=swiftshader',
  '--no-sandbox',
  '--disable-gpu-sandbox',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
];

/** An HTML page with the import map, `style` and `body`, that imports the package as window.pkg. */
function page(importMap: object, style: string, body: string): string {
  return `<!doctype html>
<html><head><meta charset="utf-8">
<script type="importmap">${JSON.stringify(importMap)}</script>
<style>${style}</style>
</head><body>${body}
<script type="module">
  import * as pkg from '/pkg/index.js';
  window.pkg = pkg;
  window.ready = true;
</script></body></html>`;
}

export interface BrowserSession {
  tab: Page;
  browser: Browser;
  pageErrors: string[];
  close(): Promise<void>;
}

/** `imports`: more import-map entries (e.g. a peer renderer the page loads from /node_modules/); `args`: Chromium's flags instead of chromiumWebGpuArgs. */
export async function openPackagePage(options: { style: string; body: string; viewport: { width: number; height: number }; imports?: Record<string, string>; args?: string[] }): Promise<BrowserSession> {
  const { chromium } = await import('playwright-core');
  const built = builtPackageDir(root);
  const server = await startStaticServer({ root, packageDir: built.dir, page: page({ imports: { ...createImportMap(root).imports, ...options.imports } }, options.style, options.body) });
  const browser = await chromium.launch({ executablePath: chromiumPath, headless: true, args: options.args ?? chromiumWebGpuArgs });
  const close = async (): Promise<void> => {
    await browser.close();
    await server.close();
    built.cleanup();
  };
  try {
    const tab = await browser.newPage({ viewport: options.viewport, deviceScaleFactor: 1 });
    const pageErrors: string[] = [];
    tab.on('pageerror', (e) => pageErrors.push(e.message));
    await tab.goto(server.url);
    await tab.waitForFunction(() => (window as unknown as { ready?: boolean }).ready === true, undefined, { timeout: 15000 });
    return { tab, browser, pageErrors, close };
  } catch (error) {
    await close();
    throw error;
  }
}
