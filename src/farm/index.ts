// The render farm on BullMQ/Redis (Node.js): submit a sequence as one queue job per frame, run
// workers that render frames into a shared directory, read the progress.
export { resolveFarmConnection, defaultRedisUrl, defaultFarmQueue, type FarmConnectionOptions, type FarmConnection } from './connection.ts';
export { parseJobFile, type FarmFrameData } from './farm-job.ts';
export { submitFarmJob, type FarmSubmitOptions, type FarmSubmission } from './submit.ts';
export { runFarmWorker, type FarmWorkerOptions, type FarmWorkerSummary } from './worker.ts';
export { farmTrustEnv, resolveFarmTrust, type FarmTrust, type FarmTrustOptions, type FarmPathMapping } from './worker-trust.ts';
export { validateFrameData, frameDataLimits } from './frame-data-schema.ts';
export type { FrameFailure } from './failure-record.ts';
export { readFarmStatus, formatFarmStatus, type FarmStatus, type FarmJobStatus } from './status.ts';
// A farm job is a render command: build one from `render` arguments.
export { parseRenderArgs, type RenderCommand } from '../cli/args.ts';
