/**
 * Explicit WGSL composition: each module names the modules it requires, and a program is the
 * dependency-ordered concatenation of the modules its entry modules need, each exactly once.
 * Specialisation goes through WGSL `override` constants set at pipeline creation, never through
 * edits of shader text.
 */
export interface WgslModule {
  readonly name: string;
  readonly requires: readonly string[];
  readonly source: string;
}

export type WgslModuleRegistry = ReadonlyMap<string, WgslModule>;

export function createWgslModuleRegistry(modules: readonly WgslModule[]): WgslModuleRegistry {
  const registry = new Map<string, WgslModule>();
  for (const m of modules) {
    if (registry.has(m.name)) throw new Error(`WGSL module ${m.name} is defined twice`);
    registry.set(m.name, m);
  }
  for (const m of modules) {
    for (const r of m.requires) if (!registry.has(r)) throw new Error(`WGSL module ${m.name} requires unknown module ${r}`);
  }
  return registry;
}

/** Dependency order (depth-first post-order) of the modules reachable from `entries`. */
export function resolveWgslModules(registry: WgslModuleRegistry, entries: readonly string[]): WgslModule[] {
  const ordered: WgslModule[] = [];
  const state = new Map<string, 'visiting' | 'done'>();
  const visit = (name: string, chain: readonly string[]): void => {
    const s = state.get(name);
    if (s === 'done') return;
    if (s === 'visiting') throw new Error(`WGSL module cycle: ${[...chain, name].join(' -> ')}`);
    const m = registry.get(name);
    if (!m) throw new Error(`unknown WGSL module ${name}`);
    state.set(name, 'visiting');
    for (const r of m.requires) visit(r, [...chain, name]);
    state.set(name, 'done');
    ordered.push(m);
  };
  for (const e of entries) visit(e, []);
  return ordered;
}

export function composeWgsl(registry: WgslModuleRegistry, entries: readonly string[]): string {
  return resolveWgslModules(registry, entries)
    .map((m) => `// ---- module ${m.name} ----\n${m.source.trim()}\n`)
    .join('\n');
}
