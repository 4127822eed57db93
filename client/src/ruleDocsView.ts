// Opens the rules' documentation shipped with the extension at a rule's section, read-only
// (a document of its own scheme), and points the diagnostics' code links at it (ruleDocs.ts).
import * as vscode from 'vscode';
import { OPEN_RULE_COMMAND, RULES_PAGES, type RulesPage, headingLine, ruleCommandUri, ruleLinkOf } from './ruleDocs';

export const RULES_SCHEME = 'fanuc-macro-docs';

/** A diagnostic whose code links to the web site's rules page links to the shipped page instead. */
export function linkToShippedDocs(diagnostic: vscode.Diagnostic): vscode.Diagnostic {
  const code = diagnostic.code;
  if (typeof code !== 'object' || code === null || !('target' in code)) return diagnostic;
  const link = ruleLinkOf(code.target.toString(true));
  if (link === undefined) return diagnostic;
  diagnostic.code = { value: code.value, target: vscode.Uri.parse(ruleCommandUri(link.anchor, link.page)) };
  return diagnostic;
}

export class RuleDocs implements vscode.TextDocumentContentProvider {
  constructor(private readonly extensionUri: vscode.Uri) {}

  register(): vscode.Disposable[] {
    return [
      vscode.workspace.registerTextDocumentContentProvider(RULES_SCHEME, this),
      vscode.commands.registerCommand(OPEN_RULE_COMMAND, (anchor: unknown, page: unknown) =>
        this.open(typeof anchor === 'string' ? anchor : '', shippedPage(page)),
      ),
    ];
  }

  async provideTextDocumentContent(uri: vscode.Uri): Promise<string> {
    const page = shippedPage(uri.path.slice(1));
    const bytes = await vscode.workspace.fs.readFile(vscode.Uri.joinPath(this.extensionUri, 'docs', page));
    return new TextDecoder('utf-8').decode(bytes);
  }

  /** The page (English, or the page in the server's language), its section `anchor` at the top
   * of the editor. */
  async open(anchor: string, page: RulesPage = 'rules.md'): Promise<vscode.TextEditor> {
    const uri = vscode.Uri.from({ scheme: RULES_SCHEME, path: `/${page}` });
    const document = await vscode.workspace.openTextDocument(uri);
    const line = Math.max(0, headingLine(document.getText(), anchor));
    const start = new vscode.Position(line, 0);
    const editor = await vscode.window.showTextDocument(document, {
      preview: true,
      selection: new vscode.Range(start, start),
    });
    editor.revealRange(new vscode.Range(start, start), vscode.TextEditorRevealType.AtTop);
    return editor;
  }
}

/** One of the shipped pages, by name; the English page for anything else. */
function shippedPage(name: unknown): RulesPage {
  return RULES_PAGES.find((page) => page === name) ?? 'rules.md';
}
