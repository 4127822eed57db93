// The VS Code side of the Macro B debugger: starts the debug adapter (fanuc-macro-dap) with the
// Python the language server runs on, completes launch configurations from the settings, gives
// the hover the whole `#` variable (the server's fanuc-macro.variableAt), lets the Toolpath view follow the stopped block, and the
// "Debug This Program" command.
import * as vscode from 'vscode';
import { DEBUG_TYPE, adapterCommand, programConfiguration, resolveLaunch, type LaunchProblem } from './debugConfiguration';
import { TOP_FRAME_REQUEST, isStoppedEvent, stoppedLine } from './debugFollow';
import { candidateEnv, type ServerCandidate } from './serverCandidates';
import { ToolpathPanel } from './toolpathView';

const LANGUAGE_ID = 'fanuc-macro';
const CONFIG_SECTION = 'fanuc-macro';
export const COMMAND_DEBUG_PROGRAM = 'fanuc-macro.debugProgram';

/** The language server's command once it has started (undefined until then, or if none was found). */
export type StartedServer = () => Promise<ServerCandidate | undefined>;

function problemText(problem: LaunchProblem): string {
  switch (problem) {
    case 'no-active-program':
      return vscode.l10n.t('FANUC Macro: open a FANUC Macro program saved on disk to debug it.');
    case 'not-launch':
      return vscode.l10n.t('FANUC Macro: the debugger can only launch a program ("request": "launch").');
    case 'no-program':
      return vscode.l10n.t('FANUC Macro: the launch configuration needs "program", the .nc file to run.');
  }
}

/** The active editor's file, if it is a FANUC program on disk. */
function activeProgram(): string | undefined {
  const document = vscode.window.activeTextEditor?.document;
  if (document === undefined || document.languageId !== LANGUAGE_ID || document.uri.scheme !== 'file') return undefined;
  return document.uri.fsPath;
}

class LaunchConfigurations implements vscode.DebugConfigurationProvider {
  resolveDebugConfiguration(
    _folder: vscode.WorkspaceFolder | undefined,
    config: vscode.DebugConfiguration,
  ): vscode.ProviderResult<vscode.DebugConfiguration> {
    const settings = vscode.workspace.getConfiguration(CONFIG_SECTION);
    const resolved = resolveLaunch(config, {
      activeProgram: activeProgram(),
      controller: settings.get<string>('controller'),
      stepBudget: settings.get<number>('analysis.stepBudget'),
    });
    if (!resolved.ok) {
      void vscode.window.showErrorMessage(problemText(resolved.problem));
      return undefined; // abandons the launch
    }
    return resolved.config as vscode.DebugConfiguration;
  }
}

class AdapterFactory implements vscode.DebugAdapterDescriptorFactory {
  constructor(private readonly startedServer: StartedServer) {}

  async createDebugAdapterDescriptor(): Promise<vscode.DebugAdapterDescriptor> {
    const candidate = await this.startedServer();
    if (candidate === undefined) {
      throw new Error(
        vscode.l10n.t(
          'FANUC Macro: the debugger runs on the language server\'s Python, and the language server was not found (see the "{0}" setting).',
          `${CONFIG_SECTION}.server.path`,
        ),
      );
    }
    const adapter = adapterCommand(candidate, process.platform);
    const env = candidateEnv({ ...candidate, env: adapter.env }, process.env);
    const defined: Record<string, string> = { PYTHONUNBUFFERED: '1' };
    for (const [name, value] of Object.entries(env)) if (value !== undefined) defined[name] = value;
    return new vscode.DebugAdapterExecutable(adapter.command, [...adapter.args], { env: defined });
  }
}

/** Lights the stopped block in the Toolpath view, if the view draws the stopped frame's file. */
async function followStop(session: vscode.DebugSession): Promise<void> {
  const panel = ToolpathPanel.current;
  if (panel === undefined) return;
  let body: unknown;
  try {
    body = await session.customRequest('stackTrace', TOP_FRAME_REQUEST);
  } catch {
    return; // the run went on or ended meanwhile
  }
  const line = stoppedLine(body, panel.documentPath, process.platform);
  if (line !== undefined && ToolpathPanel.current === panel) panel.showStoppedBlock(line);
}

const followStops: vscode.DebugAdapterTrackerFactory = {
  createDebugAdapterTracker(session) {
    return {
      onDidSendMessage: (message: unknown) => {
        if (isStoppedEvent(message)) void followStop(session);
      },
    };
  },
};

/** Asks the running language server, if there is one; undefined otherwise. */
export type AskServer = (command: string, args: unknown[]) => Promise<unknown>;

/** The hover's expression: the whole `#` variable under the mouse, as the server finds it. */
function hoverVariables(ask: AskServer): vscode.EvaluatableExpressionProvider {
  return {
    async provideEvaluatableExpression(document, position) {
      const found = (await ask('fanuc-macro.variableAt', [document.lineAt(position.line).text, position.character])) as
        | { start?: unknown; end?: unknown }
        | undefined;
      if (typeof found?.start !== 'number' || typeof found.end !== 'number') return undefined;
      return new vscode.EvaluatableExpression(new vscode.Range(position.line, found.start, position.line, found.end));
    },
  };
}

/** "Debug This Program": runs the active program until a breakpoint, an alarm or its end. */
async function debugProgram(resource?: vscode.Uri): Promise<void> {
  const uri = resource instanceof vscode.Uri ? resource : vscode.window.activeTextEditor?.document.uri;
  if (uri === undefined || uri.scheme !== 'file') {
    void vscode.window.showErrorMessage(problemText('no-active-program'));
    return;
  }
  const document = vscode.workspace.textDocuments.find((d) => d.uri.toString() === uri.toString());
  if (document?.isDirty === true) await document.save(); // the adapter reads the file from disk
  const folder = vscode.workspace.getWorkspaceFolder(uri);
  await vscode.debug.startDebugging(folder, programConfiguration(uri.fsPath, false) as vscode.DebugConfiguration);
}

/** Registers the debugger's parts; `startedServer` waits for the language server's start-up. */
export function registerDebugger(startedServer: StartedServer, ask: AskServer): vscode.Disposable[] {
  return [
    vscode.debug.registerDebugConfigurationProvider(DEBUG_TYPE, new LaunchConfigurations()),
    vscode.debug.registerDebugAdapterDescriptorFactory(DEBUG_TYPE, new AdapterFactory(startedServer)),
    vscode.debug.registerDebugAdapterTrackerFactory(DEBUG_TYPE, followStops),
    vscode.languages.registerEvaluatableExpressionProvider(LANGUAGE_ID, hoverVariables(ask)),
    vscode.commands.registerCommand(COMMAND_DEBUG_PROGRAM, debugProgram),
  ];
}
