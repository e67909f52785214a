/**
 * The BVH build's hot loops as a small WebAssembly module with 128-bit SIMD, generated here as
 * bytes (no toolchain, no binary blob in the repository). WebAssembly 2.0 (core spec, sec. 5:
 * binary format) with fixed-width SIMD (v128), non-trapping float-to-int conversions and bulk
 * memory (memory.fill); every engine that runs WebGPU runs it, and where compiling fails the JS
 * loops take over (`compiledBvhWasm` returns null).
 *
 * Slot layout (shared with the JS loops in bvh-kernels.ts): 32 bytes per slot, two f32x4 vectors
 * (min x, y, z, 0) and (max x, y, z, 0); triangle ids in a separate u32 array. Bins: 32 bytes each
 * (min vector, max vector), `binStride` bins per axis; counts: i32, `binStride` per axis.
 *
 * Each function mirrors its JS twin operation for operation: the doubled centroid is the f32 sum
 * min + max (f32x4.add is lane-wise IEEE binary32 addition, as Math.fround(min + max)); the bin is
 * trunc(k * (f64(c) - m)) clamped to [0, bins - 1] in f64; min/max use pmin/pmax (`b < a ? b : a`,
 * the JS `if (v < cur) cur = v`). So both give the same bins, partitions and trees, bit for bit.
 */

// Opcodes (core spec sec. 5.4) and SIMD opcodes (0xFD prefix, LEB128 sub-opcodes).
const I32 = 0x7f, F64 = 0x7c, V128 = 0x7b;
const OP = {
  block: 0x02, loop: 0x03, if: 0x04, else: 0x05, end: 0x0b, br: 0x0c, brIf: 0x0d, return: 0x0f,
  localGet: 0x20, localSet: 0x21, localTee: 0x22,
  i32Load: 0x28, f32Load: 0x2a, i32Store: 0x36, f64Store: 0x39,
  i32Const: 0x41, f64Const: 0x44,
  i32Eqz: 0x45, i32Ne: 0x47, i32LtS: 0x48, i32GtS: 0x4a, i32LtU: 0x49, i32GeS: 0x4e, i32GeU: 0x4f, i32And: 0x71,
  f64Load: 0x2b, f64Lt: 0x63, f64Add: 0xa0, f64ConvertI32S: 0xb7,
  i32Add: 0x6a, i32Sub: 0x6b, i32Mul: 0x6c, i32Shl: 0x74, i32ShrU: 0x76,
  f32Add: 0x92, f64Sub: 0xa1, f64Mul: 0xa2, f64PromoteF32: 0xbb,
  select: 0x1b,
} as const;
const SIMD = {
  load: 0x00, store: 0x0b, const: 0x0c, i8x16Shuffle: 0x0d, f64x2Splat: 0x14, i32x4ExtractLane: 0x1b,
  f32x4ExtractLane: 0x1f, f64x2ReplaceLane: 0x22, f64x2PromoteLowF32x4: 0x5f, f32x4Add: 0xe4, f32x4Pmin: 0xea,
  f32x4Pmax: 0xeb, f64x2Sub: 0xf1, f64x2Mul: 0xf2, f64x2Pmin: 0xf6, f64x2Pmax: 0xf7, i32x4TruncSatF64x2SZero: 0xfc,
} as const;
const TRUNC_SAT_F64_S = 0x02; // 0xFC prefix

function uleb(value: number, out: number[]): void {
  let v = value >>> 0;
  do {
    let byte = v & 0x7f;
    v >>>= 7;
    if (v !== 0) byte |= 0x80;
    out.push(byte);
  } while (v !== 0);
}

function sleb(value: number, out: number[]): void {
  let v = value | 0;
  for (;;) {
    const byte = v & 0x7f;
    v >>= 7;
    if ((v === 0 && (byte & 0x40) === 0) || (v === -1 && (byte & 0x40) !== 0)) {
      out.push(byte);
      return;
    }
    out.push(byte | 0x80);
  }
}

