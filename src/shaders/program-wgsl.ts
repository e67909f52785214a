/**
 * The linked WGSL of a program, from its group's generated module: imported on first use (once),
 * so bundlers put each group's WGSL in a chunk of its own that only the apps using it download.
 */
import { programWgslModules } from './program-sources.generated.ts';
import { programSpecs, type ProgramName } from './programs.ts';

const modules: Readonly<Record<string, () => Promise<{ wgsl: Readonly<Record<string, string>> }>>> = programWgslModules;

/** The program's linked WGSL, loading its group's module if that is not loaded yet. */
export async function programWgsl(program: ProgramName): Promise<string> {
  const code = (await modules[programSpecs[program].group]!()).wgsl[program];
  if (code === undefined) throw new Error(`program ${program} has no generated WGSL (run npm run generate)`);
  return code;
}
