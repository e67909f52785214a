// `npm run generate`: links every GPU program of src/shaders/programs.ts with the WESL linker
// (imports written in the .wesl files themselves; layout modules generated from the TypeScript
// tables), reflects the bindings and override constants each program uses, and writes the
// generated program modules under src/shaders/ (shader-build/programs.ts), the only shader text
// the runtime reads (without comments: shader-build/compact-wgsl.ts).
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { generatePrograms } from './shader-build/programs.ts';
import { weslProjectSources } from './shader-build/wesl-project.ts';
import { embedCodecs } from './codec-build/embed-codecs.ts';
import { generateOidnWeightModules } from './oidn-weights.ts';
import { materialLayerReferencesModule, materialLayerReferencesPath } from './shader-build/material-layers.ts';

const sources = weslProjectSources();
let programCount: number;
try {
  programCount = await generatePrograms(sources);
} catch (error) {
  console.error(`generate: ${(error as Error).message}`);
  process.exit(1);
}
const root = fileURLToPath(new URL('..', import.meta.url));
const layerReferences = materialLayerReferencesModule();
const layerReferencesPath = `${root}${materialLayerReferencesPath}`;
if (!existsSync(layerReferencesPath) || readFileSync(layerReferencesPath, 'utf8') !== layerReferences) writeFileSync(layerReferencesPath, layerReferences);
const codecs = embedCodecs();
for (const codec of codecs) {
  const path = `${root}${codec.path}`;
  if (!existsSync(path) || readFileSync(path, 'utf8') !== codec.text) writeFileSync(path, codec.text);
}
const weights = generateOidnWeightModules();
console.log(`generate: ${programCount} programs linked, ${codecs.length} codec modules, ${weights.length} OIDN weights`);