/** Instruction emitter for one function body. */
class Code {
  readonly bytes: number[] = [];
  op(...codes: number[]): this {
    this.bytes.push(...codes);
    return this;
  }
  get(i: number): this {
    this.bytes.push(OP.localGet);
    uleb(i, this.bytes);
    return this;
  }
  set(i: number): this {
    this.bytes.push(OP.localSet);
    uleb(i, this.bytes);
    return this;
  }
  tee(i: number): this {
    this.bytes.push(OP.localTee);
    uleb(i, this.bytes);
    return this;
  }
  i32(v: number): this {
    this.bytes.push(OP.i32Const);
    sleb(v, this.bytes);
    return this;
  }
  f64(v: number): this {
    this.bytes.push(OP.f64Const);
    const b = new Uint8Array(new Float64Array([v]).buffer);
    this.bytes.push(...b);
    return this;
  }
  /** Memory access with alignment exponent `align` and constant `offset`. */
  mem(opcode: number, align: number, offset = 0): this {
    this.bytes.push(opcode);
    uleb(align, this.bytes);
    uleb(offset, this.bytes);
    return this;
  }
  simd(sub: number): this {
    this.bytes.push(0xfd);
    uleb(sub, this.bytes);
    return this;
  }
  vload(offset = 0): this {
    this.simd(SIMD.load);
    uleb(4, this.bytes);
    uleb(offset, this.bytes);
    return this;
  }
  vstore(offset = 0): this {
    this.simd(SIMD.store);
    uleb(4, this.bytes);
    uleb(offset, this.bytes);
    return this;
  }
  /** v128.const of four f32. */
  vconstF32(a: number, b: number, c: number, d: number): this {
    this.simd(SIMD.const);
    this.bytes.push(...new Uint8Array(new Float32Array([a, b, c, d]).buffer));
    return this;
  }
  lane(index: number): this {
    this.simd(SIMD.f32x4ExtractLane);
    this.bytes.push(index);
    return this;
  }
  truncSat(): this {
    this.bytes.push(0xfc);
    uleb(TRUNC_SAT_F64_S, this.bytes);
    return this;
  }
}

interface FunctionDef {
  name: string;
  params: number[];
  results: number[];
  /** Extra locals, in order after the params. */
  locals: number[];
  body: Code;
}

function encodeModule(functions: FunctionDef[], shared: boolean): Uint8Array {
  const out: number[] = [0x00, 0x61, 0x73, 0x6d, 0x01, 0x00, 0x00, 0x00];
  const section = (id: number, content: number[]): void => {
    out.push(id);
    uleb(content.length, out);
    out.push(...content);
  };
  const vec = (items: number[][]): number[] => {
    const v: number[] = [];
    uleb(items.length, v);
    for (const item of items) v.push(...item);
    return v;
  };
  const name = (s: string): number[] => {
    const bytes = [...new TextEncoder().encode(s)];
    const v: number[] = [];
    uleb(bytes.length, v);
    return [...v, ...bytes];
  };
  // 1 types (one per function), 2 imports (env.memory), 3 functions, 7 exports, 10 code.
  section(1, vec(functions.map((f) => [0x60, ...vec(f.params.map((t) => [t])), ...vec(f.results.map((t) => [t]))])));
  // Memory limits: min 1 page; a shared memory needs a maximum (the whole 4 GiB address space, so any
  // shared memory the caller makes fits).
  const limits: number[] = shared ? [0x03, 0x01] : [0x00, 0x01];
  if (shared) uleb(65536, limits);
  section(2, vec([[...name('env'), ...name('memory'), 0x02, ...limits]]));
  section(3, vec(functions.map((_, i) => { const v: number[] = []; uleb(i, v); return v; })));
  section(7, vec(functions.map((f, i) => { const v: number[] = [...name(f.name), 0x00]; uleb(i, v); return v; })));
  section(10, vec(functions.map((f) => {
    const body: number[] = [];
    // Locals, run-length encoded by type.
    const groups: Array<[number, number]> = [];
    for (const t of f.locals) {
      const g = groups[groups.length - 1];
      if (g && g[1] === t) g[0]++;
      else groups.push([1, t]);
    }
    uleb(groups.length, body);
    for (const [count, t] of groups) { uleb(count, body); body.push(t); }
    body.push(...f.body.bytes, OP.end);
    const sized: number[] = [];
    uleb(body.length, sized);
    return [...sized, ...body];
  })));
  return new Uint8Array(out);
}

