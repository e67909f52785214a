// What draws the scene. The raster / animated view (issue 10) is a second DemoView here; the view
// picker appears once there are two.
import type { DemoView } from '../extensions.ts';
import { PathTracedView } from './path-traced-view.ts';

export const demoViews: readonly (() => DemoView)[] = [() => new PathTracedView()];
