/**
 * `loadGltfScene`: a glTF 2.0 asset (.glb or .gltf) -> the renderer's scene description.
 */
import type { Camera, Document, Material, Mesh, Node, Scene } from '@gltf-transform/core';
import type { InstancedMesh, Light, Variant } from '@gltf-transform/extensions';
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import type {
  WavefrontCameraInput,
  WavefrontImageInput,
  WavefrontInstanceInput,
  WavefrontMaterialInput,
  WavefrontMeshInput,
  WavefrontPunctualLightInput,
  WavefrontTextureInput,
  WavefrontTextureRefInput,
} from '../../scene/types.ts';
import { accessorToFloat32 } from '../accessors.ts';
import { cameraFromNode, framingCamera, type GltfBounds, type GltfCameraInfo } from './cameras.ts';
import { readGltfDocument, type GltfSource } from './document-reader.ts';
import { failGltf, pointer } from './errors.ts';
import { primitiveGeometry, type PrimitiveGeometryOptions } from './geometry.ts';
import { usesPrimitiveRestart } from './primitive/read-primitive.ts';
import { worldLight } from './lights.ts';
import { defaultGltfMaterial, mapMaterial } from './materials.ts';
import { composeTrs, determinant3, IDENTITY, multiply, transformPoint, type Mat4 } from '../../math/mat4.ts';
import { flattenNodes } from './node-flattening.ts';
import { chooseAnimation, needsRig, poseRig, poseTime, readRig, type GltfAnimationInfo, type GltfPoseOptions, type GltfRig } from './posing.ts';
import { withMikkTSpaceTangents } from './tangents.ts';
import { TextureTable } from './textures.ts';
import type { EnvironmentMap } from '../../lighting/environment-map.ts';
import { createNeutralEnvironment } from '../../lighting/neutral-environment.ts';
import { sceneLightSources } from '../../lighting/scene-light-sources.ts';
import { listVariants, selectVariant, variantMaterial } from './variants.ts';
import { validateGltfLoadOptions, type GltfLoadOptions } from './load-options.ts';
import { acceptScene, type SceneOrigins } from './scene-acceptance.ts';
import { resolveResourcePolicy } from '../resource-policy.ts';
import type { VertexStreams } from './vertex-streams.ts';

export type { GltfLoadOptions } from './load-options.ts';

/**
 * A loaded glTF scene. Its own enumerable keys are exactly renderer scene keys, so
 * `createWavefrontPathTracingComputeRenderer({ ...scene, width, height })` renders it; the
 * metadata below are non-enumerable properties, left out by spreading.
 *
 * - Every glTF primitive the scene uses is one entry of `meshes` (its own material index); a glTF
 *   mesh placed by several nodes (or EXT_mesh_gpu_instancing instances) stays one set of entries
 *   with several `instances`, each carrying the node's world matrix (column-major).
 * - `materials` holds one entry per glTF material, in asset order, plus the glTF default material
 *   at the end when some primitive has none.
 * - Skinned and morphed meshes are posed (skinned on the CPU) at `time` of `animation` (default the
 *   first animation at 0 s); animated nodes place meshes, cameras and lights where the animation has them.
 * - `camera` is the chosen glTF camera; its aspect ratio is the renderer's width / height (the glTF
 *   aspectRatio is not used). Without a camera it frames the scene bounds (`frameBounds`): a raised
 *   three-quarter view of their centre (azimuth 30 degrees from +Z towards +X, elevation 25, 45
 *   degree vertical field of view) at the nearest distance where the whole box is in view.
 */
