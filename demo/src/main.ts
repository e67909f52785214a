// Entry point: reads the URL parameters, builds the panel, and shows the first scene.
//   ?scene=cornell|swatches|product  &size=640x480  &depth=8  &spf=1  &stop=1024
//   &light=colour|hdri|sky  &hdri=studio|city|sunset  &sky=clear|noon|sunset|overcast|studio  &view=path-traced|raster
import { supportsWebGpu } from '@plasius/gpu-renderer';
import { DemoApp } from './app.ts';
import type { RenderSettings } from './extensions.ts';
import { demoFeatures } from './features/index.ts';
import { acceptedExtensions, isSceneFile, sceneFromFiles } from './scene-files.ts';
import { builtInScenes } from './scenes/index.ts';
import { section, selectControl } from './ui/controls.ts';
import { demoViews } from './views/index.ts';
import './style.css';

function byId<T extends HTMLElement>(id: string): T {
  const el = document.getElementById(id);
  if (!el) throw new Error(`index.html has no #${id}`);
  return el as T;
}

function settingsFromUrl(params: URLSearchParams): RenderSettings {
  const int = (name: string, fallback: number, min: number, max: number): number => {
    const value = Number(params.get(name));
    return params.has(name) && Number.isInteger(value) && value >= min && value <= max ? value : fallback;
  };
  const [w, h] = (params.get('size') ?? '').split('x').map(Number);
  const size = Number.isInteger(w) && Number.isInteger(h) && w! >= 8 && h! >= 8 && w! <= 4096 && h! <= 4096 ? { width: w!, height: h! } : { width: 640, height: 480 };
  return { ...size, maxDepth: int('depth', 8, 1, 32), samplesPerFrame: int('spf', 1, 1, 64), maxSamples: int('stop', 1024, 0, 1 << 20) };
}

async function main(): Promise<void> {
  const params = new URLSearchParams(location.search);
  const viewport = byId('viewport');
  const panel = byId('panel');
  const viewChoices = demoViews.map((create) => create());
  const firstView = Math.max(0, viewChoices.findIndex((v) => v.id === params.get('view')));
  const app = new DemoApp(
    { viewport, panel, readouts: byId('readouts'), notes: byId('notes') },
    { settings: settingsFromUrl(params), features: demoFeatures, view: demoViews[firstView]!() },
  );
  if (!(await supportsWebGpu())) {
    app.status('This browser has no WebGPU adapter: try a recent Chrome or Edge, or enable WebGPU.', 'error');
    document.body.dataset.state = 'no-webgpu';
    return;
  }

  // Scene: the built-in scenes, or the user's file (picked or dropped).
  const sceneBox = section(panel, 'Scene', 'scene');
  const first = builtInScenes.find((s) => s.id === params.get('scene')) ?? builtInScenes[0]!;
  const picker = selectControl(sceneBox, 'scene', 'Scene', builtInScenes.map((s) => ({ value: s.id, label: s.label })), first.id, (id) => {
    const scene = builtInScenes.find((s) => s.id === id);
    if (scene) app.showScene(scene.create());
  });
  if (demoViews.length > 1) {
    selectControl(sceneBox, 'view', 'View', viewChoices.map((v) => ({ value: v.id, label: v.label })), viewChoices[firstView]!.id, (id) => app.switchView(demoViews[viewChoices.findIndex((v) => v.id === id)]!()));
  }
  const fileInput = Object.assign(document.createElement('input'), { type: 'file', multiple: true, accept: acceptedExtensions.join(',') });
  fileInput.dataset.control = 'file';
  const fileLabel = Object.assign(document.createElement('label'), { className: 'file-button', textContent: 'Open .glb / .gltf…' });
  fileLabel.append(fileInput);
  sceneBox.append(fileLabel, Object.assign(document.createElement('p'), { className: 'hint', textContent: 'or drop files on the picture · drag to orbit, shift-drag to pan, wheel to zoom, double-click to reset' }));

  const openFiles = async (files: File[]): Promise<void> => {
    const main = files.find((f) => isSceneFile(f.name));
    if (!main) {
      app.status(`Not a glTF file: ${files.map((f) => f.name).join(', ')}`, 'error');
      return;
    }
    app.status(`Loading ${main.name}…`, 'busy');
    try {
      const scene = await sceneFromFiles(files);
      let option = picker.querySelector<HTMLOptionElement>('option[value="file"]');
      if (!option) {
        option = Object.assign(document.createElement('option'), { value: 'file' });
        picker.append(option);
      }
      option.textContent = `${main.name} (file)`;
      picker.value = 'file';
      app.showScene(scene);
    } catch (error) {
      console.error(error);
      app.status(`Could not load ${main.name}: ${(error as Error).message}`, 'error');
    }
  };
  fileInput.addEventListener('change', () => {
    void openFiles([...(fileInput.files ?? [])]);
    fileInput.value = '';
  });
  let dragDepth = 0;
  document.addEventListener('dragenter', (e) => {
    e.preventDefault();
    if (++dragDepth === 1) document.body.dataset.dragging = 'true';
  });
  document.addEventListener('dragleave', () => {
    if (--dragDepth <= 0) {
      dragDepth = 0;
      delete document.body.dataset.dragging;
    }
  });
  document.addEventListener('dragover', (e) => e.preventDefault());
  document.addEventListener('drop', (e) => {
    e.preventDefault();
    dragDepth = 0;
    delete document.body.dataset.dragging;
    void openFiles([...(e.dataTransfer?.files ?? [])]);
  });

  app.mountFeatures(panel);
  app.showScene(first.create());
}

void main();
