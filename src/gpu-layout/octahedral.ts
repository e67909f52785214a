/**
 * Octahedral unit-vector encoding in two snorm16 values (Cigolle et al., "A Survey of Efficient
 * Representations for Independent Unit Vectors", JCGT 3(2), 2014), bit-compatible with WGSL's
 * pack2x16snorm/unpack2x16snorm.
 */
export function encodeOctahedralSnorm16(n: readonly number[]): number {
  const l1 = Math.abs(n[0]!) + Math.abs(n[1]!) + Math.abs(n[2]!);
  if (!(l1 > 0)) return 0;
  let x = n[0]! / l1;
  let y = n[1]! / l1;
  if (n[2]! < 0) {
    const ox = x;
    x = (1 - Math.abs(y)) * (ox >= 0 ? 1 : -1);
    y = (1 - Math.abs(ox)) * (y >= 0 ? 1 : -1);
  }
  const q = (v: number): number => Math.round(Math.min(1, Math.max(-1, v)) * 32767) & 0xffff;
  return (q(x) | (q(y) << 16)) >>> 0;
}

export function decodeOctahedralSnorm16(bits: number): [number, number, number] {
  const s = (v: number): number => Math.max(((v << 16) >> 16) / 32767, -1);
  const x = s(bits & 0xffff);
  const y = s(bits >>> 16);
  let nx = x, ny = y;
  const nz = 1 - Math.abs(x) - Math.abs(y);
  const t = Math.max(-nz, 0);
  nx += nx >= 0 ? -t : t;
  ny += ny >= 0 ? -t : t;
  const len = Math.hypot(nx, ny, nz);
  return len > 0 ? [nx / len, ny / len, nz / len] : [0, 0, 1];
}
