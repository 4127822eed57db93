// The Toolpath view: a webview beside the editor that draws what the program cuts
// (client/webview/toolpath.ts), fed by the server's `fanuc-macro.toolpath` command. It follows
// the document as the user types, highlights the cursor's block, and a click on a segment
// reveals its block in the editor. While a debug session is stopped in the document, it lights
// the stopped block instead (client/src/debugAdapter.ts), until the cursor moves.
import { randomBytes } from 'node:crypto';
import * as vscode from 'vscode';

export const SERVER_COMMAND_TOOLPATH = 'fanuc-macro.toolpath';
/** How long typing pauses before the view asks for the toolpath again. */
export const FOLLOW_DELAY_MS = 400;
/** The layout of the command's answer the view reads (ide/toolpath_view.py VIEW_FORMAT). */
export const TOOLPATH_FORMAT = 3;

type Execute = (command: string, args: unknown[]) => Promise<unknown>;

interface Reveal {
  type: 'reveal';
  line: number;
  path?: string;
  /** Playback: the editor follows the block without taking the focus. */
  follow?: boolean;
}

interface BlockText {
  type: 'blockText';
  line: number;
  path?: string;
}

/** The answer's error, or undefined when it is the view's data. */
export function toolpathError(answer: unknown): string | undefined {
  if (answer === null || typeof answer !== 'object') return 'the server gave no toolpath';
  const error = (answer as { error?: unknown }).error;
  if (typeof error === 'string') return error;
  const segments = (answer as { segments?: unknown }).segments;
  if (segments === null || typeof segments !== 'object') return 'the server gave no segments';
  // The segments come packed (base64 of typed arrays); a server of another layout is refused.
  const format = (answer as { format?: unknown }).format;
  if (format !== TOOLPATH_FORMAT) {
    return `the server's toolpath is of format ${String(format ?? 1)}, this view reads ${TOOLPATH_FORMAT}: update the extension and the server together`;
  }
  return undefined;
}

/**
 * What the page is sent for the server's answer: the data to draw, why nothing is drawn (a
 * program that makes no move is not a failure), or the error.
 */
export function toolpathMessage(
  answer: unknown,
  title: string,
  words: Record<string, string> = {},
):
  | { type: 'data'; data: unknown; title: string; words: Record<string, string> }
  | { type: 'empty'; reason: string; title: string; words: Record<string, string> }
  | { type: 'error'; message: string } {
  const error = toolpathError(answer);
  if (error === undefined) return { type: 'data', data: answer, title, words };
  const empty = answer !== null && typeof answer === 'object' && (answer as { empty?: unknown }).empty === true;
  return empty ? { type: 'empty', reason: error, title, words } : { type: 'error', message: `${title}: ${error}` };
}

/**
 * The page's words of its notes and tooltips (client/webview/backplot.ts `ENGLISH_WORDS`, the
 * same keys) in the user's language: templates whose {0}, {1} the page fills.
 */
export function toolpathWords(): Record<string, string> {
  const t = vscode.l10n.t;
  return {
    notKnown: t('not known'),
    line: t('line {0} ({1})', '{0}', '{1}'),
    rapid: t('rapid'),
    feedNotKnown: t('F not known'),
    speedNotKnown: t('S not known'),
    assumed: t('assumed {0}', '{0}'),
    segments: t('{0} segments, {1}', '{0}', '{1}'),
    xShown: t('X shown as a {0} (the program writes diameters)', '{0}'),
    diameter: t('diameter'),
    radius: t('radius'),
    stock: t('stock: Ø{0} from {1}', '{0}', '{1}'),
    noStockLathe: t('stock: not given by the program (no stock removal cycle, no thread blank)'),
    noStock: t('stock: not given by the program'),
    tool: t('tool: radius {0}, {1}', '{0}', '{1}'),
    noTool: t('tool: its radius is not given by the program: drawn at a nominal size'),
    cutShort: t('cut short: the program makes more moves than the view keeps'),
    unknownAxes: t('{0} unknown: ', '{0}'),
    lost: t('line {0}: {1}{2}', '{0}', '{1}', '{2}'),
    nothingToDraw: t('{0}: nothing to draw', '{0}'),
  };
}

/** The page's fixed labels, in English unless the extension says them (`vscode.l10n.t`). */
type Say = (text: string) => string;

