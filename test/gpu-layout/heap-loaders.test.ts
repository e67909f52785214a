// The generated WGSL heap loaders (`load_<record>(offset)` in package::layout::heaps) read back,
// field by field, records that Vec4Heap packed at arbitrary offsets among other records.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { heapRecordLayouts } from '../../src/gpu-layout/records.ts';
import { readStruct, type StructLayout } from '../../src/gpu-layout/struct-layout.ts';
import { Vec4Heap } from '../../src/gpu-layout/vec4-heap.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import { readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { runTestProgram } from '../helpers/wgsl.ts';

function snake(name: string): string {
  return name.replace(/([a-z0-9])([A-Z])/g, '$1_$2').toLowerCase();
}

/** Distinct, exactly representable values per component. */
function values(layout: StructLayout, salt: number): Record<string, number[]> {
  const out: Record<string, number[]> = {};
  layout.fields.forEach((f, i) => {
    out[f.name] = Array.from({ length: f.components }, (_, c) => (f.scalar === 'f32' ? 0.25 + salt * 64 + i * 4 + c : salt * 1000 + i * 4 + c + 7));
  });
  return out;
}

test('every heap record reads back through its generated loader at any offset', async () => {
  const device = await testDevice();
  for (const layout of heapRecordLayouts.materials) {
    const heap = new Vec4Heap();
    const offsets: number[] = [];
    for (let k = 0; k < 3; k++) {
      // Another record before each one, so offsets are not multiples of the record size.
      heap.append(heapRecordLayouts.materials[0]!, values(heapRecordLayouts.materials[0]!, 9));
      offsets.push(heap.append(layout, values(layout, k)));
    }
    const words = layout.fields.reduce((n, f) => n + f.components, 0);
    const stores = layout.fields.flatMap((f) =>
      Array.from({ length: f.components }, (_, c) => `  out[w] = bitcast<u32>(r.${f.name}${f.components > 1 ? `[${c}]` : ''}); w += 1u;`),
    );
    const source = `import package::layout::heaps::load_${snake(layout.name)};
@group(3) @binding(20) var<storage, read> offsets: array<u32>;
@group(3) @binding(21) var<storage, read_write> out: array<u32>;
@compute @workgroup_size(1) fn main(@builtin(global_invocation_id) id: vec3u) {
  let r = load_${snake(layout.name)}(offsets[id.x]);
  var w = id.x * ${words}u;
${stores.join('\n')}
}`;
    const bytes = heap.finish();
    const output = device.createBuffer({ size: 3 * words * 4, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
    await runTestProgram(device, { source, resources: { materials: uploadBuffer(device, bytes), offsets: uploadBuffer(device, new Uint32Array(offsets)), out: output }, workgroups: 3 });
    const got = new DataView(await readBuffer(device, output));
    offsets.forEach((offset, k) => {
      const expected = readStruct(layout, new DataView(bytes, offset * 16, layout.size), 0);
      let w = k * words;
      for (const f of layout.fields) {
        for (const v of ([] as number[]).concat(expected[f.name] as number | number[])) {
          assert.equal(f.scalar === 'f32' ? got.getFloat32(w * 4, true) : got.getUint32(w * 4, true), v, `${layout.name}[${k}].${f.name}`);
          w++;
        }
      }
    });
  }
});
