export { encodePng, type Rgba8Image } from './png.ts';
export { writePng } from './png-node.ts';
export * from './files/index.ts';
