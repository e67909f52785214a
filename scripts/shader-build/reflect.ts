/**
 * Reflection of a linked WGSL program through the WESL parser's syntax tree: which resource
 * bindings (`@group @binding var`) and which `override` constants the program declares. The linker
 * keeps only declarations reachable from the entry points, so these are exactly what the program uses.
 */
import { parseSrcModule } from 'wesl/core';

export interface ProgramReflection {
  bindings: { name: string; group: number; binding: number }[];
  overrides: string[];
}

interface AttributeNode {
  attribute?: { name?: string; params?: { expression?: { kind?: string; value?: string } }[] };
}

interface DeclNode {
  kind: string;
  name?: { decl?: { ident?: { originalName?: string } } };
  attributes?: AttributeNode[];
}

function attributeValue(decl: DeclNode, name: string): number | undefined {
  const attr = decl.attributes?.find((a) => a.attribute?.name === name)?.attribute;
  const literal = attr?.params?.[0]?.expression;
  if (literal?.kind !== 'literal' || literal.value === undefined) return undefined;
  return Number.parseInt(literal.value, 10);
}

export function reflectProgram(wgsl: string, label: string): ProgramReflection {
  const ast = parseSrcModule({ modulePath: label, debugFilePath: `${label}.wgsl`, src: wgsl });
  const decls = ast.moduleElem.decls as unknown as DeclNode[];
  const bindings: ProgramReflection['bindings'] = [];
  const overrides: string[] = [];
  for (const decl of decls) {
    const name = decl.name?.decl?.ident?.originalName;
    if (name === undefined) continue;
    if (decl.kind === 'override') overrides.push(name);
    if (decl.kind !== 'gvar') continue;
    const group = attributeValue(decl, 'group');
    const binding = attributeValue(decl, 'binding');
    if (group === undefined || binding === undefined) continue;
    bindings.push({ name, group, binding });
  }
  return { bindings, overrides };
}
