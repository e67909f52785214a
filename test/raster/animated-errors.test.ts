// Bad input to the animated scene renderers is a typed error naming the field, raised before any
// GPU work: missing textures, a model without a skinned mesh, clips targeting nodes the model lacks,
// beats naming unknown clips, non-finite route points, a legacy 2D render mode, and the professional
// renderer's fail-closed requirements.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { createAnimatedSceneRenderer, createProfessionalAnimatedSceneRenderer, createRasterRenderer, type AnimatedSceneRendererOptions } from '../../src/raster/index.ts';
import { ADVENTURE_BEATS, ADVENTURE_CLIPS, ADVENTURE_ROUTE, adventureFigure } from '../animation/fixtures/adventure-scene.ts';
import { createRiggedFigure } from '../animation/fixtures/rigged-figure.ts';
import { testDevice } from '../helpers/gpu.ts';

async function expectError(run: () => Promise<unknown>, code: string, field: string | RegExp): Promise<void> {
  await assert.rejects(run, (e: unknown) => {
    assert.ok(e instanceof GpuRendererError, `expected a GpuRendererError, got ${String(e)}`);
    assert.equal(e.code, code, e.message);
    if (typeof field === 'string') assert.equal(e.field, field, e.message);
    else assert.match(e.field ?? '', field, e.message);
    return true;
  });
}

async function base(overrides: Partial<AnimatedSceneRendererOptions> = {}): Promise<AnimatedSceneRendererOptions> {
  return { device: await testDevice(), width: 16, height: 16, modelAsset: adventureFigure().document, clipAssets: ADVENTURE_CLIPS, beats: ADVENTURE_BEATS, route: ADVENTURE_ROUTE, ...overrides };
}

test('non-skinned model, unknown clip in a beat, non-finite route point, 2D proxy mode: typed errors', async () => {
  await expectError(async () => createAnimatedSceneRenderer(await base({ modelAsset: createRiggedFigure({ unskinned: true }).document })), 'INVALID_MODEL', 'modelAsset.skins');
  await expectError(async () => createAnimatedSceneRenderer(await base({ beats: [{ id: 'a', order: 0, clipId: 'dance', durationMs: 500 }] })), 'INVALID_OPTION', 'beats[0].clipId');
  await expectError(async () => createAnimatedSceneRenderer(await base({ route: [{ position: [0, Number.NaN, 0], arriveMs: 0 }] })), 'INVALID_OPTION', 'route[0].position[1]');
  await expectError(async () => createAnimatedSceneRenderer(await base({ route: [{ position: [0, 0, 0], arriveMs: Infinity }] })), 'INVALID_OPTION', 'route[0].arriveMs');
  await expectError(async () => createAnimatedSceneRenderer({ ...(await base()), renderMode: '2d-proxy' } as AnimatedSceneRendererOptions), 'INVALID_OPTION', 'renderMode');
  await expectError(async () => createAnimatedSceneRenderer(await base({ modelAsset: new Uint8Array([1, 2, 3]) })), 'INVALID_OPTION', 'modelAsset');
});

test('a clip from another document targeting nodes the model lacks is an animation error', async () => {
  const other = createRiggedFigure().document;
  other.getRoot().listNodes().find((n) => n.getName() === 'LeftLeg')!.setName('Tail');
  await expectError(async () => createAnimatedSceneRenderer(await base({ clipAssets: [...ADVENTURE_CLIPS, { id: 'swish', document: other, animation: 'Walk' }] })), 'INVALID_ANIMATION', /^clipAssets\[2\]/);
});

test('a material texture index past the scene textures is an INVALID_MATERIAL error naming the slot', async () => {
  await expectError(
    () => createRasterRenderer({ device: undefined, width: 8, height: 8, meshes: [{ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], material: { baseColorTexture: { index: 0 } } }] }),
    'INVALID_MATERIAL',
    'meshes[0].material.baseColorTexture.index',
  );
  await expectError(
    () => createRasterRenderer({ width: 8, height: 8, textures: [], materials: [{ clearcoatFactor: 0.5, clearcoatTexture: { index: 2 } }] }),
    'INVALID_MATERIAL',
    'materials[0].clearcoatTexture.index',
  );
  await expectError(() => createRasterRenderer({ width: 8, height: 8, materials: [{ iridescenceFactor: 1 }] }), 'INVALID_MATERIAL', 'materials[0].iridescenceFactor');
});

test('the professional renderer fails closed on missing normal textures and in-place travel clips, and reports what it draws', async () => {
  await expectError(async () => createProfessionalAnimatedSceneRenderer(await base({ modelAsset: adventureFigure({ omitNormalTexture: true }).document })), 'INVALID_MODEL', 'modelAsset.materials[1].normalTexture');
  const inPlace = [{ id: 'walk', animation: 'Walk', movementProfile: { rootMotion: 'in-place' as const } }, ADVENTURE_CLIPS[1]!];
  await expectError(async () => createProfessionalAnimatedSceneRenderer(await base({ clipAssets: inPlace })), 'INVALID_ANIMATION', 'clipAssets[0].movementProfile.rootMotion');
  const renderer = await createProfessionalAnimatedSceneRenderer(await base({ msaa: 1 }));
  const snapshot = await renderer.renderOnce(1500);
  renderer.destroy();
  assert.equal(snapshot.renderMode, 'webgpu-pbr');
  assert.equal(snapshot.fallbackProxyActive, false);
  assert.equal(snapshot.normalMapReady, true);
  assert.equal(snapshot.characterTextureCount, 2);
  assert.equal(snapshot.rootMotionPolicy, 'authored-travel');
  assert.ok(Math.abs(snapshot.characterPosition[2] - 0.5) < 1e-9);
});
