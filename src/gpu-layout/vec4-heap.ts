import { writeStruct, type StructLayout, type StructValues } from './struct-layout.ts';

/**
 * A growable heap of 16-byte cells holding records of different layouts (material cores,
 * extension blocks, texture bindings, texture infos). Offsets are in vec4 units, as the generated
 * WGSL loaders (`load_<record>(offset)`) expect.
 */
export class Vec4Heap {
  private bytes = new ArrayBuffer(1024);
  private cells = 0;

  /** Vec4 cells used so far (the offset the next record gets). */
  get size(): number {
    return this.cells;
  }

  /** Reserves room for `layout` and returns its offset; write it later with `write`. */
  reserve(layout: StructLayout): number {
    if (layout.size % 16 !== 0) throw new Error(`${layout.name} (${layout.size} bytes) cannot live in a vec4 heap`);
    const offset = this.cells;
    this.cells += layout.size / 16;
    this.grow(this.cells * 16);
    return offset;
  }

  write(layout: StructLayout, offset: number, values: StructValues): void {
    writeStruct(layout, new DataView(this.bytes, offset * 16, layout.size), 0, values);
  }

  append(layout: StructLayout, values: StructValues): number {
    const offset = this.reserve(layout);
    this.write(layout, offset, values);
    return offset;
  }

  private grow(needed: number): void {
    if (needed <= this.bytes.byteLength) return;
    let capacity = this.bytes.byteLength;
    while (capacity < needed) capacity *= 2;
    const next = new ArrayBuffer(capacity);
    new Uint8Array(next).set(new Uint8Array(this.bytes));
    this.bytes = next;
  }

  /** The heap's contents (at least one cell, since WebGPU bindings cannot be empty). */
  finish(): ArrayBuffer {
    return this.bytes.slice(0, Math.max(1, this.cells) * 16);
  }
}
