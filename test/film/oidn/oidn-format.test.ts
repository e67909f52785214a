// The CPU side of the OIDN denoiser: the TZA reader (and its refusals), half floats, the PU
// transfer function and autoexposure, the network read from the shipped weights, the GPU weight
// packing and the tile plan.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { channelGroups, floatToHalfBits, packConv, paddedInputChannel, planTensors, planTiles } from '../../../src/film/denoise/oidn/packing.ts';
import { autoexposure, puForward, puInverse, puNormScale } from '../../../src/film/denoise/oidn/transfer.ts';
import { halfToFloat, parseTza } from '../../../src/film/denoise/oidn/tza.ts';
import { unetFromTensors } from '../../../src/film/denoise/oidn/unet.ts';
import { loadOidnModel } from '../../../src/film/denoise/oidn/weights.ts';

const weightsFile = (name: string) => readFileSync(new URL(`../../../weights/oidn/${name}.tza`, import.meta.url));

/** A TZA v2 file written by the format's rules (training/tza.py): tensors, then the table. */
function tza(tensors: { name: string; dims: number[]; layout: string; type: 'f' | 'h'; values: number[] }[], version = 2): Uint8Array {
  const chunks: number[] = [];
  const u8 = (v: number) => chunks.push(v & 0xff);
  const u16 = (v: number) => (u8(v), u8(v >> 8));
  const u32 = (v: number) => (u16(v & 0xffff), u16(v >>> 16));
  const u64 = (v: number) => (u32(v), u32(0));
  u16(0x41d7);
  u8(version);
  u8(0);
  u64(0);
  const offsets: number[] = [];
  for (const t of tensors) {
    offsets.push(chunks.length);
    for (const v of t.values) {
      if (t.type === 'h') u16(floatToHalfBits(v));
      else u32(new Uint32Array(new Float32Array([v]).buffer)[0]!);
    }
  }
  const table = chunks.length;
  u32(tensors.length);
  tensors.forEach((t, i) => {
    u16(t.name.length);
    for (const ch of t.name) u8(ch.charCodeAt(0));
    u8(t.dims.length);
    for (const d of t.dims) u32(d);
    for (const ch of t.layout) u8(ch.charCodeAt(0));
    u8(t.type.charCodeAt(0));
    u64(offsets[i]!);
  });
  const bytes = new Uint8Array(chunks);
  new DataView(bytes.buffer).setUint32(4, table, true);
  return bytes;
}

const refused = (field: string, pattern: RegExp) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field && pattern.test(e.message);

test('TZA: tensors read back exactly (float16 and float32); bad files are typed errors naming the field', () => {
  const file = tza([
    { name: 'a.weight', dims: [1, 2, 1, 1], layout: 'oihw', type: 'h', values: [0.5, -1.75] },
    { name: 'a.bias', dims: [1], layout: 'x', type: 'f', values: [0.1] },
  ]);
  const tensors = parseTza(file);
  assert.deepEqual([...tensors.keys()], ['a.weight', 'a.bias']);
  assert.deepEqual([...tensors.get('a.weight')!.data], [0.5, -1.75]);
  assert.equal(tensors.get('a.bias')!.data[0], Math.fround(0.1));
  assert.deepEqual(tensors.get('a.weight')!.dims, [1, 2, 1, 1]);
  assert.throws(() => parseTza(file.slice(0, file.length - 3)), refused('weights', /runs past the end/));
  const badMagic = file.slice();
  badMagic[0] = 0;
  assert.throws(() => parseTza(badMagic), refused('weights', /magic/));
  assert.throws(() => parseTza(tza([], 1)), refused('weights', /version 1/));
  assert.throws(() => parseTza(tza([{ name: 'x', dims: [1], layout: 'q', type: 'f', values: [1] }])), refused('weights', /layout/));
  // A data offset past the end of the file.
  const lying = tza([{ name: 'x', dims: [1000], layout: 'x', type: 'f', values: [1] }]);
  assert.throws(() => parseTza(lying), refused('weights', /past the end/));
  assert.throws(() => parseTza('tza' as never), refused('weights', /ArrayBuffer/));
  // Weights that are a valid TZA but not an RT U-Net.
  assert.throws(() => unetFromTensors(tensors, 'denoise.weights'), refused('denoise.weights', /enc_conv0/));
});

