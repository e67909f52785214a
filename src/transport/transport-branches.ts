import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { requireNumberInRange } from '../errors/validate.ts';
import { dielectricInterface } from './fresnel.ts';
import { isMediumStack, type MediumStack } from './medium-stack.ts';

/**
 * Reference split of a path at a dielectric boundary into at most two continuations, the bound the
 * GPU wavefront honours. Weights follow the exact dielectric Fresnel term (./fresnel.ts, shared with src/materials):
 *  - reflected:   F
 *  - transmitted: transmission * (1 - F)   (KHR_materials_transmission: the fraction of the light
 *    not reflected by the specular layer that passes through instead of reaching the diffuse base)
 *  - the remainder (1 - transmission) * (1 - F) belongs to the opaque base BRDF, not a branch.
 * With transmission = 1 the interface is lossless and the two weights sum to 1.
 */
export interface TransportBranchOptions {
  /** The ray's medium stack before the hit. */
  mediumStack: MediumStack;
  /** Medium enclosed by the hit surface. The ray exits it when it is innermost on the stack. */
  mediumId: number;
  /** KHR_materials_transmission `transmissionFactor`, [0, 1]. */
  transmission: number;
  /** KHR_materials_ior `ior` of the enclosed medium relative to its surroundings, >= 1. */
  ior: number;
  /** Cosine between the incident direction (reversed) and the surface normal on the incident side, [0, 1]; default 1. */
  cosTheta?: number;
}

export interface TransportBranch {
  readonly kind: 'reflection' | 'transmission';
  /** Energy fraction this continuation carries (multiplies path throughput). */
  readonly weight: number;
  /** Medium stack the continuation travels in. */
  readonly mediumStack: MediumStack;
  /** Innermost medium of the continuation (0 = none). */
  readonly mediumId: number;
  /** Cosine of the outgoing direction to the normal on its own side. */
  readonly cosTheta: number;
  /** The stack could not hold the entered medium (see medium-stack.ts). */
  readonly overflow: boolean;
  /** The exited medium was not innermost (see medium-stack.ts). */
  readonly mismatch: boolean;
}

export interface TransportBranches {
  /** True when the ray crosses into `mediumId`, false when it leaves it. */
  readonly entering: boolean;
  /** Relative IOR eta_t / eta_i of the crossing. */
  readonly eta: number;
  readonly fresnel: number;
  readonly totalInternalReflection: boolean;
  readonly reflected: TransportBranch;
  /** Null under total internal reflection or when transmission is 0. */
  readonly transmitted: TransportBranch | null;
  /** The reflected and (when present) transmitted continuations, at most two. */
  readonly branches: readonly TransportBranch[];
  /** Energy handed to the opaque base layer: (1 - transmission) * (1 - F). */
  readonly baseWeight: number;
}

export function createTransportBranches(options: TransportBranchOptions): TransportBranches {
  if (typeof options !== 'object' || options === null) throw new GpuRendererError('INVALID_OPTION', 'expected an options object', { field: 'options' });
  if (!isMediumStack(options.mediumStack)) {
    throw new GpuRendererError('INVALID_OPTION', 'expected a stack from createMediumStack', { field: 'mediumStack' });
  }
  const stack = options.mediumStack;
  const mediumId = requireNumberInRange(options.mediumId, 'mediumId', { min: 1, max: 0xffffffff });
  if (!Number.isInteger(mediumId)) throw new GpuRendererError('INVALID_OPTION', `expected an integer, got ${mediumId}`, { field: 'mediumId' });
  const transmission = requireNumberInRange(options.transmission, 'transmission', { min: 0, max: 1 });
  const ior = requireNumberInRange(options.ior, 'ior', { min: 1 });
  const cosTheta = requireNumberInRange(options.cosTheta ?? 1, 'cosTheta', { min: 0, max: 1 });

  const entering = stack.current !== mediumId;
  const eta = entering ? ior : 1 / ior;
  const fr = dielectricInterface(cosTheta, eta);
  const reflected: TransportBranch = Object.freeze({
    kind: 'reflection',
    weight: fr.reflectance,
    mediumStack: stack,
    mediumId: stack.current,
    cosTheta,
    overflow: false,
    mismatch: false,
  });
  let transmitted: TransportBranch | null = null;
  const transmittedWeight = transmission * (1 - fr.reflectance);
  if (!fr.totalInternalReflection && transmittedWeight > 0) {
    const next = entering ? stack.enter(mediumId) : stack.exit(mediumId);
    transmitted = Object.freeze({
      kind: 'transmission',
      weight: transmittedWeight,
      mediumStack: next.stack,
      mediumId: next.stack.current,
      cosTheta: fr.cosThetaT,
      overflow: next.overflow,
      mismatch: next.mismatch,
    });
  }
  return Object.freeze({
    entering,
    eta,
    fresnel: fr.reflectance,
    totalInternalReflection: fr.totalInternalReflection,
    reflected,
    transmitted,
    branches: Object.freeze(transmitted ? [reflected, transmitted] : [reflected]),
    baseWeight: (1 - transmission) * (1 - fr.reflectance),
  });
}
