// The built-in scenes, in picker order. A new one is a module exporting a BuiltInScene and one
// line here.
import { cornellBox } from './cornell-box.ts';
import { materialSwatches } from './material-swatches.ts';
import { productShot } from './product-shot.ts';
import type { BuiltInScene } from './types.ts';

export const builtInScenes: readonly BuiltInScene[] = [cornellBox, materialSwatches, productShot];

export type { BuiltInScene, DemoScene } from './types.ts';
