import { createCornellBoxScene } from '@plasius/gpu-renderer';
import type { BuiltInScene } from './types.ts';

/** The package's Cornell box (what the CLI renders by default). */
export const cornellBox: BuiltInScene = {
  id: 'cornell',
  label: 'Cornell box',
  create() {
    const description = createCornellBoxScene();
    return { name: 'cornell-box', description: { ...description, camera: description.camera! }, suggestedEnvironment: [0, 0, 0], notes: [] };
  },
};
