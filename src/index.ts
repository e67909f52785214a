// Public facade of @plasius/gpu-renderer: one re-export per subsystem.
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