/** A script nonce of the page's content security policy: 128 random bits. */
const nonce = (): string => randomBytes(16).toString('hex');

export function toolpathHtml(scriptUri: string, cspSource: string, t: Say = (text) => text): string {
  const n = nonce();
  return `<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="UTF-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; style-src 'nonce-${n}'; script-src 'nonce-${n}' ${cspSource};">
<meta name="viewport" content="width=device-width, initial-scale=1.0">
<title>${t('Toolpath')}</title>
<style nonce="${n}">
  html, body { height: 100%; margin: 0; padding: 0; overflow: hidden; }
  body { display: flex; flex-direction: column; color: var(--vscode-foreground); background: var(--vscode-editor-background); font: 12px var(--vscode-font-family); }
  #bar { display: flex; flex-wrap: wrap; gap: 6px 10px; align-items: center; padding: 4px 8px; border-bottom: 1px solid var(--vscode-panel-border); }
  .group { display: inline-flex; align-items: center; gap: 4px; }
  select, button { font: inherit; }
  select { color: var(--vscode-dropdown-foreground); background: var(--vscode-dropdown-background); border: 1px solid var(--vscode-dropdown-border, transparent); border-radius: 2px; padding: 1px 2px; }
  button { color: var(--vscode-button-foreground); background: var(--vscode-button-background); border: 1px solid var(--vscode-button-border, transparent); border-radius: 2px; padding: 1px 8px; cursor: pointer; }
  button:hover { background: var(--vscode-button-hoverBackground); }
  button.secondary { color: var(--vscode-button-secondaryForeground); background: var(--vscode-button-secondaryBackground); min-width: 26px; }
  button.secondary:hover { background: var(--vscode-button-secondaryHoverBackground); }
  button:disabled { opacity: 0.5; cursor: default; }
  select:focus, button:focus { outline: 1px solid var(--vscode-focusBorder); outline-offset: 1px; }
  .key { display: inline-flex; align-items: center; gap: 4px; }
  .swatch { width: 18px; height: 0; border-top: 2px solid; display: inline-block; }
  .swatch.rapid { border-top-style: dashed; border-color: var(--vscode-descriptionForeground, #9a9a9a); }
  .swatch.feed { border-color: var(--vscode-charts-blue, #3b82f6); }
  .swatch.arc { border-color: var(--vscode-charts-green, #22a05a); }
  .swatch.thread { border-color: var(--vscode-charts-red, #e4572e); }
  #stage { flex: 1; position: relative; min-height: 0; }
  canvas { position: absolute; inset: 0; width: 100%; height: 100%; cursor: crosshair; display: block; }
  #readout { position: absolute; white-space: pre; right: 8px; top: 6px; padding: 2px 6px; font-family: var(--vscode-editor-font-family); color: var(--vscode-editor-foreground); background: var(--vscode-editorWidget-background); border: 1px solid var(--vscode-editorWidget-border, transparent); pointer-events: none; }
  #readout:empty { display: none; }
  #tooltip { position: absolute; display: none; max-width: min(70%, 480px); padding: 4px 8px; white-space: pre-wrap; overflow-wrap: anywhere; font-family: var(--vscode-editor-font-family); color: var(--vscode-editorHoverWidget-foreground, var(--vscode-foreground)); background: var(--vscode-editorHoverWidget-background); border: 1px solid var(--vscode-editorHoverWidget-border); pointer-events: none; z-index: 2; }
  #empty { position: absolute; inset: 0; display: none; align-items: center; justify-content: center; text-align: center; padding: 24px; color: var(--vscode-descriptionForeground); }
  #empty strong { display: block; font-size: 14px; margin-bottom: 6px; color: var(--vscode-foreground); }
  #status { max-height: 30%; overflow: auto; padding: 4px 8px; border-top: 1px solid var(--vscode-panel-border); color: var(--vscode-descriptionForeground); }
  #status ul { margin: 2px 0 0 0; padding-left: 18px; }
  #status li { white-space: normal; overflow-wrap: anywhere; }
  #summary { color: var(--vscode-foreground); }
</style>
</head>
<body>
<div id="bar">
  <label class="group">${t('View')} <select id="view" title="${t('The plane drawn, or an orbit in 3D')}"><option value="XZ">XZ</option><option value="XY">XY</option><option value="YZ">YZ</option><option value="3D">${t('3D orbit')}</option></select></label>
  <label class="group" id="xmode-group">${t('X as')} <select id="xmode" title="${t('A lathe\'s X labelled as the diameter the program writes, or as the radius drawn')}"><option value="diameter">${t('diameter')}</option><option value="radius">${t('radius')}</option></select></label>
  <button id="fit" title="${t('Show the whole toolpath, as large as the view allows')}">${t('Fit')}</button>
  <span class="group" title="${t('Playback: the tool runs the program block by block')}">
    <button id="start" class="secondary" title="${t('Back to the first block')}">⇤</button>
    <button id="back" class="secondary" title="${t('One block back')}">◀︎</button>
    <button id="play" class="secondary" title="${t('Play or pause')}">▶︎</button>
    <button id="next" class="secondary" title="${t('One block on (single block)')}">▶︎|</button>
    <button id="end" class="secondary" title="${t('To the end: the whole path')}">⇥</button>
    <select id="speed" title="${t('Playback speed')}"><option value="1">${t('slow')}</option><option value="4" selected>${t('normal')}</option><option value="20">${t('fast')}</option></select>
  </span>
  <span class="key"><span class="swatch rapid"></span>${t('rapid')}</span>
  <span class="key"><span class="swatch feed"></span>${t('feed')}</span>
  <span class="key"><span class="swatch arc"></span>${t('arc')}</span>
  <span class="key"><span class="swatch thread"></span>${t('thread')}</span>
</div>
<div id="stage">
  <canvas id="toolpath"></canvas>
  <div id="readout"></div>
  <div id="tooltip" role="tooltip"></div>
  <div id="empty"><div><strong>${t('Nothing to draw')}</strong><span id="empty-reason"></span></div></div>
</div>
<div id="status"><div id="summary">${t('Running the program…')}</div><ul id="notes"></ul></div>
<script nonce="${n}" src="${scriptUri}"></script>
</body>
</html>`;
}

