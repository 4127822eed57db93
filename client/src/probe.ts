// Checks a server candidate by running it with `--version`. Uses only
// node's child_process, so it is unit-tested without VS Code.
import { execFile, type ExecFileException } from 'node:child_process';
import { candidateEnv, parseVersionOutput, versionArgs, type ProbeResult, type ServerCandidate } from './serverCandidates';

/** Default time allowed for `--version` (Python start-up can be slow on a cold cache). */
export const DEFAULT_PROBE_TIMEOUT_MS = 15000;

const MAX_OUTPUT = 64 * 1024;

function lastLine(text: string): string {
  const line = text.trim().split(/\r?\n/).pop() ?? '';
  return line.length > 200 ? `${line.slice(0, 200)}...` : line;
}

/**
 * Spawns `candidate` with `--version` and resolves with its version, or with
 * the reason it cannot be used (not found, non-zero exit, timeout, output
 * that is not from fanuc-macro-ls). Never rejects.
 *
 * `env` is the environment the candidate runs in; the candidate's own
 * variables (`candidate.env`, such as the bundled server's PYTHONPATH) are
 * applied on top of it, so the probe sees what the server will see.
 */
export function probeCandidate(
  candidate: ServerCandidate,
  timeoutMs: number = DEFAULT_PROBE_TIMEOUT_MS,
  env: NodeJS.ProcessEnv = process.env,
): Promise<ProbeResult> {
  return new Promise<ProbeResult>((resolve) => {
    const options = { env: candidateEnv(candidate, env), timeout: timeoutMs, maxBuffer: MAX_OUTPUT, windowsHide: true };
    try {
      execFile(candidate.command, versionArgs(candidate), options, (err, stdout, stderr) =>
        resolve(err === null ? versionOf(stdout, stderr) : failure(err, stdout, stderr, timeoutMs)),
      );
    } catch (err) {
      resolve({ ok: false, reason: `cannot be started (${String(err)})` });
    }
  });
}

function versionOf(stdout: string, stderr: string): ProbeResult {
  const version = parseVersionOutput(stdout) ?? parseVersionOutput(stderr);
  if (version !== undefined) return { ok: true, version };
  const shown = lastLine(stdout) || lastLine(stderr) || '(nothing)';
  return { ok: false, reason: `--version printed ${JSON.stringify(shown)}, not fanuc-macro-ls` };
}

/** Why the run failed: not started, too slow, or an exit that is not 0. */
function failure(err: ExecFileException, stdout: string, stderr: string, timeoutMs: number): ProbeResult {
  if (err.code === 'ENOENT') return { ok: false, reason: 'not found' };
  if (err.code === 'EACCES') return { ok: false, reason: 'not executable' };
  if (err.killed === true && err.code === null) return { ok: false, reason: `no answer to --version within ${timeoutMs} ms` };
  if (typeof err.code !== 'number' && err.signal === null) return { ok: false, reason: `cannot be started (${err.message})` };
  const detail = lastLine(stderr) || lastLine(stdout);
  const how = typeof err.code === 'number' ? `exited with code ${err.code}` : `was killed by ${err.signal ?? 'a signal'}`;
  return { ok: false, reason: detail ? `${how}: ${detail}` : how };
}
