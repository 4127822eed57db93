// VS Code client for the fanuc-macro language server (fanuc-macro-ls).
import * as os from 'node:os';
import * as vscode from 'vscode';
import {
  ExecuteCommandRequest,
  LanguageClient,
  State,
  TransportKind,
  type LanguageClientOptions,
  type Middleware,
  type ServerOptions,
} from 'vscode-languageclient/node';
import { registerCheckTasks } from './checkTaskProvider';
import { registerDebugger } from './debugAdapter';
import { registerGeneratorCommands } from './generatorCommands';
import { DEFAULT_PROBE_TIMEOUT_MS, probeCandidate } from './probe';
import {
  BUNDLED_MIN_PYTHON,
  buildCandidates,
  candidateEnv,
  describeAttempts,
  type ProbeResult,
  type ServerCandidate,
} from './serverCandidates';
import { RuleDocs, linkToShippedDocs } from './ruleDocsView';
import { StatusItem } from './statusItem';
import { ToolpathPanel } from './toolpathView';
import { TraceDocuments, traceViewOf } from './traceView';

const LANGUAGE_ID = 'fanuc-macro';
const CONFIG_SECTION = 'fanuc-macro';
const SERVER_PATH_SETTING = `${CONFIG_SECTION}.server.path`;

/** Server-side commands (workspace/executeCommand). */
export const SERVER_COMMAND_TRACE_VIEW = 'fanuc-macro.traceView';
export const SERVER_COMMAND_CONTROLLERS = 'fanuc-macro.controllers';

let client: LanguageClient | undefined;
/** Folder the extension is installed in (holds the bundled server, if any). */
let extensionPath: string | undefined;
/** The same folder as a URI, for the webview's resources. */
let extensionUri: vscode.Uri | undefined;
/** The server.path setting as it read when the running server was started. */
let startedWithPath = '';
let output: vscode.OutputChannel | undefined;
/** The trace views: read-only documents whose rows lead to the blocks (made by activate). */
let traces: TraceDocuments | undefined;
/** Serialises start/stop/restart so that commands and setting changes do not race. */
let lifecycle: Promise<unknown> = Promise.resolve();
/** The status bar item: controller and server state (made by activate). */
let statusItem: StatusItem | undefined;
/** The server candidate the running server was started with, for the check task's command. */
let startedCandidate: ServerCandidate | undefined;

/** Sample program of the walkthrough, in the extension's folder. */
const SAMPLE_PATH = ['samples', 'o1000_walkthrough.nc'] as const;

function outputChannel(): vscode.OutputChannel {
  output ??= vscode.window.createOutputChannel('FANUC Macro Language Server');
  return output;
}

function log(message: string): void {
  outputChannel().appendLine(`[${new Date().toLocaleTimeString()}] ${message}`);
}

function enqueue<T>(task: () => Promise<T>): Promise<T> {
  const next = lifecycle.then(task, task);
  lifecycle = next.catch(() => undefined);
  return next;
}

/** The `fanuc-macro` settings as a plain JSON object (sent as initializationOptions). */
function settingsObject(): Record<string, unknown> {
  const config = vscode.workspace.getConfiguration(CONFIG_SECTION);
  const plain: unknown = JSON.parse(JSON.stringify(config));
  return typeof plain === 'object' && plain !== null ? (plain as Record<string, unknown>) : {};
}

const PYTHON_EXTENSION_TIMEOUT_MS = 10000;

/** `promise`'s value, or undefined after `ms` milliseconds. */
function withTimeout<T>(promise: Thenable<T>, ms: number): Promise<T | undefined> {
  let timer: ReturnType<typeof setTimeout> | undefined;
  const late = new Promise<undefined>((resolve) => (timer = setTimeout(resolve, ms, undefined)));
  return Promise.race([Promise.resolve(promise), late]).finally(() => clearTimeout(timer));
}

