// Sun and sky: the renderer's procedural presets (`environmentLighting`). Daylight is in cd/m²
// (tens of thousands), so choosing a preset applies the exposure the package suggests for it
// (createEnvironmentLighting(input).suggestedExposure: a white surface facing the brightest
// direction displays at about 1); the exposure slider moves on from there.
import { createEnvironmentLighting, type EnvironmentLightingPreset } from '@plasius/gpu-renderer';
import type { EnvironmentSource } from './environment-source.ts';
import { selectControl } from '../ui/controls.ts';

const presets: { value: EnvironmentLightingPreset; label: string }[] = [
  { value: 'clear', label: 'Clear sky' },
  { value: 'noon', label: 'Noon' },
  { value: 'sunset', label: 'Sunset' },
  { value: 'overcast', label: 'Overcast (CIE)' },
  { value: 'studio', label: 'Studio dome' },
];

export function skySource(): EnvironmentSource {
  let preset: EnvironmentLightingPreset = 'clear';
  // The bake behind the suggestion is the renderer's own work; once per preset is enough here.
  const suggestions = new Map<EnvironmentLightingPreset, number>();
  const suggestedExposure = (p: EnvironmentLightingPreset): number => {
    let value = suggestions.get(p);
    if (value === undefined) {
      value = createEnvironmentLighting({ preset: p }).suggestedExposure;
      suggestions.set(p, value);
    }
    return value;
  };
  return {
    id: 'sky',
    label: 'Sun and sky',
    mount(parent, context, params) {
      preset = presets.find((p) => p.value === params.get('sky'))?.value ?? preset;
      selectControl(parent, 'sky-preset', 'Preset', presets, preset, (value) => {
        preset = value;
        context.rebuild();
      });
    },
    rendererOptions: () => ({ environmentLighting: { preset } }),
    exposureEv: () => Math.log2(suggestedExposure(preset)),
  };
}
