// CPU reference silhouettes: the posed character's triangles (baked on the CPU by bakePose)
// projected with the camera and rasterised at pixel centres.
import { mat4d, vec3d } from 'wgpu-matrix';
import type { WavefrontSceneDescription } from '../../src/scene/types.ts';

/** Coverage mask of the meshes `meshIds` of a posed scene seen by its camera (perspective). */
export function cpuSilhouette(scene: WavefrontSceneDescription, instanceFilter: (meshIndex: number) => boolean, width: number, height: number): Uint8Array {
  const cam = scene.camera!;
  const view = mat4d.lookAt(cam.position, cam.target, cam.up ?? [0, 1, 0]);
  const proj = mat4d.perspective(((cam.fovYDegrees ?? 45) * Math.PI) / 180, width / height, 0.01, 1000);
  const viewProj = mat4d.multiply(proj, view);
  const mask = new Uint8Array(width * height);
  for (const inst of scene.instances ?? []) {
    if (!instanceFilter(inst.mesh)) continue;
    const mesh = scene.meshes![inst.mesh]!;
    const m = mat4d.multiply(viewProj, inst.transform ?? mat4d.identity());
    const p = mesh.positions;
    const screen: number[][] = [];
    for (let v = 0; v < p.length / 3; v++) {
      const c = vec3d.transformMat4([p[3 * v]!, p[3 * v + 1]!, p[3 * v + 2]!], m);
      screen.push([((c[0]! + 1) / 2) * width, ((1 - c[1]!) / 2) * height]);
    }
    const idx = mesh.indices ?? Array.from({ length: p.length / 3 }, (_, i) => i);
    for (let t = 0; t < idx.length; t += 3) {
      const [a, b, c] = [screen[idx[t]!]!, screen[idx[t + 1]!]!, screen[idx[t + 2]!]!];
      const x0 = Math.max(0, Math.floor(Math.min(a[0]!, b[0]!, c[0]!)));
      const x1 = Math.min(width - 1, Math.ceil(Math.max(a[0]!, b[0]!, c[0]!)));
      const y0 = Math.max(0, Math.floor(Math.min(a[1]!, b[1]!, c[1]!)));
      const y1 = Math.min(height - 1, Math.ceil(Math.max(a[1]!, b[1]!, c[1]!)));
      const edge = (u: number[], w: number[], x: number, y: number): number => (w[0]! - u[0]!) * (y - u[1]!) - (w[1]! - u[1]!) * (x - u[0]!);
      for (let y = y0; y <= y1; y++) {
        for (let x = x0; x <= x1; x++) {
          const px = x + 0.5, py = y + 0.5;
          const e0 = edge(a, b, px, py), e1 = edge(b, c, px, py), e2 = edge(c, a, px, py);
          if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0)) mask[y * width + x] = 1;
        }
      }
    }
  }
  return mask;
}

/** Intersection over union of two masks, and the size of each. */
export function maskOverlap(a: Uint8Array, b: Uint8Array): { iou: number; a: number; b: number } {
  let inter = 0, union = 0, na = 0, nb = 0;
  for (let i = 0; i < a.length; i++) {
    if (a[i]) na++;
    if (b[i]) nb++;
    if (a[i] && b[i]) inter++;
    if (a[i] || b[i]) union++;
  }
  return { iou: union === 0 ? 1 : inter / union, a: na, b: nb };
}
