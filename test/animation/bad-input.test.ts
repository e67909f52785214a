import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document } from '@gltf-transform/core';
import { createClipLibrary } from '../../src/animation/clips/clip-library.ts';
import { readAnimatedModel } from '../../src/animation/model/read-model.ts';
import { createSceneTimeline } from '../../src/animation/timeline/scene-timeline.ts';
import { createFigureSetup } from './fixtures/figure-library.ts';
import { createRiggedFigure } from './fixtures/rigged-figure.ts';
import { expectRendererError } from './helpers.ts';

function figure(): ReturnType<typeof createRiggedFigure> {
  return createRiggedFigure();
}

function walkSampler(document: Document, index: number): ReturnType<ReturnType<Document['getRoot']>['listAnimations']>[number]['listSamplers'] extends () => (infer S)[] ? S : never {
  return document.getRoot().listAnimations()[0].listSamplers()[index];
}

const bodyMeshIndex = (document: Document): number => document.getRoot().listMeshes().findIndex((m) => m.getName() === 'Body');

test('clip data errors: missing target node, non-finite keys, non-increasing or negative times, mismatched outputs', () => {
  {
    const { document, nodes } = figure();
    const tail = document.createNode('Tail');
    nodes.hips.addChild(tail);
    const sampler = document.createAnimationSampler().setInput(document.createAccessor().setType('SCALAR').setArray(new Float32Array([0, 1]))).setOutput(document.createAccessor().setType('VEC3').setArray(new Float32Array(6)));
    document.createAnimation('Wag').addSampler(sampler).addChannel(document.createAnimationChannel().setTargetNode(tail).setTargetPath('translation').setSampler(sampler));
    tail.dispose();
    expectRendererError(() => readAnimatedModel(document), 'INVALID_ANIMATION', 'animations[2].channels[0].target.node', /does not exist/);
  }
  const cases: [string, (d: Document) => void, string][] = [
    ['non-finite time', (d) => walkSampler(d, 0).getInput()!.setArray(new Float32Array([0, NaN, 1])), 'animations[0].samplers[0].input[1]'],
    ['non-finite value', (d) => walkSampler(d, 0).getOutput()!.setArray(new Float32Array([0, 2, 0, 0, Infinity, 1, 0, 2, 2])), 'animations[0].samplers[0].output[1]'],
    ['repeated time', (d) => walkSampler(d, 1).getInput()!.setArray(new Float32Array([0, 0.5, 0.5])), 'animations[0].samplers[1].input[2]'],
    ['decreasing time', (d) => walkSampler(d, 1).getInput()!.setArray(new Float32Array([0, 0.7, 0.6])), 'animations[0].samplers[1].input[2]'],
    ['negative time', (d) => walkSampler(d, 2).getInput()!.setArray(new Float32Array([-0.1, 0.5, 1])), 'animations[0].samplers[2].input[0]'],
    ['too few outputs', (d) => walkSampler(d, 0).getOutput()!.setArray(new Float32Array([0, 2, 0, 0, 2, 2])), 'animations[0].samplers[0].output'],
    ['cubic output not 3 per key', (d) => walkSampler(d, 3).getOutput()!.setArray(new Float32Array(4 * 3)), 'animations[0].samplers[3].output'],
    ['rotation output as VEC3', (d) => walkSampler(d, 1).getOutput()!.setType('VEC3').setArray(new Float32Array(9)), 'animations[0].samplers[1].output'],
    ['zero rotation key', (d) => walkSampler(d, 1).getOutput()!.setArray(new Float32Array(12)), 'animations[0].samplers[1].output[0]'],
    ['bad interpolation', (d) => walkSampler(d, 0).setInterpolation('SMOOTH' as never), 'animations[0].samplers[0].interpolation'],
    ['no channels', (d) => d.getRoot().listAnimations()[1].listChannels().forEach((c) => c.dispose()), 'animations[1].channels'],
  ];
  for (const [label, mutate, field] of cases) {
    const { document } = figure();
    mutate(document);
    expectRendererError(() => readAnimatedModel(document), 'INVALID_ANIMATION', field, undefined, label);
  }
});

test('weights channels must target a node with as many morph targets as outputs per key', () => {
  {
    const { document, nodes } = figure();
    const sampler = document.createAnimationSampler().setInput(document.createAccessor().setType('SCALAR').setArray(new Float32Array([0, 1]))).setOutput(document.createAccessor().setType('SCALAR').setArray(new Float32Array([0, 1])));
    document.createAnimation('Bad').addSampler(sampler).addChannel(document.createAnimationChannel().setTargetNode(nodes.hips).setTargetPath('weights').setSampler(sampler));
    expectRendererError(() => readAnimatedModel(document), 'INVALID_ANIMATION', 'animations[2].channels[0].target.node', /no morph targets/);
  }
  {
    const { document } = figure();
    const weights = document.getRoot().listAnimations()[1].listSamplers()[2];
    weights.getOutput()!.setArray(new Float32Array([0, 0, 1, 1, 0, 0]));
    expectRendererError(() => readAnimatedModel(document), 'INVALID_ANIMATION', 'animations[1].channels[2].sampler', /2 morph weights/);
  }
});