/**
 * Pushes the clamped bin of f = (c - m) * k (f64 in local `f`): f >= last ? lastI : f > 0 ? trunc(f) : 0,
 * as the JS `f >= last ? last : f > 0 ? f | 0 : 0`.
 */
function binIndex(code: Code, f: number, last: number, lastI: number): void {
  code.get(lastI).get(f).truncSat().i32(0).get(f).f64(0).op(0x64 /* f64.gt */).op(OP.select)
    .get(f).get(last).op(0x66 /* f64.ge */).op(OP.select);
}

const INF = Infinity;

// f64 parameters come through memory, not arguments: a JS call passing doubles to WebAssembly may box
// each one, and the build makes hundreds of thousands of calls. Layout at `prm`: k0, k1, k2, m0, m1,
// m2, last bin (as f64), parent half area.

/** k and m of the axis whose byte offset in a slot (axis * 4) is in local `axisOff`, and `last`. */
function loadAxisParams(code: Code, prm: number, axisOff: number, k: number, m: number, last: number): void {
  code.get(prm).get(axisOff).i32(1).op(OP.i32Shl).op(OP.i32Add).mem(OP.f64Load, 3, 0).set(k);
  code.get(prm).get(axisOff).i32(1).op(OP.i32Shl).op(OP.i32Add).mem(OP.f64Load, 3, 24).set(m);
  code.get(prm).mem(OP.f64Load, 3, 48).set(last);
}

