// A small stand-in for the `vscode` module, enough to run client/src/extension.ts
// under node:test. The test build aliases `vscode` to this file.

export type Handler = (...args: unknown[]) => unknown;

export const ViewColumn = { Active: -1, Beside: -2, One: 1 } as const;
export const ProgressLocation = { SourceControl: 1, Window: 10, Notification: 15 } as const;
export enum InputBoxValidationSeverity {
  Info = 1,
  Warning = 2,
  Error = 3,
}
export const StatusBarAlignment = { Left: 1, Right: 2 } as const;
export const ConfigurationTarget = { Global: 1, Workspace: 2, WorkspaceFolder: 3 } as const;
export const TextEditorRevealType = { Default: 0, InCenter: 1, InCenterIfOutsideViewport: 2, AtTop: 3 } as const;
export const TaskScope = { Global: 1, Workspace: 2 } as const;
export const TaskGroup = { Build: { id: 'build' } } as const;

export class ThemeColor {
  constructor(readonly id: string) {}
}

/** vscode.l10n with no bundle loaded: the message, its {0} {1}... filled in. */
export const l10n = {
  t(message: string, ...args: Array<string | number>): string {
    return message.replace(/\{(\d+)\}/g, (whole, index: string) => {
      const value = args[Number(index)];
      return value === undefined ? whole : String(value);
    });
  },
};

export class ProcessExecution {
  constructor(
    readonly process: string,
    readonly args: string[],
    readonly options?: { cwd?: string; env?: Record<string, string> },
  ) {}
}

export class Task {
  group?: unknown;
  constructor(
    readonly definition: { type: string; [key: string]: unknown },
    readonly scope: unknown,
    readonly name: string,
    readonly source: string,
    readonly execution: ProcessExecution,
    readonly problemMatchers: string[],
  ) {}
}

