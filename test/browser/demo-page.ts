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

/** The view's restart counter (rebuilds and camera moves each add to it). */
export async function restartsNow(tab: Page): Promise<number> {
  return tab.evaluate(() => Number(document.querySelector('[data-readout="samples"]')?.getAttribute('data-restarts') ?? 0));
}

/** Waits for an image begun after restart count `after` to reach `samples` spp, then reads it. */
export async function captureAfterRestart(tab: Page, after: number, samples: number, timeoutMs: number): Promise<FilmCapture> {
  await tab.waitForFunction(
    ([r, n]) => {
      const el = document.querySelector('[data-readout="samples"]');
      return Number(el?.getAttribute('data-restarts') ?? 0) > r! && Number(el?.getAttribute('data-value') ?? 0) >= n!;
    },
    [after, samples],
    { timeout: timeoutMs, polling: 50 },
  );
  return captureNow(tab);
}

/** Reads a canvas of the viewport (`film`: the path tracer's, `raster`: the raster view's). */
export async function captureCanvas(tab: Page, view: 'film' | 'raster'): Promise<FilmCapture> {
  return tab.evaluate((v) => {
    const canvas = document.querySelector<HTMLCanvasElement>(`canvas[data-view="${v}"]`)!;
    const image = canvas.getContext('2d')!.getImageData(0, 0, canvas.width, canvas.height);
    const samples = Number(document.querySelector('[data-readout="samples"]')!.getAttribute('data-value'));
    return { samples, width: image.width, height: image.height, data: Array.from(image.data) };
  }, view);
}

/** Chooses `value` in the select control `id` (as a user would). */
export async function choose(tab: Page, id: string, value: string): Promise<void> {
  await tab.locator(`[data-control="${id}"]`).selectOption(value);
}

/** Per-pixel luminance-like value: the mean of the 8-bit RGB channels. */
export function grey(a: FilmCapture): number[] {
  const out: number[] = [];
  for (let i = 0; i < a.data.length; i += 4) out.push((a.data[i]! + a.data[i + 1]! + a.data[i + 2]!) / 3);
  return out;
}

/**
 * Pixel-to-pixel noise: the median, over the pairs of horizontally or vertically adjacent pixels that
 * are not both black, of |ΔR| + |ΔG| + |ΔB| (8-bit steps). Monte Carlo noise makes most neighbours
 * differ; the image's own edges are a minority of pairs, which the median ignores.
 */
export function medianNeighbourDifference(a: FilmCapture): number {
  const d = a.data;
  const differences: number[] = [];
  const pair = (i: number, j: number): void => {
    if (d[i]! + d[i + 1]! + d[i + 2]! === 0 && d[j]! + d[j + 1]! + d[j + 2]! === 0) return;
    differences.push(Math.abs(d[i]! - d[j]!) + Math.abs(d[i + 1]! - d[j + 1]!) + Math.abs(d[i + 2]! - d[j + 2]!));
  };
  for (let y = 0; y < a.height; y++) {
    for (let x = 0; x < a.width; x++) {
      const i = 4 * (y * a.width + x);
      if (x + 1 < a.width) pair(i, i + 4);
      if (y + 1 < a.height) pair(i, i + 4 * a.width);
    }
  }
  differences.sort((p, q) => p - q);
  return differences[differences.length >> 1]!;
}

/** Pearson correlation of two captures' grey values. */
export function correlation(a: FilmCapture, b: FilmCapture): number {
  const x = grey(a);
  const y = grey(b);
  if (x.length !== y.length) throw new Error('captures differ in size');
  const mean = (v: number[]): number => v.reduce((s, t) => s + t, 0) / v.length;
  const mx = mean(x);
  const my = mean(y);
  let sxy = 0;
  let sxx = 0;
  let syy = 0;
  for (let i = 0; i < x.length; i++) {
    sxy += (x[i]! - mx) * (y[i]! - my);
    sxx += (x[i]! - mx) ** 2;
    syy += (y[i]! - my) ** 2;
  }
  return sxy / Math.sqrt(sxx * syy);
}
