// Group 0: the scene, constant for a render.
@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var<storage, read> triangles: array<Triangle>;
@group(0) @binding(2) var<storage, read> triangleAttributes: array<TriangleAttributes>;
@group(0) @binding(3) var<storage, read> bvhNodes: array<BvhNode>;
@group(0) @binding(4) var<storage, read> materials: array<Material>;
@group(0) @binding(5) var<storage, read> sceneObjects: array<SceneObject>;
@group(0) @binding(6) var<storage, read> lights: array<LightEntry>;
