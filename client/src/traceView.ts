// The trace view: a read-only document of its own scheme and language, one row per motion
// block the program executes (the server's fanuc-macro.traceView writes it). A row's
// `O0003 line 33` is a link to the block, and F12 (Go to Definition) on any line of a row
// opens the block too.
import * as vscode from 'vscode';

/** A row of the trace view that leads to a block (lines 0-based). */
export interface TraceRow {
  readonly line: number;
  readonly sourceLine: number;
  /** The block's file (a URI) when it is not the traced document. */
  readonly path?: string;
  /** Columns of the row's link (the `O0003 line 33` part), when it has one. */
  readonly link?: { readonly start: number; readonly end: number };
  /** What the link says it opens. */
  readonly label: string;
}

/** The trace view's text and the rows that lead to the source, in the order of the text. */
export interface TraceView {
  readonly text: string;
  readonly rows: readonly TraceRow[];
}

/** The server's answer as a view, or the error it gives (or why it is none). */
export function traceViewOf(answer: unknown): TraceView | { error: string } {
  if (typeof answer !== 'object' || answer === null || Array.isArray(answer)) return { error: 'the language server returned no trace' };
  const { error, text, rows } = answer as Record<string, unknown>;
  if (typeof error === 'string' && error !== '') return { error };
  if (typeof text !== 'string' || !Array.isArray(rows)) return { error: 'the language server returned a trace without its text' };
  return { text, rows: rows as TraceRow[] };
}

/** The row on a line of the trace view, if that line leads to a block. */
export const rowAt = (view: TraceView, line: number): TraceRow | undefined => view.rows.find((row) => row.line === line);

export const TRACE_SCHEME = 'fanuc-macro-trace';
export const TRACE_LANGUAGE = 'fanuc-macro-trace';

interface Shown {
  readonly view: TraceView;
  /** The traced document: the rows without a path are its blocks. */
  readonly source: vscode.Uri;
}

/** A block's file from the server's `path`: a URI, or a file system path. */
export function uriOfPath(path: string): vscode.Uri {
  return /^[a-z][a-z0-9+.-]*:/i.test(path) ? vscode.Uri.parse(path) : vscode.Uri.file(path);
}

/** The trace views shown, by their URI: their text, and the links and definitions of their rows. */
export class TraceDocuments
  implements vscode.TextDocumentContentProvider, vscode.DocumentLinkProvider, vscode.DefinitionProvider
{
  private readonly shown = new Map<string, Shown>();
  private readonly changed = new vscode.EventEmitter<vscode.Uri>();
  readonly onDidChange = this.changed.event;
  /** The view whose language is being set: VS Code closes and opens it again then. */
  private relabelling: string | undefined;

  /** Registers the content, link and definition providers of the scheme. */
  register(): vscode.Disposable[] {
    const selector: vscode.DocumentSelector = { scheme: TRACE_SCHEME };
    return [
      this.changed,
      vscode.workspace.registerTextDocumentContentProvider(TRACE_SCHEME, this),
      vscode.languages.registerDocumentLinkProvider(selector, this),
      vscode.languages.registerDefinitionProvider(selector, this),
      vscode.workspace.onDidCloseTextDocument((document) => {
        const key = document.uri.toString();
        if (document.uri.scheme === TRACE_SCHEME && key !== this.relabelling) this.shown.delete(key);
      }),
    ];
  }

  /** The trace view of `source`: one per traced document, shown again when traced again. */
  static uriFor(source: vscode.Uri): vscode.Uri {
    const name = source.path.split('/').pop() || 'program';
    return vscode.Uri.from({ scheme: TRACE_SCHEME, path: `/Trace of ${name}`, query: source.toString() });
  }

  /** Opens (or updates) the trace view of `source` beside the editor. */
  async show(source: vscode.Uri, view: TraceView): Promise<vscode.TextEditor> {
    const uri = TraceDocuments.uriFor(source);
    const known = this.shown.has(uri.toString());
    this.shown.set(uri.toString(), { view, source });
    if (known) this.changed.fire(uri);
    let document = await vscode.workspace.openTextDocument(uri);
    if (document.languageId !== TRACE_LANGUAGE) {
      this.relabelling = uri.toString();
      try {
        document = await vscode.languages.setTextDocumentLanguage(document, TRACE_LANGUAGE);
      } finally {
        this.relabelling = undefined;
      }
    }
    return vscode.window.showTextDocument(document, {
      viewColumn: vscode.ViewColumn.Beside,
      preview: false,
      preserveFocus: false,
    });
  }

  provideTextDocumentContent(uri: vscode.Uri): string {
    return (
      this.shown.get(uri.toString())?.view.text ??
      vscode.l10n.t('This trace is closed: run "FANUC Macro: Show Trace of Current Program" on the program again.') + '\n'
    );
  }

  /** Where a row leads: its block's line in its file. */
  target(uri: vscode.Uri, line: number): { uri: vscode.Uri; row: TraceRow } | undefined {
    const shown = this.shown.get(uri.toString());
    if (shown === undefined) return undefined;
    const row = rowAt(shown.view, line);
    if (row === undefined) return undefined;
    return { uri: row.path === undefined ? shown.source : uriOfPath(row.path), row };
  }

  provideDocumentLinks(document: vscode.TextDocument): vscode.DocumentLink[] {
    const shown = this.shown.get(document.uri.toString());
    if (shown === undefined) return [];
    const links: vscode.DocumentLink[] = [];
    for (const row of shown.view.rows) {
      if (row.link === undefined) continue;
      const file = row.path === undefined ? shown.source : uriOfPath(row.path);
      // `#L34` opens the file at line 34 (VS Code's opener reads the fragment as a selection).
      const link = new vscode.DocumentLink(
        new vscode.Range(row.line, row.link.start, row.line, row.link.end),
        file.with({ fragment: `L${row.sourceLine + 1}` }),
      );
      link.tooltip = vscode.l10n.t('Open {0}', row.label);
      links.push(link);
    }
    return links;
  }

  provideDefinition(document: vscode.TextDocument, position: vscode.Position): vscode.Location | undefined {
    const found = this.target(document.uri, position.line);
    if (found === undefined) return undefined;
    return new vscode.Location(found.uri, new vscode.Position(found.row.sourceLine, 0));
  }
}
