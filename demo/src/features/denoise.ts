// Denoise: the renderer's denoisers (README "Denoising"): Open Image Denoise's network (`denoise:
// 'oidn'`, production quality) or the edge-avoiding à-trous filter (`'atrous'`, a fast preview).
// While checked the renderer is built with the chosen one and the page shows `readDenoised()`
// instead of the raw estimate; exports then save the denoised image. Changing either rebuilds (the
// denoiser's buffers, weights and kernels are only made when asked for).
import type { DemoFeature } from '../extensions.ts';
import { checkboxControl, section, selectControl } from '../ui/controls.ts';

type Denoiser = 'oidn' | 'atrous';

const hints: Record<Denoiser, string> = {
  oidn: "Open Image Denoise's U-Net on the GPU (f16 where the adapter has shader-f16), guided by albedo and normals; emitters stay exact.",
  atrous: 'A fast biased preview: an edge-avoiding à-trous filter guided by albedo, normals and depth; the image keeps its energy.',
};

export const denoiseFeature: DemoFeature = (() => {
  let enabled = false;
  let denoiser: Denoiser = 'oidn';
  return {
    id: 'denoise',
    mount(panel, context) {
      const box = section(panel, 'Denoise', 'denoise');
      checkboxControl(box, 'denoise', 'Denoise', enabled, (checked) => {
        enabled = checked;
        context.rebuild();
      });
      const hint = Object.assign(document.createElement('p'), { className: 'hint', textContent: hints[denoiser] });
      selectControl(box, 'denoiser', 'Denoiser', [{ value: 'oidn', label: 'OIDN (network)' }, { value: 'atrous', label: 'À-trous (preview)' }], denoiser, (value) => {
        denoiser = value;
        hint.textContent = hints[value];
        if (enabled) context.rebuild();
      });
      box.append(hint);
    },
    rendererOptions: () => (enabled ? { denoise: denoiser } : {}),
    radianceSource: () => (enabled ? (renderer) => renderer.readDenoised() : undefined),
  };
})();
