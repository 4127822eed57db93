// What the status bar item says: the controller the analysis is for (lathe or mill; with 0i-F,
// the machine the active document was read as) and the language server's state. Pure logic,
// no `vscode` import: the UI strings go through the translator given (vscode.l10n.t in the
// extension), so it is unit-tested with node:test.

/** Formats a UI string: `{0}`, `{1}`... are replaced by the arguments (as vscode.l10n.t does). */
export type Translate = (message: string, ...args: Array<string | number>) => string;

/** The identity translation, English (tests, and the fallback). */
export const english: Translate = (message, ...args) =>
  message.replace(/\{(\d+)\}/g, (whole, index: string) => {
    const value = args[Number(index)];
    return value === undefined ? whole : String(value);
  });

export type MachineKind = 'lathe' | 'mill' | 'lathe and mill' | 'lathe or mill';

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
  return kind === undefined ? undefined : { lathe: t('lathe'), mill: t('mill'), 'lathe and mill': t('lathe and mill'), 'lathe or mill': t('lathe or mill') }[kind];
}

/** "0i-TF lathe": the controller as the status bar shows it. */
export function controllerLabel(id: string | undefined, known: Controllers, t: Translate = english): string {
  const controller = controllerOf(id, known);
  const kind = kindText(controller.kind, t);
  return kind === undefined ? controller.id : `${controller.id} ${kind}`;
}

/**
 * The machine the server read a document as (its fanuc-macro.machine): the controller resolved
 * (0i-F as 0i-TF or 0i-MF), the kind ("unknown": the codes show neither, read as a lathe), and
 * the sentence that says which and why.
 */
export interface DocumentMachine {
  readonly controller: string;
  readonly kind: 'lathe' | 'mill' | 'unknown';
  readonly text: string;
}

/** The server's answer read; undefined when it is not one (a refusal, no server). */
export function documentMachineOf(answer: unknown): DocumentMachine | undefined {
  const { controller, kind, text } = (typeof answer === 'object' && answer !== null ? answer : {}) as Record<string, unknown>;
  if (typeof controller !== 'string' || typeof text !== 'string') return undefined;
  if (kind !== 'lathe' && kind !== 'mill' && kind !== 'unknown') return undefined;
  return { controller, kind, text };
}

/**
 * "0i-F mill": the controller whose kind is "lathe or mill" (each document read as its codes
 * show) with the machine the active document was read as; "0i-F lathe?" when its codes show
 * neither. Any other controller, or no answer yet: the controller's label.
 */
export function machineLabel(
  id: string | undefined,
  known: Controllers,
  machine: DocumentMachine | undefined,
  t: Translate = english,
): string {
  const shown = shownMachine(id, known, machine);
  if (shown === undefined) return controllerLabel(id, known, t);
  const kind = { lathe: t('lathe'), mill: t('mill'), unknown: t('lathe?') }[shown.kind];
  return `${controllerOf(id, known).id} ${kind}`;
}

/** The document's machine, with a controller that reads each document as its codes show. */
function shownMachine(
  id: string | undefined,
  known: Controllers,
  machine: DocumentMachine | undefined,
): DocumentMachine | undefined {
  return controllerOf(id, known).kind === 'lathe or mill' ? machine : undefined;
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
  /** The machine each document was read as, by URI, and the number of the newest question. */
  private readonly machines = new Map<string, DocumentMachine>();
  private readonly asked = new Map<string, number>();
  private questions = 0;
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

  /** A question of `uri`'s machine is sent: its number, for {@link machineAnswered}. */
  askingMachine(uri: string): number {
    this.questions += 1;
    this.asked.set(uri, this.questions);
    return this.questions;
  }

  /**
   * The server's answer to question `question` of `uri`'s machine; the answer to an older
   * question than the newest one sent is dropped, a refusal forgets the machine.
   */
  machineAnswered(uri: string, question: number, answer: unknown): void {
    if (this.asked.get(uri) !== question) return;
    this.asked.delete(uri);
    const machine = documentMachineOf(answer);
    if (machine === undefined) this.machines.delete(uri);
    else this.machines.set(uri, machine);
    this.changed();
  }

  /** The machine `uri` was read as, when the server has said. */
  machine(uri: string | undefined): DocumentMachine | undefined {
    return uri === undefined ? undefined : this.machines.get(uri);
  }

  /** Forgets the machine of `uri` (closed), or of every document (the controller changed). */
  forgetMachines(uri?: string): void {
    if (uri === undefined) {
      this.machines.clear();
      this.asked.clear();
    } else {
      this.machines.delete(uri);
      this.asked.delete(uri);
    }
    this.changed();
  }

  private set(state: Exclude<ServerState, 'analysing'>, reason: string | undefined): void {
    this.state = state;
    this.reason = reason;
    this.pending.clear();
    this.changed();
  }

  /**
   * The status bar item's text, tooltip and whether it shows an error; `document`, the active
   * editor's URI, names the machine shown with a controller that reads each document as its
   * codes show.
   */
  view(
    controller: string | undefined,
    t: Translate = english,
    document?: string,
  ): { text: string; tooltip: string; error: boolean } {
    const machine = this.machine(document);
    const label = machineLabel(controller, this.controllers, machine, t);
    const series = controllerOf(controller, this.controllers).series;
    const machineShown = shownMachine(controller, this.controllers, machine);
    const machineLine = machineShown === undefined ? '' : `\n${machineShown.text}`;
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
      tooltip: `${t('Controller: {0}', series)}${machineLine}\n${line}\n${t('Click to choose another controller.')}`,
      error: this.current === 'error',
    };
  }
}
