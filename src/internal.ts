// Every subsystem's exports, public or not: the entry tests, benchmarks and scripts use for the
// building blocks the public API (src/index.ts) leaves out. It is not a package export, so nothing
// here is a promise to users; code outside this repository imports the package root only.
export * from './errors/index.ts';
export * from './gpu/index.ts';
export * from './gpu-layout/index.ts';
export * from './scene/index.ts';
export * from './accel/index.ts';
export * from './lighting/index.ts';
export * from './pathtracer/index.ts';
export * from './film/index.ts';
export * from './runtime/index.ts';
export * from './planning/index.ts';
export * from './transport/index.ts';
export * from './xr/index.ts';
export * from './animation/index.ts';
export * from './io/index.ts';
export * from './raster/index.ts';
export * from './sequence/index.ts';
export * from './materials/index.ts';