function binFunction(): FunctionDef {
  // (p, end, lastI, binBase, cntBase, binStride, prm): empties bins 0..lastI of each axis, then bins
  // every slot from address p to end on all three axes; prm: the f64 parameters. The three bin
  // indices come from f64x2 lanes (x, y) and (z, 0): trunc(min(max(f, 0), last)) with pmin/pmax
  // equals the scalar f >= last ? last : f > 0 ? trunc(f) : 0, NaN included (it gives 0).
  const [p, end, lastI, binBase, cntBase, binStride, prm] = [0, 1, 2, 3, 4, 5, 6];
  const [kxy, kz, mxy, mz, lastv, zero, qv] = [7, 8, 9, 10, 11, 12, 13];
  const [mn, mx, c, q, addr, b1, b2, n1, n2] = [14, 15, 16, 17, 18, 19, 20, 21, 22];
  const code = new Code();
  // (k0, k1), (k2, 0), (m0, m1), (m2, 0), (last, last), (0, 0).
  const pair = (lo: number, hi: number | null, into: number): void => {
    code.get(prm).mem(OP.f64Load, 3, lo * 8).simd(SIMD.f64x2Splat);
    if (hi === null) code.f64(0);
    else code.get(prm).mem(OP.f64Load, 3, hi * 8);
    code.simd(SIMD.f64x2ReplaceLane).op(1).set(into);
  };
  pair(0, 1, kxy);
  pair(2, null, kz);
  pair(3, 4, mxy);
  pair(5, null, mz);
  pair(6, 6, lastv);
  code.vconstF32(0, 0, 0, 0).set(zero);
  // Axis bases: bins at binBase + a * binStride * 32, counts at cntBase + a * binStride * 4.
  code.get(binBase).get(binStride).i32(5).op(OP.i32Shl).op(OP.i32Add).tee(b1)
    .get(binStride).i32(5).op(OP.i32Shl).op(OP.i32Add).set(b2);
  code.get(cntBase).get(binStride).i32(2).op(OP.i32Shl).op(OP.i32Add).tee(n1)
    .get(binStride).i32(2).op(OP.i32Shl).op(OP.i32Add).set(n2);
  // Empty the bins first: (min +inf, max -inf, count 0) for bins 0..lastI of each axis.
  for (const [base, cnt] of [[binBase, cntBase], [b1, n1], [b2, n2]] as const) {
    code.get(base).set(addr).get(lastI).i32(1).op(OP.i32Add).i32(5).op(OP.i32Shl).get(base).op(OP.i32Add).set(q);
    code.op(OP.loop, 0x40);
    code.get(addr).vconstF32(INF, INF, INF, INF).vstore(0).get(addr).vconstF32(-INF, -INF, -INF, -INF).vstore(16);
    code.get(addr).i32(32).op(OP.i32Add).tee(addr).get(q).op(OP.i32LtU).op(OP.brIf, 0);
    code.op(OP.end);
    // memory.fill(cnt, 0, (lastI + 1) * 4)
    code.get(cnt).i32(0).get(lastI).i32(1).op(OP.i32Add).i32(2).op(OP.i32Shl).op(0xfc, 0x0b, 0x00);
  }
  code.op(OP.block, 0x40).get(p).get(end).op(OP.i32GeU).op(OP.brIf, 0);
  code.op(OP.loop, 0x40);
  code.get(p).vload(0).set(mn).get(p).vload(16).set(mx).get(mn).get(mx).simd(SIMD.f32x4Add).set(c);
  // Bin indices: lanes 0, 1 of qv from (x, y), lanes 2, 3 from (z, 0).
  const clampedIndex = (lanes: () => void, k: number, m: number): void => {
    code.get(lastv).get(zero);
    lanes();
    code.simd(SIMD.f64x2PromoteLowF32x4).get(m).simd(SIMD.f64x2Sub).get(k).simd(SIMD.f64x2Mul)
      .simd(SIMD.f64x2Pmax).simd(SIMD.f64x2Pmin).simd(SIMD.i32x4TruncSatF64x2SZero);
  };
  clampedIndex(() => code.get(c), kxy, mxy);
  clampedIndex(() => code.get(c).get(c).simd(SIMD.i8x16Shuffle).op(8, 9, 10, 11, 12, 13, 14, 15, 8, 9, 10, 11, 12, 13, 14, 15), kz, mz);
  // (qx, qy, 0, 0) and (qz, 0, 0, 0) -> (qx, qy, qz, 0)
  code.simd(SIMD.i8x16Shuffle).op(0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23).set(qv);
  const axes: Array<[number, number]> = [[binBase, cntBase], [b1, n1], [b2, n2]];
  axes.forEach(([base, cnt], axis) => {
    code.get(qv).simd(SIMD.i32x4ExtractLane).op(axis).set(q);
    code.get(q).i32(5).op(OP.i32Shl).get(base).op(OP.i32Add).set(addr);
    code.get(addr).get(addr).vload(0).get(mn).simd(SIMD.f32x4Pmin).vstore(0);
    code.get(addr).get(addr).vload(16).get(mx).simd(SIMD.f32x4Pmax).vstore(16);
    code.get(q).i32(2).op(OP.i32Shl).get(cnt).op(OP.i32Add).tee(addr).get(addr).mem(OP.i32Load, 2).i32(1).op(OP.i32Add).mem(OP.i32Store, 2);
  });
  code.get(p).i32(32).op(OP.i32Add).tee(p).get(end).op(OP.i32LtU).op(OP.brIf, 0);
  code.op(OP.end, OP.end);
  return {
    name: 'bin', params: [I32, I32, I32, I32, I32, I32, I32], results: [],
    locals: [V128, V128, V128, V128, V128, V128, V128, V128, V128, V128, I32, I32, I32, I32, I32, I32], body: code,
  };
}

/** Pushes the clamped bin of the slot at address local `p` on the axis at byte offset local `axisOff`. */
function slotBin(code: Code, p: number, axisOff: number, k: number, m: number, last: number, lastI: number, a: number, f: number): void {
  code.get(p).get(axisOff).op(OP.i32Add).tee(a).mem(OP.f32Load, 2).get(a).mem(OP.f32Load, 2, 16).op(OP.f32Add)
    .op(OP.f64PromoteF32).get(m).op(OP.f64Sub).get(k).op(OP.f64Mul).set(f);
  binIndex(code, f, last, lastI);
}