export interface GltfScene {
  meshes: WavefrontMeshInput[];
  instances: WavefrontInstanceInput[];
  materials: WavefrontMaterialInput[];
  textures: WavefrontTextureInput[];
  images: WavefrontImageInput[];
  camera: WavefrontCameraInput;
  lights: WavefrontPunctualLightInput[];
  /** The built-in neutral environment, with `defaultLighting: 'neutral'` where the asset has no light. */
  environmentMap?: EnvironmentMap;
  /** Non-enumerable. Things skipped, converted or dropped (points and lines, unsupported optional extensions, ...). */
  readonly warnings: readonly string[];
  /** Non-enumerable. Every camera placed in the scene, in node order. */
  readonly cameras: readonly GltfCameraInfo[];
  /** Non-enumerable. The asset's KHR_materials_variants names. */
  readonly variants: readonly string[];
  /** Non-enumerable. World-space bounds of the instanced geometry; undefined for an empty scene. */
  readonly bounds: GltfBounds | undefined;
  /** Non-enumerable. The asset's extensionsUsed. */
  readonly extensionsUsed: readonly string[];
  /** Non-enumerable. The @gltf-transform document the scene was built from. */
  readonly document: Document;
  /** Non-enumerable. The asset's animations, in asset order. */
  readonly animations: readonly GltfAnimationInfo[];
  /** Non-enumerable. The animation the scene is posed at; null for none (nodes at their authored transforms). */
  readonly animation: GltfAnimationInfo | null;
  /** Non-enumerable. The time the scene is posed at, in seconds. */
  readonly time: number;
  /** Non-enumerable. The KHR_materials_variants variant shown; undefined for the default materials. */
  readonly variant: string | undefined;
  /**
   * Non-enumerable. The same asset posed again without reading it again: options left out keep this
   * scene's (`{ time: 1.5 }` moves along the same animation). Materials, textures and images are the
   * same arrays in every pose, so only meshes, instances, camera and lights change; unanimated meshes
   * are the same objects from one pose to the next.
   */
  pose(options?: GltfPoseAgainOptions): Promise<GltfScene>;
}

/** What `GltfScene.pose` may change. */
export interface GltfPoseAgainOptions extends GltfPoseOptions {
  camera?: number | string;
  variant?: string;
}

interface MeshEntry {
  index: number;
  min: [number, number, number];
  max: [number, number, number];
}

function optionError(field: string, message: string): GpuRendererError {
  return new GpuRendererError('INVALID_OPTION', message, { field });
}

function indexMap<T>(items: readonly T[]): Map<T, number> {
  return new Map(items.map((item, i) => [item, i]));
}

function pickScene(document: Document, choice: number | string | undefined, warnings: string[]): { roots: Node[]; scene: Scene | undefined } {
  const root = document.getRoot();
  const scenes = root.listScenes();
  let scene: Scene | undefined;
  if (typeof choice === 'number') {
    scene = scenes[choice];
    if (!Number.isInteger(choice) || scene === undefined) throw optionError('scene', `scene index ${choice} is out of range (the asset has ${scenes.length} scenes)`);
  } else if (typeof choice === 'string') {
    scene = scenes.find((s) => s.getName() === choice);
    if (scene === undefined) throw optionError('scene', `no scene named ${JSON.stringify(choice)} (the asset has ${scenes.map((s) => JSON.stringify(s.getName())).join(', ') || 'none'})`);
  } else {
    scene = root.getDefaultScene() ?? scenes[0];
  }
  if (scene !== undefined) return { roots: scene.listChildren(), scene };
  warnings.push('the asset has no scene; rendering every root node');
  return { roots: root.listNodes().filter((n) => n.getParentNode() === null), scene: undefined };
}

/** UV set a material's tangent-space slots sample (normal, clearcoat normal, anisotropy), if any. */
function tangentSpaceTexCoord(material: WavefrontMaterialInput): number | undefined {
  const refs: Array<WavefrontTextureRefInput | undefined> = [material.normalTexture, material.clearcoatNormalTexture, material.anisotropyTexture];
  const ref = refs.find((r) => r !== undefined);
  if (ref === undefined) return material.anisotropyStrength !== undefined && material.anisotropyStrength !== 0 ? 0 : undefined;
  return ref.transform?.texCoord ?? ref.texCoord ?? 0;
}