/** Interpreter selected in the Python extension, if that extension is installed and answers. */
async function pythonExtensionInterpreter(): Promise<string | undefined> {
  try {
    const extension = vscode.extensions.getExtension('ms-python.python');
    if (extension === undefined) return undefined;
    const api: unknown = extension.isActive
      ? extension.exports
      : await withTimeout(extension.activate(), PYTHON_EXTENSION_TIMEOUT_MS);
    const environments = (api as { environments?: unknown } | undefined)?.environments as
      | {
          getActiveEnvironmentPath?: (resource?: vscode.Uri) => { path?: unknown } | undefined;
          resolveEnvironment?: (env: unknown) => Promise<{ executable?: { uri?: vscode.Uri } } | undefined>;
        }
      | undefined;
    if (typeof environments?.getActiveEnvironmentPath !== 'function') return undefined;
    const resource = vscode.workspace.workspaceFolders?.[0]?.uri;
    const active = environments.getActiveEnvironmentPath(resource);
    if (active === undefined) return undefined;
    // `path` may be an environment folder rather than an interpreter: resolve it when possible.
    if (typeof environments.resolveEnvironment === 'function') {
      try {
        const resolved = await environments.resolveEnvironment(active);
        const executable = resolved?.executable?.uri?.fsPath;
        if (typeof executable === 'string' && executable !== '') return executable;
      } catch {
        // fall back to the raw path below
      }
    }
    return typeof active.path === 'string' && active.path !== '' ? active.path : undefined;
  } catch (err) {
    log(`Python extension did not give an interpreter: ${String(err)}`);
    return undefined;
  }
}

interface FoundServer {
  readonly candidate: ServerCandidate;
  readonly version: string;
}

/** Tries the candidates in order and returns the first that answers `--version`. */
async function findServer(): Promise<
  { found: FoundServer; failures: string[] } | { found: undefined; failures: string[] }
> {
  const config = vscode.workspace.getConfiguration(CONFIG_SECTION);
  const candidates = buildCandidates({
    settingPath: config.get<string>('server.path', ''),
    pythonExtensionInterpreter: await pythonExtensionInterpreter(),
    platform: process.platform,
    homeDir: os.homedir(),
    workspaceFolder: vscode.workspace.workspaceFolders?.[0]?.uri.fsPath,
    extensionPath,
    env: process.env,
  });
  const attempts: Array<{ candidate: ServerCandidate; result: ProbeResult }> = [];
  for (const candidate of candidates) {
    log(`Trying ${candidate.description}`);
    const result = await probeCandidate(candidate, DEFAULT_PROBE_TIMEOUT_MS, candidateEnv(candidate, process.env));
    attempts.push({ candidate, result });
    log(`  ${describeAttempts([{ candidate, result }])[0] ?? ''}`);
    if (result.ok) {
      return {
        found: { candidate, version: result.version },
        failures: describeAttempts(attempts.filter((a) => !a.result.ok)),
      };
    }
  }
  return { found: undefined, failures: describeAttempts(attempts) };
}

async function showServerNotFound(failures: readonly string[]): Promise<void> {
  const tried = failures.map((f) => `• ${f}`).join('\n');
  const message = vscode.l10n.t(
    'FANUC Macro: the language server fanuc-macro-ls was not found, so only highlighting and snippets work. Install it with "pip install fanuc-macro" (in the Python environment VS Code uses), or set "{0}" to the fanuc-macro-ls executable or to a Python interpreter that has the package. The server bundled with the extension needs no installation, only Python {1} or later (python3 on PATH, or the interpreter selected in the Python extension). Tried: {2}.',
    SERVER_PATH_SETTING,
    BUNDLED_MIN_PYTHON,
    failures.join('; '),
  );
  log(`Language server not found. Tried:\n${tried}`);
  const openSetting = vscode.l10n.t('Open Setting');
  const showLog = vscode.l10n.t('Show Log');
  const choice = await vscode.window.showErrorMessage(message, openSetting, showLog);
  if (choice === openSetting) {
    await vscode.commands.executeCommand('workbench.action.openSettings', SERVER_PATH_SETTING);
  } else if (choice === showLog) {
    outputChannel().show(true);
  }
}

