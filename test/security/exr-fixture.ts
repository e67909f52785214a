// A single-part scanline OpenEXR writer for tests (OpenEXR file layout: magic, version, header
// attributes, offset table, one uncompressed float chunk per scanline; channels B, G, R).

/** `rgba`: width x height texels, row 0 at the top; alpha is not written. */
export function scanlineExr(width: number, height: number, rgba: Float32Array): Uint8Array {
  const out: number[] = [];
  const u8 = (...v: number[]): void => void out.push(...v);
  const i32 = (v: number): void => u8(v & 0xff, (v >> 8) & 0xff, (v >> 16) & 0xff, (v >>> 24) & 0xff);
  const f32 = (v: number): void => u8(...new Uint8Array(new Float32Array([v]).buffer));
  const str = (s: string): void => u8(...new TextEncoder().encode(s), 0);
  const attr = (name: string, type: string, size: number, write: () => void): void => {
    str(name);
    str(type);
    i32(size);
    write();
  };
  const channels = ['B', 'G', 'R'];
  u8(0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0);
  attr('channels', 'chlist', channels.length * 18 + 1, () => {
    for (const c of channels) {
      str(c);
      i32(2);
      u8(0, 0, 0, 0);
      i32(1);
      i32(1);
    }
    u8(0);
  });
  attr('compression', 'compression', 1, () => u8(0));
  attr('dataWindow', 'box2i', 16, () => [0, 0, width - 1, height - 1].forEach(i32));
  attr('displayWindow', 'box2i', 16, () => [0, 0, width - 1, height - 1].forEach(i32));
  attr('lineOrder', 'lineOrder', 1, () => u8(0));
  attr('pixelAspectRatio', 'float', 4, () => f32(1));
  attr('screenWindowCenter', 'v2f', 8, () => (f32(0), f32(0)));
  attr('screenWindowWidth', 'float', 4, () => f32(1));
  u8(0);
  const tableAt = out.length;
  for (let k = 0; k < height * 8; k++) u8(0);
  const offsets: number[] = [];
  for (let y = 0; y < height; y++) {
    offsets.push(out.length);
    i32(y);
    i32(channels.length * width * 4);
    for (const c of [2, 1, 0]) for (let x = 0; x < width; x++) f32(rgba[4 * (y * width + x) + c]!);
  }
  const bytes = new Uint8Array(out);
  const table = new DataView(bytes.buffer, tableAt, height * 8);
  offsets.forEach((offset, k) => table.setBigUint64(8 * k, BigInt(offset), true));
  return bytes;
}