function localBounds(positions: Float32Array): { min: [number, number, number]; max: [number, number, number] } {
  const min: [number, number, number] = [Infinity, Infinity, Infinity];
  const max: [number, number, number] = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      min[k] = Math.min(min[k], positions[i + k]);
      max[k] = Math.max(max[k], positions[i + k]);
    }
  }
  return { min, max };
}

/** Per-instance local matrices of EXT_mesh_gpu_instancing (TRS per instance), or undefined. */
function gpuInstances(node: Node, at: string): Mat4[] | undefined {
  const instancing = node.getExtension<InstancedMesh>('EXT_mesh_gpu_instancing');
  if (instancing === null) return undefined;
  const read = (semantic: string, size: number): Float32Array | undefined => {
    const accessor = instancing.getAttribute(semantic);
    if (accessor === null) return undefined;
    const values = accessorToFloat32(accessor);
    if (values.some((v) => !Number.isFinite(v))) failGltf(`${at}/extensions/EXT_mesh_gpu_instancing/attributes/${semantic}`, 'non-finite instance data');
    if (accessor.getElementSize() !== size) failGltf(`${at}/extensions/EXT_mesh_gpu_instancing/attributes/${semantic}`, `expected ${size} components per instance`);
    return values;
  };
  const t = read('TRANSLATION', 3);
  const r = read('ROTATION', 4);
  const s = read('SCALE', 3);
  const count = Math.max(t ? t.length / 3 : 0, r ? r.length / 4 : 0, s ? s.length / 3 : 0);
  const out: Mat4[] = [];
  for (let i = 0; i < count; i++) {
    const m: Mat4 = new Array<number>(16);
    composeTrs(t ?? [0, 0, 0], t ? 3 * i : 0, r ?? [0, 0, 0, 1], r ? 4 * i : 0, s ?? [1, 1, 1], s ? 3 * i : 0, m);
    out.push(m);
  }
  return out;
}

/** What loading reads once: the document, its materials and textures, the rig; posing reuses it. */
interface LoadedAsset {
  document: Document;
  extensionsUsed: string[];
  primitiveRestart: boolean;
  nodeIndex: Map<Node, number>;
  meshIndex: Map<Mesh, number>;
  cameraIndex: Map<Camera, number>;
  roots: Node[];
  table: TextureTable;
  materials: WavefrontMaterialInput[];
  materialIndex: Map<Material, number>;
  /** Index of the glTF default material in `materials`, when some primitive has no material. */
  defaultMaterial: number | undefined;
  /** The skeleton and animations; null for an asset that neither animates nor skins (nodes keep their matrices). */
  rig: GltfRig | null;
  /** Warnings of reading and material mapping (each pose adds its own). */
  warnings: string[];
  /** Unskinned mesh entries of the latest pose, reused by the next one when mesh, weights and variant match. */
  meshCache: Map<string, CachedMesh>;
  /** The neutral environment of `defaultLighting: 'neutral'`, baked once for every pose. */
  neutralEnvironment?: EnvironmentMap;
}

interface CachedMesh {
  meshes: WavefrontMeshInput[];
  /** JSON pointer of each mesh's primitive. */
  origins: string[];
  bounds: { min: [number, number, number]; max: [number, number, number] }[];
  warnings: string[];
}

