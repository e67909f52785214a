/**
 * Frame files written atomically (Node.js): the bytes go to a temporary file in the target's
 * directory, then a rename (replace) or a hard link (first writer wins) gives them the target's
 * name, so a reader, an interrupted run or a second writer never sees a partial image.
 */
import { nodeFileSystem } from './platform.ts';

const nodeFs = () => nodeFileSystem('writing frame files');

function splitPath(path: string): { dir: string; base: string } {
  const slash = Math.max(path.lastIndexOf('/'), path.lastIndexOf('\\'));
  return slash < 0 ? { dir: '.', base: path } : { dir: path.slice(0, slash) || '/', base: path.slice(slash + 1) };
}

/** Whether `path` exists (a finished frame: only complete files ever carry a frame's name). */
export async function frameFileExists(path: string): Promise<boolean> {
  const fs = await nodeFs();
  try {
    await fs.access(path);
    return true;
  } catch {
    return false;
  }
}

/**
 * Writes `bytes` to `path` atomically, creating its directory. `mode: 'replace'` renames over an
 * existing file; `mode: 'create'` links the temporary file to `path`, which fails when `path`
 * exists: then nothing is written and the result is false (another writer finished that frame).
 */
export async function writeFrameFile(path: string, bytes: Uint8Array, mode: 'replace' | 'create' = 'replace'): Promise<boolean> {
  const fs = await nodeFs();
  const { dir, base } = splitPath(path);
  await fs.mkdir(dir, { recursive: true });
  const temp = `${dir}/.${base}.${process.pid}.${Math.random().toString(36).slice(2, 10)}.partial`;
  await fs.writeFile(temp, bytes, { flag: 'wx' });
  let renamed = false;
  try {
    if (mode === 'create') {
      try {
        await fs.link(temp, path);
        return true;
      } catch (error) {
        const code = (error as { code?: string }).code;
        if (code === 'EEXIST') return false;
        // File systems without hard links: check, then rename (a race between two writers of one frame remains there).
        if (code !== 'EPERM' && code !== 'ENOTSUP' && code !== 'ENOSYS' && code !== 'EOPNOTSUPP') throw error;
        if (await frameFileExists(path)) return false;
      }
    }
    await fs.rename(temp, path);
    renamed = true;
    return true;
  } finally {
    if (!renamed) await fs.unlink(temp).catch(() => undefined);
  }
}
