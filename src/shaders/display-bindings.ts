import type { BindingSpec } from '../gpu-layout/bindings.ts';

/**
 * Bindings of the display programs (resolve to RGBA8 and canvas presentation): the film read-only
 * plus the display constants. Separate from the path tracer's table because the film is read-only
 * here and the programs run alone.
 */
export const displayBindings = {
  display: { group: 0, binding: 0, kind: 'uniform', type: 'ResolveUniforms', doc: 'image size, tone mapping, exposure' },
  displayFilm: { group: 0, binding: 1, kind: 'storage', access: 'read', type: 'array<vec4f>', doc: 'the accumulation: radiance sum and sample count per pixel' },
  displayPixels: { group: 0, binding: 2, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'resolved sRGB RGBA8 pixels' },
} as const satisfies Record<string, BindingSpec>;

export type DisplayBindingName = keyof typeof displayBindings;
