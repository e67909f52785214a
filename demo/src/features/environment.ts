// The environment: what lights rays that leave the scene. Each EnvironmentSource contributes
// renderer options and the exposure it looks right at; the "Light" picker chooses one. Sources:
// a uniform colour (the scene's suggestion), HDRI maps (environment-hdri.ts) and the sun and sky
// presets (environment-sky.ts). Choosing a source or changing its controls rebuilds the renderer.
import type { DemoContext, DemoFeature } from '../extensions.ts';
import { colourControl, hexToLinear, linearToHex, rangeControl, section, selectControl, setRangeValue } from '../ui/controls.ts';
import { hdriSource } from './environment-hdri.ts';
import type { EnvironmentSource } from './environment-source.ts';
import { skySource } from './environment-sky.ts';

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

export const environmentSources: EnvironmentSource[] = [uniformColourSource(), hdriSource(), skySource()];

export const environmentFeature: DemoFeature = (() => {
  let active = environmentSources[0]!;
  let context: DemoContext | undefined;
  const sceneExposureEv = (): number => {
    const suggested = context?.scene?.suggestedExposure;
    return suggested === undefined ? 0 : Math.log2(suggested);
  };
  let appliedEv: number | undefined;
  const applyExposure = (): void => {
    appliedEv = active.exposureEv?.() ?? sceneExposureEv();
    context?.setExposure(appliedEv);
  };
  return {
    id: 'environment',
    mount(panel, ctx) {
      context = ctx;
      // ?light=colour|hdri|sky picks the source at start (each source reads its own parameter).
      const params = new URLSearchParams(location.search);
      active = environmentSources.find((s) => s.id === params.get('light')) ?? active;
      const box = section(panel, 'Environment', 'environment');
      const bodies = new Map<string, HTMLElement>();
      if (environmentSources.length > 1) {
        selectControl(box, 'environment-source', 'Light', environmentSources.map((s) => ({ value: s.id, label: s.label })), active.id, (id) => {
          active = environmentSources.find((s) => s.id === id)!;
          for (const [sid, body] of bodies) body.hidden = sid !== id;
          applyExposure();
          ctx.rebuild();
        });
      }
      // A source's control that changes the source's suggested exposure (a sky preset) applies the
      // new suggestion; other controls keep the exposure the user set.
      const sourceContext: DemoContext = Object.create(ctx, {
        rebuild: {
          value: () => {
            const ev = active.exposureEv?.();
            if (ev !== undefined && ev !== appliedEv) applyExposure();
            ctx.rebuild();
          },
        },
      }) as DemoContext;
      for (const source of environmentSources) {
        const body = document.createElement('div');
        body.hidden = source !== active;
        box.append(body);
        bodies.set(source.id, body);
        source.mount(body, sourceContext, params);
      }
    },
    rendererOptions: () => active.rendererOptions(),
    sceneLoaded(scene) {
      for (const source of environmentSources) source.sceneLoaded?.(scene);
      applyExposure();
    },
  };
})();