test('half floats: every binary16 value round-trips, and floats round to nearest even', () => {
  for (let bits = 0; bits < 0x10000; bits++) {
    const exponent = (bits >> 10) & 0x1f;
    if (exponent === 31 && bits & 0x3ff) continue; // NaN payloads
    assert.equal(floatToHalfBits(halfToFloat(bits)), bits, `bits ${bits.toString(16)}`);
  }
  assert.equal(halfToFloat(floatToHalfBits(1 + 2 ** -11)), 1); // a tie rounds to even
  assert.equal(halfToFloat(floatToHalfBits(1 + 3 * 2 ** -11)), 1 + 2 ** -9);
  assert.equal(halfToFloat(floatToHalfBits(70000)), Infinity);
  assert.equal(halfToFloat(floatToHalfBits(2 ** -25)), 0); // half the smallest subnormal: to even (0)
  assert.equal(halfToFloat(floatToHalfBits(3 * 2 ** -26)), 2 ** -24);
});

test('PU transfer: inverse of forward, continuous at its knots, 65504 maps to 1; autoexposure puts the log-average at 0.18', () => {
  for (const y of [0, 1e-7, 1.5794576e-6, 1e-4, 0.0322087631, 0.5, 1, 18, 1000, 65504]) {
    assert.ok(Math.abs(puInverse(puForward(y)) - y) <= 1e-4 * y + 1e-9, `y ${y}`);
  }
  for (const knot of [1.5794576e-6, 3.22087631e-2]) assert.ok(Math.abs(puForward(knot * (1 - 1e-9)) - puForward(knot * (1 + 1e-9))) < 1e-5);
  assert.ok(Math.abs(puForward(65504) * puNormScale - 1) < 1e-6);
  // A constant image of luminance L: scale 0.18 / L. Two halves L1 and L2: 0.18 / sqrt(L1 L2).
  const image = (w: number, h: number, f: (x: number) => number) => Float32Array.from({ length: w * h * 4 }, (_, i) => (i % 4 === 3 ? 1 : f((i >> 2) % w)));
  assert.ok(Math.abs(autoexposure(image(40, 20, () => 2), 40, 20) - 0.09) < 1e-9);
  assert.ok(Math.abs(autoexposure(image(32, 16, (x) => (x < 16 ? 0.5 : 8)), 32, 16) - 0.18 / 2) < 1e-9);
  assert.equal(autoexposure(image(8, 8, () => 0), 8, 8), 1);
});

test('the shipped weights are the base U-Net: 16 convolutions, 9 or 3 inputs, the channel widths of OIDN', async () => {
  const full = await loadOidnModel('rt_hdr_alb_nrm');
  const color = await loadOidnModel('rt_hdr');
  assert.equal(full.variant, 'base');
  assert.equal(full.inputChannels, 9);
  assert.equal(color.inputChannels, 3);
  assert.deepEqual(full.convs.map((c) => c.outChannels), [32, 32, 48, 64, 80, 96, 96, 112, 112, 96, 96, 64, 64, 64, 32, 3]);
  assert.deepEqual(full.convs.map((c) => c.sourceChannels.join('+')), ['9', '32', '32', '48', '64', '80', '96', '96+64', '112', '112+48', '96', '96+32', '64', '64+9', '64', '32']);
  assert.deepEqual(full.convs.filter((c) => c.pool).map((c) => c.name), ['enc_conv1', 'enc_conv2', 'enc_conv3', 'enc_conv4']);
  // The bytes load the same way from a file.
  assert.deepEqual(unetFromTensors(parseTza(weightsFile('rt_hdr'))).convs[5]!.weights, color.convs[5]!.weights);
});

