/**
 * Scene-file mutants: a scene JSON naming an image file, a data-URI image, an environment map file
 * and two glTF assets (.gltf with a buffer file, .glb), mutated at the JSON level, with hostile
 * references, and with damaged referenced files.
 */
import { encode as encodePng } from 'fast-png';
import { packageGltf } from './container.ts';
import type { EnvSeed } from './corpus-env.ts';
import type { GltfSeed } from './corpus-gltf.ts';
import { fuzzPolicy, type LoaderCase } from './cases-gltf.ts';
import { mutateJson, setAt, type Json } from './mutate-json.ts';
import type { Random } from './random.ts';
import { expandUri, HOSTILE_URIS, type UriContext } from './sandbox.ts';

const png = encodePng({ width: 2, height: 2, data: new Uint8Array([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128]), channels: 4 });

function seedScene(): Record<string, Json> {
  return {
    camera: { position: [0, 1, 4], target: [0, 0.5, 0], fovYDegrees: 40 },
    meshes: [{ positions: [-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1], indices: [0, 2, 1, 0, 3, 2], uvs: [0, 0, 1, 0, 1, 1, 0, 1], material: { baseColorTexture: { index: 0 }, emissiveTexture: { index: 1 }, emissiveFactor: [1, 1, 1] } }],
    textures: [{ image: 0 }, { image: 1, sampler: { wrapS: 'clamp-to-edge' } }],
    images: [{ uri: 'tex.png' }, { uri: `data:image/png;base64,${Buffer.from(png).toString('base64')}` }],
    environment: { map: 'sky.hdr', intensity: 0.5, rotationDegrees: 30 },
    gltf: [{ src: 'model.gltf' }, { src: 'sub/model.glb', transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 2, 0, 0, 1] }],
  };
}

const REFERENCE_PATHS: ReadonlyArray<Array<string | number>> = [['images', 0, 'uri'], ['images', 1, 'uri'], ['environment', 'map'], ['gltf', 0, 'src'], ['gltf', 1, 'src']];

export function makeSceneCase(gltf: readonly GltfSeed[], env: readonly EnvSeed[], random: Random, context: UriContext): LoaderCase {
  let scene: Json = seedScene();
  const notes: string[] = ['scene'];
  const small = gltf.find((s) => s.name === 'minimal')!;
  const textured = gltf.find((s) => s.name === 'textured')!;
  const model = packageGltf(random.chance(0.5) ? textured.json : small.json, random.chance(0.5) ? textured.resources : small.resources, 'gltf-files');
  const glb = packageGltf(small.json, small.resources, 'glb');
  const files: Record<string, Uint8Array> = {
    'tex.png': png,
    'sky.hdr': env.find((s) => s.name.endsWith('.hdr'))!.bytes,
    'model.gltf': model.files[model.entry]!,
    'sub/model.glb': glb.files[glb.entry]!,
  };
  for (const [name, bytes] of Object.entries(model.files)) if (name !== model.entry) files[name] = bytes;
  const rounds = 1 + (random.chance(0.5) ? 0 : random.int(3));
  for (let r = 0; r < rounds; r++) {
    const kind = random.int(10);
    if (kind < 4) {
      const m = mutateJson(scene, random, { skip: (p) => p[0] === 'images' && p[1] === 1 && p[2] === 'uri' });
      scene = m.value;
      notes.push(m.note);
    } else if (kind < 8) {
      const path = random.pick(REFERENCE_PATHS);
      const uri = expandUri(random.pick(HOSTILE_URIS), context);
      scene = setAt(scene, path, uri);
      notes.push(`/${path.join('/')} = ${JSON.stringify(uri).slice(0, 80)}`);
    } else {
      const name = random.pick(Object.keys(files));
      const bytes = files[name]!.slice();
      const flips = 1 + random.int(6);
      for (let k = 0; k < flips; k++) bytes[random.int(Math.min(bytes.length, 128))] ^= 1 << random.int(8);
      files[name] = random.chance(0.3) ? bytes.subarray(0, random.int(bytes.length)) : bytes;
      notes.push(`${name} damaged`);
    }
  }
  let text = JSON.stringify(scene);
  if (random.chance(0.05)) {
    text = text.slice(0, random.int(text.length));
    notes.push('text truncated');
  }
  files['scene.json'] = new TextEncoder().encode(text);
  return { files, source: { kind: 'path', file: 'scene.json' }, options: { resourcePolicy: fuzzPolicy(random, context) }, abort: random.chance(0.02), notes };
}
