// Checks a server candidate by running it with `--version`. Uses only
// node's child_process, so it is unit-tested without VS Code.
import { spawn } from 'node:child_process';
import {
  candidateEnv,
  parseVersionOutput,
  versionArgs,
  type ProbeResult,
  type ServerCandidate,
} from './serverCandidates';

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
    let settled = false;
    let stdout = '';
    let stderr = '';
    const finish = (result: ProbeResult): void => {
      if (!settled) {
        settled = true;
        clearTimeout(timer);
        resolve(result);
      }
    };

    let child: ReturnType<typeof spawn>;
    try {
      child = spawn(candidate.command, versionArgs(candidate), {
        env: candidateEnv(candidate, env),
        shell: false,
        windowsHide: true,
        stdio: ['ignore', 'pipe', 'pipe'],
      });
    } catch (err) {
      resolve({ ok: false, reason: `cannot be started (${String(err)})` });
      return;
    }

    const timer = setTimeout(() => {
      child.kill();
      finish({ ok: false, reason: `no answer to --version within ${timeoutMs} ms` });
    }, timeoutMs);

    child.stdout?.setEncoding('utf8');
    child.stderr?.setEncoding('utf8');
    child.stdout?.on('data', (chunk: string) => {
      if (stdout.length < MAX_OUTPUT) stdout += chunk;
    });
    child.stderr?.on('data', (chunk: string) => {
      if (stderr.length < MAX_OUTPUT) stderr += chunk;
    });

    child.on('error', (err: NodeJS.ErrnoException) => {
      const reason =
        err.code === 'ENOENT'
          ? 'not found'
          : err.code === 'EACCES'
            ? 'not executable'
            : `cannot be started (${err.message})`;
      finish({ ok: false, reason });
    });

    child.on('close', (code, signal) => {
      if (settled) return;
      if (code !== 0) {
        const detail = lastLine(stderr) || lastLine(stdout);
        const how = code === null ? `was killed by ${signal ?? 'a signal'}` : `exited with code ${code}`;
        finish({ ok: false, reason: detail ? `${how}: ${detail}` : how });
        return;
      }
      const version = parseVersionOutput(stdout) ?? parseVersionOutput(stderr);
      if (version === undefined) {
        const shown = lastLine(stdout) || lastLine(stderr) || '(nothing)';
        finish({ ok: false, reason: `--version printed ${JSON.stringify(shown)}, not fanuc-macro-ls` });
        return;
      }
      finish({ ok: true, version });
    });
  });
}