/** The body of `loadGltfScene` (load-gltf-scene.ts), loaded on its first call. */
export async function readGltfScene(source: GltfSource, rawOptions: GltfLoadOptions = {}): Promise<GltfScene> {
  const options = validateGltfLoadOptions(rawOptions);
  const { signal } = options;
  signal?.throwIfAborted();
  const policy = await resolveResourcePolicy(options.resourcePolicy);
  const warnings: string[] = [];
  const { document } = await readGltfDocument(source, warnings, { signal, decoders: options.decoders, policy });
  signal?.throwIfAborted();
  const root = document.getRoot();
  const extensionsUsed = root.listExtensionsUsed().map((e) => e.extensionName);
  const rig = needsRig(document) ? readRig(document) : null;
  // Option errors before the expensive part (textures).
  selectVariant(document, options.variant);
  if (rig !== null) {
    chooseAnimation(rig.animations, options.animation);
  } else if (options.animation !== undefined && options.animation !== null) {
    throw optionError('animation', 'the asset has no animations');
  }
  poseTime(options.time);
  const { roots } = pickScene(document, options.scene, warnings);

  const table = new TextureTable(root.listTextures(), warnings, policy);
  const materials: WavefrontMaterialInput[] = [];
  const gltfMaterials = root.listMaterials();
  for (let i = 0; i < gltfMaterials.length; i++) materials.push(await mapMaterial(gltfMaterials[i], pointer('materials', i), table));
  // Appended up front so that every pose and variant of the asset shares one material list.
  const needsDefault = root.listMeshes().some((mesh) => mesh.listPrimitives().some((primitive) => primitive.getMaterial() === null));
  const defaultMaterial = needsDefault ? materials.push(defaultGltfMaterial()) - 1 : undefined;
  signal?.throwIfAborted();
  const asset: LoadedAsset = {
    document,
    extensionsUsed,
    primitiveRestart: usesPrimitiveRestart(document),
    nodeIndex: indexMap(root.listNodes()),
    meshIndex: indexMap(root.listMeshes()),
    cameraIndex: indexMap(root.listCameras()),
    roots,
    table,
    materials,
    materialIndex: indexMap(gltfMaterials),
    defaultMaterial,
    rig,
    warnings,
    meshCache: new Map(),
  };
  return poseAsset(asset, options);
}