async function startClient(): Promise<void> {
  startedWithPath = vscode.workspace.getConfiguration(CONFIG_SECTION).get<string>('server.path', '');
  statusItem?.status.starting();
  const { found, failures } = await findServer();
  if (found === undefined) {
    statusItem?.status.failed(vscode.l10n.t('fanuc-macro-ls was not found (tried {0})', failures.length));
    void showServerNotFound(failures);
    return;
  }
  const { candidate, version } = found;
  startedCandidate = candidate;
  log(`Starting ${candidate.description} (fanuc-macro-ls ${version})`);
  const configured = vscode.workspace.getConfiguration(CONFIG_SECTION).get<string>('server.path', '');
  if (candidate.source !== 'setting' && configured.trim() !== '') {
    void vscode.window.showWarningMessage(
      `FANUC Macro: "${SERVER_PATH_SETTING}" (${configured}) does not start fanuc-macro-ls ` +
        `(${failures[0] ?? 'unknown reason'}); using ${candidate.description} instead.`,
    );
  }

  const executable = {
    command: candidate.command,
    args: [...candidate.args],
    transport: TransportKind.stdio,
    options: { env: { ...candidateEnv(candidate, process.env), PYTHONUNBUFFERED: '1' } },
  };
  const serverOptions: ServerOptions = { run: executable, debug: executable };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [{ scheme: 'file', language: LANGUAGE_ID }, { scheme: 'untitled', language: LANGUAGE_ID }],
    // The settings, and that this extension contributes the snippets (the server then does not
    // offer them a second time).
    initializationOptions: { ...settingsObject(), contributesSnippets: true },
    synchronize: { configurationSection: CONFIG_SECTION },
    outputChannel: outputChannel(),
    traceOutputChannel: outputChannel(),
    middleware: statusMiddleware(),
  };
  const newClient = new LanguageClient(LANGUAGE_ID, 'FANUC Macro Language Server', serverOptions, clientOptions);
  client = newClient;
  newClient.onDidChangeState((event) => {
    if (client !== newClient) return;
    if (event.newState === State.Running) statusItem?.status.ready(version);
    else if (event.newState === State.Starting) statusItem?.status.starting();
    else statusItem?.status.stopped();
  });
  try {
    await newClient.start();
    statusItem?.status.ready(version);
    // The controllers the status item offers, with their kind: the server's list.
    try {
      statusItem?.setControllers(await executeServerCommand(newClient, SERVER_COMMAND_CONTROLLERS, []));
    } catch (err) {
      log(`The server gave no controllers: ${errorText(err)}`);
    }
  } catch (err) {
    client = undefined;
    statusItem?.status.failed(errorText(err));
    log(`The language server failed to start: ${String(err)}`);
    const showLog = vscode.l10n.t('Show Log');
    const choice = await vscode.window.showErrorMessage(
      `FANUC Macro: the language server (${candidate.description}) failed to start: ${errorText(err)}`,
      showLog,
    );
    if (choice === showLog) outputChannel().show(true);
  }
}

async function stopClient(): Promise<void> {
  const current = client;
  client = undefined;
  if (current === undefined) return;
  statusItem?.status.stopped();
  try {
    if (current.state !== State.Stopped) await current.stop(5000);
  } catch (err) {
    log(`Stopping the language server failed: ${String(err)}`);
  }
  try {
    await current.dispose(2000);
  } catch {
    // already stopped
  }
}

function restart(): Promise<void> {
  return enqueue(async () => {
    await stopClient();
    await startClient();
  });
}

function errorText(err: unknown): string {
  if (err instanceof Error) return err.message;
  if (typeof err === 'object' && err !== null && 'message' in err) return String((err as { message: unknown }).message);
  return String(err);
}

/** Waits for pending start-ups and returns a running client, or tells the user there is none. */
async function runningClient(): Promise<LanguageClient | undefined> {
  await lifecycle;
  if (client === undefined || client.state !== State.Running) {
    const restartLabel = vscode.l10n.t('Restart Server');
    const choice = await vscode.window.showErrorMessage(
      vscode.l10n.t('FANUC Macro: the language server is not running.'),
      restartLabel,
    );
    if (choice === restartLabel) await vscode.commands.executeCommand('fanuc-macro.restartServer');
    return undefined;
  }
  return client;
}

async function executeServerCommand(
  languageClient: LanguageClient,
  command: string,
  args: unknown[],
): Promise<unknown> {
  return languageClient.sendRequest(ExecuteCommandRequest.type, { command, arguments: args });
}

async function showTrace(): Promise<void> {
  const editor = vscode.window.activeTextEditor;
  if (editor === undefined || editor.document.languageId !== LANGUAGE_ID) {
    void vscode.window.showErrorMessage(vscode.l10n.t('FANUC Macro: open a FANUC macro program to trace it.'));
    return;
  }
  const languageClient = await runningClient();
  if (languageClient === undefined) return;
  const document = editor.document;
  const source = document.isUntitled ? document.uri.toString() : document.uri.fsPath;
  let answer: unknown;
  try {
    answer = await vscode.window.withProgress(
      { location: vscode.ProgressLocation.Window, title: vscode.l10n.t('FANUC Macro: tracing program') },
      () => executeServerCommand(languageClient, SERVER_COMMAND_TRACE_VIEW, [document.uri.toString(), source]),
    );
  } catch (err) {
    answer = { error: errorText(err) };
  }
  const view = traceViewOf(answer);
  if ('error' in view) {
    void vscode.window.showErrorMessage(vscode.l10n.t('FANUC Macro: trace failed: {0}', view.error));
    return;
  }
  await (traces ??= new TraceDocuments()).show(document.uri, view);
}

