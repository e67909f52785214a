// Render settings: image size, path depth and adaptive sampling's noise threshold (the renderer is
// created again), samples per frame and where accumulation stops (the loop picks them up).
import type { DemoFeature } from '../extensions.ts';
import { section, selectControl } from '../ui/controls.ts';

const sizes = ['160x120', '320x240', '480x360', '640x480', '960x540', '1280x720', '1920x1080'];
const depths = [1, 2, 4, 8, 12, 16, 32];
const samplesPerFrame = [1, 2, 4, 8, 16];
const stopAt = [16, 64, 256, 1024, 4096, 0];
/** Adaptive sampling thresholds (README "Adaptive sampling"); 0: off. */
const noiseThresholds = [0, 0.1, 0.05, 0.02, 0.01, 0.005];

const choices = (values: readonly (string | number)[], label: (v: string) => string = (v) => v) => {
  return values.map(String).map((value) => ({ value, label: label(value) }));
};

let adaptiveThreshold = 0;

export const renderSettingsFeature: DemoFeature = {
  id: 'render-settings',
  rendererOptions: () => (adaptiveThreshold > 0 ? { adaptiveThreshold } : {}),
  mount(panel, context) {
    const box = section(panel, 'Render', 'render');
    const s = context.settings;
    const size = `${s.width}x${s.height}`;
    selectControl(box, 'size', 'Size', choices(sizes.includes(size) ? sizes : [size, ...sizes], (v) => v.replace('x', ' × ')), size, (value) => {
      const [w, h] = value.split('x').map(Number);
      s.width = w!;
      s.height = h!;
      context.rebuild();
    });
    selectControl(box, 'max-depth', 'Bounces', choices(depths.includes(s.maxDepth) ? depths : [s.maxDepth, ...depths]), String(s.maxDepth), (value) => {
      s.maxDepth = Number(value);
      context.rebuild();
    });
    selectControl(box, 'samples-per-frame', 'Samples / frame', choices(samplesPerFrame.includes(s.samplesPerFrame) ? samplesPerFrame : [s.samplesPerFrame, ...samplesPerFrame]), String(s.samplesPerFrame), (value) => {
      s.samplesPerFrame = Number(value);
      context.resume();
    });
    const stops = stopAt.includes(s.maxSamples) ? stopAt : [s.maxSamples, ...stopAt];
    selectControl(box, 'max-samples', 'Stop at', choices(stops, (v) => (v === '0' ? 'never' : `${v} spp`)), String(s.maxSamples), (value) => {
      s.maxSamples = Number(value);
      context.resume();
    });
    selectControl(box, 'noise-threshold', 'Noise threshold', choices(noiseThresholds, (v) => (v === '0' ? 'off (uniform)' : `${v} (adaptive)`)), String(adaptiveThreshold), (value) => {
      adaptiveThreshold = Number(value);
      context.rebuild();
    });
  },
};
