// The status bar item of FANUC Macro programs: the controller the analysis is for (with 0i-F,
// the machine the active document was read as, asked of the server when its diagnostics come
// and when the active editor changes) and the language server's state
// (client/src/serverStatus.ts says what it shows). A click picks another controller and writes
// the `fanuc-macro.controller` setting.
import * as vscode from 'vscode';
import type { AskServer } from './debugAdapter';
import { ServerStatus, controllerChoices, controllersOf, settingTarget } from './serverStatus';

export const SELECT_CONTROLLER_COMMAND = 'fanuc-macro.selectController';
/** The server's command: the machine a document was read as. */
export const SERVER_COMMAND_MACHINE = 'fanuc-macro.machine';
const LANGUAGE_ID = 'fanuc-macro';
const CONFIG_SECTION = 'fanuc-macro';
const CONTROLLER_KEY = 'controller';

const t = (message: string, ...args: Array<string | number>): string => vscode.l10n.t(message, ...args);

function configuredController(): string | undefined {
  return vscode.workspace.getConfiguration(CONFIG_SECTION).get<string>(CONTROLLER_KEY);
}

/** The active editor's document when it is a FANUC Macro program: its URI. */
function activeProgram(): string | undefined {
  const document = vscode.window.activeTextEditor?.document;
  return document?.languageId === LANGUAGE_ID ? document.uri.toString() : undefined;
}

export class StatusItem implements vscode.Disposable {
  readonly status: ServerStatus;
  private readonly item: vscode.StatusBarItem;
  private readonly disposables: vscode.Disposable[] = [];

  constructor(private readonly ask: AskServer = () => Promise.resolve(undefined)) {
    this.item = vscode.window.createStatusBarItem('fanuc-macro.status', vscode.StatusBarAlignment.Right, 100);
    this.item.name = t('FANUC Macro B');
    this.item.command = SELECT_CONTROLLER_COMMAND;
    this.status = new ServerStatus(() => this.update());
    this.disposables.push(
      this.item,
      vscode.commands.registerCommand(SELECT_CONTROLLER_COMMAND, () => selectController(this.status)),
      vscode.workspace.onDidChangeConfiguration((event) => {
        // The documents are analysed again: their machines come with their diagnostics.
        if (event.affectsConfiguration(`${CONFIG_SECTION}.${CONTROLLER_KEY}`)) this.status.forgetMachines();
      }),
      vscode.window.onDidChangeActiveTextEditor(() => {
        this.update();
        const uri = activeProgram();
        if (uri !== undefined) void this.askMachine(uri);
      }),
    );
    this.update();
  }

  /** The diagnostics of `uri` came: its analysis is done, so is the machine it was read as. */
  documentAnalysed(uri: string): void {
    if (uri === activeProgram()) void this.askMachine(uri);
  }

  /** `uri` was closed: its machine is not shown again. */
  documentClosed(uri: string): void {
    this.status.forgetMachines(uri);
  }

  private async askMachine(uri: string): Promise<void> {
    const question = this.status.askingMachine(uri);
    let answer: unknown;
    try {
      answer = await this.ask(SERVER_COMMAND_MACHINE, [uri]);
    } catch {
      answer = undefined; // no machine shown, the controller's label instead
    }
    this.status.machineAnswered(uri, question, answer);
  }

  /** The server's answer to fanuc-macro.controllers: the controllers and their kinds. */
  setControllers(answer: unknown): void {
    this.status.controllers = controllersOf(answer);
    this.update();
  }

  /** Shown while a FANUC Macro program is the active editor. */
  update(): void {
    const view = this.status.view(configuredController(), t, activeProgram());
    this.item.text = view.text;
    this.item.tooltip = view.tooltip;
    this.item.backgroundColor = view.error ? new vscode.ThemeColor('statusBarItem.errorBackground') : undefined;
    if (activeProgram() !== undefined || view.error) this.item.show();
    else this.item.hide();
  }

  dispose(): void {
    for (const d of this.disposables.splice(0)) d.dispose();
  }
}

/** Quick pick of the controllers; the choice is written where the setting is set now. */
export async function selectController(status: ServerStatus): Promise<string | undefined> {
  const config = vscode.workspace.getConfiguration(CONFIG_SECTION);
  const current = config.get<string>(CONTROLLER_KEY);
  const picked = await vscode.window.showQuickPick(controllerChoices(current, status.controllers, t), {
    title: t('FANUC Macro: controller of the analysis'),
    placeHolder: t('The controller whose Custom Macro B dialect and limits the analysis uses'),
  });
  if (picked === undefined || picked.id === current) return undefined;
  const where = settingTarget(config.inspect(CONTROLLER_KEY));
  const target =
    where === 'workspaceFolder'
      ? vscode.ConfigurationTarget.WorkspaceFolder
      : where === 'workspace'
        ? vscode.ConfigurationTarget.Workspace
        : vscode.ConfigurationTarget.Global;
  await config.update(CONTROLLER_KEY, picked.id, target);
  return picked.id;
}
