/**
 * Cameras placed from a scene's bounds: `frameBounds` looks at the centre of an axis-aligned box
 * from an orbit direction (azimuth about +Y, elevation above the horizontal plane) at the nearest
 * distance where the whole box is in view; `sceneBounds` measures a scene description's world box.
 * The glTF loader frames assets without a camera with it, the CLI's --orbit and the turntable
 * sequences build on it.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { Vec3Input, WavefrontCameraInput, WavefrontSceneDescription } from './types.ts';

/** An axis-aligned box in world space. */
export interface SceneBounds {
  min: [number, number, number];
  max: [number, number, number];
}

export interface FrameBoundsOptions {
  /**
   * Degrees about +Y, from +Z towards +X: 0 looks at the front of a glTF asset (its +Z side),
   * 90 at its +X side. Default 30 (a three-quarter view).
   */
  azimuthDegrees?: number;
  /** Degrees above the horizontal plane, -90..90 (90 looks straight down). Default 25. */
  elevationDegrees?: number;
  /** Vertical field of view in degrees, in (0, 179]. Default 45. */
  fovYDegrees?: number;
  /** Image width / height: the box must fit the horizontal field of view too. Default 1. */
  aspectRatio?: number;
  /**
   * Distance from the box centre to the eye. Default: fitted, the nearest distance at which all
   * eight corners of the box project inside the image less `margin`.
   */
  distance?: number;
  /**
   * 'box' (default) fits the eight corners seen from this direction; 'sphere' fits the box's
   * bounding sphere, a distance that does not change with the direction (turntables).
   */
  fit?: 'box' | 'sphere';
  /** Share of the half-image kept free around the fitted bounds, in [0, 0.5]. Default 0.05. */
  margin?: number;
}

export const defaultFraming = { azimuthDegrees: 30, elevationDegrees: 25, fovYDegrees: 45 } as const;

const DEG = Math.PI / 180;

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

function finiteIn(value: number | undefined, fallback: number, field: string, min: number, max: number, open = false): number {
  const v = value ?? fallback;
  if (typeof v !== 'number' || !Number.isFinite(v) || (open ? v <= min || v >= max : v < min || v > max)) {
    invalid(field, `expected a finite number ${open ? 'in' : 'within'} ${open ? '(' : '['}${min}, ${max}${open ? ')' : ']'}, got ${String(v)}`);
  }
  return v;
}

/**
 * Orbit frame of a direction: `toEye` points from the target to the eye, `right` and `up` span the
 * image plane. `up` is the derivative of `toEye` by elevation, so it stays defined looking straight
 * down or up.
 */
function orbitFrame(azimuth: number, elevation: number): { toEye: number[]; right: number[]; up: number[] } {
  const [sa, ca, se, ce] = [Math.sin(azimuth), Math.cos(azimuth), Math.sin(elevation), Math.cos(elevation)];
  return { toEye: [sa * ce, se, ca * ce], right: [ca, 0, -sa], up: [-sa * se, ce, -ca * se] };
}

const dot = (a: readonly number[], b: readonly number[]): number => a[0]! * b[0]! + a[1]! * b[1]! + a[2]! * b[2]!;

/**
 * A perspective camera looking at the centre of `bounds` from the orbit direction of `options`.
 * Without bounds (an empty scene) it frames the unit sphere at the origin.
 */
export function frameBounds(bounds: SceneBounds | undefined, options: FrameBoundsOptions = {}): WavefrontCameraInput {
  const azimuth = finiteIn(options.azimuthDegrees, defaultFraming.azimuthDegrees, 'azimuthDegrees', -1e6, 1e6) * DEG;
  const elevation = finiteIn(options.elevationDegrees, defaultFraming.elevationDegrees, 'elevationDegrees', -90, 90) * DEG;
  const fovY = finiteIn(options.fovYDegrees, defaultFraming.fovYDegrees, 'fovYDegrees', 0, 179);
  if (fovY === 0) invalid('fovYDegrees', 'must be > 0');
  const aspect = finiteIn(options.aspectRatio, 1, 'aspectRatio', 0, Infinity, true);
  const margin = finiteIn(options.margin, 0.05, 'margin', 0, 0.5);
  const fit = options.fit ?? 'box';
  if (fit !== 'box' && fit !== 'sphere') invalid('fit', `expected "box" or "sphere", got ${String(fit)}`);
  const min = bounds?.min ?? [-1, -1, -1];
  const max = bounds?.max ?? [1, 1, 1];
  if (![...min, ...max].every(Number.isFinite) || min.some((v, i) => v > max[i]!)) invalid('bounds', 'expected finite bounds with min <= max');
  const center = min.map((v, i) => (v + max[i]!) / 2);
  const { toEye, right, up } = orbitFrame(azimuth, elevation);
  const tanY = Math.tan((fovY * DEG) / 2) * (1 - margin);
  const tanX = tanY * aspect;
  // The eye stays at least a thousandth of the box diagonal in front of every corner; a point box
  // still gets a distance (a thousandth of its largest coordinate, or 1e-3).
  const diagonal = Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
  const floor = 1e-3 * (diagonal > 0 ? diagonal : Math.max(1, ...center.map(Math.abs)));
  let distance: number;
  if (options.distance !== undefined) {
    distance = finiteIn(options.distance, 0, 'distance', 0, Infinity, true);
  } else if (fit === 'sphere') {
    // The sphere's silhouette cone of half-angle asin(r / d) must fit the narrower half-field.
    distance = Math.max(floor, diagonal / 2 / Math.sin(Math.atan(Math.min(tanX, tanY))));
  } else {
    // Each corner at depth d - z in front of the eye (z along toEye) needs |x| <= (d - z) tanX and
    // |y| <= (d - z) tanY: d >= z + |x| / tanX and d >= z + |y| / tanY.
    distance = floor;
    for (let c = 0; c < 8; c++) {
      const p = [c & 1 ? max[0] : min[0], c & 2 ? max[1] : min[1], c & 4 ? max[2] : min[2]].map((v, i) => v - center[i]!);
      const z = dot(p, toEye);
      distance = Math.max(distance, z + Math.abs(dot(p, right)) / tanX, z + Math.abs(dot(p, up)) / tanY, z + floor);
    }
  }
  const position = center.map((v, i) => v + distance * toEye[i]!);
  // `+ 0` turns -0 into 0 (sin(0) * -x) so equal views compare equal.
  return { type: 'perspective', position, target: center, up: up.map((v) => v + 0), fovYDegrees: fovY };
}

