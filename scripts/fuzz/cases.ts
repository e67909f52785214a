/** The four case kinds and how a case is made from (seed, kind, index). */
import { makeEnvCase } from './cases-env.ts';
import { makeGltfCase, type LoaderCase } from './cases-gltf.ts';
import { makeOptionsCase, type OptionsCase } from './cases-options.ts';
import { makeSceneCase } from './cases-scene.ts';
import { buildEnvCorpus, type EnvSeed } from './corpus-env.ts';
import { buildGltfCorpus, type GltfSeed } from './corpus-gltf.ts';
import { caseSeed, createRandom } from './random.ts';
import type { UriContext } from './sandbox.ts';

export const CASE_KINDS = ['gltf', 'scene', 'env', 'options'] as const;
export type CaseKind = (typeof CASE_KINDS)[number];

export interface Corpora {
  gltf: GltfSeed[];
  env: EnvSeed[];
}

export async function buildCorpora(): Promise<Corpora> {
  return { gltf: await buildGltfCorpus(), env: buildEnvCorpus() };
}

export function makeCase(kind: CaseKind, index: number, seed: number, corpora: Corpora, context: UriContext & { hasFifo: boolean }): LoaderCase | OptionsCase {
  const random = createRandom(caseSeed(seed, kind, index));
  if (kind === 'gltf') return makeGltfCase(corpora.gltf, random, context);
  if (kind === 'scene') return makeSceneCase(corpora.gltf, corpora.env, random, context);
  if (kind === 'env') return makeEnvCase(corpora.env, random, context);
  return makeOptionsCase(random);
}
