/**
 * Typed errors raised at the public boundary. Every error names a machine-readable `code` and, when
 * the fault lies in caller input, the offending `field` (a dotted path such as
 * `meshes[2].positions[7]`), so callers can react without parsing messages.
 */
export type GpuRendererErrorCode =
  | 'INVALID_OPTION'
  | 'INVALID_MESH'
  | 'INVALID_SCENE_OBJECT'
  | 'INVALID_MATERIAL'
  | 'INVALID_TEXTURE'
  | 'INVALID_INSTANCE'
  | 'INVALID_SCENE_FILE'
  /** glTF animation data: channels, samplers, keyframes, clip bindings. */
  | 'INVALID_ANIMATION'
  /** A model that cannot be animated or drawn as asked: skins, joints, weights, required attributes or textures. */
  | 'INVALID_MODEL'
  /** A glTF 2.0 asset the loader rejects; `field` is a JSON pointer into the asset (`/accessors/7`). */
  | 'INVALID_GLTF'
  | 'SCENE_TOO_LARGE'
  | 'WEBGPU_UNAVAILABLE'
  | 'DEVICE_LOST'
  | 'RENDERER_DESTROYED'
  | 'SHADER_COMPILATION_FAILED'
  | 'GPU_VALIDATION_FAILED'
  /** The GPU BVH build or refit reported a failure (accelerationBuildMode 'gpu', updateGeometry). */
  | 'ACCELERATION_BUILD_FAILED'
  | 'INVALID_CANVAS'
  | 'INVALID_STATE'
  /** An environment map, environment file, sky description or portal that cannot be used. */
  | 'INVALID_ENVIRONMENT'
  /** A punctual or area light with missing, non-finite or out-of-range parameters. */
  | 'INVALID_LIGHT'
  /** A feature flag asking for a transport that would add bias (this renderer is unbiased by construction). */
  | 'BIASED_TRANSPORT_REFUSED'
  /** The render farm's job queue (Redis) cannot be reached; `field` names where its address came from. */
  | 'QUEUE_UNAVAILABLE'
  /**
   * A render farm job a worker will not run: its data breaks the frame schema, or a path it names
   * (scene, environment map, output) resolves outside the worker's roots; `field` names the job's field.
   */
  | 'FARM_JOB_REFUSED';

export class GpuRendererError extends Error {
  readonly code: GpuRendererErrorCode;
  readonly field: string | undefined;

  constructor(code: GpuRendererErrorCode, message: string, options: { field?: string; cause?: unknown } = {}) {
    super(options.field ? `${options.field}: ${message}` : message, options.cause === undefined ? undefined : { cause: options.cause });
    this.name = 'GpuRendererError';
    this.code = code;
    this.field = options.field;
  }
}

export function isGpuRendererError(value: unknown): value is GpuRendererError {
  return value instanceof GpuRendererError;
}
