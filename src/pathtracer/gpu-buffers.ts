import { BufferUsage } from '../gpu/webgpu-constants.ts';

/** Tracks the buffers a renderer owns so memory is reported and everything is released once. */
export class GpuBufferSet {
  readonly device: GPUDevice;
  private readonly buffers: { buffer: GPUBuffer; category: 'scene' | 'queue' | 'frame' }[] = [];

  constructor(device: GPUDevice) {
    this.device = device;
  }

  create(label: string, size: number, usage: number, category: 'scene' | 'queue' | 'frame'): GPUBuffer {
    const buffer = this.device.createBuffer({ label, size: Math.max(16, Math.ceil(size / 4) * 4), usage });
    this.buffers.push({ buffer, category });
    return buffer;
  }

  upload(label: string, data: ArrayBuffer, usage: number, category: 'scene' | 'queue' | 'frame'): GPUBuffer {
    const buffer = this.create(label, data.byteLength, usage | BufferUsage.COPY_DST, category);
    this.device.queue.writeBuffer(buffer, 0, data);
    return buffer;
  }

  /** Destroys `buffer` and stops counting it (work already submitted keeps it until that work is done). */
  release(buffer: GPUBuffer): void {
    const at = this.buffers.findIndex((b) => b.buffer === buffer);
    if (at >= 0) this.buffers.splice(at, 1);
    buffer.destroy();
  }

  /** Destroys `old` and creates its successor of `size` bytes (a buffer that had to grow). */
  replace(old: GPUBuffer, label: string, size: number, usage: number, category: 'scene' | 'queue' | 'frame'): GPUBuffer {
    this.release(old);
    return this.create(label, size, usage, category);
  }

  bytes(category: 'scene' | 'queue' | 'frame'): number {
    return this.buffers.filter((b) => b.category === category).reduce((n, b) => n + b.buffer.size, 0);
  }

  destroy(): void {
    for (const { buffer } of this.buffers) buffer.destroy();
    this.buffers.length = 0;
  }
}

export { readGpuBuffer } from '../gpu/read-buffer.ts';
