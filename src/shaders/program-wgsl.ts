/**
 * The linked WGSL of a program: from the generated module bundled with the code for the groups a
 * first frame needs, from its group's own module (dynamically imported, once) for the others.
 */
import { eagerProgramWgsl, lazyProgramWgsl } from './program-sources.generated.ts';
import { programSpecs, type ProgramName } from './programs.ts';

const eager: Readonly<Record<string, string>> = eagerProgramWgsl;
const lazy: Readonly<Record<string, () => Promise<{ wgsl: Readonly<Record<string, string>> }>>> = lazyProgramWgsl;

/** The program's linked WGSL, loading its group's module if that is not loaded yet. */
export async function programWgsl(program: ProgramName): Promise<string> {
  const code = eager[program] ?? (await lazy[programSpecs[program].group]!()).wgsl[program];
  if (code === undefined) throw new Error(`program ${program} has no generated WGSL (run npm run generate)`);
  return code;
}
