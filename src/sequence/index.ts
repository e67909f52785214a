// Sequences: frame lists, output patterns, turntables, glTF animation/variant sequences, one renderer
// updated in place over a sequence, and atomic frame files.
export { parseFrameList, checkFrameNumbers, maxSequenceFrames } from './frame-list.ts';
export { expandOutputPattern, outputPaths, fileSafeName, hasFramePlaceholder, hasVariantPlaceholder, hasCameraPlaceholder, type OutputPatternValues } from './output-pattern.ts';
export { turntableCamera, checkTurntable, type TurntableOptions } from './turntable.ts';
export { planGltfSequence, poseGltfSequenceItem, gltfSequence, sequencePatternValues, type GltfSequenceOptions, type GltfSequenceItem, type GltfSequenceFrame } from './gltf-sequence.ts';
export { createSequenceRenderer, sameTopology, type SequenceRenderer, type SequenceRendererOptions, type SequenceRendererSettings } from './sequence-renderer.ts';
// Frame files are written by src/io (the one place touching files); re-exported where they were published.
export { writeFrameFile, frameFileExists } from '../io/frame-files.ts';
