// An orbit camera: the eye on a sphere around a target (yaw about +y, pitch above the horizon,
// distance), plus panning of the target and zoom. Pure math, no DOM; orbit-controls.ts feeds it
// pointer input. The renderer takes the result as a WavefrontCameraInput (position/target/up).
import type { WavefrontCameraInput } from '@plasius/gpu-renderer';

type Vec3 = [number, number, number];

const maxPitch = (89 * Math.PI) / 180;

export interface OrbitState {
  target: Vec3;
  yaw: number;
  pitch: number;
  distance: number;
}

const sub = (a: readonly number[], b: readonly number[]): Vec3 => [a[0]! - b[0]!, a[1]! - b[1]!, a[2]! - b[2]!];
const length = (v: Vec3): number => Math.hypot(v[0], v[1], v[2]);

export class OrbitCamera {
  private state: OrbitState;
  /** The camera as given (projection, up), which orbiting keeps apart from position and target. */
  private base: WavefrontCameraInput;
  /** True until the user moves the camera: until then the scene's own camera is used verbatim. */
  private pristine = true;

  constructor(camera: WavefrontCameraInput) {
    this.base = camera;
    this.state = OrbitCamera.stateOf(camera);
  }

  static stateOf(camera: WavefrontCameraInput): OrbitState {
    const offset = sub(camera.position, camera.target);
    const distance = Math.max(length(offset), 1e-6);
    return {
      target: [camera.target[0]!, camera.target[1]!, camera.target[2]!],
      yaw: Math.atan2(offset[0], offset[2]),
      pitch: Math.asin(Math.max(-1, Math.min(1, offset[1] / distance))),
      distance,
    };
  }

  get orbit(): Readonly<OrbitState> {
    return this.state;
  }

  /** Rotates by yaw and pitch increments in radians (pitch kept short of the poles). */
  rotate(deltaYaw: number, deltaPitch: number): void {
    this.pristine = false;
    this.state.yaw += deltaYaw;
    this.state.pitch = Math.max(-maxPitch, Math.min(maxPitch, this.state.pitch + deltaPitch));
  }

  /** Moves the eye towards (factor < 1) or away from (factor > 1) the target. */
  zoom(factor: number): void {
    if (!(factor > 0) || !Number.isFinite(factor)) return;
    this.pristine = false;
    this.state.distance *= factor;
  }

  /** Moves the target in the view plane by fractions of the view height at the target. */
  pan(dx: number, dy: number): void {
    this.pristine = false;
    const { right, up } = this.basis();
    const scale = this.viewHeightAtTarget();
    for (let i = 0; i < 3; i++) this.state.target[i] += (-dx * right[i]! + dy * up[i]!) * scale;
  }

  /** The camera for the renderer. */
  camera(): WavefrontCameraInput {
    if (this.pristine) return this.base;
    const { target, yaw, pitch, distance } = this.state;
    const position: Vec3 = [
      target[0] + distance * Math.cos(pitch) * Math.sin(yaw),
      target[1] + distance * Math.sin(pitch),
      target[2] + distance * Math.cos(pitch) * Math.cos(yaw),
    ];
    const camera: WavefrontCameraInput = { ...this.base, position, target: [...target], up: [0, 1, 0] };
    if (camera.type === 'orthographic') {
      // Zooming an orthographic camera scales its view volume instead of moving it.
      const initial = OrbitCamera.stateOf(this.base).distance;
      camera.orthographicHeight = (this.base.orthographicHeight ?? 2) * (distance / initial);
    }
    return camera;
  }

  private basis(): { right: Vec3; up: Vec3 } {
    const { yaw, pitch } = this.state;
    const right: Vec3 = [Math.cos(yaw), 0, -Math.sin(yaw)];
    const up: Vec3 = [-Math.sin(pitch) * Math.sin(yaw), Math.cos(pitch), -Math.sin(pitch) * Math.cos(yaw)];
    return { right, up };
  }

  private viewHeightAtTarget(): number {
    if (this.base.type === 'orthographic') return (this.base.orthographicHeight ?? 2) * (this.state.distance / OrbitCamera.stateOf(this.base).distance);
    const fov = ((this.base.fovYDegrees ?? 45) * Math.PI) / 180;
    return 2 * this.state.distance * Math.tan(fov / 2);
  }
}