test('model errors: skin weights, joint indices, missing joints, primitive mode, incomplete or out-of-range indices, inverse bind matrices', () => {
  const primitiveOf = (d: Document): ReturnType<ReturnType<Document['createPrimitive']>['setMode']> => d.getRoot().listMeshes()[bodyMeshIndex(d)].listPrimitives()[0];
  const at = (d: Document, suffix: string): string => `modelAsset.meshes[${bodyMeshIndex(d)}].primitives[0]${suffix}`;
  const cases: [(d: Document) => void, (d: Document) => string][] = [
    [(d) => { const w = primitiveOf(d).getAttribute('WEIGHTS_0')!; const a = w.getArray()!.slice(); a.fill(0, 4 * 5, 4 * 6); w.setArray(a); }, (d) => at(d, '.attributes.WEIGHTS_0[5]')],
    [(d) => { const w = primitiveOf(d).getAttribute('WEIGHTS_0')!; const a = w.getArray()!.slice(); a[4 * 7] = -0.5; w.setArray(a); }, (d) => at(d, '.attributes.WEIGHTS_0[7]')],
    [(d) => { const j = primitiveOf(d).getAttribute('JOINTS_0')!; const a = j.getArray()!.slice(); a[4 * 3] = 9; j.setArray(a); }, (d) => at(d, '.attributes.JOINTS_0[3]')],
    [(d) => primitiveOf(d).setAttribute('JOINTS_0', null), (d) => at(d, '.attributes.JOINTS_0')],
    [(d) => { primitiveOf(d).setAttribute('JOINTS_0', null).setAttribute('WEIGHTS_0', null); }, (d) => at(d, '.attributes.JOINTS_0')],
    [(d) => primitiveOf(d).setMode(1), (d) => at(d, '.mode')],
    [(d) => primitiveOf(d).getAttribute('NORMAL')!.setArray(new Float32Array(9)), (d) => at(d, '.attributes.NORMAL')],
    [(d) => { const i = primitiveOf(d).getIndices()!; i.setArray(i.getArray()!.slice(0, -1)); }, (d) => at(d, '.indices')],
    [(d) => { const i = primitiveOf(d).getIndices()!; const a = i.getArray()!.slice(); a[4] = 999; i.setArray(a); }, (d) => at(d, '.indices')],
    [(d) => d.getRoot().listSkins()[0].getInverseBindMatrices()!.setArray(new Float32Array(16 * 2)), () => 'modelAsset.skins[0].inverseBindMatrices'],
  ];
  for (const [mutate, field] of cases) {
    const { document } = figure();
    mutate(document);
    expectRendererError(() => readAnimatedModel(document, { field: 'modelAsset' }), 'INVALID_MODEL', field(document));
  }
});

test('clip asset errors: a separate clip file targeting nodes the model lacks, unknown animations, duplicate ids, bad profiles', () => {
  const model = readAnimatedModel(createRiggedFigure().document, { field: 'modelAsset' });
  const clipFile = new Document();
  clipFile.createBuffer();
  const hips = clipFile.createNode('Hips');
  const tail = clipFile.createNode('Tail');
  hips.addChild(tail);
  const sampler = clipFile.createAnimationSampler().setInput(clipFile.createAccessor().setType('SCALAR').setArray(new Float32Array([0, 1]))).setOutput(clipFile.createAccessor().setType('VEC4').setArray(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1])));
  clipFile.createAnimation('Wag').addSampler(sampler)
    .addChannel(clipFile.createAnimationChannel().setTargetNode(hips).setTargetPath('rotation').setSampler(sampler))
    .addChannel(clipFile.createAnimationChannel().setTargetNode(tail).setTargetPath('rotation').setSampler(sampler));
  expectRendererError(() => createClipLibrary(model, [{ id: 'wag', document: clipFile }]), 'INVALID_ANIMATION', 'clipAssets[0].animations[0].channels[1].target.node', /"Tail"/);
  expectRendererError(() => createClipLibrary(model, [{ id: 'walk', animation: 'Run' }]), 'INVALID_OPTION', 'clipAssets[0].animation', /no animation named "Run"/);
  expectRendererError(() => createClipLibrary(model, [{ id: 'walk', animation: 7 }]), 'INVALID_OPTION', 'clipAssets[0].animation');
  expectRendererError(() => createClipLibrary(model, [{ id: 'a', animation: 'Walk' }, { id: 'a', animation: 'Idle' }]), 'INVALID_OPTION', 'clipAssets[1].id');
  expectRendererError(() => createClipLibrary(model, [{ id: 'a', animation: 'Walk', movementProfile: { rootMotion: 'sideways' as never } }]), 'INVALID_OPTION', 'clipAssets[0].movementProfile.rootMotion');
  expectRendererError(() => createClipLibrary(model, [{ id: 'a', animation: 'Walk', movementProfile: { distancePerLoop: -1 } }]), 'INVALID_OPTION', 'clipAssets[0].movementProfile.distancePerLoop');
  expectRendererError(() => createClipLibrary(model, [{ id: 'a', animation: 'Walk', movementProfile: { rootNode: 'Pelvis' } }]), 'INVALID_OPTION', 'clipAssets[0].movementProfile.rootNode');
  // Without the Tail channel every target exists in the model, and the clip binds by name.
  clipFile.getRoot().listAnimations()[0].listChannels()[1].dispose();
  const bound = createClipLibrary(model, [{ id: 'wag', document: clipFile }]).clips.get('wag')!;
  assert.equal(bound.clip.channels[0].node, model.nodes.findIndex((n) => n.name === 'Hips'));
});

