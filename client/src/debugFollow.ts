// Which block the Toolpath view lights when a debug session stops: the top stack frame's line,
// when that frame is in the document the view draws. Pure logic (no `vscode`), unit-tested.

/** The arguments of the stackTrace request the tracker sends on a stop: the top frame only. */
export const TOP_FRAME_REQUEST = { threadId: 1, levels: 1 } as const;

/** A path as the file system compares it: `\` and `/` alike, case-insensitive on Windows and macOS. */
export function samePath(a: string, b: string, platform: NodeJS.Platform): boolean {
  const norm = (p: string) => {
    const slashes = p.replace(/\\/g, '/');
    return platform === 'win32' || platform === 'darwin' ? slashes.toLowerCase() : slashes;
  };
  return norm(a) === norm(b);
}

/**
 * The 0-based line of the stopped block, from the body of a stackTrace answer (DAP lines start
 * at 1, VS Code's default), or undefined when the top frame is in another file than
 * `documentPath` or the answer has no frame.
 */
export function stoppedLine(body: unknown, documentPath: string, platform: NodeJS.Platform): number | undefined {
  if (body === null || typeof body !== 'object') return undefined;
  const frames = (body as { stackFrames?: unknown }).stackFrames;
  if (!Array.isArray(frames) || frames.length === 0) return undefined;
  const top = frames[0] as { line?: unknown; source?: { path?: unknown } } | null;
  if (top === null || typeof top !== 'object') return undefined;
  const line = top.line;
  const path = top.source?.path;
  if (typeof line !== 'number' || !Number.isInteger(line) || line < 1 || typeof path !== 'string') return undefined;
  return samePath(path, documentPath, platform) ? line - 1 : undefined;
}

/** True for a DAP message the adapter sent that says the run stopped. */
export function isStoppedEvent(message: unknown): boolean {
  if (message === null || typeof message !== 'object') return false;
  const m = message as { type?: unknown; event?: unknown };
  return m.type === 'event' && m.event === 'stopped';
}
