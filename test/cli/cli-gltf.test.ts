// End-to-end: the CLI renders glTF assets made in the test (node src/cli/main.ts render model.glb).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Document, NodeIO, Primitive } from '@gltf-transform/core';
import { ALL_EXTENSIONS, KHRMaterialsEmissiveStrength, KHRMaterialsVariants } from '@gltf-transform/extensions';
import { decode, encode } from 'fast-png';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = join(root, 'src/cli/main.ts');

function run(args: string[]): Promise<{ code: number | null; stdout: string; stderr: string }> {
  return new Promise((resolve, reject) => {
    const child = spawn(process.execPath, [cli, ...args], { cwd: root, stdio: ['ignore', 'pipe', 'pipe'] });
    let stdout = '';
    let stderr = '';
    child.stdout.setEncoding('utf8').on('data', (d: string) => (stdout += d));
    child.stderr.setEncoding('utf8').on('data', (d: string) => (stderr += d));
    child.on('error', reject);
    child.on('close', (code) => resolve({ code, stdout, stderr }));
  });
}

/**
 * A floor textured red (left half) and green (right half), lit by an emissive quad above it, seen
 * by a camera node; the floor mesh is shared by two nodes, and a points primitive is skipped.
 */
async function writeModel(path: string): Promise<void> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const acc = (type: 'VEC2' | 'VEC3' | 'SCALAR', array: Float32Array<ArrayBuffer> | Uint16Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
  const quad = (y: number, flip: boolean) => {
    const p = new Float32Array([-1, y, 1, 1, y, 1, 1, y, -1, -1, y, -1]);
    return doc
      .createPrimitive()
      .setAttribute('POSITION', acc('VEC3', p))
      .setAttribute('TEXCOORD_0', acc('VEC2', new Float32Array([0, 1, 1, 1, 1, 0, 0, 0])))
      .setIndices(acc('SCALAR', new Uint16Array(flip ? [0, 2, 1, 0, 3, 2] : [0, 1, 2, 0, 2, 3])));
  };
  const checker = new Uint8Array([230, 20, 20, 255, 20, 230, 20, 255]);
  const texture = doc.createTexture('halves').setMimeType('image/png').setImage(encode({ width: 2, height: 1, data: checker, channels: 4 }));
  const floorMaterial = doc.createMaterial('floor').setBaseColorTexture(texture).setMetallicFactor(0).setRoughnessFactor(1);
  floorMaterial.getBaseColorTextureInfo()!.setMagFilter(9728);
  const strength = doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(8);
  const lamp = doc.createMaterial('lamp').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 1, 1]).setExtension('KHR_materials_emissive_strength', strength);
  const points = doc.createPrimitive().setMode(Primitive.Mode.POINTS).setAttribute('POSITION', acc('VEC3', new Float32Array([0, 0, 0])));
  const floor = doc.createMesh('floor').addPrimitive(quad(0, false).setMaterial(floorMaterial)).addPrimitive(points);
  const light = doc.createMesh('light').addPrimitive(quad(0, true).setMaterial(lamp));
  const variants = doc.createExtension(KHRMaterialsVariants);
  variants.createVariant('Night');
  const camera = doc.createCamera('view').setType('perspective').setYFov(1).setZNear(0.1);
  // Looking down at the floor from above: rotate -90 degrees about X so -Z points down.
  const s = Math.sin(-Math.PI / 4);
  doc.createScene()
    .addChild(doc.createNode('floor-a').setMesh(floor))
    .addChild(doc.createNode('floor-b').setMesh(floor).setTranslation([0, -0.01, 0]).setScale([3, 1, 3]))
    .addChild(doc.createNode('lamp').setMesh(light).setTranslation([0, 2, 0]).setScale([0.3, 1, 0.3]))
    .addChild(doc.createNode('eye').setCamera(camera).setTranslation([0, 1.6, 0]).setRotation([s, 0, 0, Math.cos(-Math.PI / 4)]));
  await writeFile(path, await new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(doc));
}

test('a bad glTF exits 1 naming the JSON pointer; an unknown variant names the option', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-gltf-'));
  try {
    const model = join(dir, 'model.glb');
    await writeModel(model);
    const bytes = await readFile(model);
    bytes.writeUInt32LE(3, 4);
    const broken = join(dir, 'broken.glb');
    await writeFile(broken, bytes);
    let r = await run(['render', broken, '--out', join(dir, 'x.png')]);
    assert.equal(r.code, 1);
    assert.equal(r.stderr, 'error [INVALID_GLTF] glb:/header/version: expected GLB version 2, got 3\n');
    r = await run(['render', model, '--variant', 'Day', '--out', join(dir, 'x.png')]);
    assert.equal(r.code, 1);
    assert.match(r.stderr, /^error \[INVALID_OPTION\] variant: unknown KHR_materials_variants variant "Day" \(the asset has "Night"\)/);
    r = await run(['render', model, '--camera', 'nope', '--out', join(dir, 'x.png')]);
    assert.equal(r.code, 1);
    assert.match(r.stderr, /^error \[INVALID_OPTION\] camera: no camera "nope"/);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('renders a generated .glb from its camera, with loader warnings on stderr', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-gltf-'));
  try {
    const model = join(dir, 'model.glb');
    await writeModel(model);
    const out = join(dir, 'model.png');
    const r = await run(['render', model, '--camera', 'eye', '--variant', 'Night', '--width', '32', '--height', '24', '--spp', '4', '--max-depth', '3', '--out', out]);
    assert.equal(r.code, 0, r.stderr);
    assert.match(r.stderr, /warning: \/meshes\/0\/primitives\/1: skipped, POINTS/);
    assert.match(r.stderr, /wrote .*model\.png \(32x24, 4 spp\)/);
    const png = decode(await readFile(out));
    assert.deepEqual([png.width, png.height], [32, 24]);
    // Seen from above, the floor's left half is red and its right half green (texture halves).
    const red = [0, 0];
    const green = [0, 0];
    for (let i = 0; i < png.data.length; i += 4) {
      const side = (i / 4) % 32 < 16 ? 0 : 1;
      if (png.data[i] > png.data[i + 1] + 30) red[side]++;
      if (png.data[i + 1] > png.data[i] + 30) green[side]++;
    }
    assert.ok(red[0] > 40 && red[0] > 4 * red[1], `red left/right ${red}`);
    assert.ok(green[1] > 40 && green[1] > 4 * green[0], `green left/right ${green}`);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});
