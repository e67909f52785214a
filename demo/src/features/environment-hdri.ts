// HDRI environments: small CC0 equirectangular maps from the npm package @pmndrs/assets (each a
// module whose default export is a `data:application/exr;base64,…` string of 150-200 kB, imported
// on first use so each is its own chunk), decoded by the package's loadEnvironmentMap with
// three.js's EXRLoader (the browser build takes the class; it is imported on first use too).
//
// These maps are DWAB-compressed (lossy, DCT based). Its ringing leaves some texels below zero
// beside bright sources, which the renderer refuses as radiance by default: the demo asks the
// loader to set them to zero (`negativeTexels: 'zero'`) and says how many and how much energy that
// adds, under the picker.
import { loadEnvironmentMap, type EnvironmentMap, type ExrLoaderConstructor, type NegativeTexelReport } from '@plasius/gpu-renderer';
import type { EnvironmentSource } from './environment-source.ts';
import { rangeControl, selectControl } from '../ui/controls.ts';

interface HdriChoice {
  id: string;
  label: string;
  load(): Promise<{ default: string }>;
}

/** Picked for variety: a softbox studio, an overcast city street, a low sun. */
export const hdriChoices: readonly HdriChoice[] = [
  { id: 'studio', label: 'Studio', load: () => import('@pmndrs/assets/hdri/studio.exr.js') },
  { id: 'city', label: 'City', load: () => import('@pmndrs/assets/hdri/city.exr.js') },
  { id: 'sunset', label: 'Sunset', load: () => import('@pmndrs/assets/hdri/sunset.exr.js') },
];

export interface LoadedHdri {
  map: EnvironmentMap;
  /** Set when negative texels of the lossy encoding were set to zero. */
  repair?: NegativeTexelReport;
}

async function fetchBytes(dataUrl: string): Promise<Uint8Array> {
  return new Uint8Array(await (await fetch(dataUrl)).arrayBuffer());
}

/** Decodes one of the choices, zeroing the lossy codec's negative ringing (and saying so). */
export async function loadHdri(choice: HdriChoice): Promise<LoadedHdri> {
  const [three, asset] = await Promise.all([import('three/examples/jsm/loaders/EXRLoader.js'), choice.load()]);
  // @types/three declares parse()'s width and height optional; the package's ExrLoaderLike wants numbers.
  const EXRLoader = three.EXRLoader as unknown as ExrLoaderConstructor;
  const bytes = await fetchBytes(asset.default);
  let repair: NegativeTexelReport | undefined;
  const map = await loadEnvironmentMap(bytes, { EXRLoader, field: `${choice.id}.exr`, negativeTexels: 'zero', onNegativeTexels: (report) => (repair = report) });
  return { map, ...(repair && repair.channels > 0 ? { repair } : {}) };
}

export function hdriSource(): EnvironmentSource {
  let choice = hdriChoices[0]!;
  let intensity = 1;
  let rotationDegrees = 0;
  const cache = new Map<string, Promise<LoadedHdri>>();
  let info: HTMLElement | undefined;
  const loaded = (c: HdriChoice): Promise<LoadedHdri> => {
    let promise = cache.get(c.id);
    if (!promise) {
      promise = loadHdri(c);
      cache.set(c.id, promise);
      // A failed download or decode is tried again next time.
      promise.catch(() => cache.delete(c.id));
    }
    return promise;
  };
  return {
    id: 'hdri',
    label: 'HDRI map',
    mount(parent, context, params) {
      choice = hdriChoices.find((c) => c.id === params.get('hdri')) ?? choice;
      selectControl(parent, 'hdri', 'Map', hdriChoices.map((c) => ({ value: c.id, label: c.label })), choice.id, (id) => {
        choice = hdriChoices.find((c) => c.id === id)!;
        context.rebuild();
      });
      rangeControl(parent, 'hdri-intensity', 'Intensity', { min: 0, max: 4, step: 0.05, value: intensity, format: (v) => `${v.toFixed(2)}×`, commit: true }, (value) => {
        intensity = value;
        context.rebuild();
      });
      rangeControl(parent, 'hdri-rotation', 'Rotation', { min: 0, max: 360, step: 5, value: rotationDegrees, format: (v) => `${v}°`, commit: true }, (value) => {
        rotationDegrees = value;
        context.rebuild();
      });
      info = Object.assign(document.createElement('p'), { className: 'hint', textContent: 'CC0 maps from @pmndrs/assets (Poly Haven), 512 × 256' });
      info.dataset.info = 'hdri';
      parent.append(info);
    },
    async rendererOptions() {
      const current = choice;
      const { map, repair } = await loaded(current);
      if (info && current === choice) {
        info.textContent = repair
          ? `${current.label}: ${repair.channels.toLocaleString('en')} channel values below zero (DWAB compression ringing) set to 0, adding ${(100 * repair.addedEnergyFraction).toFixed(2)}% to the map's energy`
          : `${current.label}: decoded as is`;
      }
      return { environmentMap: { ...map, intensity, rotationRadians: (rotationDegrees * Math.PI) / 180 } };
    },
  };
}