/** `frameBounds` options for an orbit of the bounds centre: the CLI's `--orbit azimuth,elevation[,distance]`. */
export function orbitCamera(bounds: SceneBounds | undefined, orbit: { azimuthDegrees: number; elevationDegrees: number; distance?: number }, options: Omit<FrameBoundsOptions, 'azimuthDegrees' | 'elevationDegrees' | 'distance'> = {}): WavefrontCameraInput {
  return frameBounds(bounds, { ...options, ...orbit });
}

/**
 * A camera at `position` looking at `target` (default the bounds centre) with +Y up, or -Z / +Z
 * up when looking straight down / up, where +Y is no usable up direction.
 */
export function lookAtCamera(position: Vec3Input, target: Vec3Input, fovYDegrees: number = defaultFraming.fovYDegrees): WavefrontCameraInput {
  const forward = [0, 1, 2].map((i) => Number(target[i]) - Number(position[i]));
  const length = Math.hypot(...forward);
  if (!(length > 0)) invalid('target', 'the camera position and target coincide');
  const vertical = Math.abs(forward[1]!) / length > 0.9999;
  const up = vertical ? [0, 0, forward[1]! < 0 ? -1 : 1] : [0, 1, 0];
  return { type: 'perspective', position: [...position], target: [...target], up, fovYDegrees };
}

function growByBox(out: SceneBounds, min: readonly number[], max: readonly number[], transform?: ArrayLike<number>): void {
  for (let c = 0; c < 8; c++) {
    const p = [c & 1 ? max[0]! : min[0]!, c & 2 ? max[1]! : min[1]!, c & 4 ? max[2]! : min[2]!];
    const q = transform === undefined ? p : [0, 1, 2].map((r) => transform[r]! * p[0]! + transform[4 + r]! * p[1]! + transform[8 + r]! * p[2]! + transform[12 + r]!);
    for (let a = 0; a < 3; a++) {
      out.min[a] = Math.min(out.min[a]!, q[a]!);
      out.max[a] = Math.max(out.max[a]!, q[a]!);
    }
  }
}

/**
 * World bounds of what a scene description draws: every mesh instance (each mesh once at the
 * identity when the scene lists no instances) and every analytic scene object. Undefined when it
 * draws nothing. Instance transforms are column-major 4x4 (WavefrontInstanceInput).
 */
export function sceneBounds(scene: Pick<WavefrontSceneDescription, 'meshes' | 'instances' | 'sceneObjects'>): SceneBounds | undefined {
  const out: SceneBounds = { min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity] };
  const meshes = scene.meshes ?? [];
  const local = meshes.map((mesh) => {
    const min = [Infinity, Infinity, Infinity];
    const max = [-Infinity, -Infinity, -Infinity];
    const p = mesh.positions;
    for (let i = 0; i + 2 < p.length; i += 3) {
      for (let a = 0; a < 3; a++) {
        const v = Number(p[i + a]);
        if (v < min[a]!) min[a] = v;
        if (v > max[a]!) max[a] = v;
      }
    }
    return p.length >= 3 ? { min, max } : undefined;
  });
  if (scene.instances === undefined) {
    for (const box of local) if (box) growByBox(out, box.min, box.max);
  } else {
    for (const instance of scene.instances) {
      const box = typeof instance.mesh === 'number' ? local[instance.mesh] : undefined;
      if (box) growByBox(out, box.min, box.max, instance.transform);
    }
  }
  for (const object of scene.sceneObjects ?? []) {
    if (object.center !== undefined && object.radius !== undefined) {
      const c = object.center.map(Number);
      const r = Number(object.radius);
      growByBox(out, [c[0]! - r, c[1]! - r, c[2]! - r], [c[0]! + r, c[1]! + r, c[2]! + r]);
    } else if (object.min !== undefined && object.max !== undefined) {
      growByBox(out, object.min.map(Number), object.max.map(Number));
    }
  }
  return out.min.every(Number.isFinite) && out.max.every(Number.isFinite) ? out : undefined;
}
