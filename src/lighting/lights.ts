import { describe, fail } from '../errors/validate.ts';
import { validateAreaLight, type AreaLight } from './area-lights.ts';
import { validatePunctualLight, type PunctualLight } from './punctual-lights.ts';

/** The scene's `lights`, split by kind; `order[i]` says where input light i went. */
export interface ValidatedLights {
  punctual: PunctualLight[];
  area: AreaLight[];
  order: { kind: 'punctual' | 'area'; index: number }[];
}

/**
 * Validates a `lights` array of KHR_lights_punctual lights ('point', 'spot', 'directional') and
 * area lights ('rectangle', 'disk', 'sphere'); `INVALID_LIGHT` errors name the field
 * (`lights[3].intensity`).
 */
export function validateLights(input: unknown, field = 'lights'): ValidatedLights {
  const out: ValidatedLights = { punctual: [], area: [], order: [] };
  if (input === undefined) return out;
  if (!Array.isArray(input)) fail('INVALID_LIGHT', field, `expected an array, got ${describe(input)}`);
  input.forEach((light: unknown, i) => {
    const f = `${field}[${i}]`;
    const type = typeof light === 'object' && light !== null ? (light as { type?: unknown }).type : undefined;
    if (type === 'rectangle' || type === 'disk' || type === 'sphere') {
      out.order.push({ kind: 'area', index: out.area.length });
      out.area.push(validateAreaLight(light, f));
    } else {
      if (type !== 'point' && type !== 'spot' && type !== 'directional') {
        fail('INVALID_LIGHT', `${f}.type`, `expected 'point', 'spot', 'directional', 'rectangle', 'disk' or 'sphere', got ${describe(type)}`);
      }
      out.order.push({ kind: 'punctual', index: out.punctual.length });
      out.punctual.push(validatePunctualLight(light, f));
    }
  });
  return out;
}
