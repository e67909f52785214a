// The readouts under the picture: samples per pixel, time since accumulation restarted, rays per
// second, adaptive sampling's share of pixels still sampling, plus a status line and the notes (what
// the loader or the demo left out). The raster view shows its frame time and draw counts instead.
import type { ViewProgress } from './extensions.ts';

function si(value: number, unit: string): string {
  const prefixes = ['', 'k', 'M', 'G', 'T'];
  let i = 0;
  while (value >= 1000 && i < prefixes.length - 1) {
    value /= 1000;
    i++;
  }
  return `${value.toFixed(value < 10 ? 2 : value < 100 ? 1 : 0)} ${prefixes[i]}${unit}`;
}

export class Readouts {
  private readonly fields: Record<'samples' | 'time' | 'rays' | 'adaptive' | 'status', HTMLElement>;
  private readonly notes: HTMLElement;

  constructor(root: HTMLElement, notes: HTMLElement) {
    const field = (name: string): HTMLElement => {
      const el = root.querySelector<HTMLElement>(`[data-readout="${name}"]`);
      if (!el) throw new Error(`missing readout ${name}`);
      return el;
    };
    this.fields = { samples: field('samples'), time: field('time'), rays: field('rays'), adaptive: field('adaptive'), status: field('status') };
    this.notes = notes;
  }

  progress(p: ViewProgress): void {
    this.fields.samples.textContent = p.frameTimeMs !== undefined ? `raster · ${p.frameTimeMs.toFixed(1)} ms/frame` : `${p.samples} spp`;
    this.fields.samples.dataset.value = String(p.samples);
    this.fields.samples.dataset.idle = String(p.idle);
    this.fields.samples.dataset.restarts = String(p.restarts);
    this.fields.time.textContent = `${(p.elapsedMs / 1000).toFixed(1)} s`;
    this.fields.rays.textContent = p.detail ?? `${si(p.raysPerSecond, 'rays/s')} · ${si(p.samplesPerSecond, 'samples/s')}`;
    const adaptive = p.activePixels;
    this.fields.adaptive.hidden = !adaptive;
    this.fields.adaptive.textContent = adaptive ? `${((100 * adaptive.active) / Math.max(1, adaptive.total)).toFixed(1)}% of pixels sampling` : '';
    if (adaptive) this.fields.adaptive.dataset.value = String(adaptive.active);
    else delete this.fields.adaptive.dataset.value;
  }

  status(text: string, kind: 'busy' | 'ok' | 'error'): void {
    this.fields.status.textContent = text;
    this.fields.status.dataset.kind = kind;
  }

  setNotes(notes: readonly string[]): void {
    this.notes.replaceChildren(...notes.map((n) => Object.assign(document.createElement('li'), { textContent: n })));
  }
}