async function showToolpath(): Promise<void> {
  const editor = vscode.window.activeTextEditor;
  if (editor === undefined || editor.document.languageId !== LANGUAGE_ID) {
    void vscode.window.showErrorMessage(vscode.l10n.t('FANUC Macro: open a FANUC macro program to see its toolpath.'));
    return;
  }
  const languageClient = await runningClient();
  if (languageClient === undefined || extensionUri === undefined) return;
  ToolpathPanel.show(extensionUri, editor.document, (command, args) =>
    executeServerCommand(languageClient, command, args),
  );
}

/**
 * The analysis of a document opened or changed runs until its diagnostics come back (the server
 * publishes them after each analysis): the status item says "analysing" meanwhile. The
 * diagnostics' rule links are pointed at the documentation shipped with the extension.
 */
function statusMiddleware(): Middleware {
  return {
    didOpen: (document, next) => {
      statusItem?.status.analysisStarted(document.uri.toString());
      return next(document);
    },
    didChange: (event, next) => {
      if (event.contentChanges.length > 0) statusItem?.status.analysisStarted(event.document.uri.toString());
      return next(event);
    },
    didClose: (document, next) => {
      statusItem?.status.analysisDone(document.uri.toString());
      statusItem?.documentClosed(document.uri.toString());
      return next(document);
    },
    handleDiagnostics: (uri, diagnostics, next) => {
      statusItem?.status.analysisDone(uri.toString());
      next(uri, diagnostics.map(linkToShippedDocs));
      statusItem?.documentAnalysed(uri.toString()); // the machine it was read as
    },
  };
}

/** Asks the running server quietly: undefined without one or when it fails. */
async function askServer(command: string, args: unknown[]): Promise<unknown> {
  return client?.state === State.Running ? executeServerCommand(client, command, args).catch(() => undefined) : undefined;
}

/** The walkthrough's sample, as an untitled program: edited freely, nothing on disk changes. */
async function openSample(): Promise<void> {
  if (extensionUri === undefined) return;
  const bytes = await vscode.workspace.fs.readFile(vscode.Uri.joinPath(extensionUri, ...SAMPLE_PATH));
  const document = await vscode.workspace.openTextDocument({
    language: LANGUAGE_ID,
    content: new TextDecoder('utf-8').decode(bytes),
  });
  await vscode.window.showTextDocument(document, { preview: false });
}

export function activate(context: vscode.ExtensionContext): void {
  // Undefined in tests that pass a bare context: then there is no bundled server.
  extensionPath = typeof context.extensionPath === 'string' ? context.extensionPath : undefined;
  extensionUri = context.extensionUri;
  traces = new TraceDocuments();
  statusItem = new StatusItem(askServer);
  context.subscriptions.push(outputChannel(), ...traces.register(), statusItem);
  if (extensionUri !== undefined) context.subscriptions.push(...new RuleDocs(extensionUri).register());
  context.subscriptions.push(registerCheckTasks(() => startedCandidate));
  // The debug adapter runs on the language server's Python: wait for its start-up first.
  context.subscriptions.push(
    ...registerDebugger(
      async () => {
        await lifecycle;
        return startedCandidate;
      },
      // The hover asks the server quietly: without one it has no expression.
      askServer,
    ),
  );

  context.subscriptions.push(
    vscode.commands.registerCommand('fanuc-macro.restartServer', restart),
    vscode.commands.registerCommand('fanuc-macro.showTrace', showTrace),
    vscode.commands.registerCommand('fanuc-macro.showToolpath', showToolpath),
    ...registerGeneratorCommands(async () => {
      const languageClient = await runningClient();
      return languageClient === undefined ? undefined : (command, args) => executeServerCommand(languageClient, command, args);
    }),
    vscode.commands.registerCommand('fanuc-macro.openSample', openSample),
    vscode.workspace.onDidChangeConfiguration((event) => {
      if (event.affectsConfiguration(SERVER_PATH_SETTING)) {
        log(`${SERVER_PATH_SETTING} changed: restarting the language server`);
        void restart();
      }
    }),
    // The setting is restricted in untrusted workspaces: until trust is granted it reads as
    // empty, and granting it fires no configuration change. Look again then.
    vscode.workspace.onDidGrantWorkspaceTrust(() => {
      const configured = vscode.workspace
        .getConfiguration(CONFIG_SECTION)
        .get<string>('server.path', '');
      if (configured.trim() !== '' && configured !== startedWithPath) {
        log(`workspace trusted: ${SERVER_PATH_SETTING} is now readable, restarting the server`);
        void restart();
      }
    }),
  );

  void enqueue(startClient);
}

export async function deactivate(): Promise<void> {
  await enqueue(stopClient);
}
