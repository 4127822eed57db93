// "Insert Symmetric Thread Module...", "Insert Arc Thread Program..." and "Insert Drum Groove
// Program...": one input box or quick pick per step, each answer checked by the server as it is
// typed (generatorForms.ts), the server command that writes the program, and the text inserted
// at the cursor.
import * as vscode from 'vscode';
import {
  SERVER_COMMAND_CHECK,
  SERVER_COMMAND_DEFAULTS,
  SERVER_COMMAND_READ_DESIGNATION,
  SERVER_COMMAND_THREAD_MODULE,
  arcThreadForm,
  boxValue,
  checked,
  designationReading,
  drumGrooveForm,
  isRecord,
  refusal,
  summaryText,
  threadModuleArgs,
  type Answer,
  type GeneratorForm,
} from './generatorForms';

/** Runs a command on the language server. */
export type ServerCall = (command: string, args: unknown[]) => Promise<unknown>;
/** The running server's commands; undefined when there is none (the user was told). */
export type Connect = () => Promise<ServerCall | undefined>;

type Validation = string | vscode.InputBoxValidationMessage | undefined;

function errorText(err: unknown): string {
  return err instanceof Error ? err.message : String(err);
}

function showError(message: string): void {
  void vscode.window.showErrorMessage(message);
}

/** The server's check of the answers: its refusal blocks the box, its warning does not. */
async function validate(call: ServerCall, generator: string, answers: readonly Answer[], complete: boolean): Promise<Validation> {
  try {
    const result = checked(await call(SERVER_COMMAND_CHECK, [{ generator, answers, complete }]));
    if ('error' in result) return result.error;
    return result.warning === undefined ? undefined : { message: result.warning, severity: vscode.InputBoxValidationSeverity.Warning };
  } catch (err) {
    return errorText(err);
  }
}

/** The answers checked as a whole: the generator's parameters, or undefined (the user was told). */
async function checkedParameters(call: ServerCall, generator: string, answers: readonly Answer[], failed: (error: string) => string) {
  let result: ReturnType<typeof checked>;
  try {
    result = checked(await call(SERVER_COMMAND_CHECK, [{ generator, answers, complete: true }]));
  } catch (err) {
    result = { error: errorText(err) };
  }
  if ('error' in result) {
    showError(failed(result.error));
    return undefined;
  }
  return result.parameters;
}

/** The program inserted at the cursor: after a text on the cursor's line, on the next. */
async function insert(editor: vscode.TextEditor, text: string, ownLine: boolean): Promise<boolean> {
  // The editor may have changed while the user answered the prompts.
  const target = vscode.window.activeTextEditor ?? editor;
  const position = target.selection.active;
  const inserted = ownLine && position.character > 0 ? `\n${text}` : text;
  return target.edit((builder) => builder.insert(position, inserted));
}

async function insertProgram(form: GeneratorForm, connect: Connect): Promise<void> {
  const editor = vscode.window.activeTextEditor;
  if (editor === undefined) {
    showError(vscode.l10n.t('FANUC Macro: open a program to insert the generated program into.'));
    return;
  }
  const call = await connect();
  if (call === undefined) return;
  const failed = (error: string) => vscode.l10n.t('FANUC Macro: the program was not generated: {0}', error);
  let defaults: Record<string, string> = {};
  try {
    const answer = await call(SERVER_COMMAND_DEFAULTS, [form.generator]);
    if (isRecord(answer) && isRecord(answer['defaults'])) defaults = answer['defaults'] as Record<string, string>;
  } catch (err) {
    showError(failed(errorText(err)));
    return;
  }
  const answers: Answer[] = [];
  const total = form.boxes.length;
  for (const [i, box] of form.boxes.entries()) {
    const before = [...answers];
    const value = boxValue(box, defaults);
    const input = await vscode.window.showInputBox({
      title: vscode.l10n.t('{0} ({1}/{2})', form.title, i + 1, total),
      prompt: box.prompt,
      value,
      placeHolder: box.placeHolder ?? value,
      ignoreFocusOut: true,
      validateInput: (text) => validate(call, form.generator, [...before, { names: box.names, value: text }], i + 1 === total),
    });
    if (input === undefined) return;
    answers.push({ names: box.names, value: input });
  }
  const parameters = await checkedParameters(call, form.generator, answers, failed);
  if (parameters === undefined) return;
  let ran: unknown;
  try {
    ran = await vscode.window.withProgress(
      { location: vscode.ProgressLocation.Window, title: vscode.l10n.t('FANUC Macro: writing the {0}', form.title) },
      () => call(form.command, [parameters]),
    );
  } catch (err) {
    showError(failed(errorText(err)));
    return;
  }
  const error = refusal(ran, 'the language server returned no program');
  const text = isRecord(ran) ? ran['text'] : undefined;
  if (error !== undefined || typeof text !== 'string' || text === '') {
    showError(failed(error ?? 'the language server returned a program without text'));
    return;
  }
  if (!(await insert(editor, text, true))) {
    showError(vscode.l10n.t('FANUC Macro: the generated program could not be inserted.'));
    return;
  }
  const said = summaryText(form.command, isRecord(ran) ? ran['summary'] : undefined, vscode.l10n.t);
  if (said !== undefined) vscode.window.setStatusBarMessage(`FANUC Macro: ${said}`, 10000);
}

async function readDesignation(call: ServerCall, text: string) {
  try {
    return designationReading(await call(SERVER_COMMAND_READ_DESIGNATION, [text]));
  } catch (err) {
    return { error: errorText(err) };
  }
}

