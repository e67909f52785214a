// The browser build, dist/browser: what the package's `exports` give bundlers that set the
// "browser" condition (esbuild for platform browser, webpack for web targets, Vite for the
// client). It is dist/esm's module graph (modules.ts: the same code, module for module, so
// consumers' bundlers tree-shake it as well) with three dependencies carried along as browser-safe
// copies in dist/browser/vendor (vendor.ts, vendored.ts), so that no bundler needs configuration,
// and the root's statements moved to modules of their own under `export *` (root.ts), so that
// esbuild's code splitting loads only what an app imports.
// Node.js resolves neither the "browser" condition nor anything in here.
import { rmSync } from 'node:fs';
import { copyBrowserModules, type ModuleCopyReport } from './modules.ts';
import { splitRootModule, type RootSplitReport } from './root.ts';
import { buildVendorModules, type VendorReport } from './vendor.ts';

export { vendoredModules } from './vendored.ts';

export interface BrowserBuildReport {
  modules: ModuleCopyReport;
  root: RootSplitReport;
  vendor: VendorReport;
}

/**
 * Writes the browser build of the ESM build in `esmDir` to `outDir` (emptied first). `root` is
 * where the vendored dependencies resolve from (the repository).
 */
export async function buildBrowserDist(options: { root: string; esmDir: string; outDir: string }): Promise<BrowserBuildReport> {
  rmSync(options.outDir, { recursive: true, force: true });
  const modules = await copyBrowserModules(options.esmDir, options.outDir);
  const root = await splitRootModule(options.outDir);
  const vendor = await buildVendorModules(options.root, options.outDir);
  return { modules, root, vendor };
}
