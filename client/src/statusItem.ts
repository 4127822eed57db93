// The status bar item of FANUC Macro programs: the controller the analysis is for and the
// language server's state (client/src/serverStatus.ts says what it shows). A click picks
// another controller and writes the `fanuc-macro.controller` setting.
import * as vscode from 'vscode';
import { ServerStatus, controllerChoices, controllersOf, settingTarget } from './serverStatus';

export const SELECT_CONTROLLER_COMMAND = 'fanuc-macro.selectController';
const CONFIG_SECTION = 'fanuc-macro';
const CONTROLLER_KEY = 'controller';

const t = (message: string, ...args: Array<string | number>): string => vscode.l10n.t(message, ...args);

function configuredController(): string | undefined {
  return vscode.workspace.getConfiguration(CONFIG_SECTION).get<string>(CONTROLLER_KEY);
}

export class StatusItem implements vscode.Disposable {
  readonly status: ServerStatus;
  private readonly item: vscode.StatusBarItem;
  private readonly disposables: vscode.Disposable[] = [];

  constructor() {
    this.item = vscode.window.createStatusBarItem('fanuc-macro.status', vscode.StatusBarAlignment.Right, 100);
    this.item.name = t('FANUC Macro B');
    this.item.command = SELECT_CONTROLLER_COMMAND;
    this.status = new ServerStatus(() => this.update());
    this.disposables.push(
      this.item,
      vscode.commands.registerCommand(SELECT_CONTROLLER_COMMAND, () => selectController(this.status)),
      vscode.workspace.onDidChangeConfiguration((event) => {
        if (event.affectsConfiguration(`${CONFIG_SECTION}.${CONTROLLER_KEY}`)) this.update();
      }),
      vscode.window.onDidChangeActiveTextEditor(() => this.update()),
    );
    this.update();
  }

  /** The server's answer to fanuc-macro.controllers: the controllers and their kinds. */
  setControllers(answer: unknown): void {
    this.status.controllers = controllersOf(answer);
    this.update();
  }

  /** Shown while a FANUC Macro program is the active editor. */
  update(): void {
    const view = this.status.view(configuredController(), t);
    this.item.text = view.text;
    this.item.tooltip = view.tooltip;
    this.item.backgroundColor = view.error ? new vscode.ThemeColor('statusBarItem.errorBackground') : undefined;
    const language = vscode.window.activeTextEditor?.document.languageId;
    if (language === 'fanuc-macro' || view.error) this.item.show();
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