/** One Toolpath view, for the document it was opened on. */
export class ToolpathPanel {
  static current: ToolpathPanel | undefined;

  private readonly disposables: vscode.Disposable[] = [];
  private timer: ReturnType<typeof setTimeout> | undefined;
  private ready = false;
  private asked = 0;
  /** The 0-based line of the block a debug session stopped on, lit until the cursor moves. */
  private stoppedLine: number | undefined;

  private constructor(
    private readonly panel: vscode.WebviewPanel,
    private document: vscode.TextDocument,
    private readonly execute: Execute,
  ) {
    panel.onDidDispose(() => this.dispose(), null, this.disposables);
    panel.webview.onDidReceiveMessage((message: unknown) => this.received(message), null, this.disposables);
    vscode.workspace.onDidChangeTextDocument(
      (event) => {
        if (event.document === this.document) this.followSoon();
      },
      null,
      this.disposables,
    );
    vscode.window.onDidChangeTextEditorSelection(
      (event) => {
        if (event.textEditor.document !== this.document) return;
        this.stoppedLine = undefined;
        this.postCursor(event.textEditor);
      },
      null,
      this.disposables,
    );
  }

  static show(extensionUri: vscode.Uri, document: vscode.TextDocument, execute: Execute): ToolpathPanel {
    const existing = ToolpathPanel.current;
    if (existing !== undefined) {
      existing.panel.reveal(vscode.ViewColumn.Beside, true);
      if (existing.document !== document) {
        existing.document = document;
        existing.stoppedLine = undefined;
        existing.panel.title = ToolpathPanel.title(document);
      }
      void existing.refresh();
      return existing;
    }
    const webviewRoot = vscode.Uri.joinPath(extensionUri, 'client', 'out', 'webview');
    const panel = vscode.window.createWebviewPanel(
      'fanuc-macro.toolpath',
      ToolpathPanel.title(document),
      { viewColumn: vscode.ViewColumn.Beside, preserveFocus: true },
      { enableScripts: true, localResourceRoots: [webviewRoot], retainContextWhenHidden: true },
    );
    const script = panel.webview.asWebviewUri(vscode.Uri.joinPath(webviewRoot, 'toolpath.js'));
    panel.webview.html = toolpathHtml(script.toString(), panel.webview.cspSource, (text) => vscode.l10n.t(text));
    ToolpathPanel.current = new ToolpathPanel(panel, document, execute);
    return ToolpathPanel.current;
  }

