import { fail } from '../../errors/validate.ts';
import type { ModelMesh, ModelNode } from '../model/model-types.ts';
import type { AnimationChannelData, AnimationClip } from './clip-types.ts';

/** What binding a clip needs of a model: node names and meshes, and each mesh's morph target count. */
type ModelTargets = { readonly nodes: readonly Pick<ModelNode, 'name' | 'mesh'>[]; readonly meshes: readonly Pick<ModelMesh, 'targetCount'>[] };

/**
 * Checks that every channel of a clip can drive the model: the node exists and a `weights` channel
 * has one output per morph target of the node's mesh.
 */
export function checkClipTargets(model: ModelTargets, clip: AnimationClip): void {
  for (const channel of clip.channels) {
    const node = model.nodes[channel.node];
    if (node === undefined) fail('INVALID_ANIMATION', `${channel.field}.target.node`, `node ${channel.node} does not exist`);
    if (channel.path !== 'weights') continue;
    const targetCount = node.mesh >= 0 ? model.meshes[node.mesh].targetCount : 0;
    if (targetCount === 0) fail('INVALID_ANIMATION', `${channel.field}.target.node`, `weights channel targets node ${JSON.stringify(node.name)}, which has no morph targets`);
    if (channel.sampler.components !== targetCount) {
      fail('INVALID_ANIMATION', `${channel.field}.sampler`, `animates ${channel.sampler.components} morph weights, node ${JSON.stringify(node.name)} has ${targetCount} morph targets`);
    }
  }
}

/**
 * Binds a clip read from another document (a separate clip file, as Mixamo exports them) to a
 * model by node name. A channel whose node name the model lacks, or has twice, is an
 * `INVALID_ANIMATION` error naming the channel.
 */
export function bindClipByNodeName(model: ModelTargets, clip: AnimationClip, id: string = clip.id): AnimationClip {
  const byName = new Map<string, number>();
  const duplicated = new Set<string>();
  model.nodes.forEach((node, i) => {
    if (byName.has(node.name)) duplicated.add(node.name);
    else byName.set(node.name, i);
  });
  const channels: AnimationChannelData[] = clip.channels.map((channel) => {
    const name = channel.nodeName;
    if (name === '') fail('INVALID_ANIMATION', `${channel.field}.target.node`, 'channel targets an unnamed node, which cannot be matched to the model');
    const node = byName.get(name);
    if (node === undefined) fail('INVALID_ANIMATION', `${channel.field}.target.node`, `channel targets node ${JSON.stringify(name)}, which the model does not have`);
    if (duplicated.has(name)) fail('INVALID_ANIMATION', `${channel.field}.target.node`, `the model has several nodes named ${JSON.stringify(name)}`);
    return { ...channel, node };
  });
  const bound = { ...clip, id, channels };
  checkClipTargets(model, bound);
  return bound;
}