/** The asset's scene for one pose, variant and camera choice (everything per pose; materials and textures shared). */
async function poseAsset(asset: LoadedAsset, options: GltfLoadOptions): Promise<GltfScene> {
  const { signal } = options;
  const { document, nodeIndex, materials } = asset;
  const variant = selectVariant(document, options.variant);
  const pose = asset.rig === null ? null : poseRig(asset.rig, options);
  const time = pose?.time ?? poseTime(options.time);
  const flat = flattenNodes(asset.roots, nodeIndex, pose === null ? undefined : (index) => pose.world(index));
  const warnings = [...asset.warnings];
  // Where each scene entry came from, for errors the renderer's validation raises (scene-acceptance.ts).
  const origins: SceneOrigins = { meshes: [], materials: asset.document.getRoot().listMaterials().map((_, i) => pointer('materials', i)), instances: [], lights: [], images: [] };

  const meshes: WavefrontMeshInput[] = [];
  const meshIndexOf = new Map<WavefrontMeshInput, number>();
  const previousCache = asset.meshCache;
  const meshCache = new Map<string, CachedMesh>();
  const meshEntries = async (mesh: Mesh, weights: readonly number[], skin: number): Promise<MeshEntry[]> => {
    const m = asset.meshIndex.get(mesh) ?? -1;
    const key = `${m}|${skin}|${variant?.getName() ?? ''}|${weights.join(',')}`;
    let cached = meshCache.get(key);
    if (cached === undefined && skin < 0) cached = previousCache.get(key);
    if (cached === undefined) {
      cached = await primitiveMeshes(asset, mesh, m, weights, skin < 0 || pose === null ? undefined : { jointMatrices: pose.jointMatrices(skin), jointCount: asset.rig!.skins[skin]!.joints.length }, variant);
    }
    if (!meshCache.has(key)) {
      meshCache.set(key, cached);
      warnings.push(...cached.warnings);
    }
    return cached.meshes.map((entry, k) => {
      let index = meshIndexOf.get(entry);
      if (index === undefined) {
        meshIndexOf.set(entry, (index = meshes.push(entry) - 1));
        origins.meshes.push(cached.origins[k]!);
      }
      return { index, ...cached.bounds[k]! };
    });
  };

  const instances: WavefrontInstanceInput[] = [];
  const cameras: GltfCameraInfo[] = [];
  const lights: WavefrontPunctualLightInput[] = [];
  const boundsMin: [number, number, number] = [Infinity, Infinity, Infinity];
  const boundsMax: [number, number, number] = [-Infinity, -Infinity, -Infinity];
  for (const { node, index, world } of flat) {
    const at = pointer('nodes', index);
    const name = node.getName();
    const mesh = node.getMesh();
    if (mesh !== null) {
      // Posed: the rig's weights (animated, else node then mesh defaults); unposed: node then mesh defaults.
      const nodeWeights = node.getWeights();
      const weights = pose !== null ? Array.from(pose.weights(index)) : nodeWeights.length > 0 ? nodeWeights : mesh.getWeights();
      const skin = pose === null ? -1 : asset.rig!.nodes[index]!.skin;
      const entries = await meshEntries(mesh, weights, skin);
      const locals = gpuInstances(node, at);
      // Section 3.7.3.1: a skinned mesh is placed by its joints alone; the vertices are in world space.
      const place = skin >= 0 ? IDENTITY : world;
      const transforms = locals === undefined ? [[...place]] : locals.map((local) => multiply(place, local));
      transforms.forEach((transform, k) => {
        const det = determinant3(transform);
        if (!Number.isFinite(det) || !transform.every(Number.isFinite)) failGltf(at, 'the world transform is not finite');
        if (Math.abs(det) < 1e-30) {
          warnings.push(`${at}${locals === undefined ? '' : ` instance ${k}`}: skipped, its world transform is singular (zero scale)`);
          return;
        }
        for (const entry of entries) {
          const id = `${name === '' ? `node ${index}` : name}${locals === undefined ? '' : `#${k}`}`;
          instances.push({ id, mesh: entry.index, transform });
          origins.instances.push(at);
          for (let c = 0; c < 8; c++) {
            const corner = [c & 1 ? entry.max[0] : entry.min[0], c & 2 ? entry.max[1] : entry.min[1], c & 4 ? entry.max[2] : entry.min[2]];
            const p = transformPoint(transform, corner);
            for (let a = 0; a < 3; a++) {
              boundsMin[a] = Math.min(boundsMin[a], p[a]);
              boundsMax[a] = Math.max(boundsMax[a], p[a]);
            }
          }
        }
      });
    }
    const camera = node.getCamera();
    if (camera !== null) {
      const ci = asset.cameraIndex.get(camera) ?? -1;
      const fallback = name === '' ? `camera ${ci}` : name;
      cameras.push({ name: camera.getName() === '' ? fallback : camera.getName(), cameraIndex: ci, nodeIndex: index, nodeName: name, camera: cameraFromNode(camera, world) });
    }
    const light = node.getExtension<Light>('KHR_lights_punctual');
    if (light !== null) {
      lights.push(worldLight(light, world));
      origins.lights.push(`${at}/extensions/KHR_lights_punctual`);
    }
  }
  asset.meshCache = meshCache;
  const bounds: GltfBounds | undefined = instances.length === 0 ? undefined : { min: boundsMin, max: boundsMax };
  const camera = chooseCamera(cameras, options.camera, bounds, options.aspectRatio);
  signal?.throwIfAborted();

  const scene: Pick<GltfScene, 'meshes' | 'instances' | 'materials' | 'textures' | 'images' | 'camera' | 'lights' | 'environmentMap'> = { meshes, instances, materials, textures: asset.table.textures, images: asset.table.images, camera, lights };
  if (options.defaultLighting === 'neutral' && sceneLightSources(scene).length === 0) scene.environmentMap = (asset.neutralEnvironment ??= createNeutralEnvironment());
  const chosen = cameras.find((c) => c.camera === camera);
  acceptScene(scene, origins, [{ camera, at: chosen === undefined ? '' : pointer('nodes', chosen.nodeIndex) }]);
  const poseAgain = (next: GltfPoseAgainOptions = {}): Promise<GltfScene> => {
    const merged: GltfLoadOptions = { ...options };
    for (const [key, value] of Object.entries(next)) if (value !== undefined) (merged as Record<string, unknown>)[key] = value;
    return poseAsset(asset, merged);
  };
  const metadata = {
    warnings,
    cameras,
    variants: listVariants(document).map((v) => v.getName()),
    bounds,
    extensionsUsed: asset.extensionsUsed,
    document,
    animations: asset.rig?.animations ?? [],
    animation: pose?.animation ?? null,
    time,
    variant: variant?.getName(),
    pose: poseAgain,
  };
  for (const [key, value] of Object.entries(metadata)) Object.defineProperty(scene, key, { value, enumerable: false, writable: false, configurable: true });
  return scene as GltfScene;
}

