// Opens the rules' documentation shipped with the extension at a rule's section, read-only
// (a document of its own scheme), and points the diagnostics' code links at it (ruleDocs.ts).
import * as vscode from 'vscode';
import { OPEN_RULE_COMMAND, RULES_DOC_PATH, headingLine, ruleAnchorOf, ruleCommandUri } from './ruleDocs';

export const RULES_SCHEME = 'fanuc-macro-docs';

/** A diagnostic whose code links to the web site's rules page links to the shipped page instead. */
export function linkToShippedDocs(diagnostic: vscode.Diagnostic): vscode.Diagnostic {
  const code = diagnostic.code;
  if (typeof code !== 'object' || code === null || !('target' in code)) return diagnostic;
  const anchor = ruleAnchorOf(code.target.toString(true));
  if (anchor === undefined) return diagnostic;
  diagnostic.code = { value: code.value, target: vscode.Uri.parse(ruleCommandUri(anchor)) };
  return diagnostic;
}

export class RuleDocs implements vscode.TextDocumentContentProvider {
  constructor(private readonly extensionUri: vscode.Uri) {}

  register(): vscode.Disposable[] {
    return [
      vscode.workspace.registerTextDocumentContentProvider(RULES_SCHEME, this),
      vscode.commands.registerCommand(OPEN_RULE_COMMAND, (anchor: unknown) =>
        this.open(typeof anchor === 'string' ? anchor : ''),
      ),
    ];
  }

  async provideTextDocumentContent(): Promise<string> {
    const bytes = await vscode.workspace.fs.readFile(vscode.Uri.joinPath(this.extensionUri, ...RULES_DOC_PATH));
    return new TextDecoder('utf-8').decode(bytes);
  }

  /** The page, its section `anchor` at the top of the editor. */
  async open(anchor: string): Promise<vscode.TextEditor> {
    const uri = vscode.Uri.from({ scheme: RULES_SCHEME, path: '/rules.md' });
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
