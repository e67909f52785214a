// Denoise: the renderer's edge-avoiding à-trous filter (`denoise: true`, README "Denoising"). While
// checked the renderer is built with it and the page shows `readDenoised()` instead of the raw
// estimate; exports then save the denoised image. Toggling rebuilds (the filter's buffers and
// kernels are compiled in only when asked for).
import type { DemoFeature } from '../extensions.ts';
import { checkboxControl, section } from '../ui/controls.ts';

export const denoiseFeature: DemoFeature = (() => {
  let enabled = false;
  return {
    id: 'denoise',
    mount(panel, context) {
      const box = section(panel, 'Denoise', 'denoise');
      checkboxControl(box, 'denoise', 'À-trous filter', enabled, (checked) => {
        enabled = checked;
        context.rebuild();
      });
      box.append(Object.assign(document.createElement('p'), { className: 'hint', textContent: 'A biased estimate: smoother, guided by albedo, normals and depth; emitters stay exact.' }));
    },
    rendererOptions: () => (enabled ? { denoise: true } : {}),
    radianceSource: () => (enabled ? (renderer) => renderer.readDenoised() : undefined),
  };
})();
