// What every view's single render loop needs: a sleep that a state change ends, a yield to the
// page between frames, and a GPU device acquired once and dropped when it is lost.
import { acquireGpuDevice } from '@plasius/gpu-renderer';

/** Resolves at the next animation frame: the page handles input between frames. */
export const nextFrame = (): Promise<void> => new Promise((resolve) => requestAnimationFrame(() => resolve()));

/** The loop's sleep: `sleep()` waits until `wake()` (a wake with nobody asleep is dropped). */
export class Wakeup {
  private resume: (() => void) | null = null;

  sleep(): Promise<void> {
    return new Promise<void>((resolve) => (this.resume = resolve));
  }

  wake(): void {
    const resume = this.resume;
    this.resume = null;
    resume?.();
  }
}

/** The view's GPU device: acquired on first use, forgotten when lost (`onLost` hears why). */
export class ViewDevice {
  private device: GPUDevice | null = null;
  private readonly onLost: (error: Error) => void;

  constructor(onLost: (error: Error) => void) {
    this.onLost = onLost;
  }

  async acquire(): Promise<GPUDevice> {
    if (this.device) return this.device;
    const device = (this.device = (await acquireGpuDevice()).device);
    void device.lost.then((info) => {
      if (this.device === device) this.device = null;
      if (info.reason !== 'destroyed') this.onLost(new Error(`GPU device lost: ${info.message}`));
    });
    return device;
  }

  destroy(): void {
    this.device?.destroy();
    this.device = null;
  }
}
