// "Insert Arc Thread Program..." and "Insert Drum Groove Program...": one input box per prompt
// of the form (generatorParameters.ts, each answer checked as it is typed), the server command
// that writes the program (ide/generator_requests.py), and the text inserted at the cursor.
import * as vscode from 'vscode';
import {
  arcThreadForm,
  drumGrooveForm,
  generatedProgram,
  summaryText,
  validateAnswer,
  type GeneratorForm,
  type GeneratorParameters,
} from './generatorParameters';

/** Runs a server command; undefined when there is no running server (the user was told). */
export type RunOnServer = (command: string, args: unknown[]) => Promise<{ answer: unknown } | undefined>;

function errorText(err: unknown): string {
  return err instanceof Error ? err.message : String(err);
}

/** The form's boxes in turn; undefined when one is dismissed. */
async function askParameters(form: GeneratorForm): Promise<GeneratorParameters | undefined> {
  let parameters: GeneratorParameters = {};
  const total = form.prompts.length;
  for (const [i, prompt] of form.prompts.entries()) {
    const before = parameters;
    const input = await vscode.window.showInputBox({
      title: vscode.l10n.t('{0} ({1}/{2})', form.title, i + 1, total),
      prompt: prompt.prompt,
      value: prompt.value,
      placeHolder: prompt.placeHolder,
      ignoreFocusOut: true,
      validateInput: (text) => validateAnswer(prompt, text, before),
    });
    if (input === undefined) return undefined;
    const read = prompt.read(input, before);
    if (typeof read === 'string') {
      void vscode.window.showErrorMessage(`FANUC Macro: ${read}`);
      return undefined;
    }
    parameters = { ...parameters, ...read };
  }
  return parameters;
}

async function insertProgram(form: GeneratorForm, run: RunOnServer): Promise<void> {
  const editor = vscode.window.activeTextEditor;
  if (editor === undefined) {
    void vscode.window.showErrorMessage(vscode.l10n.t('FANUC Macro: open a program to insert the generated program into.'));
    return;
  }
  const parameters = await askParameters(form);
  if (parameters === undefined) return;
  let ran: { answer: unknown } | undefined;
  try {
    ran = await vscode.window.withProgress(
      { location: vscode.ProgressLocation.Window, title: vscode.l10n.t('FANUC Macro: writing the {0}', form.title) },
      () => run(form.command, [parameters]),
    );
  } catch (err) {
    void vscode.window.showErrorMessage(vscode.l10n.t('FANUC Macro: the program was not generated: {0}', errorText(err)));
    return;
  }
  if (ran === undefined) return;
  const result = generatedProgram(ran.answer);
  if ('error' in result) {
    void vscode.window.showErrorMessage(vscode.l10n.t('FANUC Macro: the program was not generated: {0}', result.error));
    return;
  }
  // The editor may have changed while the user answered the prompts.
  const target = vscode.window.activeTextEditor ?? editor;
  const position = target.selection.active;
  // The program starts with its own % line: after a text on the cursor's line, on the next.
  const text = position.character > 0 ? `\n${result.text}` : result.text;
  const applied = await target.edit((builder) => builder.insert(position, text));
  if (!applied) {
    void vscode.window.showErrorMessage(vscode.l10n.t('FANUC Macro: the generated program could not be inserted.'));
    return;
  }
  const said = summaryText(form.command, result.summary, vscode.l10n.t);
  if (said !== undefined) vscode.window.setStatusBarMessage(`FANUC Macro: ${said}`, 10000);
}

/** The two commands, running the generators on the server through `run`. */
export function registerGeneratorCommands(run: RunOnServer): vscode.Disposable[] {
  return [
    vscode.commands.registerCommand('fanuc-macro.insertArcThread', () => insertProgram(arcThreadForm(vscode.l10n.t), run)),
    vscode.commands.registerCommand('fanuc-macro.insertDrumGroove', () => insertProgram(drumGrooveForm(vscode.l10n.t), run)),
  ];
}