/** The thread module's steps: designation, length, the kind when the designation does not say it, infeed, taper. */
async function insertThreadModule(connect: Connect): Promise<void> {
  const editor = vscode.window.activeTextEditor;
  if (editor === undefined) {
    showError(vscode.l10n.t('FANUC Macro: open a program to insert the thread module into.'));
    return;
  }
  const call = await connect();
  if (call === undefined) return;
  const title = (step: number, steps: number) => vscode.l10n.t('Symmetric Thread Module ({0}/{1})', step, steps);
  const designationInput = await vscode.window.showInputBox({
    title: title(1, 4),
    prompt: vscode.l10n.t('Metric thread designation: lower-case tolerance for external (M50x3-5g6g), upper case for internal (M50x3-6H)'),
    placeHolder: 'M50x3-5g6g',
    ignoreFocusOut: true,
    validateInput: async (text) => {
      const reading = await readDesignation(call, text);
      return 'error' in reading ? reading.error : undefined;
    },
  });
  if (designationInput === undefined) return;
  const designation = await readDesignation(call, designationInput);
  if ('error' in designation) {
    showError(`FANUC Macro: ${designation.error}`);
    return;
  }
  const answers: Answer[] = [{ names: ['designation'], value: designation.text }];
  // One more step when the designation does not tell an external from an internal thread.
  const steps = designation.side === 'undecided' ? 5 : 4;
  const lengthInput = await vscode.window.showInputBox({
    title: title(2, steps),
    prompt: vscode.l10n.t('Thread length of {0} in mm', designation.text),
    placeHolder: '40',
    ignoreFocusOut: true,
    validateInput: (text) => validate(call, 'threadModule', [...answers, { names: ['length'], value: text }], false),
  });
  if (lengthInput === undefined) return;
  answers.push({ names: ['length'], value: lengthInput });
  let internal = designation.side === 'internal';
  if (designation.side === 'undecided') {
    const external = { label: vscode.l10n.t('External thread'), description: vscode.l10n.t('bolt, turned on the outside'), internal: false };
    const inner = { label: vscode.l10n.t('Internal thread'), description: vscode.l10n.t('nut, bored on the inside'), internal: true };
    const picked = await vscode.window.showQuickPick([external, inner], {
      title: title(3, steps),
      placeHolder: designation.question ?? '',
      ignoreFocusOut: true,
    });
    if (picked === undefined) return;
    internal = picked.internal;
  }
  answers.push({ names: ['internal'], value: internal });
  const infeeds = [
    { label: vscode.l10n.t('Symmetric'), description: vscode.l10n.t('both flanks every pass, the paper\'s'), infeed: 'symmetric' },
    { label: vscode.l10n.t('Alternate flanks'), description: vscode.l10n.t('left one pass, right the next'), infeed: 'alternate' },
    { label: vscode.l10n.t('Left flank'), description: vscode.l10n.t('every pass on the -Z flank, as G76'), infeed: 'left' },
    { label: vscode.l10n.t('Right flank'), description: vscode.l10n.t('every pass on the +Z flank'), infeed: 'right' },
  ];
  const kind = [
    designation.starts > 1 ? vscode.l10n.t('{0} starts', designation.starts) : '',
    designation.leftHand ? vscode.l10n.t('left hand') : '',
  ].filter((part) => part !== '');
  const infeed = await vscode.window.showQuickPick(infeeds, {
    title: title(steps - 1, steps),
    placeHolder: kind.length > 0
      ? vscode.l10n.t('How the rough passes of {0} ({1}) go down', designation.text, kind.join(', '))
      : vscode.l10n.t('How the rough passes of {0} go down', designation.text),
    ignoreFocusOut: true,
  });
  if (infeed === undefined) return;
  answers.push({ names: ['infeed'], value: infeed.infeed });
  const taperInput = await vscode.window.showInputBox({
    title: title(steps, steps),
    prompt: vscode.l10n.t('Taper as 1:16, or the diameter change per mm; empty for a parallel thread'),
    placeHolder: '1:16',
    value: '',
    ignoreFocusOut: true,
    validateInput: (text) => validate(call, 'threadModule', [...answers, { names: ['taper'], value: text }], true),
  });
  if (taperInput === undefined) return;
  answers.push({ names: ['taper'], value: taperInput });
  const failed = (error: string) => `FANUC Macro: thread module failed: ${error}`;
  const parameters = await checkedParameters(call, 'threadModule', answers, failed);
  if (parameters === undefined) return;
  let answer: unknown;
  try {
    answer = await call(SERVER_COMMAND_THREAD_MODULE, [threadModuleArgs(parameters)]);
  } catch (err) {
    showError(failed(errorText(err)));
    return;
  }
  const error = refusal(answer, 'the language server returned no thread module');
  const text = isRecord(answer) ? answer['text'] : undefined;
  if (error !== undefined || typeof text !== 'string') {
    showError(failed(error ?? 'the language server returned a thread module without text'));
    return;
  }
  if (!(await insert(editor, text, false))) {
    showError(vscode.l10n.t('FANUC Macro: the thread module could not be inserted.'));
  }
}

/** The three commands, answered by the server `connect` gives. */
export function registerGeneratorCommands(connect: Connect): vscode.Disposable[] {
  return [
    vscode.commands.registerCommand('fanuc-macro.insertThreadModule', () => insertThreadModule(connect)),
    vscode.commands.registerCommand('fanuc-macro.insertArcThread', () => insertProgram(arcThreadForm(vscode.l10n.t), connect)),
    vscode.commands.registerCommand('fanuc-macro.insertDrumGroove', () => insertProgram(drumGrooveForm(vscode.l10n.t), connect)),
  ];
}
