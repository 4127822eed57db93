// Pure logic that decides which commands may start the fanuc-macro language
// server. Nothing here imports `vscode`, so it is unit-tested with node:test.

/** Python module that runs the language server (`python -m ...`). */
export const SERVER_MODULE = 'fanuc_macro.lsp.server';

/** Console script installed by `pip install fanuc-macro`. */
export const SERVER_EXECUTABLE = 'fanuc-macro-ls';

/** Where a candidate came from, in the order they are tried. */
export type CandidateSource = 'setting' | 'python-extension' | 'path' | 'python';

export interface ServerCandidate {
  /** Program to spawn (an absolute path or a name looked up on PATH). */
  readonly command: string;
  /** Arguments that start the server over stdio. */
  readonly args: readonly string[];
  readonly source: CandidateSource;
  /** Human-readable description used in logs and error messages. */
  readonly description: string;
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
export function expandPath(
  raw: string,
  homeDir: string | undefined,
  workspaceFolder: string | undefined,
): string {
  let path = raw.trim();
  // Strip one pair of surrounding quotes, as people paste "C:\Program Files\...".
  if (path.length >= 2 && /^(["']).*\1$/.test(path)) {
    path = path.slice(1, -1);
  }
  if (homeDir !== undefined) {
    path = path.replace(/\$\{userHome\}/g, homeDir);
    if (path === '~') {
      path = homeDir;
    } else if (path.startsWith('~/') || path.startsWith('~\\')) {
      path = homeDir + path.slice(1);
    }
  }
  if (workspaceFolder !== undefined) {
    path = path.replace(/\$\{workspaceFolder\}/g, workspaceFolder);
  }
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

function sameCandidate(a: ServerCandidate, b: ServerCandidate): boolean {
  return a.command === b.command && a.args.join('\u0000') === b.args.join('\u0000');
}

/**
 * Candidates in the order they are tried:
 * 1. the `fanuc-macro.server.path` setting;
 * 2. the interpreter selected in the Python extension, with `-m fanuc_macro.lsp.server`;
 * 3. `fanuc-macro-ls` on PATH;
 * 4. `python3 -m fanuc_macro.lsp.server` (and `python` / `py -3` on Windows).
 * Duplicates are dropped, keeping the first.
 */
export function buildCandidates(inputs: CandidateInputs): ServerCandidate[] {
  const result: ServerCandidate[] = [];
  const add = (candidate: ServerCandidate): void => {
    if (!result.some((c) => sameCandidate(c, candidate))) {
      result.push(candidate);
    }
  };

  const setting = inputs.settingPath?.trim() ?? '';
  if (setting !== '') {
    add(candidateFromPath(expandPath(setting, inputs.homeDir, inputs.workspaceFolder), 'setting'));
  }

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

  const pythons = inputs.platform === 'win32' ? ['python3', 'python'] : ['python3'];
  for (const python of pythons) {
    add({
      command: python,
      args: ['-m', SERVER_MODULE],
      source: 'python',
      description: `${python} -m ${SERVER_MODULE}`,
    });
  }
  if (inputs.platform === 'win32') {
    add({
      command: 'py',
      args: ['-3', '-m', SERVER_MODULE],
      source: 'python',
      description: `py -3 -m ${SERVER_MODULE}`,
    });
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
