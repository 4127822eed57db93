// A small stand-in for the `vscode` module, enough to run client/src/extension.ts
// under node:test. The test build aliases `vscode` to this file.

export type Handler = (...args: unknown[]) => unknown;

export const ViewColumn = { Active: -1, Beside: -2, One: 1 } as const;
export const ProgressLocation = { SourceControl: 1, Window: 10, Notification: 15 } as const;

export class Uri {
  private constructor(
    readonly scheme: string,
    readonly fsPath: string,
    readonly query = '',
    readonly fragment = '',
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
  static parse(text: string): Uri {
    const match = /^([a-z][a-z0-9+.-]*):(?:\/\/)?([^?#]*)(?:\?([^#]*))?(?:#(.*))?$/i.exec(text);
    if (match === null) throw new Error(`not a URI: ${text}`);
    return new Uri(match[1]!, match[2]!, match[3] ?? '', match[4] ?? '');
  }
  get path(): string {
    return this.fsPath;
  }
  with(change: { fragment?: string; query?: string }): Uri {
    return new Uri(this.scheme, this.fsPath, change.query ?? this.query, change.fragment ?? this.fragment);
  }
  toString(): string {
    const base = this.scheme === 'file' ? `file://${this.fsPath}` : `${this.scheme}:${this.fsPath}`;
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
  constructor(startLine: number, startCharacter: number, endLine: number, endCharacter: number) {
    this.start = new Position(startLine, startCharacter);
    this.end = new Position(endLine, endCharacter);
  }
}

export class Location {
  constructor(
    readonly uri: Uri,
    readonly range: Position,
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
  content: new Map<string, { provideTextDocumentContent(uri: Uri): string }>(),
  links: [] as Array<{ selector: unknown; provider: { provideDocumentLinks(d: FakeDocument): DocumentLink[] } }>,
  definitions: [] as Array<{
    selector: unknown;
    provider: { provideDefinition(d: FakeDocument, p: Position): Location | undefined };
  }>,
};

/** Everything the extension did, for the assertions. */
export const recorded = {
  errors: [] as Array<{ message: string; items: string[] }>,
  warnings: [] as string[],
  executed: [] as Array<{ command: string; args: unknown[] }>,
  openedDocuments: [] as Array<{ content: string; language: string }>,
  shownDocuments: [] as Array<{ content: string; options: unknown }>,
  inserts: [] as Array<{ position: Position; text: string }>,
  log: [] as string[],
};

/** Scripted answers for the next prompts, consumed in order. */
export const answers = {
  errorChoice: [] as Array<string | undefined>,
  inputBox: [] as Array<string | undefined>,
  quickPick: [] as Array<(items: ReadonlyArray<{ label: string }>) => unknown>,
  inputValidation: [] as Array<string | undefined>,
};

export function resetRecorded(): void {
  recorded.errors.length = 0;
  recorded.warnings.length = 0;
  recorded.executed.length = 0;
  recorded.openedDocuments.length = 0;
  recorded.shownDocuments.length = 0;
  recorded.inserts.length = 0;
}

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

class Configuration {
  constructor(values: Record<string, unknown>) {
    Object.assign(this, nested(values));
  }
  get<T>(key: string, fallback?: T): T | undefined {
    return (key in settings ? settings[key] : fallback) as T | undefined;
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

export const window = {
  activeTextEditor: undefined as FakeEditor | undefined,
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
  showInputBox(options: { validateInput?: (value: string) => string | undefined }): Promise<string | undefined> {
    const answer = answers.inputBox.shift();
    if (answer !== undefined && options.validateInput) {
      answers.inputValidation.push(options.validateInput(answer));
    }
    return Promise.resolve(answer);
  },
  showQuickPick<T extends { label: string }>(items: readonly T[]): Promise<T | undefined> {
    const choose = answers.quickPick.shift();
    return Promise.resolve(choose ? (choose(items) as T | undefined) : undefined);
  },
  withProgress<T>(_options: unknown, task: () => Promise<T>): Promise<T> {
    return task();
  },
  showTextDocument(document: { content: string }, options: unknown): Promise<unknown> {
    recorded.shownDocuments.push({ content: document.content, options });
    return Promise.resolve(undefined);
  },
};

export const workspace = {
  workspaceFolders: undefined as Array<{ uri: Uri }> | undefined,
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
  openTextDocument(what: { content: string; language: string } | Uri): Promise<FakeDocument | { content: string }> {
    if (what instanceof Uri) {
      const provider = providers.content.get(what.scheme);
      if (provider === undefined) return Promise.reject(new Error(`no provider of ${what.scheme}`));
      const content = provider.provideTextDocumentContent(what);
      recorded.openedDocuments.push({ content, language: 'plaintext' });
      return Promise.resolve({ uri: what, languageId: 'plaintext', content, getText: () => content });
    }
    recorded.openedDocuments.push(what);
    return Promise.resolve({ content: what.content });
  },
  registerTextDocumentContentProvider(scheme: string, provider: { provideTextDocumentContent(uri: Uri): string }) {
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

export const extensions = {
  getExtension(id: string): unknown {
    return id === 'ms-python.python' ? pythonExtension : undefined;
  },
};
