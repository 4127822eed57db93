// What the status bar item says: the controller the analysis is for (lathe or mill) and the
// language server's state. Pure logic, no `vscode` import: the UI strings go through the
// translator given (vscode.l10n.t in the extension), so it is unit-tested with node:test.

/** Formats a UI string: `{0}`, `{1}`... are replaced by the arguments (as vscode.l10n.t does). */
export type Translate = (message: string, ...args: Array<string | number>) => string;

/** The identity translation, English (tests, and the fallback). */
export const english: Translate = (message, ...args) =>
  message.replace(/\{(\d+)\}/g, (whole, index: string) => {
    const value = args[Number(index)];
    return value === undefined ? whole : String(value);
  });

export type MachineKind = 'lathe' | 'mill' | 'lathe and mill';

export interface Controller {
  /** The value of the `fanuc-macro.controller` setting. */
  readonly id: string;
  /** Undefined for a value the server does not know. */
  readonly kind: MachineKind | undefined;
  /** The series name, as FANUC calls it. */
  readonly series: string;
}

/** What the server's fanuc-macro.controllers gives: its controllers and the setting's default. */
export interface Controllers {
  readonly list: readonly Controller[];
  readonly default: string | undefined;
}

export const NO_CONTROLLERS: Controllers = { list: [], default: undefined };

/** The server's answer read; none when it is not one. */
export function controllersOf(answer: unknown): Controllers {
  const { controllers, default: fallback } = (typeof answer === 'object' && answer !== null ? answer : {}) as Record<string, unknown>;
  if (!Array.isArray(controllers)) return NO_CONTROLLERS;
  const list = controllers.filter(
    (c): c is Controller => typeof c === 'object' && c !== null && typeof c.id === 'string' && typeof c.series === 'string',
  );
  return { list, default: typeof fallback === 'string' ? fallback : undefined };
}

/** The controller of a setting's value; one the server did not name is shown as it is, of no kind. */
export function controllerOf(id: string | undefined, known: Controllers): Controller {
  const value = id === undefined || id.trim() === '' ? (known.default ?? '') : id;
  return known.list.find((c) => c.id === value) ?? { id: value, kind: undefined, series: value };
}

function kindText(kind: MachineKind | undefined, t: Translate): string | undefined {
  return kind === undefined ? undefined : { lathe: t('lathe'), mill: t('mill'), 'lathe and mill': t('lathe and mill') }[kind];
}

/** "0i-TF lathe": the controller as the status bar shows it. */
export function controllerLabel(id: string | undefined, known: Controllers, t: Translate = english): string {
  const controller = controllerOf(id, known);
  const kind = kindText(controller.kind, t);
  return kind === undefined ? controller.id : `${controller.id} ${kind}`;
}

/** A quick pick's item for each controller, the current one marked. */
export function controllerChoices(
  current: string | undefined,
  known: Controllers,
  t: Translate = english,
): Array<{ label: string; description: string; detail?: string; id: string; picked: boolean }> {
  const now = controllerOf(current, known).id;
  return known.list.map((c) => ({
    label: c.id === now ? `$(check) ${c.id}` : c.id,
    description: kindText(c.kind, t) ?? '',
    detail: c.series,
    id: c.id,
    picked: c.id === now,
  }));
}

/** Where a changed setting is written: where it is set now, the most specific place first. */
export type SettingTarget = 'workspaceFolder' | 'workspace' | 'global';

export function settingTarget(inspected: {
  workspaceFolderValue?: unknown;
  workspaceValue?: unknown;
} | undefined): SettingTarget {
  if (inspected?.workspaceFolderValue !== undefined) return 'workspaceFolder';
  if (inspected?.workspaceValue !== undefined) return 'workspace';
  return 'global';
}

export type ServerState = 'starting' | 'ready' | 'analysing' | 'stopped' | 'error';

/**
 * The language server's state, from the client's life cycle and the documents it sends:
 * a document opened or changed is being analysed until its diagnostics come back.
 */
export class ServerStatus {
  private state: Exclude<ServerState, 'analysing'> = 'stopped';
  private reason: string | undefined;
  private version: string | undefined;
  private readonly pending = new Set<string>();
  /** The server's controllers, once it has named them. */
  controllers: Controllers = NO_CONTROLLERS;

  constructor(private readonly changed: () => void = () => undefined) {}

  get current(): ServerState {
    return this.state === 'ready' && this.pending.size > 0 ? 'analysing' : this.state;
  }

  /** The reason of the error state. */
  get error(): string | undefined {
    return this.state === 'error' ? this.reason : undefined;
  }

  /** Documents whose analysis has not answered yet. */
  get analysing(): number {
    return this.pending.size;
  }

  starting(): void {
    this.set('starting', undefined);
  }

  ready(version: string | undefined): void {
    this.version = version;
    this.set('ready', undefined);
  }

  /** Stopped on purpose (a restart, the window closing); an error stays shown. */
  stopped(): void {
    if (this.state !== 'error') this.set('stopped', undefined);
  }

  failed(reason: string): void {
    this.set('error', reason);
  }

  analysisStarted(uri: string): void {
    this.pending.add(uri);
    this.changed();
  }

  /** Diagnostics came for `uri` (or it was closed): its analysis answered. */
  analysisDone(uri: string): void {
    if (this.pending.delete(uri)) this.changed();
  }

  private set(state: Exclude<ServerState, 'analysing'>, reason: string | undefined): void {
    this.state = state;
    this.reason = reason;
    this.pending.clear();
    this.changed();
  }

  /** The status bar item's text, tooltip and whether it shows an error. */
  view(controller: string | undefined, t: Translate = english): { text: string; tooltip: string; error: boolean } {
    const label = controllerLabel(controller, this.controllers, t);
    const series = controllerOf(controller, this.controllers).series;
    const server = this.version === undefined ? 'fanuc-macro-ls' : `fanuc-macro-ls ${this.version}`;
    // Each state: its icon, its word after the label (none when ready), its tooltip line.
    const shown: Record<ServerState, [string, string | undefined, string]> = {
      starting: ['loading~spin', t('starting'), t('Language server: starting')],
      ready: ['check', undefined, t('Language server: ready ({0})', server)],
      analysing: ['sync~spin', t('analysing'), t('Language server: analysing {0} document(s) ({1})', this.pending.size, server)],
      stopped: ['circle-slash', t('stopped'), t('Language server: stopped')],
      error: ['error', t('error'), t('Language server: error: {0}', this.reason ?? t('unknown reason'))],
    };
    const [icon, word, line] = shown[this.current];
    return {
      text: `$(${icon}) ${label}${word === undefined ? '' : ` · ${word}`}`,
      tooltip: `${t('Controller: {0}', series)}\n${line}\n${t('Click to choose another controller.')}`,
      error: this.current === 'error',
    };
  }
}
