// Pointer input for the orbit camera: drag to orbit, shift-drag or right-drag to pan, wheel to
// zoom, double-click to return to the scene's camera. Each change calls `onChange` once per event.
import type { OrbitCamera } from './orbit-camera.ts';

export function attachOrbitControls(element: HTMLElement, camera: () => OrbitCamera, onChange: () => void, onReset: () => void): () => void {
  let drag: { id: number; x: number; y: number; pan: boolean } | null = null;
  const down = (e: PointerEvent): void => {
    if (drag) return;
    drag = { id: e.pointerId, x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 };
    element.setPointerCapture(e.pointerId);
    e.preventDefault();
  };
  const move = (e: PointerEvent): void => {
    if (!drag || e.pointerId !== drag.id) return;
    const height = Math.max(element.clientHeight, 1);
    const dx = (e.clientX - drag.x) / height;
    const dy = (e.clientY - drag.y) / height;
    drag.x = e.clientX;
    drag.y = e.clientY;
    if (dx === 0 && dy === 0) return;
    if (drag.pan) camera().pan(dx, dy);
    else camera().rotate(-dx * Math.PI, dy * Math.PI);
    onChange();
  };
  const up = (e: PointerEvent): void => {
    if (drag?.id !== e.pointerId) return;
    drag = null;
    element.releasePointerCapture(e.pointerId);
  };
  const wheel = (e: WheelEvent): void => {
    e.preventDefault();
    camera().zoom(Math.exp(e.deltaY * 0.001));
    onChange();
  };
  const menu = (e: Event): void => e.preventDefault();
  element.addEventListener('pointerdown', down);
  element.addEventListener('pointermove', move);
  element.addEventListener('pointerup', up);
  element.addEventListener('pointercancel', up);
  element.addEventListener('wheel', wheel, { passive: false });
  element.addEventListener('contextmenu', menu);
  element.addEventListener('dblclick', onReset);
  return () => {
    element.removeEventListener('pointerdown', down);
    element.removeEventListener('pointermove', move);
    element.removeEventListener('pointerup', up);
    element.removeEventListener('pointercancel', up);
    element.removeEventListener('wheel', wheel);
    element.removeEventListener('contextmenu', menu);
    element.removeEventListener('dblclick', onReset);
  };
}
