// glTF test scenes for the GPU tests of test/pathtracer/gltf-*.test.ts, built in memory with
// @gltf-transform/core, written as .glb bytes and read back with loadGltfScene, so each test goes
// through the whole loader before the renderer sees the scene.
import { NodeIO, type Accessor, type Document, type Buffer as GltfBuffer, type Material, type Mesh, type Node, type TypedArray } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { loadGltfScene, type GltfScene } from '../../src/io/index.ts';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { WavefrontFrameStats, WavefrontPathTracingOptions } from '../../src/pathtracer/types.ts';
import { testDevice } from '../helpers/gpu.ts';

/** The document written as GLB and loaded again (the full loader path). */
export async function roundTrip(doc: Document, options: Parameters<typeof loadGltfScene>[1] = {}): Promise<GltfScene> {
  const glb = await new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(doc);
  return loadGltfScene(glb, options);
}

export function floatAccessor(doc: Document, buffer: GltfBuffer, type: 'VEC2' | 'VEC3' | 'VEC4', values: readonly number[]): Accessor {
  return doc.createAccessor().setType(type).setArray(new Float32Array(values) as TypedArray).setBuffer(buffer);
}

export interface QuadOptions {
  /** Corners (x0, y0) bottom left to (x1, y1) top right, in the plane z. */
  x0: number;
  y0: number;
  x1: number;
  y1: number;
  z?: number;
  /** Per-vertex normals (omitted: the primitive has no NORMAL). */
  normals?: boolean;
  /** TEXCOORD_1 = (1 - u, v) of TEXCOORD_0. */
  uv1?: boolean;
  /** COLOR_0, rgba per corner in the order bottom left, bottom right, top right, top left. */
  colors?: readonly number[];
  /** Reverse the winding (the counter-clockwise front then faces -z). */
  flip?: boolean;
}

/**
 * A rectangle in a z plane, front face +z (counter-clockwise seen from +z), with TEXCOORD_0 (0, 0)
 * at its top left corner (x0, y1) and (1, 1) at its bottom right (x1, y0), glTF's convention.
 */
export function quad(doc: Document, buffer: GltfBuffer, material: Material | null, o: QuadOptions): Mesh {
  const z = o.z ?? 0;
  const positions = [o.x0, o.y0, z, o.x1, o.y0, z, o.x1, o.y1, z, o.x0, o.y1, z];
  const uvs = [0, 1, 1, 1, 1, 0, 0, 0];
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', floatAccessor(doc, buffer, 'VEC3', positions))
    .setAttribute('TEXCOORD_0', floatAccessor(doc, buffer, 'VEC2', uvs))
    .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint16Array(o.flip ? [0, 2, 1, 0, 3, 2] : [0, 1, 2, 0, 2, 3])).setBuffer(buffer));
  if (o.normals) primitive.setAttribute('NORMAL', floatAccessor(doc, buffer, 'VEC3', [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1].map((v) => (o.flip ? -v : v))));
  if (o.uv1) primitive.setAttribute('TEXCOORD_1', floatAccessor(doc, buffer, 'VEC2', [1, 1, 0, 1, 0, 0, 1, 0]));
  if (o.colors) primitive.setAttribute('COLOR_0', floatAccessor(doc, buffer, 'VEC4', o.colors));
  if (material) primitive.setMaterial(material);
  return doc.createMesh().addPrimitive(primitive);
}

/** A node placing an orthographic camera at (x, y, distance) looking down -z, `height` units tall. */
export function orthographicCameraNode(doc: Document, height: number, at: readonly [number, number, number] = [0, 0, 2]): Node {
  const camera = doc.createCamera('ortho').setType('orthographic').setYMag(height / 2).setXMag(height / 2).setZNear(0.01).setZFar(100);
  return doc.createNode('camera').setCamera(camera).setTranslation([...at]);
}

export interface RenderResult {
  stats: WavefrontFrameStats;
  radiance: Float32Array;
  albedo?: Float32Array;
  normal?: Float32Array;
  warnings: readonly string[];
  textureCount: number;
}

/** Renders a loaded scene once (`spp` samples) on the shared test device and reads it back. */
export async function renderScene(scene: GltfScene, options: Partial<WavefrontPathTracingOptions> & { width: number; height: number }, spp: number): Promise<RenderResult> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, samplesPerPixel: spp, seed: 5, maxDepth: 4, ...scene, ...options });
  try {
    const stats = await renderer.renderFrame();
    const radiance = (await renderer.readRadiance()).data;
    const snapshot = renderer.getSnapshot();
    const result: RenderResult = { stats, radiance, warnings: snapshot.warnings, textureCount: snapshot.textureCount };
    if (options.aovs) {
      result.albedo = (await renderer.readAov('albedo')).data;
      result.normal = (await renderer.readAov('normal')).data;
    }
    return result;
  } finally {
    renderer.destroy();
  }
}
