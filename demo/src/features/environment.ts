// The environment: what lights rays that leave the scene. Each EnvironmentSource contributes
// renderer options; a picker appears once there is more than one. Today's renderer has the uniform
// colour. Extension point: the HDRI source (issue 8: `environmentMap` from loadEnvironmentMap on a
// small CC0 map) and the sky presets (`environmentLighting`) are new entries of
// `environmentSources`, each with its own controls.
import type { WavefrontPathTracingOptions } from '@plasius/gpu-renderer';
import type { DemoContext, DemoFeature } from '../extensions.ts';
import type { DemoScene } from '../scenes/types.ts';
import { colourControl, hexToLinear, linearToHex, rangeControl, section, selectControl, setRangeValue } from '../ui/controls.ts';

export interface EnvironmentSource {
  id: string;
  label: string;
  /** Adds the source's controls to `parent` (shown only while the source is selected). */
  mount(parent: HTMLElement, context: DemoContext): void;
  rendererOptions(): Partial<WavefrontPathTracingOptions>;
  sceneLoaded?(scene: DemoScene): void;
}

/** Uniform radiance: a colour (sRGB picker, converted to linear) times a strength. */
function uniformColourSource(): EnvironmentSource {
  let hex = '#ffffff';
  let strength = 0;
  let colourInput: HTMLInputElement | undefined;
  let strengthInput: HTMLInputElement | undefined;
  const format = (v: number): string => v.toFixed(2);
  return {
    id: 'colour',
    label: 'Uniform colour',
    mount(parent, context) {
      colourInput = colourControl(parent, 'environment-colour', 'Colour', hex, (value) => {
        hex = value;
        context.rebuild();
      });
      strengthInput = rangeControl(parent, 'environment-strength', 'Strength', { min: 0, max: 2, step: 0.01, value: strength, format, commit: true }, (value) => {
        strength = value;
        context.rebuild();
      });
    },
    rendererOptions() {
      const rgb = hexToLinear(hex).map((c) => c * strength);
      return { environment: { color: rgb } };
    },
    sceneLoaded(scene) {
      const rgb = scene.suggestedEnvironment;
      strength = Math.max(...rgb);
      hex = strength > 0 ? linearToHex(rgb.map((c) => c / strength)) : '#ffffff';
      if (colourInput) colourInput.value = hex;
      if (strengthInput) setRangeValue(strengthInput, strength);
    },
  };
}

export const environmentSources: EnvironmentSource[] = [uniformColourSource()];

export const environmentFeature: DemoFeature = (() => {
  let active = environmentSources[0]!;
  return {
    id: 'environment',
    mount(panel, context) {
      const box = section(panel, 'Environment', 'environment');
      const bodies = new Map<string, HTMLElement>();
      if (environmentSources.length > 1) {
        selectControl(box, 'environment-source', 'Light', environmentSources.map((s) => ({ value: s.id, label: s.label })), active.id, (id) => {
          active = environmentSources.find((s) => s.id === id)!;
          for (const [sid, body] of bodies) body.hidden = sid !== id;
          context.rebuild();
        });
      }
      for (const source of environmentSources) {
        const body = document.createElement('div');
        body.hidden = source !== active;
        box.append(body);
        bodies.set(source.id, body);
        source.mount(body, context);
      }
    },
    rendererOptions: () => active.rendererOptions(),
    sceneLoaded(scene) {
      for (const source of environmentSources) source.sceneLoaded?.(scene);
    },
  };
})();
