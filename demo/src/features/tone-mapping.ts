// Display: tone mapping operator and exposure in stops. Both only change how the current estimate
// is shown, so they apply instantly and keep every sample. The exposure a scene and its light
// suggest is set by the environment feature through DemoContext.setExposure.
import type { WavefrontToneMapping } from '@plasius/gpu-renderer';
import type { DemoFeature } from '../extensions.ts';
import { rangeControl, section, selectControl, setRangeValue } from '../ui/controls.ts';

const operators: { value: WavefrontToneMapping; label: string }[] = [
  { value: 'neutral', label: 'Khronos PBR Neutral' },
  { value: 'agx', label: 'AgX' },
  { value: 'aces', label: 'ACES (fitted)' },
  { value: 'linear', label: 'Linear (clipped)' },
];

export const toneMappingFeature: DemoFeature = (() => {
  let exposureInput: HTMLInputElement | undefined;
  let display: { exposureEv: number } | undefined;
  return {
    id: 'tone-mapping',
    mount(panel, context) {
      display = context.display;
      const box = section(panel, 'Display', 'display');
      selectControl(box, 'tone-mapping', 'Tone mapping', operators, context.display.toneMapping, (value) => {
        context.display.toneMapping = value;
        context.redisplay();
      });
      const format = (ev: number): string => `${ev > 0 ? '+' : ''}${ev.toFixed(1)} EV`;
      exposureInput = rangeControl(box, 'exposure', 'Exposure', { min: -18, max: 6, step: 0.1, value: context.display.exposureEv, format }, (ev) => {
        context.display.exposureEv = ev;
        context.redisplay();
      });
    },
    // The environment feature picks the exposure for a scene and light (setExposure).
    displayChanged() {
      if (display && exposureInput) setRangeValue(exposureInput, display.exposureEv);
    },
  };
})();
