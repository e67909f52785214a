/**
 * Child process of `npm run bench` for the instancing benchmark (bench/instancing.ts): runs it on a
 * WebGPU device of its own and prints the result as one JSON line after RESULT_PREFIX
 * (child-protocol.ts). Run by hand, `node bench/instancing-child.ts --print` also prints the tables.
 */
import { RESULT_PREFIX } from './child-protocol.ts';
import { printInstancingResult, runInstancingBenchmark } from './instancing.ts';

const result = await runInstancingBenchmark();
if (process.argv.includes('--print')) printInstancingResult(result);
await new Promise<void>((resolve) => process.stdout.write(`\n${RESULT_PREFIX}${JSON.stringify(result)}\n`, () => resolve()));
// Dawn can keep the event loop alive after the device is destroyed.
process.exit(0);
