import { test } from 'node:test';
import assert from 'node:assert/strict';
import { wavefrontRecordLayouts } from '../../src/gpu-layout/records.ts';
import { writeStruct, readStruct, allocateStructArray, leafFields, type StructLayout, type StructValues } from '../../src/gpu-layout/struct-layout.ts';
import { testDevice, uploadBuffer, readBuffer } from '../helpers/gpu.ts';
import { runTestProgram } from '../helpers/wgsl.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';

// Distinct, exactly representable values per component so any offset mistake shows (nested
// structs take nested values; `i` numbers the leaf fields).
function sampleValues(layout: StructLayout, record: number, counter = { i: 0 }): StructValues {
  const values: StructValues = {};
  for (const f of layout.fields) {
    if (f.struct) {
      values[f.name] = sampleValues(f.struct, record, counter);
      continue;
    }
    const i = counter.i++;
    values[f.name] = Array.from({ length: f.components }, (_, c) => (f.scalar === 'f32' ? 0.5 + record * 100 + i * 4 + c : record * 1000 + i * 4 + c + 1));
  }
  return values;
}

test('every record layout packed in TypeScript reads back field by field in WGSL', async () => {
  const device = await testDevice();
  for (const layout of Object.values(wavefrontRecordLayouts)) {
    const count = 3;
    const data = allocateStructArray(layout, count);
    const view = new DataView(data);
    for (let r = 0; r < count; r++) writeStruct(layout, view, r, sampleValues(layout, r));
    const leaves = leafFields(layout);
    const wordsPerRecord = leaves.reduce((n, f) => n + f.components, 0);
    const body = leaves
      .flatMap((f) =>
        Array.from({ length: f.components }, (_, c) => {
          const access = f.components === 1 ? `src[r].${f.name}` : `src[r].${f.name}[${c}]`;
          return `  out[base + ${0}u] = bitcast<u32>(${access}); base += 1u;`.replace('base + 0u', 'base');
        }),
      )
      .join('\n');
    const code = `import package::layout::records::${layout.name};
@group(0) @binding(0) var<storage, read> src: array<${layout.name}>;
@group(0) @binding(1) var<storage, read_write> out: array<u32>;
@compute @workgroup_size(1) fn main(@builtin(global_invocation_id) id: vec3u) {
  let r = id.x;
  var base = r * ${wordsPerRecord}u;
${body}
}`;
    const srcBuffer = uploadBuffer(device, data);
    const outBuffer = device.createBuffer({ size: count * wordsPerRecord * 4, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
    await runTestProgram(device, { source: code, resources: { src: srcBuffer, out: outBuffer }, workgroups: count });
    const words = new DataView(await readBuffer(device, outBuffer));
    for (let r = 0; r < count; r++) {
      const expected = readStruct(layout, view, r);
      let w = r * wordsPerRecord;
      for (const f of leaves) {
        const comps = Array.isArray(expected[f.name]) ? (expected[f.name] as number[]) : [expected[f.name] as number];
        for (const value of comps) {
          const got = f.scalar === 'f32' ? words.getFloat32(w * 4, true) : words.getUint32(w * 4, true);
          assert.equal(got, value, `${layout.name}[${r}].${f.name}`);
          w++;
        }
      }
    }
    srcBuffer.destroy();
    outBuffer.destroy();
  }
});
