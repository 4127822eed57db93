// Pure logic that decides which commands may start the fanuc-macro language
// server. Nothing here imports `vscode`, so it is unit-tested with node:test.
import { statSync } from 'node:fs';
import { posix, win32 } from 'node:path';

/** Python module that runs the language server (`python -m ...`). */
export const SERVER_MODULE = 'fanuc_macro.lsp.server';

/** Console script installed by `pip install fanuc-macro`. */
export const SERVER_EXECUTABLE = 'fanuc-macro-ls';

/**
 * Folder of the extension that holds the bundled server: the `fanuc_macro`
 * package and its pure-Python dependencies, put on PYTHONPATH
 * (created by client/scripts/bundle-server.mjs).
 */
export const BUNDLED_PYTHON_DIR = ['bundled', 'python'] as const;

/** Oldest Python the bundled server runs on. */
export const BUNDLED_MIN_PYTHON = '3.10';

/** Where a candidate came from, in the order they are tried. */
export type CandidateSource = 'setting' | 'python-extension' | 'path' | 'python' | 'bundled';

export interface ServerCandidate {
  /** Program to spawn (an absolute path or a name looked up on PATH). */
  readonly command: string;
  /** Arguments that start the server over stdio. */
  readonly args: readonly string[];
  readonly source: CandidateSource;
  /** Human-readable description used in logs and error messages. */
  readonly description: string;
  /**
   * Environment variables set for this candidate on top of the extension
   * host's environment (see `candidateEnv`), both for the `--version` probe
   * and for the server itself. Values are final: PYTHONPATH already holds
   * the previous PYTHONPATH after the bundled folder.
   */
  readonly env?: Readonly<Record<string, string>> | undefined;
}

export interface CandidateInputs {
  /** Value of the `fanuc-macro.server.path` setting (may be empty). */
  readonly settingPath?: string | undefined;
  /** Interpreter selected in the Python extension, if any. */
  readonly pythonExtensionInterpreter?: string | undefined;
  /** `process.platform`. */
  readonly platform: NodeJS.Platform;
  /** Home directory used to expand a leading `~`. */
  readonly homeDir?: string | undefined;
  /** First workspace folder, used to expand `${workspaceFolder}`. */
  readonly workspaceFolder?: string | undefined;
  /** Folder the extension is installed in; the bundled server is looked for in it. */
  readonly extensionPath?: string | undefined;
  /** Environment the server would inherit (for the PYTHONPATH the bundled server extends). */
  readonly env?: NodeJS.ProcessEnv | undefined;
  /** Tells whether a folder exists; defaults to a check of the file system. */
  readonly isDirectory?: ((path: string) => boolean) | undefined;
}

/** Last path component, for both `/` and `\` separators. */
export function baseName(path: string): string {
  const parts = path.split(/[\\/]/);
  return parts[parts.length - 1] ?? path;
}

/**
 * True when `path` names a Python interpreter rather than the server
 * executable: its file name is `python`, `python3`, `python3.12`,
 * `python.exe`, `python3.exe`, `pythonw.exe` and the like.
 */
export function isPythonInterpreter(path: string): boolean {
  return /^python[w]?(\d+(\.\d+)*)?(\.exe)?$/i.test(baseName(path.trim()));
}

