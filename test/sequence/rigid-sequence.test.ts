// The sequence renderer (--frames, the farm) passes updateGeometry only what changed since the
// last frame: a rigid animation (instances moving, meshes still) takes the patched top-level path,
// a deforming mesh the flattened one, and either renders what a renderer created for the frame
// renders.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createSequenceRenderer } from '../../src/sequence/sequence-renderer.ts';
import type { WavefrontGeometryUpdateStats, WavefrontSceneDescription } from '../../src/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { relativeL1 } from '../helpers/image-stats.ts';
import { icosphere } from '../helpers/meshes.ts';
import { trs } from '../pathtracer/instancing-scenes.ts';

const SIZE = 40;
// Materials by index, as the glTF loader gives them (the sequence keeps one material heap).
const MATERIALS = [
  { baseColorFactor: [0.6, 0.6, 0.6], metallicFactor: 0, roughnessFactor: 1 },
  { baseColorFactor: [0.8, 0.3, 0.2], metallicFactor: 0, roughnessFactor: 0.5 },
] as WavefrontSceneDescription['materials'];

function frame(t: number, sphere: { positions: number[]; indices: number[] }): WavefrontSceneDescription {
  return {
    meshes: [
      { positions: [-3, 0, -3, 3, 0, -3, 3, 0, 3, -3, 0, 3], indices: [0, 2, 1, 0, 3, 2], material: 0 },
      // A fresh array each frame, as a new pose gives.
      { positions: sphere.positions.slice(), indices: sphere.indices, material: 1 },
    ],
    materials: MATERIALS,
    instances: [
      { mesh: 0 },
      ...[-1, 0, 1].map((x, i) => ({ mesh: 1, transform: trs([x + 0.3 * t, 0.4 + 0.2 * t * i, 0], [0, 1, 0], t, [1, 1, 1]) })),
    ],
    camera: { position: [0, 2.2, 4], target: [0, 0.4, 0], up: [0, 1, 0], fovYDegrees: 45 },
    environment: { color: [0.4, 0.45, 0.5] },
  };
}

test('a rigid animation patches the moved placements; a deforming mesh (new arrays or written in place) flattens; each renders the frame', async () => {
  const device = await testDevice();
  const options = { device, width: SIZE, height: SIZE, samplesPerPixel: 4, maxDepth: 3, seed: 5, instancing: 'always' as const };
  const sphere = icosphere(0.35, [0, 0, 0], 2);
  const sequence = createSequenceRenderer(options);
  const seen: WavefrontGeometryUpdateStats[] = [];
  try {
    const renderer = await sequence.show(frame(0, sphere));
    // The renderer's own updateGeometry, its stats recorded.
    const update = renderer.updateGeometry.bind(renderer);
    renderer.updateGeometry = async (u) => {
      const stats = await update(u);
      seen.push(stats);
      return stats;
    };
    const inflated = { ...sphere, positions: sphere.positions.map((v) => 1.2 * v) };
    for (const [t, mesh, want] of [[0.5, sphere, 'patched'], [0.9, inflated, 'flattened']] as const) {
      const next = frame(t, mesh);
      assert.equal(await sequence.show(next), renderer, 'moved in place');
      assert.equal(seen.at(-1)!.topLevel, want);
      // The ground stays: 3 moved placements of 4 under 'patched'.
      if (want === 'patched') assert.equal(seen.at(-1)!.topLevelRecordsWritten, 3);
      await renderer.renderFrame();
      const fresh = await createWavefrontPathTracingComputeRenderer({ ...options, ...next });
      try {
        await fresh.renderFrame();
        const got = (await renderer.readRadiance()).data;
        const expected = (await fresh.readRadiance()).data;
        assert.ok(relativeL1(got, expected) < 0.005, `t = ${t}: relative L1 ${relativeL1(got, expected).toFixed(5)} against a renderer created for the frame`);
      } finally {
        fresh.destroy();
      }
    }
    // Vertices written in place into the array the last frame showed: it cannot be known unchanged, so it is sent.
    const last = frame(0.9, inflated);
    await sequence.show(last);
    const positions = last.meshes![1]!.positions as number[];
    positions.forEach((v, i) => (positions[i] = 0.9 * v));
    await sequence.show({ ...last });
    assert.equal(seen.at(-1)!.topLevel, 'flattened', 'a mesh written in place is moved');
    await renderer.renderFrame();
    const fresh = await createWavefrontPathTracingComputeRenderer({ ...options, ...last });
    try {
      await fresh.renderFrame();
      assert.ok(relativeL1((await renderer.readRadiance()).data, (await fresh.readRadiance()).data) < 0.005, 'the in-place move is rendered');
    } finally {
      fresh.destroy();
    }
    assert.deepEqual(sequence.counts, { created: 1, moved: 4, replaced: 0 });
  } finally {
    sequence.destroy();
  }
});
