/**
 * The generated WESL module `package::raster::generated_layout`: the raster records as WGSL structs,
 * the shared constants and every binding declaration, all from the TypeScript tables
 * (raster-layout.ts, raster-bindings.ts), so a struct, constant or binding has one definition.
 */
import { structLayoutToWgsl } from '../../gpu-layout/struct-layout.ts';
import { bindingDeclaration } from '../../gpu-layout/bindings.ts';
import { rasterBindings } from './raster-bindings.ts';
import { rasterConstants, rasterRecordLayouts } from './raster-layout.ts';

/** Module key of the generated layout (linker source path). */
export const rasterLayoutModuleKey = 'raster/generated_layout.wesl';

export function rasterLayoutModule(): string {
  const structs = Object.values(rasterRecordLayouts).map(structLayoutToWgsl).join('\n');
  const constants = Object.entries(rasterConstants)
    .map(([name, value]) => `const ${name}: u32 = ${value >>> 0}u;`)
    .join('\n');
  const bindings = Object.entries(rasterBindings)
    .map(([name, spec]) => bindingDeclaration(name, spec))
    .join('\n');
  return `${structs}\n${constants}\n\n${bindings}\n`;
}