  private static title(document: vscode.TextDocument): string {
    return vscode.l10n.t('Toolpath: {0}', ToolpathPanel.name(document));
  }

  private static name(document: vscode.TextDocument): string {
    return document.uri.path.split('/').pop() ?? 'program';
  }

  private followSoon(): void {
    if (this.timer !== undefined) clearTimeout(this.timer);
    this.timer = setTimeout(() => {
      this.timer = undefined;
      void this.refresh();
    }, FOLLOW_DELAY_MS);
  }

  /** Ask the server for the toolpath of the document as it is now, and draw it. */
  async refresh(): Promise<void> {
    if (!this.ready) return;
    const asked = ++this.asked;
    let answer: unknown;
    try {
      answer = await this.execute(SERVER_COMMAND_TOOLPATH, [this.document.uri.toString()]);
    } catch (err) {
      answer = { error: err instanceof Error ? err.message : String(err) };
    }
    if (asked !== this.asked) return; // a newer request is on its way
    const title = ToolpathPanel.name(this.document);
    await this.panel.webview.postMessage(toolpathMessage(answer, title, toolpathWords()));
    if (this.stoppedLine !== undefined) {
      await this.panel.webview.postMessage({ type: 'cursor', line: this.stoppedLine });
      return;
    }
    const editor = vscode.window.visibleTextEditors.find((e) => e.document === this.document);
    if (editor !== undefined) this.postCursor(editor);
  }

  private postCursor(editor: vscode.TextEditor): void {
    void this.panel.webview.postMessage({ type: 'cursor', line: editor.selection.active.line });
  }

  /** The file system path of the document the view draws (for a debug session's frames). */
  get documentPath(): string {
    return this.document.uri.fsPath;
  }

  /** Lights the block at `line` (0-based) of the view's document: where a debug session stopped. */
  showStoppedBlock(line: number): void {
    this.stoppedLine = line;
    void this.panel.webview.postMessage({ type: 'cursor', line });
  }

  private received(message: unknown): void {
    if (message === null || typeof message !== 'object') return;
    const type = (message as { type?: unknown }).type;
    if (type === 'ready') {
      this.ready = true;
      void this.refresh();
    } else if (type === 'reveal') {
      void this.reveal(message as Reveal);
    } else if (type === 'blockText') {
      void this.blockText(message as BlockText);
    }
  }

  /** The text of a block, for the tooltip of its segments. */
  private async blockText(message: BlockText): Promise<void> {
    if (typeof message.line !== 'number') return;
    let document = this.document;
    if (typeof message.path === 'string') {
      const uri = /^[a-z][a-z0-9+.-]*:/i.test(message.path) ? vscode.Uri.parse(message.path) : vscode.Uri.file(message.path);
      document = await vscode.workspace.openTextDocument(uri);
    }
    if (message.line < 0 || message.line >= document.lineCount) return;
    const text = document.lineAt(message.line).text;
    await this.panel.webview.postMessage({ type: 'blockText', line: message.line, path: message.path, text });
  }

  private async reveal(message: Reveal): Promise<void> {
    if (typeof message.line !== 'number') return;
    let document = this.document;
    if (typeof message.path === 'string') {
      // A block of a called program in another file.
      const uri = /^[a-z][a-z0-9+.-]*:/i.test(message.path) ? vscode.Uri.parse(message.path) : vscode.Uri.file(message.path);
      document = await vscode.workspace.openTextDocument(uri);
    }
    const visible = vscode.window.visibleTextEditors.find((e) => e.document === document);
    const editor = await vscode.window.showTextDocument(document, {
      viewColumn: visible?.viewColumn ?? vscode.ViewColumn.One,
      preserveFocus: message.follow === true,
    });
    const position = new vscode.Position(message.line, 0);
    editor.selection = new vscode.Selection(position, position);
    editor.revealRange(new vscode.Range(position, position), vscode.TextEditorRevealType.InCenterIfOutsideViewport);
  }

  dispose(): void {
    ToolpathPanel.current = undefined;
    if (this.timer !== undefined) clearTimeout(this.timer);
    this.panel.dispose();
    for (const d of this.disposables.splice(0)) d.dispose();
  }
}
