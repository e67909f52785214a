export {
  fresnelDielectric,
  ggxD,
  gltfBsdfEval,
  gltfBsdfPdf,
  gltfDeltaAlpha,
  gltfSpecularProbability,
  smithG1,
  smithHeightCorrelatedV,
  type GltfBsdfMaterial,
  type Vec3,
} from './gltf-bsdf-reference.ts';