/** Folds the slot vectors (mn, mx) and their sum c into a side's box (bmin, bmax) and centroid bounds (cmin, cmax). */
function accumulate(code: Code, mn: number, mx: number, c: number, bmin: number, bmax: number, cmin: number, cmax: number): void {
  code.get(bmin).get(mn).simd(SIMD.f32x4Pmin).set(bmin).get(bmax).get(mx).simd(SIMD.f32x4Pmax).set(bmax);
  code.get(cmin).get(c).simd(SIMD.f32x4Pmin).set(cmin).get(cmax).get(c).simd(SIMD.f32x4Pmax).set(cmax);
}

function partitionFunction(): FunctionDef {
  // (i, j, ii, ij, axisOff, lastI, plane, out, prm) -> left count. In-place Hoare partition of the
  // slots from address i to address j (the last slot; ids from ii to ij) by bin < plane, as
  // bvh-kernels' partitionInPlace: both sides' boxes and centroid bounds go to out (8 vectors:
  // left box min, max, left centroid min, max, then the right side's).
  const [i, j, ii, ij, axisOff, lastI, plane, out, prm] = [0, 1, 2, 3, 4, 5, 6, 7, 8];
  const [k, m, last, f] = [9, 10, 11, 12];
  const [mnI, mxI, cI, mnJ, mxJ, cJ, lbmin, lbmax, lcmin, lcmax, rbmin, rbmax, rcmin, rcmax] = [13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26];
  const [a, start, id] = [27, 28, 29];
  const code = new Code();
  loadAxisParams(code, prm, axisOff, k, m, last);
  code.get(i).set(start);
  code.vconstF32(INF, INF, INF, INF).tee(lbmin).tee(lcmin).tee(rbmin).set(rcmin);
  code.vconstF32(-INF, -INF, -INF, -INF).tee(lbmax).tee(lcmax).tee(rbmax).set(rcmax);
  code.op(OP.block, 0x40).op(OP.loop, 0x40); // $outer: block depth 1, loop depth 0
  // Advance i over left slots.
  code.op(OP.block, 0x40).op(OP.loop, 0x40);
  code.get(i).get(j).op(0x4b /* i32.gt_u */).op(OP.brIf, 1);
  code.get(i).vload(0).set(mnI).get(i).vload(16).set(mxI).get(mnI).get(mxI).simd(SIMD.f32x4Add).set(cI);
  slotBin(code, i, axisOff, k, m, last, lastI, a, f);
  code.get(plane).op(OP.i32GeS).op(OP.brIf, 1);
  accumulate(code, mnI, mxI, cI, lbmin, lbmax, lcmin, lcmax);
  code.get(i).i32(32).op(OP.i32Add).set(i).get(ii).i32(4).op(OP.i32Add).set(ii);
  code.op(OP.br, 0);
  code.op(OP.end, OP.end);
  // Retreat j over right slots.
  code.op(OP.block, 0x40).op(OP.loop, 0x40);
  code.get(i).get(j).op(0x4b /* i32.gt_u */).op(OP.brIf, 1);
  code.get(j).vload(0).set(mnJ).get(j).vload(16).set(mxJ).get(mnJ).get(mxJ).simd(SIMD.f32x4Add).set(cJ);
  slotBin(code, j, axisOff, k, m, last, lastI, a, f);
  code.get(plane).op(OP.i32LtS).op(OP.brIf, 1);
  accumulate(code, mnJ, mxJ, cJ, rbmin, rbmax, rcmin, rcmax);
  code.get(j).i32(32).op(OP.i32Sub).set(j).get(ij).i32(4).op(OP.i32Sub).set(ij);
  code.op(OP.br, 0);
  code.op(OP.end, OP.end);
  // Done when the cursors crossed; else swap the right slot at i with the left slot at j.
  code.get(i).get(j).op(OP.i32GeU).op(OP.brIf, 1);
  code.get(i).get(mnJ).vstore(0).get(i).get(mxJ).vstore(16).get(j).get(mnI).vstore(0).get(j).get(mxI).vstore(16);
  code.get(ii).mem(OP.i32Load, 2).set(id).get(ii).get(ij).mem(OP.i32Load, 2).mem(OP.i32Store, 2).get(ij).get(id).mem(OP.i32Store, 2);
  accumulate(code, mnJ, mxJ, cJ, lbmin, lbmax, lcmin, lcmax);
  accumulate(code, mnI, mxI, cI, rbmin, rbmax, rcmin, rcmax);
  code.get(i).i32(32).op(OP.i32Add).set(i).get(ii).i32(4).op(OP.i32Add).set(ii);
  code.get(j).i32(32).op(OP.i32Sub).set(j).get(ij).i32(4).op(OP.i32Sub).set(ij);
  code.op(OP.br, 0);
  code.op(OP.end, OP.end);
  code.get(out).get(lbmin).vstore(0).get(out).get(lbmax).vstore(16).get(out).get(lcmin).vstore(32).get(out).get(lcmax).vstore(48);
  code.get(out).get(rbmin).vstore(64).get(out).get(rbmax).vstore(80).get(out).get(rcmin).vstore(96).get(out).get(rcmax).vstore(112);
  code.get(i).get(start).op(OP.i32Sub).i32(5).op(OP.i32ShrU);
  return {
    name: 'partition', params: [I32, I32, I32, I32, I32, I32, I32, I32, I32], results: [I32],
    locals: [F64, F64, F64, F64, V128, V128, V128, V128, V128, V128, V128, V128, V128, V128, V128, V128, V128, V128, I32, I32, I32], body: code,
  };
}

