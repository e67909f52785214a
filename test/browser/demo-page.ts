// The demo page in a real browser for the end-to-end tests: starts the demo's Vite dev server on a
// free loopback port, opens it in Debian's Chromium (SwiftShader WebGPU), collects console errors
// and page errors, and reads what the page shows (the film canvas's pixels with the sample count
// they belong to).
import { mkdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import type { Browser, Page } from 'playwright-core';
import { startDemoServer, type DemoServer } from '../../scripts/demo-server.ts';
import { chromiumPath, chromiumWebGpuArgs } from './browser-session.ts';

export { chromiumSkip } from './browser-session.ts';

/** Where the end-to-end tests keep their screenshots (gitignored). */
export const testOutputDir = fileURLToPath(new URL('../../test-output/', import.meta.url));

export interface DemoPage {
  tab: Page;
  /** Console errors and uncaught page errors, as they happened. */
  errors: string[];
  close(): Promise<void>;
}

export async function openDemo(query: string, viewport = { width: 1000, height: 700 }): Promise<DemoPage> {
  const { chromium } = await import('playwright-core');
  const server: DemoServer = await startDemoServer({ port: 0, quiet: true });
  let browser: Browser | undefined;
  const close = async (): Promise<void> => {
    await browser?.close();
    await server.close();
  };
  try {
    browser = await chromium.launch({ executablePath: chromiumPath, headless: true, args: chromiumWebGpuArgs });
    const tab = await browser.newPage({ viewport, deviceScaleFactor: 1, acceptDownloads: true });
    const errors: string[] = [];
    tab.on('console', (message) => {
      if (message.type() === 'error') errors.push(`console: ${message.text()}`);
    });
    tab.on('pageerror', (error) => errors.push(`page: ${error.message}`));
    await tab.goto(`${server.url}${query}`);
    return { tab, errors, close };
  } catch (error) {
    await close();
    throw error;
  }
}

export interface FilmCapture {
  samples: number;
  width: number;
  height: number;
  /** RGBA8 as displayed. */
  data: number[];
}

/** Waits until the page shows at least `samples` spp, then reads the film canvas and its count together. */
export async function captureAtLeast(tab: Page, samples: number, timeoutMs: number): Promise<FilmCapture> {
  await tab.waitForFunction((n) => Number(document.querySelector('[data-readout="samples"]')?.getAttribute('data-value') ?? 0) >= n, samples, { timeout: timeoutMs, polling: 50 });
  return captureNow(tab);
}

export async function captureNow(tab: Page): Promise<FilmCapture> {
  return tab.evaluate(() => {
    const canvas = document.querySelector<HTMLCanvasElement>('canvas[data-view="film"]')!;
    const image = canvas.getContext('2d')!.getImageData(0, 0, canvas.width, canvas.height);
    const samples = Number(document.querySelector('[data-readout="samples"]')!.getAttribute('data-value'));
    return { samples, width: image.width, height: image.height, data: Array.from(image.data) };
  });
}

/** Mean absolute difference per RGB channel, in 8-bit steps. */
export function meanAbsoluteDifference(a: FilmCapture, b: FilmCapture): number {
  if (a.width !== b.width || a.height !== b.height) throw new Error('captures differ in size');
  let sum = 0;
  for (let i = 0; i < a.data.length; i += 4) for (let c = 0; c < 3; c++) sum += Math.abs(a.data[i + c]! - b.data[i + c]!);
  return sum / ((a.data.length / 4) * 3);
}

export function meanValue(a: FilmCapture): number {
  let sum = 0;
  for (let i = 0; i < a.data.length; i += 4) sum += a.data[i]! + a.data[i + 1]! + a.data[i + 2]!;
  return sum / ((a.data.length / 4) * 3);
}

export function ensureTestOutputDir(): string {
  mkdirSync(testOutputDir, { recursive: true });
  return testOutputDir;
}
