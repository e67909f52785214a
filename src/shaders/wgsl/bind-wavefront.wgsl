// Group 1: tile-sized wavefront queues plus the full-frame accumulation.
// paths holds two queues (ping-pong halves selected by `bounce`).
@group(1) @binding(0) var<storage, read_write> paths: array<PathState>;
@group(1) @binding(1) var<storage, read_write> shadowRays: array<ShadowRay>;
@group(1) @binding(2) var<storage, read_write> counters: array<atomic<u32>, QUEUE_COUNTER_COUNT>;
@group(1) @binding(3) var<storage, read_write> tileRadiance: array<vec4f>;
@group(1) @binding(4) var<storage, read_write> accumulation: array<vec4f>;
@group(1) @binding(5) var<storage, read_write> dispatchArgs: array<u32>;

// Group 2: per-wave and per-bounce constants, bound with dynamic offsets.
@group(2) @binding(0) var<uniform> wave: WaveUniforms;
@group(2) @binding(1) var<uniform> bounce: BounceUniforms;
