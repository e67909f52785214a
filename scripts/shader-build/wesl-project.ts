/**
 * The WESL project of the package: every `src/**\/*.wesl` file plus the layout modules generated
 * from the TypeScript tables (the path tracer's and the raster's). A file's module path is its
 * path under src/ with kebab-case segments turned into snake_case (WESL module names are
 * identifiers): src/accel/bvh-traversal.wesl is `package::accel::bvh_traversal`.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join, relative, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { link, type LinkedWesl } from 'wesl/core';
import { rasterLayoutModule, rasterLayoutModuleKey } from '../../src/raster/gpu/raster-wgsl-layout.ts';
import { layoutModules, type WeslSources } from './layout-modules.ts';

export const srcRoot = fileURLToPath(new URL('../../src/', import.meta.url));

function walk(dir: string, out: string[]): void {
  for (const entry of readdirSync(dir, { withFileTypes: true })) {
    const path = join(dir, entry.name);
    if (entry.isDirectory()) walk(path, out);
    else if (entry.name.endsWith('.wesl')) out.push(path);
  }
}

/** `accel/bvh-traversal.wesl` -> `accel/bvh_traversal.wesl` (the linker's key for the module). */
export function moduleKey(relativePath: string): string {
  return relativePath.split(sep).join('/').replace(/-/g, '_');
}

/** Every WESL source of the package, keyed by module path, layout modules included. */
export function weslProjectSources(): WeslSources {
  const files: string[] = [];
  walk(srcRoot, files);
  const sources: WeslSources = {};
  for (const file of files.sort()) {
    const key = moduleKey(relative(srcRoot, file));
    if (sources[key] !== undefined) throw new Error(`two WESL files map to module ${key}`);
    sources[key] = readFileSync(file, 'utf8');
  }
  for (const [key, text] of Object.entries({ ...layoutModules(), [rasterLayoutModuleKey]: rasterLayoutModule() })) {
    if (sources[key] !== undefined) throw new Error(`src/${key} collides with a generated layout module`);
    sources[key] = text;
  }
  return sources;
}

/** `package::a::b` -> the linker's root module name `a/b`. */
export function rootModuleName(modulePath: string): string {
  const parts = modulePath.split('::');
  if (parts[0] !== 'package') throw new Error(`program module ${modulePath} must start with package::`);
  return parts.slice(1).join('/');
}

/** Links one root module of the project (optionally an extra source, e.g. a test kernel). */
export async function linkProgram(modulePath: string, extra: WeslSources = {}, sources: WeslSources = weslProjectSources(), conditions: Readonly<Record<string, boolean>> = {}): Promise<LinkedWesl> {
  return link({ weslSrc: { ...sources, ...extra }, rootModuleName: rootModuleName(modulePath), conditions: { ...conditions } });
}