function scanFunction(): FunctionDef {
  // (p, end, out): AABB min, max and doubled-centroid min, max of slots [p, end) as four vectors.
  const [p, end, out] = [0, 1, 2];
  const [mn, mx, c, bmin, bmax, cmin, cmax] = [3, 4, 5, 6, 7, 8, 9];
  const code = new Code();
  code.vconstF32(INF, INF, INF, INF).tee(bmin).set(cmin).vconstF32(-INF, -INF, -INF, -INF).tee(bmax).set(cmax);
  code.op(OP.block, 0x40).get(p).get(end).op(OP.i32GeU).op(OP.brIf, 0);
  code.op(OP.loop, 0x40);
  code.get(p).vload(0).set(mn).get(p).vload(16).set(mx).get(mn).get(mx).simd(SIMD.f32x4Add).set(c);
  code.get(bmin).get(mn).simd(SIMD.f32x4Pmin).set(bmin).get(bmax).get(mx).simd(SIMD.f32x4Pmax).set(bmax);
  code.get(cmin).get(c).simd(SIMD.f32x4Pmin).set(cmin).get(cmax).get(c).simd(SIMD.f32x4Pmax).set(cmax);
  code.get(p).i32(32).op(OP.i32Add).tee(p).get(end).op(OP.i32LtU).op(OP.brIf, 0);
  code.op(OP.end, OP.end);
  code.get(out).get(bmin).vstore(0).get(out).get(bmax).vstore(16).get(out).get(cmin).vstore(32).get(out).get(cmax).vstore(48);
  return { name: 'scan', params: [I32, I32, I32], results: [], locals: [V128, V128, V128, V128, V128, V128, V128], body: code };
}

/** Pushes the half surface area (f64, as bvh-kernels' halfArea) of the box in vector locals `mn`, `mx`. */
function halfArea(code: Code, mn: number, mx: number, dx: number, dy: number, dz: number): void {
  [dx, dy, dz].forEach((d, lane) => {
    code.get(mx).lane(lane).op(OP.f64PromoteF32).get(mn).lane(lane).op(OP.f64PromoteF32).op(OP.f64Sub).set(d);
  });
  code.get(dx).get(dy).op(OP.f64Mul).get(dy).get(dz).op(OP.f64Mul).op(OP.f64Add).get(dz).get(dx).op(OP.f64Mul).op(OP.f64Add);
}

