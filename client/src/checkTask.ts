// The `fanuc-macro` task type: `fanuc-macro check` on files and folders, its output read by the
// `$fanuc-macro` problem matcher (package.json). The command line is derived from the language
// server that was found, so the task runs the same package (the bundled one included).
// Pure logic, no `vscode` import.
import { dirname, join } from 'node:path';
import { SERVER_MODULE, baseName, type ServerCandidate } from './serverCandidates';

export const TASK_TYPE = 'fanuc-macro';
export const PROBLEM_MATCHER = '$fanuc-macro';

/** Python module of the command line interface (`python -m fanuc_macro.cli`). */
export const CLI_MODULE = 'fanuc_macro.cli';
/** Console script installed by `pip install fanuc-macro`, beside fanuc-macro-ls. */
export const CLI_EXECUTABLE = 'fanuc-macro';

export interface CheckTaskDefinition {
  readonly type: typeof TASK_TYPE;
  readonly paths: readonly string[];
  readonly args?: readonly string[];
}

export interface CheckCommand {
  readonly command: string;
  readonly args: readonly string[];
}

/**
 * The `fanuc-macro` command of the package the server candidate runs: a Python's
 * `-m fanuc_macro.lsp.server` becomes `-m fanuc_macro.cli`; a fanuc-macro-ls executable gives
 * the fanuc-macro beside it. Without a candidate, fanuc-macro on PATH.
 */
export function cliCommand(candidate: Pick<ServerCandidate, 'command' | 'args'> | undefined): CheckCommand {
  if (candidate === undefined) return { command: CLI_EXECUTABLE, args: [] };
  const module = candidate.args.indexOf(SERVER_MODULE);
  if (module > 0 && candidate.args[module - 1] === '-m') {
    return {
      command: candidate.command,
      args: [...candidate.args.slice(0, module), CLI_MODULE, ...candidate.args.slice(module + 1)],
    };
  }
  const name = baseName(candidate.command);
  const cli = name.replace(/^fanuc-macro-ls/i, CLI_EXECUTABLE);
  if (cli === name) return { command: CLI_EXECUTABLE, args: [] };
  const folder = candidate.command.includes('/') || candidate.command.includes('\\');
  return { command: folder ? join(dirname(candidate.command), cli) : cli, args: [] };
}

/** The process a check task runs: `fanuc-macro check --format text PATHS... ARGS...` (the
 * options after the paths: an option that takes several values cannot swallow them). */
export function checkTaskCommand(
  candidate: Pick<ServerCandidate, 'command' | 'args'> | undefined,
  definition: Pick<CheckTaskDefinition, 'paths' | 'args'>,
): CheckCommand {
  const cli = cliCommand(candidate);
  const paths = definition.paths.length > 0 ? definition.paths : ['.'];
  return {
    command: cli.command,
    args: [...cli.args, 'check', '--format', 'text', ...paths, ...(definition.args ?? [])],
  };
}

/** Whether a task definition from tasks.json is one of ours and well formed. */
export function isCheckTaskDefinition(value: unknown): value is CheckTaskDefinition {
  if (typeof value !== 'object' || value === null) return false;
  const d = value as Record<string, unknown>;
  const strings = (v: unknown) => Array.isArray(v) && v.every((s) => typeof s === 'string');
  return d['type'] === TASK_TYPE && strings(d['paths']) && (d['args'] === undefined || strings(d['args']));
}
