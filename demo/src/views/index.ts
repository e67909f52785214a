// What draws the scene: the progressive path tracer and the raster preview. The view picker
// appears once there are two.
import type { DemoView } from '../extensions.ts';
import { PathTracedView } from './path-traced-view.ts';
import { RasterView } from './raster-view.ts';

export const demoViews: readonly (() => DemoView)[] = [() => new PathTracedView(), () => new RasterView()];
