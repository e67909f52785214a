import { GpuRendererError, type GpuRendererErrorCode } from './gpu-renderer-error.ts';

/** Small, explicit validators used at the public boundary. Each throws a typed error naming `field`. */

export function fail(code: GpuRendererErrorCode, field: string, message: string): never {
  throw new GpuRendererError(code, message, { field });
}

export function requireFiniteNumber(value: unknown, field: string, code: GpuRendererErrorCode = 'INVALID_OPTION'): number {
  if (typeof value !== 'number' || !Number.isFinite(value)) fail(code, field, `expected a finite number, got ${describe(value)}`);
  return value;
}

export function requireInteger(
  value: unknown,
  field: string,
  range: { min?: number; max?: number } = {},
  code: GpuRendererErrorCode = 'INVALID_OPTION',
): number {
  if (typeof value !== 'number' || !Number.isInteger(value)) fail(code, field, `expected an integer, got ${describe(value)}`);
  if (range.min !== undefined && value < range.min) fail(code, field, `must be >= ${range.min}, got ${value}`);
  if (range.max !== undefined && value > range.max) fail(code, field, `must be <= ${range.max}, got ${value}`);
  return value;
}

export function requireNumberInRange(
  value: unknown,
  field: string,
  range: { min?: number; max?: number },
  code: GpuRendererErrorCode = 'INVALID_OPTION',
): number {
  const n = requireFiniteNumber(value, field, code);
  if (range.min !== undefined && n < range.min) fail(code, field, `must be >= ${range.min}, got ${n}`);
  if (range.max !== undefined && n > range.max) fail(code, field, `must be <= ${range.max}, got ${n}`);
  return n;
}

export function requireVec(value: unknown, length: number, field: string, code: GpuRendererErrorCode = 'INVALID_OPTION'): number[] {
  if (!isArrayLike(value) || value.length !== length) fail(code, field, `expected ${length} numbers, got ${describe(value)}`);
  const out: number[] = [];
  for (let i = 0; i < length; i++) out.push(requireFiniteNumber(value[i], `${field}[${i}]`, code));
  return out;
}

export function isArrayLike(value: unknown): value is ArrayLike<unknown> {
  return Array.isArray(value) || (ArrayBuffer.isView(value) && !(value instanceof DataView));
}

export function describe(value: unknown): string {
  if (value === null) return 'null';
  if (Array.isArray(value)) return `an array of length ${value.length}`;
  if (ArrayBuffer.isView(value)) return `a ${value.constructor.name}`;
  if (typeof value === 'number') return String(value);
  if (typeof value === 'string') return JSON.stringify(value.length > 40 ? `${value.slice(0, 40)}...` : value);
  return typeof value;
}
