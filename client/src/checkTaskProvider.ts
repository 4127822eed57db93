// Provides the `fanuc-macro` check task of each workspace folder, and resolves those written in
// tasks.json, with the command line of the package the language server runs (checkTask.ts).
import * as vscode from 'vscode';
import { PROBLEM_MATCHER, TASK_TYPE, checkTaskCommand, isCheckTaskDefinition, type CheckTaskDefinition } from './checkTask';
import { candidateEnv, type ServerCandidate } from './serverCandidates';

function makeTask(
  definition: CheckTaskDefinition,
  scope: vscode.WorkspaceFolder | vscode.TaskScope,
  candidate: ServerCandidate | undefined,
): vscode.Task {
  const { command, args } = checkTaskCommand(candidate, definition);
  const env = candidate === undefined ? undefined : candidateEnv(candidate, {}, process.platform);
  const cwd = typeof scope === 'object' ? scope.uri.fsPath : undefined;
  const options: vscode.ProcessExecutionOptions = {};
  if (cwd !== undefined) options.cwd = cwd;
  if (env !== undefined && Object.keys(env).length > 0) options.env = env as Record<string, string>;
  const name = vscode.l10n.t('check {0}', definition.paths.join(' ') || '.');
  const task = new vscode.Task(
    definition,
    scope,
    name,
    'fanuc-macro',
    new vscode.ProcessExecution(command, [...args], options),
    [PROBLEM_MATCHER],
  );
  task.group = vscode.TaskGroup.Build;
  return task;
}

/** The provider; `candidate` gives the server found (undefined until one is). */
export function registerCheckTasks(candidate: () => ServerCandidate | undefined): vscode.Disposable {
  return vscode.tasks.registerTaskProvider(TASK_TYPE, {
    provideTasks: () =>
      (vscode.workspace.workspaceFolders ?? []).map((folder) =>
        makeTask({ type: TASK_TYPE, paths: ['.'] }, folder, candidate()),
      ),
    resolveTask: (task) => {
      if (!isCheckTaskDefinition(task.definition)) return undefined;
      const scope = task.scope ?? vscode.TaskScope.Workspace;
      return makeTask(task.definition, scope, candidate());
    },
  });
}
