/**
 * What a read is held to once the resource policy is resolved (resource-policy.ts resolves it,
 * resource-read.ts reads under it): the resolved limits, where a fault is reported, and the
 * decoded-bytes budget of one load.
 */
import { GpuRendererError, type GpuRendererErrorCode } from '../errors/gpu-renderer-error.ts';

export interface ResolvedResourcePolicy {
  readonly allowedOrigins: readonly string[];
  /**
   * The budget a load charges; shared by the loads one load starts (a scene file's glTF assets),
   * so that references cannot multiply it. Undefined: each load starts its own.
   */
  readonly budget?: DecodeBudget;
  /** A folder URL (ending in '/'), or undefined. */
  readonly root: URL | undefined;
  readonly maxResourceBytes: number;
  readonly maxDecodedBytes: number;
  readonly maxImageDimension: number;
  readonly fetchTimeoutMs: number;
  readonly decodeTimeoutMs: number;
}

/** Where a fault is reported: the loader's error code and the field naming the reference. */
export interface ResourceSite {
  code: GpuRendererErrorCode;
  field: string;
}

export function refuse(site: ResourceSite, message: string, cause?: unknown): never {
  throw new GpuRendererError(site.code, message, cause === undefined ? { field: site.field } : { field: site.field, cause });
}

const reachRefusals = new WeakSet<object>();

/**
 * A refusal of where a read would go (outside the asset's folder or the policy's root, through a
 * link out, an origin or scheme not allowed), as opposed to what a resource holds: callers that
 * confine loads (farm workers) tell the two apart with `isReachRefusal`.
 */
export function refuseReach(site: ResourceSite, message: string, cause?: unknown): never {
  const error = new GpuRendererError(site.code, message, cause === undefined ? { field: site.field } : { field: site.field, cause });
  reachRefusals.add(error);
  throw error;
}

/** Whether `error`, or an error it was caused by, is a `refuseReach` refusal. */
export function isReachRefusal(error: unknown): boolean {
  for (let e = error, depth = 0; typeof e === 'object' && e !== null && depth < 8; e = (e as { cause?: unknown }).cause, depth++) {
    if (reachRefusals.has(e)) return true;
  }
  return false;
}

function formatBytes(n: number): string {
  if (n >= 2 ** 30) return `${(n / 2 ** 30).toFixed(1)} GiB`;
  if (n >= 2 ** 20) return `${(n / 2 ** 20).toFixed(1)} MiB`;
  return `${n} bytes`;
}

/**
 * The decoded-bytes budget of one load (`resourcePolicy.maxDecodedBytes`): every allocation the
 * asset's numbers decide (resources read, accessor arrays, image texels, map texels) is charged
 * before it is made, and a charge over the budget is a typed error at the site that asked.
 */
export class DecodeBudget {
  private used = 0;
  readonly limit: number;

  constructor(limit: number) {
    this.limit = limit;
  }

  get spent(): number {
    return this.used;
  }

  charge(bytes: number, site: ResourceSite, what: string): void {
    if (!(bytes >= 0) || this.used + bytes > this.limit) {
      const need = Number.isFinite(bytes) ? formatBytes(bytes) : String(bytes);
      refuse(site, `${what} need ${need}, which would bring this load to ${formatBytes(this.used + bytes)}, over its budget of ${formatBytes(this.limit)} (resourcePolicy.maxDecodedBytes)`);
    }
    this.used += bytes;
  }
}
