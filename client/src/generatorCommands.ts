// "Insert Symmetric Thread Module...", "Insert Arc Thread Program..." and "Insert Drum Groove
// Program...": one input box or quick pick per step of the form (generatorForms.ts), each answer
// checked by the server as it is typed, the server command that writes the program, and the text
// inserted at the cursor.
import * as vscode from 'vscode';
import {
  SERVER_COMMAND_THREAD_MODULE,
  answerOf,
  arcThreadForm,
  boxValue,
  defaultsArgs,
  drumGrooveForm,
  threadModuleArgs,
  threadModuleForm,
  summaryText,
  type Answer,
  type DesignationReading,
  type GeneratorForm,
} from './generatorForms';

/** Runs a command on the language server. */
export type ServerCall = (command: string, args: unknown[]) => Promise<unknown>;
/** The running server's commands; undefined when there is none (the user was told). */
export type Connect = () => Promise<ServerCall | undefined>;

const errorText = (err: unknown): string => (err instanceof Error ? err.message : String(err));

/** The server's answer to `command`, or its refusal (or why there is none). */
async function ask(call: ServerCall, command: string, args: unknown[], needed: string) {
  try {
    return answerOf(await call(command, args), needed, `the language server did not answer ${command}`);
  } catch (err) {
    return { error: errorText(err) };
  }
}

const check = (call: ServerCall, generator: string, answers: readonly Answer[], complete: boolean) =>
  ask(call, 'fanuc-macro.checkParameters', [{ generator, answers, complete }], 'parameters');

/** Each step in turn, the answers checked by the server; undefined when one is dismissed. */
async function askSteps(call: ServerCall, form: GeneratorForm, answers: Answer[], before: number): Promise<Answer[] | undefined> {
  const defaults = await ask(call, 'fanuc-macro.parameterDefaults', defaultsArgs(form), 'defaults');
  const known = 'error' in defaults ? {} : (defaults['defaults'] as Record<string, string>);
  const total = before + form.steps.length;
  for (const [i, step] of form.steps.entries()) {
    const title = vscode.l10n.t('{0} ({1}/{2})', form.title, before + i + 1, total);
    let value: unknown;
    if (step.picks !== undefined) {
      value = (await vscode.window.showQuickPick(step.picks, { title, placeHolder: step.prompt, ignoreFocusOut: true }))?.value;
    } else {
      const shown = boxValue(step, known);
      const earlier = [...answers];
      value = await vscode.window.showInputBox({
        title,
        prompt: step.prompt,
        value: shown,
        placeHolder: step.placeHolder ?? shown,
        ignoreFocusOut: true,
        // The server's refusal blocks the box; its warning (the later boxes may change it) does not.
        validateInput: async (text) => {
          const said = await check(call, form.generator, [...earlier, { names: step.names, value: text }], i + 1 === form.steps.length);
          if ('error' in said) return said.error as string;
          const warning = said['warning'];
          return typeof warning === 'string' ? { message: warning, severity: vscode.InputBoxValidationSeverity.Warning } : undefined;
        },
      });
    }
    if (value === undefined) return undefined;
    answers.push({ names: step.names, value });
  }
  return answers;
}