function sweepFunction(): FunctionDef {
  // (binBase, cntBase, bins, binStride, mask, tmp, out, prm): the SAH plane search of
  // bvh-kernels' sweepBins; out: f64 best cost, i32 axis, plane, left count, binned count. tmp: f64
  // suffix areas, then i32 suffix counts, binStride of each.
  const [binBase, cntBase, bins, binStride, mask, tmp, out, prm] = [0, 1, 2, 3, 4, 5, 6, 7];
  const parentArea = 8;
  const [a, b, q, rn, ln, vmin, vmax, cost, best, bestAxis, bestPlane, bestLeftN, binned, dx, dy, dz, rnb, axisBase] =
    [9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26];
  const code = new Code();
  code.get(prm).mem(OP.f64Load, 3, 56).set(parentArea);
  code.f64(INF).set(best).i32(-1).set(bestAxis);
  code.op(OP.block, 0x40).op(OP.loop, 0x40); // axes
  code.get(mask).get(a).op(0x75 /* i32.shr_s */).i32(1).op(OP.i32And).op(OP.if, 0x40);
  code.get(a).get(binStride).op(OP.i32Mul).set(axisBase);
  // Right to left: suffix areas and counts into tmp (f64 areas at tmp, i32 counts at tmp + 8 * binStride).
  code.vconstF32(INF, INF, INF, INF).set(vmin).vconstF32(-INF, -INF, -INF, -INF).set(vmax).i32(0).set(rn);
  code.get(bins).i32(1).op(OP.i32Sub).set(b);
  code.op(OP.block, 0x40).get(b).i32(1).op(OP.i32LtS).op(OP.brIf, 0).op(OP.loop, 0x40);
  code.get(axisBase).get(b).op(OP.i32Add).set(q);
  code.get(rn).get(q).i32(2).op(OP.i32Shl).get(cntBase).op(OP.i32Add).mem(OP.i32Load, 2).op(OP.i32Add).set(rn);
  code.get(q).i32(5).op(OP.i32Shl).get(binBase).op(OP.i32Add).set(q);
  code.get(vmin).get(q).vload(0).simd(SIMD.f32x4Pmin).set(vmin).get(vmax).get(q).vload(16).simd(SIMD.f32x4Pmax).set(vmax);
  code.get(b).i32(3).op(OP.i32Shl).get(tmp).op(OP.i32Add);
  halfArea(code, vmin, vmax, dx, dy, dz);
  code.f64(0).get(rn).i32(0).op(OP.i32GtS).op(OP.select).mem(OP.f64Store, 3);
  code.get(b).i32(2).op(OP.i32Shl).get(tmp).op(OP.i32Add).get(binStride).i32(3).op(OP.i32Shl).op(OP.i32Add).get(rn).mem(OP.i32Store, 2);
  code.get(b).i32(1).op(OP.i32Sub).tee(b).i32(1).op(OP.i32GeS).op(OP.brIf, 0);
  code.op(OP.end, OP.end);
  code.get(rn).get(axisBase).i32(2).op(OP.i32Shl).get(cntBase).op(OP.i32Add).mem(OP.i32Load, 2).op(OP.i32Add).set(binned);
  // Left to right: prefix boxes, one cost per plane b + 1.
  code.vconstF32(INF, INF, INF, INF).set(vmin).vconstF32(-INF, -INF, -INF, -INF).set(vmax).i32(0).set(ln).i32(0).set(b);
  code.op(OP.block, 0x40).get(b).get(bins).i32(1).op(OP.i32Sub).op(OP.i32GeS).op(OP.brIf, 0).op(OP.loop, 0x40);
  code.get(axisBase).get(b).op(OP.i32Add).set(q);
  code.get(ln).get(q).i32(2).op(OP.i32Shl).get(cntBase).op(OP.i32Add).mem(OP.i32Load, 2).op(OP.i32Add).set(ln);
  code.get(q).i32(5).op(OP.i32Shl).get(binBase).op(OP.i32Add).set(q);
  code.get(vmin).get(q).vload(0).simd(SIMD.f32x4Pmin).set(vmin).get(vmax).get(q).vload(16).simd(SIMD.f32x4Pmax).set(vmax);
  code.get(b).i32(1).op(OP.i32Add).i32(2).op(OP.i32Shl).get(tmp).op(OP.i32Add).get(binStride).i32(3).op(OP.i32Shl).op(OP.i32Add).mem(OP.i32Load, 2).set(rnb);
  code.get(ln).i32(0).op(OP.i32Ne).get(rnb).i32(0).op(OP.i32Ne).op(OP.i32And).op(OP.if, 0x40);
  // cost = parentArea + (area(left) * ln + rightArea[b + 1] * rn)
  code.get(parentArea);
  halfArea(code, vmin, vmax, dx, dy, dz);
  code.get(ln).op(OP.f64ConvertI32S).op(OP.f64Mul);
  code.get(b).i32(1).op(OP.i32Add).i32(3).op(OP.i32Shl).get(tmp).op(OP.i32Add).mem(OP.f64Load, 3).get(rnb).op(OP.f64ConvertI32S).op(OP.f64Mul);
  code.op(OP.f64Add).op(OP.f64Add).tee(cost).get(best).op(OP.f64Lt).op(OP.if, 0x40);
  code.get(cost).set(best).get(a).set(bestAxis).get(b).i32(1).op(OP.i32Add).set(bestPlane).get(ln).set(bestLeftN);
  code.op(OP.end, OP.end);
  code.get(b).i32(1).op(OP.i32Add).tee(b).get(bins).i32(1).op(OP.i32Sub).op(OP.i32LtS).op(OP.brIf, 0);
  code.op(OP.end, OP.end);
  code.op(OP.end); // if axis
  code.get(a).i32(1).op(OP.i32Add).tee(a).i32(3).op(OP.i32LtS).op(OP.brIf, 0);
  code.op(OP.end, OP.end);
  code.get(out).get(best).mem(OP.f64Store, 3);
  code.get(out).get(bestAxis).mem(OP.i32Store, 2, 8).get(out).get(bestPlane).mem(OP.i32Store, 2, 12);
  code.get(out).get(bestLeftN).mem(OP.i32Store, 2, 16).get(out).get(binned).mem(OP.i32Store, 2, 20);
  return {
    name: 'sweep', params: [I32, I32, I32, I32, I32, I32, I32, I32], results: [],
    locals: [F64, I32, I32, I32, I32, I32, V128, V128, F64, F64, I32, I32, I32, I32, F64, F64, F64, I32, I32], body: code,
  };
}