/** A glTF mesh's primitives as renderer meshes (morphed with `weights`, skinned with `skin`), with local bounds. */
async function primitiveMeshes(asset: LoadedAsset, mesh: Mesh, m: number, weights: readonly number[], skin: PrimitiveGeometryOptions['skin'], variant: Variant | undefined): Promise<CachedMesh> {
  const out: CachedMesh = { meshes: [], origins: [], bounds: [], warnings: [] };
  const primitives = mesh.listPrimitives();
  for (let p = 0; p < primitives.length; p++) {
    const at = pointer('meshes', m, 'primitives', p);
    const primitive = primitives[p];
    const geometry = primitiveGeometry(primitive, { at, weights, primitiveRestart: asset.primitiveRestart, warn: (message) => out.warnings.push(`${at}: ${message}`), ...(skin ? { skin } : {}) });
    if ('skip' in geometry) {
      out.warnings.push(`${at}: skipped, ${geometry.skip}`);
      continue;
    }
    const gltfMaterial = variantMaterial(primitive, variant);
    const material = gltfMaterial === null ? (asset.defaultMaterial as number) : (asset.materialIndex.get(gltfMaterial) as number);
    let streams: VertexStreams = geometry;
    const texCoord = tangentSpaceTexCoord(asset.materials[material]);
    if (texCoord !== undefined && streams.tangents === undefined) {
      if ((texCoord === 0 ? streams.uvs : streams.uvs1) === undefined) {
        out.warnings.push(`${at}: no TEXCOORD_${texCoord} for MikkTSpace tangents; the normal map cannot be applied`);
      } else {
        if (streams.normals === undefined) out.warnings.push(`${at}: flat normals computed for MikkTSpace tangents (the primitive has no NORMAL)`);
        try {
          streams = await withMikkTSpaceTangents(streams, texCoord);
        } catch (error) {
          failGltf(at, `MikkTSpace tangents could not be generated for the normal map (${(error as Error).message})`, error);
        }
      }
    }
    const name = mesh.getName();
    out.meshes.push({ id: `${name === '' ? `mesh ${m}` : name}/${p}`, ...streams, material });
    out.origins.push(at);
    out.bounds.push(localBounds(streams.positions));
  }
  return out;
}

function chooseCamera(cameras: readonly GltfCameraInfo[], choice: number | string | undefined, bounds: GltfBounds | undefined, aspectRatio: number | undefined): WavefrontCameraInput {
  if (choice === undefined) return cameras[0]?.camera ?? framingCamera(bounds, aspectRatio);
  const found = typeof choice === 'number' ? cameras.find((c) => c.cameraIndex === choice) : (cameras.find((c) => c.nodeName === choice) ?? cameras.find((c) => c.name === choice));
  if (found === undefined) {
    const known = cameras.map((c) => `${c.cameraIndex} ${JSON.stringify(c.name)}`).join(', ');
    throw optionError('camera', `no camera ${JSON.stringify(choice)} in the scene (cameras: ${known === '' ? 'none' : known})`);
  }
  return found.camera;
}