test('beat, route, prop and terrain errors name the offending option', () => {
  const { library } = createFigureSetup();
  const route = [{ position: [0, 0, 0], arriveMs: 0 }, { position: [0, 0, 2], arriveMs: 2000 }];
  const beat = { id: 'a', order: 0, clipId: 'walk', durationMs: 1000 };
  const timeline = (options: Record<string, unknown>): unknown => createSceneTimeline(library, { beats: [beat], route, ...options });
  expectRendererError(() => timeline({ beats: [beat, { ...beat, id: 'b', clipId: 'run' }] }), 'INVALID_OPTION', 'beats[1].clipId', /unknown clip "run"/);
  expectRendererError(() => timeline({ beats: [] }), 'INVALID_OPTION', 'beats');
  expectRendererError(() => timeline({ beats: [beat, { ...beat }] }), 'INVALID_OPTION', 'beats[1].id', /duplicate/);
  expectRendererError(() => timeline({ beats: [{ ...beat, durationMs: 0 }] }), 'INVALID_OPTION', 'beats[0].durationMs');
  expectRendererError(() => timeline({ beats: [{ ...beat, order: NaN }] }), 'INVALID_OPTION', 'beats[0].order');
  expectRendererError(() => timeline({ beats: [{ ...beat, blend: { inMs: 600, outMs: 500 } }] }), 'INVALID_OPTION', 'beats[0].blend');
  expectRendererError(() => timeline({ beats: [{ ...beat, blend: { inMs: -1 } }] }), 'INVALID_OPTION', 'beats[0].blend.inMs');
  expectRendererError(() => timeline({ beats: [{ ...beat, movementRequirement: { kind: 'fly' } }] }), 'INVALID_OPTION', 'beats[0].movementRequirement.kind');
  expectRendererError(() => timeline({ beats: [{ ...beat, movementRequirement: { kind: 'travel', distance: -2 } }] }), 'INVALID_OPTION', 'beats[0].movementRequirement.distance');
  expectRendererError(() => timeline({ route: [route[0], { position: [0, 0, NaN], arriveMs: 100 }] }), 'INVALID_OPTION', 'route[1].position[2]');
  expectRendererError(() => timeline({ route: [route[0], { position: [0, Infinity, 1], arriveMs: 100 }] }), 'INVALID_OPTION', 'route[1].position[1]');
  expectRendererError(() => timeline({ route: [route[0], { position: [1, 0, 1], arriveMs: Number.NaN }] }), 'INVALID_OPTION', 'route[1].arriveMs');
  expectRendererError(() => timeline({ route: [...route, { position: [1, 0, 1], arriveMs: 1500 }] }), 'INVALID_OPTION', 'route[2].arriveMs', /must not decrease/);
  expectRendererError(() => timeline({ route: [] }), 'INVALID_OPTION', 'route');
  expectRendererError(() => timeline({ props: [{ kind: '', position: [0, 0, 0] }] }), 'INVALID_OPTION', 'props[0].kind');
  expectRendererError(() => timeline({ props: [{ kind: 'crate', position: [0, 0] }] }), 'INVALID_OPTION', 'props[0].position');
  expectRendererError(() => timeline({ terrain: () => Number.NaN }), 'INVALID_OPTION', 'terrain');
  expectRendererError(() => timeline({ terrain: 3 }), 'INVALID_OPTION', 'terrain');
});