/**
 * The module's bytes, importing `env.memory`: shared (any maximum up to 4 GiB) for the parallel
 * build, plain otherwise (an import's kind must match the memory it is instantiated with).
 */
export function bvhWasmModuleBytes(shared: boolean): Uint8Array {
  return encodeModule([binFunction(), partitionFunction(), scanFunction(), sweepFunction()], shared);
}

const compiled = new Map<boolean, WebAssembly.Module | null>();

/**
 * The compiled module (cached per thread), or null where WebAssembly, its SIMD or (for `shared`)
 * shared memory is unavailable, or a Content Security Policy forbids compiling it.
 */
export function compiledBvhWasm(shared: boolean): WebAssembly.Module | null {
  if (!compiled.has(shared)) {
    let module: WebAssembly.Module | null = null;
    try {
      if (typeof WebAssembly === 'object' && (!shared || typeof SharedArrayBuffer === 'function')) {
        module = new WebAssembly.Module(bvhWasmModuleBytes(shared) as Uint8Array<ArrayBuffer>);
      }
    } catch {
      module = null;
    }
    compiled.set(shared, module);
  }
  return compiled.get(shared)!;
}

/** Byte offsets of one build's arrays in WebAssembly memory (see `wasmSlotLayout`). */
export interface WasmSlotLayout {
  /** Per-thread scratch (bins and results), `scratchBytes` apart from 0. */
  scratchBytes: number;
  boxes: number;
  ids: number;
  pages: number;
}

/** [scratch x threads][boxes: n * 32][ids: n * 4], in 64 KiB pages; null beyond the 4 GiB of a 32-bit memory. */
export function wasmSlotLayout(n: number, threads: number, binCount: number): WasmSlotLayout | null {
  const binStride = binCount;
  // Bins (32 bytes) and counts (4) per axis, 8 result vectors, the sweep's result (32), its suffix
  // arrays (12 per bin) and the f64 parameters (64).
  const scratchBytes = Math.ceil((3 * binStride * 36 + 128 + 32 + binStride * 12 + 64) / 64) * 64;
  const boxes = threads * scratchBytes;
  const ids = boxes + n * 32;
  const pages = Math.max(1, Math.ceil((ids + n * 4) / 65536));
  if (pages > 65536) return null;
  return { scratchBytes, boxes, ids, pages };
}