export class Uri {
  private constructor(
    readonly scheme: string,
    readonly fsPath: string,
    readonly query = '',
    readonly fragment = '',
    readonly authority = '',
  ) {}
  static file(path: string): Uri {
    return new Uri('file', path);
  }
  static untitled(name: string): Uri {
    return new Uri('untitled', name);
  }
  static from(parts: { scheme: string; path?: string; query?: string; fragment?: string }): Uri {
    return new Uri(parts.scheme, parts.path ?? '', parts.query ?? '', parts.fragment ?? '');
  }
  static joinPath(base: Uri, ...parts: string[]): Uri {
    return new Uri(base.scheme, [base.fsPath, ...parts].join('/'), '', '', base.authority);
  }
  static parse(text: string): Uri {
    const match = /^([a-z][a-z0-9+.-]*):(?:\/\/([^/?#]*))?([^?#]*)(?:\?([^#]*))?(?:#(.*))?$/i.exec(text);
    if (match === null) throw new Error(`not a URI: ${text}`);
    return new Uri(match[1]!, match[3]!, match[4] ?? '', match[5] ?? '', match[2] ?? '');
  }
  get path(): string {
    return this.fsPath;
  }
  with(change: { fragment?: string; query?: string }): Uri {
    return new Uri(this.scheme, this.fsPath, change.query ?? this.query, change.fragment ?? this.fragment, this.authority);
  }
  toString(_skipEncoding?: boolean): string {
    const base =
      this.scheme === 'file'
        ? `file://${this.fsPath}`
        : this.authority !== ''
          ? `${this.scheme}://${this.authority}${this.fsPath}`
          : `${this.scheme}:${this.fsPath}`;
    return `${base}${this.query ? `?${this.query}` : ''}${this.fragment ? `#${this.fragment}` : ''}`;
  }
}

export class EventEmitter<T> {
  private readonly listeners: Array<(value: T) => void> = [];
  readonly event = (listener: (value: T) => void) => {
    this.listeners.push(listener);
    return { dispose: () => undefined };
  };
  fire(value: T): void {
    for (const listener of this.listeners) listener(value);
  }
  dispose(): void {
    this.listeners.length = 0;
  }
}

export class Position {
  constructor(
    readonly line: number,
    readonly character: number,
  ) {}
}

export class Range {
  readonly start: Position;
  readonly end: Position;
  constructor(start: Position, end: Position);
  constructor(startLine: number, startCharacter: number, endLine: number, endCharacter: number);
  constructor(a: number | Position, b: number | Position, c?: number, d?: number) {
    this.start = a instanceof Position ? a : new Position(a, b as number);
    this.end = b instanceof Position ? b : new Position(c ?? 0, d ?? 0);
  }
}

export class Location {
  constructor(
    readonly uri: Uri,
    readonly range: Position,
  ) {}
}

export class EvaluatableExpression {
  constructor(
    readonly range: Range,
    readonly expression?: string,
  ) {}
}

export class DebugAdapterExecutable {
  constructor(
    readonly command: string,
    readonly args: string[],
    readonly options?: { env?: Record<string, string>; cwd?: string },
  ) {}
}

export class DocumentLink {
  tooltip?: string;
  constructor(
    readonly range: Range,
    readonly target?: Uri,
  ) {}
}

/** A document of the fakes: what openTextDocument gives. */
export interface FakeDocument {
  uri: Uri;
  languageId: string;
  content: string;
  getText(): string;
}

/** Providers the extension registered, by kind. */
export const providers = {
  content: new Map<string, { provideTextDocumentContent(uri: Uri): string | Promise<string> }>(),
  links: [] as Array<{ selector: unknown; provider: { provideDocumentLinks(d: FakeDocument): DocumentLink[] } }>,
  definitions: [] as Array<{
    selector: unknown;
    provider: { provideDefinition(d: FakeDocument, p: Position): Location | undefined };
  }>,
  evaluatable: [] as Array<{
    selector: unknown;
    provider: {
      provideEvaluatableExpression(
        d: { lineAt(line: number): { text: string } },
        p: Position,
      ): EvaluatableExpression | undefined | PromiseLike<EvaluatableExpression | undefined>;
    };
  }>,
};

/** Everything the extension did, for the assertions. */
export const recorded = {
  settingUpdates: [] as Array<{ key: string; value: unknown; target: number }>,
  errors: [] as Array<{ message: string; items: string[] }>,
  warnings: [] as string[],
  executed: [] as Array<{ command: string; args: unknown[] }>,
  openedDocuments: [] as Array<{ content: string; language: string }>,
  shownDocuments: [] as Array<{ content: string; options: unknown }>,
  revealed: [] as Array<{ line: number; type: number | undefined }>,
  inserts: [] as Array<{ position: Position; text: string }>,
  inputBoxes: [] as Array<{ title: string | undefined; value: string | undefined; placeHolder?: string | undefined }>,
  informations: [] as string[],
  quickPicks: [] as Array<{ title: string | undefined; placeHolder: string | undefined }>,
  statusMessages: [] as string[],
  log: [] as string[],
};

/** Scripted answers for the next prompts, consumed in order. */
export const answers = {
  errorChoice: [] as Array<string | undefined>,
  /** A text typed, or what the user does with the box as it opened (Enter: `(box) => box.value`). */
  inputBox: [] as Array<string | undefined | ((box: { value: string | undefined; placeHolder: string | undefined }) => string | undefined)>,
  quickPick: [] as Array<(items: ReadonlyArray<{ label: string }>) => unknown>,
  /** What each answer's validation said: an error's text, `warning: ...`, or undefined. */
  inputValidation: [] as Array<string | undefined>,
};

export function resetRecorded(): void {
  recorded.errors.length = 0;
  recorded.warnings.length = 0;
  recorded.executed.length = 0;
  recorded.openedDocuments.length = 0;
  recorded.shownDocuments.length = 0;
  recorded.revealed.length = 0;
  recorded.inserts.length = 0;
  recorded.inputBoxes.length = 0;
  recorded.informations.length = 0;
  recorded.quickPicks.length = 0;
  recorded.statusMessages.length = 0;
  recorded.settingUpdates.length = 0;
}

// --- status bar --------------------------------------------------------------

/** A status bar item; `texts` keeps each text it showed, in order. */
export class FakeStatusBarItem {
  readonly texts: string[] = [];
  private shown = '';
  tooltip: string | undefined;
  command: string | undefined;
  name: string | undefined;
  backgroundColor: ThemeColor | undefined;
  visible = false;
  constructor(readonly id: string) {}
  get text(): string {
    return this.shown;
  }
  set text(value: string) {
    if (value !== this.shown) this.texts.push(value);
    this.shown = value;
  }
  show(): void {
    this.visible = true;
  }
  hide(): void {
    this.visible = false;
  }
  dispose(): void {}
}

export const statusBarItems: FakeStatusBarItem[] = [];

// --- configuration -----------------------------------------------------------

export let settings: Record<string, unknown> = {};

export function setSettings(values: Record<string, unknown>): void {
  settings = values;
}

function nested(flat: Record<string, unknown>): Record<string, unknown> {
  const root: Record<string, unknown> = {};
  for (const [key, value] of Object.entries(flat)) {
    const parts = key.split('.');
    let node = root;
    for (const part of parts.slice(0, -1)) {
      node[part] ??= {};
      node = node[part] as Record<string, unknown>;
    }
    node[parts[parts.length - 1] ?? key] = value;
  }
  return root;
}

/** Where each setting is set, for inspect(): absent keys are set in the user settings. */
export const settingScopes: Record<string, 'workspace' | 'workspaceFolder'> = {};

class Configuration {
  constructor(values: Record<string, unknown>) {
    Object.assign(this, nested(values));
  }
  get<T>(key: string, fallback?: T): T | undefined {
    return (key in settings ? settings[key] : fallback) as T | undefined;
  }
  inspect(key: string): Record<string, unknown> | undefined {
    if (!(key in settings)) return { key };
    const scope = settingScopes[key];
    const value = settings[key];
    if (scope === 'workspaceFolder') return { key, workspaceFolderValue: value };
    if (scope === 'workspace') return { key, workspaceValue: value };
    return { key, globalValue: value };
  }
  update(key: string, value: unknown, target: number): Promise<void> {
    recorded.settingUpdates.push({ key, value, target });
    settings = { ...settings, [key]: value };
    fireConfigurationChange(`fanuc-macro.${key}`);
    return Promise.resolve();
  }
}

const configurationListeners: Handler[] = [];
const closeListeners: Handler[] = [];
const trustListeners: Array<() => void> = [];

export function fireTrustGranted(): void {
  for (const listener of trustListeners) {
    listener();
  }
}

export function fireConfigurationChange(changedKey: string): void {
  for (const listener of configurationListeners) {
    listener({ affectsConfiguration: (section: string) => changedKey.startsWith(section) });
  }
}

// --- editor ------------------------------------------------------------------

export interface FakeEditor {
  document: { uri: Uri; languageId: string; isUntitled: boolean };
  selection: { active: Position };
  edit(callback: (builder: { insert(position: Position, text: string): void }) => void): Promise<boolean>;
}

export function makeEditor(path: string, languageId = 'fanuc-macro'): FakeEditor {
  return {
    document: { uri: Uri.file(path), languageId, isUntitled: false },
    selection: { active: new Position(4, 0) },
    edit(callback) {
      callback({
        insert(position, text) {
          recorded.inserts.push({ position, text });
        },
      });
      return Promise.resolve(true);
    },
  };
}

// --- namespaces --------------------------------------------------------------

const commandHandlers = new Map<string, Handler>();

export const commands = {
  registerCommand(id: string, handler: Handler) {
    commandHandlers.set(id, handler);
    return { dispose: () => commandHandlers.delete(id) };
  },
  async executeCommand(id: string, ...args: unknown[]): Promise<unknown> {
    recorded.executed.push({ command: id, args });
    const handler = commandHandlers.get(id);
    return handler ? handler(...args) : undefined;
  },
};

const activeEditorListeners: Handler[] = [];

/** Makes `editor` the active one, as a click on its tab does. */
export function setActiveEditor(editor: FakeEditor | undefined): void {
  window.activeTextEditor = editor;
  for (const listener of [...activeEditorListeners]) listener(editor);
}

export const window = {
  activeTextEditor: undefined as FakeEditor | undefined,
  createStatusBarItem(id: string, _alignment?: number, _priority?: number): FakeStatusBarItem {
    const item = new FakeStatusBarItem(id);
    statusBarItems.push(item);
    return item;
  },
  onDidChangeActiveTextEditor(listener: Handler) {
    activeEditorListeners.push(listener);
    return { dispose: () => activeEditorListeners.splice(activeEditorListeners.indexOf(listener), 1) };
  },
  createOutputChannel(_name: string) {
    return {
      appendLine: (line: string) => recorded.log.push(line),
      append: (text: string) => recorded.log.push(text),
      show: () => undefined,
      clear: () => undefined,
      dispose: () => undefined,
    };
  },
  showErrorMessage(message: string, ...items: string[]): Promise<string | undefined> {
    recorded.errors.push({ message, items });
    return Promise.resolve(answers.errorChoice.shift());
  },
  showWarningMessage(message: string): Promise<undefined> {
    recorded.warnings.push(message);
    return Promise.resolve(undefined);
  },
  showInformationMessage(message: string): Promise<undefined> {
    recorded.informations.push(message);
    return Promise.resolve(undefined);
  },
  async showInputBox(options: {
    title?: string;
    value?: string;
    placeHolder?: string;
    validateInput?: (
      value: string,
    ) =>
      | string
      | { message: string; severity: InputBoxValidationSeverity }
      | undefined
      | PromiseLike<string | { message: string; severity: InputBoxValidationSeverity } | undefined>;
  }): Promise<string | undefined> {
    recorded.inputBoxes.push({ title: options.title, value: options.value, placeHolder: options.placeHolder });
    const scripted = answers.inputBox.shift();
    const answer = typeof scripted === 'function' ? scripted({ value: options.value, placeHolder: options.placeHolder }) : scripted;
    if (answer !== undefined && options.validateInput) {
      const said = await options.validateInput(answer);
      answers.inputValidation.push(typeof said === 'object' ? `warning: ${said.message}` : said);
    }
    return answer;
  },
  showQuickPick<T extends { label: string }>(
    items: readonly T[],
    options?: { title?: string; placeHolder?: string },
  ): Promise<T | undefined> {
    recorded.quickPicks.push({ title: options?.title, placeHolder: options?.placeHolder });
    const choose = answers.quickPick.shift();
    return Promise.resolve(choose ? (choose(items) as T | undefined) : undefined);
  },
  setStatusBarMessage(text: string, _timeout?: number) {
    recorded.statusMessages.push(text);
    return { dispose: () => undefined };
  },
  withProgress<T>(_options: unknown, task: () => Promise<T>): Promise<T> {
    return task();
  },
  showTextDocument(document: { content: string }, options: unknown): Promise<unknown> {
    recorded.shownDocuments.push({ content: document.content, options });
    return Promise.resolve({
      document,
      revealRange: (range: Range, type?: number) => recorded.revealed.push({ line: range.start.line, type }),
    });
  },
};

/** Files workspace.fs reads, by path. */
export const files = new Map<string, string>();

export const workspace = {
  workspaceFolders: undefined as Array<{ uri: Uri }> | undefined,
  fs: {
    readFile(uri: Uri): Promise<Uint8Array> {
      const text = files.get(uri.fsPath);
      if (text === undefined) return Promise.reject(new Error(`no file ${uri.fsPath}`));
      return Promise.resolve(new TextEncoder().encode(text));
    },
  },
  textDocuments: [] as Array<{ uri: Uri; isDirty: boolean; save(): Promise<boolean> }>,
  getWorkspaceFolder(_uri: Uri): { uri: Uri } | undefined {
    return workspace.workspaceFolders?.[0];
  },
  getConfiguration(_section: string) {
    return new Configuration(settings);
  },
  onDidChangeConfiguration(listener: Handler) {
    configurationListeners.push(listener);
    return { dispose: () => undefined };
  },
  onDidGrantWorkspaceTrust(listener: () => void) {
    trustListeners.push(listener);
    return { dispose: () => undefined };
  },
  async openTextDocument(what: { content: string; language: string } | Uri): Promise<FakeDocument | { content: string }> {
    if (what instanceof Uri) {
      const provider = providers.content.get(what.scheme);
      if (provider === undefined) throw new Error(`no provider of ${what.scheme}`);
      const content = await provider.provideTextDocumentContent(what);
      recorded.openedDocuments.push({ content, language: 'plaintext' });
      return { uri: what, languageId: 'plaintext', content, getText: () => content };
    }
    recorded.openedDocuments.push(what);
    return Promise.resolve({ content: what.content });
  },
  registerTextDocumentContentProvider(
    scheme: string,
    provider: { provideTextDocumentContent(uri: Uri): string | Promise<string> },
  ) {
    providers.content.set(scheme, provider);
    return { dispose: () => providers.content.delete(scheme) };
  },
  onDidCloseTextDocument(listener: Handler) {
    closeListeners.push(listener);
    return { dispose: () => undefined };
  },
};

export const languages = {
  registerDocumentLinkProvider(selector: unknown, provider: (typeof providers.links)[number]['provider']) {
    providers.links.push({ selector, provider });
    return { dispose: () => undefined };
  },
  registerDefinitionProvider(selector: unknown, provider: (typeof providers.definitions)[number]['provider']) {
    providers.definitions.push({ selector, provider });
    return { dispose: () => undefined };
  },
  registerEvaluatableExpressionProvider(selector: unknown, provider: (typeof providers.evaluatable)[number]['provider']) {
    providers.evaluatable.push({ selector, provider });
    return { dispose: () => undefined };
  },
  setTextDocumentLanguage(document: FakeDocument, languageId: string): Promise<FakeDocument> {
    // As VS Code does: the document is closed, then opened again with the new language.
    for (const listener of closeListeners) listener(document);
    const last = recorded.openedDocuments[recorded.openedDocuments.length - 1];
    if (last !== undefined) last.language = languageId;
    return Promise.resolve({ ...document, languageId });
  },
};

export let pythonExtension: unknown;

export function setPythonExtension(extension: unknown): void {
  pythonExtension = extension;
}

/** Task providers the extension registered, by type. */
export const taskProviders = new Map<
  string,
  { provideTasks(): Task[]; resolveTask(task: { definition: unknown; scope?: unknown }): Task | undefined }
>();

export const tasks = {
  registerTaskProvider(type: string, provider: (typeof taskProviders extends Map<string, infer P> ? P : never)) {
    taskProviders.set(type, provider);
    return { dispose: () => taskProviders.delete(type) };
  },
};

export const extensions = {
  getExtension(id: string): unknown {
    return id === 'ms-python.python' ? pythonExtension : undefined;
  },
};

// --- debug -------------------------------------------------------------------

/** What the extension registered for a debugger type, and the sessions it started. */
export const debuggers = {
  configurationProviders: new Map<string, { resolveDebugConfiguration(folder: unknown, config: Record<string, unknown>): unknown }>(),
  descriptorFactories: new Map<string, { createDebugAdapterDescriptor(session: unknown, executable: unknown): unknown }>(),
  trackerFactories: new Map<
    string,
    { createDebugAdapterTracker(session: unknown): { onDidSendMessage?(message: unknown): void } | undefined }
  >(),
  started: [] as Array<{ folder: unknown; config: Record<string, unknown> }>,
};

export const debug = {
  registerDebugConfigurationProvider(type: string, provider: Parameters<typeof debuggers.configurationProviders.set>[1]) {
    debuggers.configurationProviders.set(type, provider);
    return { dispose: () => debuggers.configurationProviders.delete(type) };
  },
  registerDebugAdapterDescriptorFactory(type: string, factory: Parameters<typeof debuggers.descriptorFactories.set>[1]) {
    debuggers.descriptorFactories.set(type, factory);
    return { dispose: () => debuggers.descriptorFactories.delete(type) };
  },
  registerDebugAdapterTrackerFactory(type: string, factory: Parameters<typeof debuggers.trackerFactories.set>[1]) {
    debuggers.trackerFactories.set(type, factory);
    return { dispose: () => debuggers.trackerFactories.delete(type) };
  },
  startDebugging(folder: unknown, config: Record<string, unknown>): Promise<boolean> {
    debuggers.started.push({ folder, config });
    return Promise.resolve(true);
  },
};