/** The form asked, checked whole, and the server's program inserted at the cursor. */
async function generate(form: GeneratorForm, call: ServerCall, editor: vscode.TextEditor, answers: Answer[], before: number, failed: (e: string) => string) {
  if ((await askSteps(call, form, answers, before)) === undefined) return;
  const checked = await check(call, form.generator, answers, true);
  if ('error' in checked) return void vscode.window.showErrorMessage(failed(checked.error as string));
  const parameters = checked['parameters'] as Record<string, unknown>;
  // The editor may have changed while the user answered: the program goes into the active one,
  // under program numbers that document does not have.
  const target = vscode.window.activeTextEditor ?? editor;
  const uri = target.document.uri.toString();
  const args = form.command === SERVER_COMMAND_THREAD_MODULE ? threadModuleArgs(parameters, uri) : { ...parameters, uri };
  const ran = await vscode.window.withProgress(
    { location: vscode.ProgressLocation.Window, title: vscode.l10n.t('FANUC Macro: writing the {0}', form.title) },
    () => ask(call, form.command, [args], 'text'),
  );
  if ('error' in ran || typeof ran['text'] !== 'string') {
    return void vscode.window.showErrorMessage(failed('error' in ran ? (ran.error as string) : 'the language server returned no text'));
  }
  // A program starts with its own % line: after a text on the cursor's line, on the next.
  const position = target.selection.active;
  const ownLine = form.command !== SERVER_COMMAND_THREAD_MODULE && position.character > 0;
  if (!(await target.edit((builder) => builder.insert(position, ownLine ? `\n${ran['text']}` : ran['text'] as string)))) {
    const module = form.command === SERVER_COMMAND_THREAD_MODULE;
    return void vscode.window.showErrorMessage(
      module ? vscode.l10n.t('FANUC Macro: the thread module could not be inserted.') : vscode.l10n.t('FANUC Macro: the generated program could not be inserted.'),
    );
  }
  // Which free numbers it took, where the document had the paper's.
  if (typeof ran['note'] === 'string') void vscode.window.showInformationMessage(`FANUC Macro: ${ran['note']}`);
  const said = summaryText(form.command, ran['summary'], vscode.l10n.t);
  if (said !== undefined) vscode.window.setStatusBarMessage(`FANUC Macro: ${said}`, 10000);
}

async function insertProgram(form: GeneratorForm, connect: Connect): Promise<void> {
  const editor = vscode.window.activeTextEditor;
  if (editor === undefined) {
    return void vscode.window.showErrorMessage(vscode.l10n.t('FANUC Macro: open a program to insert the generated program into.'));
  }
  const call = await connect();
  if (call === undefined) return;
  await generate(form, call, editor, [], 0, (e) => vscode.l10n.t('FANUC Macro: the program was not generated: {0}', e));
}

/** The thread module: its designation read by the server, then the form of the thread it names. */
async function insertThreadModule(connect: Connect): Promise<void> {
  const editor = vscode.window.activeTextEditor;
  if (editor === undefined) {
    return void vscode.window.showErrorMessage(vscode.l10n.t('FANUC Macro: open a program to insert the thread module into.'));
  }
  const call = await connect();
  if (call === undefined) return;
  const read = (text: string) => ask(call, 'fanuc-macro.readDesignation', [text], 'side');
  const input = await vscode.window.showInputBox({
    title: vscode.l10n.t('{0} ({1}/{2})', vscode.l10n.t('Symmetric Thread Module'), 1, 4),
    prompt: vscode.l10n.t('Metric thread designation: lower-case tolerance for external (M50x3-5g6g), upper case for internal (M50x3-6H)'),
    placeHolder: 'M50x3-5g6g',
    ignoreFocusOut: true,
    validateInput: async (text) => {
      const reading = await read(text);
      return 'error' in reading ? (reading.error as string) : undefined;
    },
  });
  if (input === undefined) return;
  const reading = await read(input);
  if ('error' in reading) return void vscode.window.showErrorMessage(`FANUC Macro: ${String(reading.error)}`);
  const designation = reading as unknown as DesignationReading;
  const form = threadModuleForm(designation, vscode.l10n.t);
  const side = designation.side === 'undecided' ? [] : [{ names: ['internal'], value: designation.side === 'internal' }];
  const answers = [{ names: ['designation'], value: designation.text }, ...side];
  await generate(form, call, editor, answers, 1, (e) => `FANUC Macro: thread module failed: ${e}`);
}

/** The three commands, answered by the server `connect` gives. */
export function registerGeneratorCommands(connect: Connect): vscode.Disposable[] {
  return [
    vscode.commands.registerCommand('fanuc-macro.insertThreadModule', () => insertThreadModule(connect)),
    vscode.commands.registerCommand('fanuc-macro.insertArcThread', () => insertProgram(arcThreadForm(vscode.l10n.t), connect)),
    vscode.commands.registerCommand('fanuc-macro.insertDrumGroove', () => insertProgram(drumGrooveForm(vscode.l10n.t), connect)),
  ];
}
