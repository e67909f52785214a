import { fail } from '../errors/validate.ts';
import type { GpuRendererErrorCode } from '../errors/gpu-renderer-error.ts';

/** Refuses keys outside `allowed` (a misspelt option is an error naming it, never ignored). */
export function requireKnownKeys(value: Record<string, unknown>, allowed: readonly string[], field: string, code: GpuRendererErrorCode): void {
  for (const key of Object.keys(value)) {
    if (!allowed.includes(key)) fail(code, `${field}.${key}`, `unknown key (expected one of ${allowed.join(', ')})`);
  }
}
