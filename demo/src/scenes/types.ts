import type { WavefrontSceneDescription } from '@plasius/gpu-renderer';

/** A scene the demo can show: what the renderer takes, plus the demo's suggestions for it. */
export interface DemoScene {
  /** Shown in the scene picker and used in saved file names. */
  name: string;
  /** The scene; its camera is where the orbit camera starts. */
  description: WavefrontSceneDescription & { camera: NonNullable<WavefrontSceneDescription['camera']> };
  /** Uniform environment radiance the scene looks right under (linear RGB). */
  suggestedEnvironment: [number, number, number];
  /** Exposure the scene looks right at. */
  suggestedExposure?: number;
  /** Things the loader skipped or the demo left out, shown under the picture. */
  notes: string[];
}

/** A built-in scene: made in code with the package's scene input types. */
export interface BuiltInScene {
  id: string;
  label: string;
  create(): DemoScene;
}
