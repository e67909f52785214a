/**
 * Runs the renderer's submission phases (a frame's encoding and submits, reads, camera changes) one
 * at a time in call order: renderFrame and renderOnce calls reach the GPU in call order even when a
 * caller does not await them, and reads and camera changes see all the work requested before them.
 */
export class SubmissionQueue {
  private submissions: Promise<unknown> = Promise.resolve();
  private queued = 0;

  /** Runs `phase` after every earlier one; at once (in the caller's turn) when nothing is queued. */
  after<T>(phase: () => T | Promise<T>): Promise<T> {
    const run = this.queued === 0 ? new Promise<T>((resolve) => resolve(phase())) : this.submissions.then(phase);
    this.queued += 1;
    const settled = run.then(
      () => undefined,
      () => undefined,
    );
    this.submissions = settled.then(() => {
      this.queued -= 1;
    });
    return run;
  }
}