test('weight packing: every weight lands in its 4x4 matrix column, padding is zero', async () => {
  const model = await loadOidnModel('rt_hdr_alb_nrm');
  const conv = model.convs.find((c) => c.name === 'dec_conv1a')!; // 64 upsampled + 9 input channels
  const packed = packConv(conv);
  assert.deepEqual(packed.sourceGroups, [16, 3]);
  assert.equal(packed.blocks, 4);
  const inputs = 19;
  const biasValues = packed.blocks * 16;
  const at = (o: number, padded: number, tap: number) => biasValues + ((((o >> 4) * inputs + (padded >> 2)) * 9 + tap) * 4 + ((o % 16) >> 2)) * 16 + (padded & 3) * 4 + (o % 4);
  let nonzero = 0;
  const used = new Set<number>();
  for (let o = 0; o < 64; o++) {
    for (let i = 0; i < 73; i++) {
      for (let tap = 0; tap < 9; tap++) {
        const k = at(o, paddedInputChannel(conv, i), tap);
        assert.equal(packed.values[k], conv.weights[(o * 73 + i) * 9 + tap]);
        used.add(k);
      }
    }
  }
  assert.equal(paddedInputChannel(conv, 64), 64);
  for (let k = biasValues; k < packed.values.length; k++) if (!used.has(k) && packed.values[k] !== 0) nonzero++;
  assert.equal(nonzero, 0, 'padding weights are zero');
  assert.deepEqual([...packed.values.subarray(0, 64)], [...conv.bias]);
  assert.equal(channelGroups(3), 1);
});

test('tensor plan: buffers are reused only after their last reader; tile plan covers the image once on the 16-pixel grid', async () => {
  const model = await loadOidnModel('rt_hdr_alb_nrm');
  const plan = planTensors(model, 64, 48, 'f16');
  const names = ['input', ...model.convs.map((c) => c.name)];
  for (const a of names) {
    for (const b of names) {
      const ta = plan.tensors.get(a)!, tb = plan.tensors.get(b)!;
      if (a === b || ta.slot !== tb.slot) continue;
      // Same buffer: their lifetimes [producedAt, lastReadAt] must not overlap.
      assert.ok(ta.lastReadAt < tb.producedAt || tb.lastReadAt < ta.producedAt, `${a} and ${b} share buffer ${ta.slot}`);
    }
  }
  for (const [name, t] of plan.tensors) assert.ok(plan.slotBytes[t.slot]! >= t.groups * (64 >> t.level) * (48 >> t.level) * 8, name);
  assert.ok(plan.totalBytes < 0.6 * [...plan.tensors.values()].reduce((a, t) => a + t.groups * (64 >> t.level) * (48 >> t.level) * 8, 0), 'reuse saves memory');

  const overlap = 96;
  for (const [w, h, tile] of [[1000, 700, 400], [1920, 1080, 1024], [300, 17, 240], [100, 60, 4096]] as const) {
    const tiles = planTiles(w, h, overlap, (tw, th) => tw <= tile && th <= tile);
    const covered = new Uint8Array(w * h);
    for (const t of tiles.tiles) {
      for (const axis of [0, 1] as const) {
        const size = axis === 0 ? w : h;
        const extent = axis === 0 ? tiles.tileWidth : tiles.tileHeight;
        assert.equal(t.origin[axis] % 16, 0, 'origins on the grid');
        assert.ok(t.origin[axis] + extent <= Math.ceil(size / 16) * 16, 'within the padded image');
        // Every written pixel has `overlap` pixels of context inside the tile, or the image edge.
        assert.ok(t.writeMin[axis] - t.origin[axis] >= overlap || t.origin[axis] === 0);
        assert.ok(t.origin[axis] + extent - t.writeMax[axis] >= overlap || t.origin[axis] + extent >= size);
      }
      for (let y = t.writeMin[1]; y < t.writeMax[1]; y++) for (let x = t.writeMin[0]; x < t.writeMax[0]; x++) covered[y * w + x]!++;
    }
    assert.ok(covered.every((c) => c === 1), `${w}x${h}: every pixel written once`);
    assert.ok(tiles.tileWidth <= Math.max(tile, 0) && tiles.tileWidth % 16 === 0 && tiles.tileHeight % 16 === 0);
  }
  assert.equal(planTiles(100, 60, overlap, () => true).tiles.length, 1);
  assert.equal(planTiles(100, 60, overlap, () => true).tileWidth, 112);
});