/** Expands `~`, `${userHome}` and `${workspaceFolder}` in a configured path. */
export function expandPath(raw: string, homeDir: string | undefined, workspaceFolder: string | undefined): string {
  let path = raw.trim();
  // Strip one pair of surrounding quotes, as people paste "C:\Program Files\...".
  if (path.length >= 2 && /^(["']).*\1$/.test(path)) path = path.slice(1, -1);
  if (homeDir !== undefined) {
    path = path.replace(/\$\{userHome\}/g, homeDir);
    if (path === '~') {
      path = homeDir;
    } else if (path.startsWith('~/') || path.startsWith('~\\')) {
      path = homeDir + path.slice(1);
    }
  }
  if (workspaceFolder !== undefined) path = path.replace(/\$\{workspaceFolder\}/g, workspaceFolder);
  return path;
}

/** Candidate that runs `path`: either `path -m SERVER_MODULE` or `path` itself. */
export function candidateFromPath(path: string, source: CandidateSource): ServerCandidate {
  if (isPythonInterpreter(path)) {
    return {
      command: path,
      args: ['-m', SERVER_MODULE],
      source,
      description: `${path} -m ${SERVER_MODULE}`,
    };
  }
  return { command: path, args: [], source, description: path };
}

/** The arguments that make a candidate print its version and exit. */
export function versionArgs(candidate: ServerCandidate): string[] {
  return [...candidate.args, '--version'];
}

function envKey(env: Readonly<Record<string, string>> | undefined): string {
  return Object.entries(env ?? {})
    .map(([name, value]) => `${name}=${value}`)
    .sort()
    .join('\u0000');
}

function sameCandidate(a: ServerCandidate, b: ServerCandidate): boolean {
  return (
    a.command === b.command &&
    a.args.join('\u0000') === b.args.join('\u0000') &&
    envKey(a.env) === envKey(b.env)
  );
}

/** True when `path` is an existing folder. */
export function directoryExists(path: string): boolean {
  try {
    return statSync(path).isDirectory();
  } catch {
    return false;
  }
}

/** Value of an environment variable; on Windows names are case-insensitive. */
function getEnv(env: NodeJS.ProcessEnv | undefined, name: string, platform: NodeJS.Platform): string | undefined {
  if (env === undefined) return undefined;
  if (platform !== 'win32') return env[name];
  const key = Object.keys(env).find((k) => k.toUpperCase() === name.toUpperCase());
  return key === undefined ? undefined : env[key];
}

/** Folder of the bundled server inside the extension at `extensionPath`. */
export function bundledServerPath(extensionPath: string, platform: NodeJS.Platform): string {
  const path = platform === 'win32' ? win32 : posix;
  return path.join(extensionPath, ...BUNDLED_PYTHON_DIR);
}

/** `dir` followed by the current PYTHONPATH, if any. */
export function prependPythonPath(dir: string, env: NodeJS.ProcessEnv | undefined, platform: NodeJS.Platform): string {
  const existing = getEnv(env, 'PYTHONPATH', platform) ?? '';
  const delimiter = platform === 'win32' ? ';' : ':';
  return existing === '' ? dir : `${dir}${delimiter}${existing}`;
}

/**
 * The environment to start `candidate` in: `base` with the candidate's own
 * variables on top. On Windows a variable of `base` that differs only in
 * case from one of the candidate's is dropped, so that the child does not
 * get both `PythonPath` and `PYTHONPATH`.
 */
export function candidateEnv(
  candidate: ServerCandidate,
  base: NodeJS.ProcessEnv,
  platform: NodeJS.Platform = process.platform,
): NodeJS.ProcessEnv {
  const extra = candidate.env ?? {};
  const names = Object.keys(extra);
  if (names.length === 0) return { ...base };
  const result: NodeJS.ProcessEnv = {};
  const upper = new Set(names.map((n) => n.toUpperCase()));
  for (const [name, value] of Object.entries(base)) {
    if (platform === 'win32' ? upper.has(name.toUpperCase()) : name in extra) continue;
    result[name] = value;
  }
  return { ...result, ...extra };
}

/**
 * Candidates in the order they are tried:
 * 1. the `fanuc-macro.server.path` setting;
 * 2. the interpreter selected in the Python extension, with `-m fanuc_macro.lsp.server`;
 * 3. `fanuc-macro-ls` on PATH;
 * 4. `python3 -m fanuc_macro.lsp.server` (and `python` / `py -3` on Windows);
 * 5. the server bundled in the extension (`<extensionPath>/bundled/python`, only
 *    when that folder exists), run by the first of these Pythons that works:
 *    the Python extension's interpreter, `python3` (`python`, `py -3` on
 *    Windows), with that folder prepended to PYTHONPATH.
 * 2, 4 and 5 run `-m fanuc_macro.lsp.server`; 2 and 4 need the package
 * installed in that Python, 5 only needs Python 3.10 or later.
 * Duplicates are dropped, keeping the first.
 */
export function buildCandidates(inputs: CandidateInputs): ServerCandidate[] {
  const result: ServerCandidate[] = [];
  const add = (candidate: ServerCandidate): void => {
    if (!result.some((c) => sameCandidate(c, candidate))) result.push(candidate);
  };

  const setting = inputs.settingPath?.trim() ?? '';
  if (setting !== '') add(candidateFromPath(expandPath(setting, inputs.homeDir, inputs.workspaceFolder), 'setting'));

  const interpreter = inputs.pythonExtensionInterpreter?.trim() ?? '';
  if (interpreter !== '') {
    add({
      command: interpreter,
      args: ['-m', SERVER_MODULE],
      source: 'python-extension',
      description: `${interpreter} -m ${SERVER_MODULE} (Python extension's interpreter)`,
    });
  }

  add({
    command: SERVER_EXECUTABLE,
    args: [],
    source: 'path',
    description: `${SERVER_EXECUTABLE} on PATH`,
  });

  // Pythons looked up on PATH: [command, args before -m].
  const pathPythons: Array<[string, string[]]> =
    inputs.platform === 'win32'
      ? [
          ['python3', []],
          ['python', []],
          ['py', ['-3']],
        ]
      : [['python3', []]];
  for (const [python, pre] of pathPythons) {
    add({
      command: python,
      args: [...pre, '-m', SERVER_MODULE],
      source: 'python',
      description: [python, ...pre, '-m', SERVER_MODULE].join(' '),
    });
  }

  const extensionPath = inputs.extensionPath?.trim() ?? '';
  if (extensionPath !== '') {
    const bundled = bundledServerPath(extensionPath, inputs.platform);
    const isDirectory = inputs.isDirectory ?? directoryExists;
    if (isDirectory(bundled)) {
      const env = { PYTHONPATH: prependPythonPath(bundled, inputs.env, inputs.platform) };
      const bundledPythons: Array<[string, string[]]> =
        interpreter !== '' ? [[interpreter, []], ...pathPythons] : pathPythons;
      for (const [python, pre] of bundledPythons) {
        add({
          command: python,
          args: [...pre, '-m', SERVER_MODULE],
          source: 'bundled',
          description: `${[python, ...pre, '-m', SERVER_MODULE].join(' ')} with the bundled server (${bundled})`,
          env,
        });
      }
    }
  }
  return result;
}

/**
 * Extracts the version from the output of `--version`, which looks like
 * `fanuc-macro-ls 0.1.0`. Returns undefined when the output does not come
 * from the fanuc-macro server.
 */
export function parseVersionOutput(output: string): string | undefined {
  const match = /fanuc[-_]macro(?:-ls)?\s+v?(\d+\.\d+(?:\.\d+)?[^\s]*)/i.exec(output);
  return match?.[1];
}

/** Outcome of checking one candidate. */
export type ProbeResult =
  | { readonly ok: true; readonly version: string }
  | { readonly ok: false; readonly reason: string };

/** One line per candidate tried, for the log and the error message. */
export function describeAttempts(
  attempts: ReadonlyArray<{ candidate: ServerCandidate; result: ProbeResult }>,
): string[] {
  return attempts.map(({ candidate, result }) =>
    result.ok
      ? `${candidate.description}: found version ${result.version}`
      : `${candidate.description}: ${result.reason}`,
  );
}
