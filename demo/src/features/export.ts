// Saving the image. Each Exporter is a button; PNG saves the displayed (tone-mapped) pixels, EXR
// the linear radiance (32-bit float, ZIP), for compositing; the raster view has no linear radiance,
// so it saves PNG only. A new format is one more entry.
import { encodeExr, encodePng } from '@plasius/gpu-renderer';
import type { CurrentImage, DemoFeature } from '../extensions.ts';
import { buttonControl, download, section } from '../ui/controls.ts';

export interface Exporter {
  id: string;
  label: string;
  extension: string;
  mimeType: string;
  /** Whether the view's image has what the format needs (EXR: linear radiance). */
  accepts?(image: CurrentImage): boolean;
  encode(image: CurrentImage): Uint8Array;
}

export const exporters: Exporter[] = [
  {
    id: 'png',
    label: 'Save PNG',
    extension: 'png',
    mimeType: 'image/png',
    encode: (image) => encodePng({ width: image.pixels.width, height: image.pixels.height, data: image.pixels.data }),
  },
  {
    id: 'exr',
    label: 'Save EXR',
    extension: 'exr',
    mimeType: 'image/x-exr',
    accepts: (image) => image.radiance !== null,
    encode: (image) => encodeExr(image.radiance!, { pixelType: 'float', compression: 'zip' }),
  },
];

export const exportFeature: DemoFeature = {
  id: 'export',
  mount(panel, context) {
    const box = section(panel, 'Save', 'save');
    const buttons = document.createElement('div');
    buttons.className = 'buttons';
    box.append(buttons);
    for (const exporter of exporters) {
      buttonControl(buttons, `save-${exporter.id}`, exporter.label, () => {
        const image = context.currentImage();
        if (!image || exporter.accepts?.(image) === false) return;
        download(exporter.encode(image), `${image.sceneName}-${image.samples}spp.${exporter.extension}`, exporter.mimeType);
      });
    }
  },
};
