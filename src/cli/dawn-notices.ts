/**
 * Dawn's adapter-limit notices, kept out of the CLI's output. When Dawn first enumerates a Vulkan
 * adapter (the first `requestAdapter` of a GPU instance) it caps the driver's dynamic-buffer limits
 * to its own fixed maximum (Limits.cpp, NormalizeLimits) and says so on stderr from native code:
 *
 *   Warning: maxDynamicUniformBuffersPerPipelineLayout artificially reduced from 1000000 to 16 to fit dynamic offset allocation limit.
 *   Warning: maxDynamicStorageBuffersPerPipelineLayout artificially reduced from 1000000 to 16 to fit dynamic offset allocation limit.
 *
 * Most Vulkan drivers (llvmpipe, RADV, NVIDIA) report such limits, so every run prints them; they
 * describe Dawn's own clamp, not a fault, and the renderer uses no dynamic offsets. Native code
 * writes them to file descriptor 2 with no hook in the API, so the CLI renders in a child process
 * and passes its stderr through this filter, which drops exactly these lines and nothing else.
 */

/** One of the notices as a whole line (without its line break). */
export const dawnLimitNotice = /^Warning: maxDynamic(?:Uniform|Storage)BuffersPerPipelineLayout artificially reduced from \d+ to \d+ to fit dynamic offset allocation limit\.\r?$/;

const prefix = 'Warning: maxDynamic';

export interface LineFilter {
  /** Passes text on (immediately, except the start of a line that may still become a notice). */
  push(text: string): void;
  /** Flushes what is held back. */
  end(): void;
}

/**
 * A stream filter dropping whole lines that match `dawnLimitNotice`. Text that cannot be the start
 * of a notice (progress bars rewriting their line with `\r`, partial lines) goes on at once.
 */
export function createDawnNoticeFilter(write: (text: string) => void): LineFilter {
  // The start of the current line, held back while it may still be a notice.
  let held = '';
  // Whether part of the current line has been passed on (then the rest is passed on too).
  let lineStarted = false;
  return {
    push(text: string): void {
      let rest = held + text;
      held = '';
      let out = '';
      for (let newline = rest.indexOf('\n'); newline >= 0; newline = rest.indexOf('\n')) {
        const line = rest.slice(0, newline);
        rest = rest.slice(newline + 1);
        if (lineStarted || !dawnLimitNotice.test(line)) out += `${line}\n`;
        lineStarted = false;
      }
      if (rest !== '') {
        if (!lineStarted && (prefix.startsWith(rest) || rest.startsWith(prefix))) held = rest;
        else {
          out += rest;
          lineStarted = true;
        }
      }
      if (out !== '') write(out);
    },
    end(): void {
      if (held !== '') write(held);
      held = '';
    },
  };
}
