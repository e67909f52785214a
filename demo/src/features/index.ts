// The control panel's features, in panel order. Each is one module; see extensions.ts for how a
// renderer feature joins.
import type { DemoFeature } from '../extensions.ts';
import { denoiseFeature } from './denoise.ts';
import { environmentFeature } from './environment.ts';
import { exportFeature } from './export.ts';
import { renderSettingsFeature } from './render-settings.ts';
import { toneMappingFeature } from './tone-mapping.ts';

export const demoFeatures: readonly DemoFeature[] = [environmentFeature, toneMappingFeature, denoiseFeature, renderSettingsFeature, exportFeature];
