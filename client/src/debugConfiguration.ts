// Pure logic of the Macro B debugger's launch: how the debug adapter (fanuc-macro-dap) is
// started from the language server's own command, and how a launch configuration is completed
// from the settings and the active editor. Nothing here imports `vscode`, so it is unit-tested
// with node:test.
import { posix, win32 } from 'node:path';
import { SERVER_EXECUTABLE, SERVER_MODULE, baseName, type ServerCandidate } from './serverCandidates';

/** The debugger type of launch.json (package.json contributes.debuggers). */
export const DEBUG_TYPE = 'fanuc-macro';

/** Python module that runs the debug adapter (`python -m ...`). */
export const DAP_MODULE = 'fanuc_macro.dap';

/** Console script installed beside fanuc-macro-ls by `pip install fanuc-macro`. */
export const DAP_EXECUTABLE = 'fanuc-macro-dap';

/** The `fanuc-macro.analysis.stepBudget` setting's default. */
export const DEFAULT_STEP_BUDGET = 300000;

/** A command that starts the adapter over stdio. */
export interface AdapterCommand {
  readonly command: string;
  readonly args: readonly string[];
  /** Variables set on top of the extension host's environment (the bundled server's PYTHONPATH). */
  readonly env?: Readonly<Record<string, string>> | undefined;
}

/**
 * The adapter is run by what runs the language server, so that it is the same package:
 * `python -m fanuc_macro.lsp.server` becomes `python -m fanuc_macro.dap` (with the same
 * interpreter, arguments before `-m` and environment), and an executable such as
 * `…/bin/fanuc-macro-ls` becomes its sibling `…/bin/fanuc-macro-dap`.
 */
export function adapterCommand(candidate: ServerCandidate, platform: NodeJS.Platform): AdapterCommand {
  const moduleAt = candidate.args.indexOf('-m');
  if (moduleAt >= 0 && candidate.args[moduleAt + 1] === SERVER_MODULE) {
    const args = [...candidate.args.slice(0, moduleAt), '-m', DAP_MODULE];
    return { command: candidate.command, args, env: candidate.env };
  }
  const name = baseName(candidate.command);
  // Keep an extension such as `.exe` (`fanuc-macro-ls.exe` -> `fanuc-macro-dap.exe`).
  const suffix = name.toLowerCase().startsWith(SERVER_EXECUTABLE) ? name.slice(SERVER_EXECUTABLE.length) : '';
  const sibling = `${DAP_EXECUTABLE}${/^\.[a-z]+$/i.test(suffix) ? suffix : ''}`;
  if (name === candidate.command) return { command: sibling, args: [], env: candidate.env };
  const path = platform === 'win32' ? win32 : posix;
  return { command: path.join(path.dirname(candidate.command), sibling), args: [], env: candidate.env };
}

/** A launch configuration as VS Code hands it over: the keys are whatever the user wrote. */
export type LaunchConfiguration = Record<string, unknown>;

/** What the configuration is completed from. */
export interface LaunchContext {
  /** The active editor's file, if it is a FANUC program saved on disk. */
  readonly activeProgram?: string | undefined;
  /** The `fanuc-macro.controller` setting. */
  readonly controller?: string | undefined;
  /** The `fanuc-macro.analysis.stepBudget` setting. */
  readonly stepBudget?: number | undefined;
}

/**
 * Why a configuration cannot be launched (the extension says it in the user's language):
 * no FANUC program is open, the request is not `launch`, or `program` is missing.
 */
export type LaunchProblem = 'no-active-program' | 'not-launch' | 'no-program';

/** The configuration to launch, or the reason it cannot be launched. */
export type ResolvedLaunch =
  | { readonly ok: true; readonly config: LaunchConfiguration }
  | { readonly ok: false; readonly problem: LaunchProblem };

function fileName(path: string): string {
  return baseName(path) || path;
}

/** The configuration that debugs `program` (the command and F5 without a launch.json). */
export function programConfiguration(program: string, stopOnEntry: boolean): LaunchConfiguration {
  return {
    type: DEBUG_TYPE,
    request: 'launch',
    name: `Debug ${fileName(program)}`,
    program,
    stopOnEntry,
  };
}

/**
 * Completes a launch configuration: an empty one (F5 with no launch.json) debugs the active
 * FANUC program, stopping on its first block; `controller` and `stepBudget` come from the
 * settings when the configuration does not give them.
 */
export function resolveLaunch(config: LaunchConfiguration, context: LaunchContext): ResolvedLaunch {
  let resolved: LaunchConfiguration = { ...config };
  const empty = config['type'] === undefined && config['request'] === undefined && config['name'] === undefined;
  if (empty) {
    if (context.activeProgram === undefined) return { ok: false, problem: 'no-active-program' };
    resolved = programConfiguration(context.activeProgram, true);
  }
  if (resolved['request'] !== undefined && resolved['request'] !== 'launch') return { ok: false, problem: 'not-launch' };
  const program = resolved['program'];
  if (typeof program !== 'string' || program.trim() === '') return { ok: false, problem: 'no-program' };
  if (resolved['controller'] === undefined && context.controller !== undefined && context.controller !== '') {
    resolved['controller'] = context.controller;
  }
  if (resolved['stepBudget'] === undefined) resolved['stepBudget'] = context.stepBudget ?? DEFAULT_STEP_BUDGET;
  return { ok: true, config: resolved };
}
