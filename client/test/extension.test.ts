// Runs client/src/extension.ts against the fakes in ./fakes (the test build
// aliases `vscode` and `vscode-languageclient/node` to them), with real
// --version probes of small shell scripts standing in for the server, and the
// server's own answers (./fakes/pythonServer.ts) to what the boxes and views ask.
import assert from 'node:assert/strict';
import { mkdtempSync } from 'node:fs';
import { join } from 'node:path';
import { after, describe, it } from 'node:test';
import type { ExtensionContext } from 'vscode';
import { activate, deactivate } from '../src/extension';
import { clients, serverAnswers, type LanguageClient } from './fakes/languageclient';
import { pythonServer } from './fakes/pythonServer';
import { serverScripts } from './fakes/serverScripts';
import * as fake from './fakes/vscode';

const { dir, server, python, remove } = serverScripts('fanuc-macro-ext-');
const answering = pythonServer();
for (const command of ['readDesignation', 'checkParameters', 'parameterDefaults', 'controllers']) {
  serverAnswers.set(`fanuc-macro.${command}`, (args) => answering.answer(`fanuc-macro.${command}`, args));
}

/** The threadModule, arcThread and drumGroove requests, the last last. */
const generated = () =>
  lastClient().requests.filter((r) => ['fanuc-macro.threadModule', 'fanuc-macro.arcThread', 'fanuc-macro.drumGroove'].includes(r.params.command));

const baseSettings = {
  'server.path': server,
  controller: '0i-TF',
  'machine.maxSpindleSpeed': 4000,
  'machine.maxThreadingFeed': 5000,
  'threading.maxDepthPerPass': 0.5,
  'rules.disabled': ['MB101'],
  'rules.severity': { MB102: 'hint' },
  'analysis.debounceMs': 250,
  'trace.server': 'off',
};

function lastClient(): LanguageClient {
  const client = clients[clients.length - 1];
  assert.ok(client, 'a language client was created');
  return client;
}

/** The drum groove's first box as it opens: the server's default profile. */
async function drumProfile(): Promise<string> {
  const answer = (await answering.answer('fanuc-macro.parameterDefaults', ['drumGroove'])) as { defaults: { points: string } };
  return answer.defaults.points;
}

/** Runs a command and waits until the extension has settled. */
async function run(command: string): Promise<void> {
  await fake.commands.executeCommand(command);
}

describe('extension', { skip: process.platform === 'win32' }, () => {
  const context = { subscriptions: [] as Array<{ dispose(): unknown }> };
  after(async () => {
    await deactivate();
    remove();
    answering.close();
  });

  it('starts the server from fanuc-macro.server.path with the settings', async () => {
    fake.setSettings({ ...baseSettings });
    activate(context as unknown as ExtensionContext);
    await run('fanuc-macro.restartServer'); // queued after the start-up: waits for it
    const client = lastClient();
    assert.equal(client.id, 'fanuc-macro');
    const options = client.serverOptions as { run: { command: string; args: string[]; transport: number } };
    assert.equal(options.run.command, server);
    assert.deepEqual(options.run.args, []);
    assert.equal(options.run.transport, 0);
    assert.deepEqual(client.clientOptions['documentSelector'], [
      { scheme: 'file', language: 'fanuc-macro' },
      { scheme: 'untitled', language: 'fanuc-macro' },
    ]);
    assert.deepEqual(client.clientOptions['synchronize'], { configurationSection: 'fanuc-macro' });
    assert.deepEqual(client.clientOptions['initializationOptions'], {
      server: { path: server },
      controller: '0i-TF',
      machine: { maxSpindleSpeed: 4000, maxThreadingFeed: 5000 },
      threading: { maxDepthPerPass: 0.5 },
      rules: { disabled: ['MB101'], severity: { MB102: 'hint' } },
      analysis: { debounceMs: 250 },
      trace: { server: 'off' },
      // The server leaves out its own thread snippets: the extension contributes them.
      contributesSnippets: true,
    });
    assert.ok(clients.slice(0, -1).every((c) => c.stopped), 'the previous client was stopped');
  });

  it('shows the trace of the current program in a read-only view beside the editor', async () => {
    fake.resetRecorded();
    fake.window.activeTextEditor = fake.makeEditor('/p/O3331.nc');
    const trace = {
      motions: [
        {
          program: 'O3331',
          line: 23,
          code: 'G92',
          words: { X: 49.816, W: -60, F: 3 },
          start: { X: 51, Z: 5.964 },
          end: { X: 51, Z: 5.964 },
          values: { '#100': 50, '#9': 0.092058049 },
        },
        { program: 'O0013', line: 4, code: 'G00', words: { X: 55 }, path: 'file:///p/O13.nc' },
      ],
      summary: { passes: 1 },
    };
    // The server's view of this trace (fanuc-macro.traceView traces the document first).
    serverAnswers.set('fanuc-macro.traceView', (args) => answering.answer('viewOfTrace', [trace, args[1]]));
    await run('fanuc-macro.showTrace');
    const request = lastClient().requests.pop();
    assert.deepEqual(request, {
      method: 'workspace/executeCommand',
      params: { command: 'fanuc-macro.traceView', arguments: ['file:///p/O3331.nc', '/p/O3331.nc'] },
    });
    // A document of the trace's own scheme and language (read-only: a content provider's).
    const opened = fake.recorded.openedDocuments[0];
    assert.equal(opened?.language, 'fanuc-macro-trace');
    // The row: its block, code, words, where the tool goes, S, F and the time it starts at
    // (none: the motion has no clock); the values under it.
    assert.match(opened?.content ?? '', /^O3331 line 23 +G92 +X49\.816 W-60\. +X51\. Z5\.964 +- +3\. +-\n {4}#100=50\. #9=0\.092058049$/m);
    assert.match(opened?.content ?? '', /^block +code +words +to +S +F +time$/m);
    assert.match(opened?.content ?? '', /Summary\n {2}passes: 1/);
    assert.deepEqual(fake.recorded.shownDocuments[0]?.options, {
      viewColumn: fake.ViewColumn.Beside,
      preview: false,
      preserveFocus: false,
    });
    assert.deepEqual(fake.recorded.errors, []);

    // Each row's "O3331 line 23" links to its block; F12 on the row goes there too.
    const traceUri = fake.Uri.from({ scheme: 'fanuc-macro-trace', path: '/Trace of O3331.nc', query: 'file:///p/O3331.nc' });
    const document = (await fake.workspace.openTextDocument(traceUri)) as fake.FakeDocument;
    const lines = document.content.split('\n');
    const row = lines.findIndex((l) => l.startsWith('O3331 line 23'));
    const other = lines.findIndex((l) => l.startsWith('O0013 line 4'));
    const links = fake.providers.links.flatMap((l) => l.provider.provideDocumentLinks(document));
    assert.deepEqual(
      links.map((l) => [l.range.start.line, l.range.start.character, l.range.end.character, l.target?.toString()]),
      [
        [row, 0, 'O3331 line 23'.length, 'file:///p/O3331.nc#L23'],
        [other, 0, 'O0013 line 4'.length, 'file:///p/O13.nc#L4'],
      ],
    );
    const definition = fake.providers.definitions[0]?.provider.provideDefinition(document, new fake.Position(row, 40));
    assert.equal(definition?.uri.toString(), 'file:///p/O3331.nc');
    assert.deepEqual(definition?.range, new fake.Position(22, 0));
    assert.equal(fake.providers.definitions[0]?.provider.provideDefinition(document, new fake.Position(0, 0)), undefined);
  });

  it('shows the error of a failed trace', async () => {
    fake.resetRecorded();
    serverAnswers.set('fanuc-macro.traceView', () => ({ error: 'vacant #101 in O3331 line 12' }));
    await run('fanuc-macro.showTrace');
    assert.equal(fake.recorded.openedDocuments.length, 0);
    assert.match(fake.recorded.errors[0]?.message ?? '', /vacant #101 in O3331 line 12/);
  });

  it('inserts an external thread module at the cursor', async () => {
    fake.resetRecorded();
    fake.answers.inputBox.push(' M50x3-5g6g ', '40', '');
    fake.answers.quickPick.push((items) => items[0]);
    serverAnswers.set('fanuc-macro.threadModule', () => ({ text: '#100=50.\nM98 P0013331\n' }));
    await run('fanuc-macro.insertThreadModule');
    // The paper's module (symmetric, parallel) is asked for without options, for the document
    // it goes into (the server takes program numbers that document does not have).
    assert.deepEqual(generated().pop()?.params, {
      command: 'fanuc-macro.threadModule',
      arguments: [{ designation: 'M50x3-5g6g', length: 40, internal: false, uri: 'file:///p/O3331.nc' }],
    });
    assert.deepEqual(
      fake.recorded.inputBoxes.map((b) => b.title),
      ['Symmetric Thread Module (1/4)', 'Symmetric Thread Module (2/4)', 'Symmetric Thread Module (4/4)'],
    );
    assert.deepEqual(fake.recorded.inserts, [
      { position: new fake.Position(4, 0), text: '#100=50.\nM98 P0013331\n' },
    ]);
  });

  it('opens every box of a command on a value Enter accepts, the taper empty for parallel', async () => {
    fake.resetRecorded();
    fake.answers.inputValidation.length = 0;
    // Enter in each box: the user keeps the text the box opened with.
    fake.answers.inputBox.push('M24x3-6g', (box) => box.value, (box) => box.value);
    fake.answers.quickPick.push((items) => items[0]);
    const note = 'O4009 and O3331 are in the file already: the main program is O4010 and the sub-program is O3332.';
    serverAnswers.set('fanuc-macro.threadModule', () => ({ text: '#100=24.\nM98 P0013332\n', note }));
    await run('fanuc-macro.insertThreadModule');
    const [, length, taper] = fake.recorded.inputBoxes;
    // The server's default length for M24: one nominal diameter, as the paper's M50 is 50 long.
    assert.equal(length?.value, '24');
    assert.deepEqual([taper?.value, taper?.placeHolder], ['', 'parallel']);
    assert.deepEqual(fake.answers.inputValidation.slice(-2), [undefined, undefined]);
    assert.deepEqual(generated().pop()?.params.arguments, [
      { designation: 'M24x3-6g', length: 24, internal: false, uri: 'file:///p/O3331.nc' },
    ]);
    // Which program numbers the module took, where the document had the paper's.
    assert.deepEqual(fake.recorded.informations.at(-1), `FANUC Macro: ${note}`);
    serverAnswers.set('fanuc-macro.threadModule', () => ({ text: '#100=50.\nM98 P0013331\n' }));
  });

  it('asks external or internal when the designation does not say', async () => {
    fake.resetRecorded();
    fake.answers.inputBox.push('M50x3', '32.5', '');
    fake.answers.quickPick.push((items) => items.find((i) => i.label.startsWith('Internal')));
    fake.answers.quickPick.push((items) => items[0]);
    await run('fanuc-macro.insertThreadModule');
    assert.deepEqual(generated().pop()?.params.arguments, [
      { designation: 'M50x3', length: 32.5, internal: true, uri: 'file:///p/O3331.nc' },
    ]);
  });

  it('asks external or internal for an all-capital class both kinds have, and sends the answer', async () => {
    fake.resetRecorded();
    fake.answers.inputBox.push('M50X3-5G6G', '40', '');
    fake.answers.quickPick.push((items) => items.find((i) => i.label.startsWith('External')));
    fake.answers.quickPick.push((items) => items[0]);
    await run('fanuc-macro.insertThreadModule');
    assert.deepEqual(fake.recorded.quickPicks[0], {
      title: 'Symmetric Thread Module (3/5)',
      placeHolder: 'M50X3-5G6G: the class 5G6G fits an external (5g6g) or an internal (5G6G) thread: which is it?',
    });
    assert.deepEqual(generated().pop()?.params.arguments, [
      { designation: 'M50X3-5G6G', length: 40, internal: false, uri: 'file:///p/O3331.nc' },
    ]);
  });

  it('does not ask the kind of the seed paper\'s M50X3-4H5H: ISO 965-1 has it internal only', async () => {
    fake.resetRecorded();
    fake.answers.inputBox.push('M50X3-4H5H', '40', '');
    fake.answers.quickPick.push((items) => items[0]);
    await run('fanuc-macro.insertThreadModule');
    assert.deepEqual(
      fake.recorded.quickPicks.map((p) => p.title),
      ['Symmetric Thread Module (3/4)'],
    );
    assert.deepEqual(generated().pop()?.params.arguments, [
      { designation: 'M50X3-4H5H', length: 40, internal: true, uri: 'file:///p/O3331.nc' },
    ]);
  });

  it('shows the server\'s refusal of a designation that does not say its kind', async () => {
    fake.resetRecorded();
    fake.answers.inputBox.push('M50x3-6H', '40', '');
    fake.answers.quickPick.push((items) => items[0]);
    const refusal =
      'M50X3-5G6G: the class 5G6G fits an external (5g6g) or an internal (5G6G) thread: say which';
    serverAnswers.set('fanuc-macro.threadModule', () => ({ error: refusal }));
    await run('fanuc-macro.insertThreadModule');
    assert.equal(fake.recorded.inserts.length, 0);
    assert.equal(fake.recorded.errors[0]?.message, `FANUC Macro: thread module failed: ${refusal}`);
    serverAnswers.set('fanuc-macro.threadModule', () => ({ text: '#100=50.\nM98 P0013331\n' }));
  });

  it('sends the infeed and the taper asked for', async () => {
    fake.resetRecorded();
    fake.answers.inputValidation.length = 0;
    fake.answers.inputBox.push('M24xPh4P2-6g-LH', '30', '1:16');
    fake.answers.quickPick.push((items) => items.find((i) => i.label === 'Left flank'));
    await run('fanuc-macro.insertThreadModule');
    assert.deepEqual(generated().pop()?.params.arguments, [
      { designation: 'M24xPh4P2-6g-LH', length: 30, internal: false, infeed: 'left', taper: 0.0625, uri: 'file:///p/O3331.nc' },
    ]);
    assert.equal(fake.answers.inputValidation.at(-1), undefined);
  });

  it('stops at a taper it cannot read', async () => {
    fake.resetRecorded();
    fake.answers.inputValidation.length = 0;
    fake.answers.inputBox.push('M24x2-6g', '30', '1:x');
    fake.answers.quickPick.push((items) => items[0]);
    const before = generated().length;
    await run('fanuc-macro.insertThreadModule');
    assert.equal(generated().length, before);
    // The command line's message (fanuc-macro thread --taper).
    const taper = /^the taper is a ratio or a number \(e\.g\. 1:16, or 0\.0625 mm of diameter per mm of length\), not 1:x$/;
    assert.match(fake.answers.inputValidation.at(-1) ?? '', taper);
    assert.match(fake.recorded.errors[0]?.message ?? '', /the taper is a ratio or a number/);
  });

  it('stops when a prompt is dismissed', async () => {
    fake.resetRecorded();
    fake.answers.inputBox.push('M50x3-6g', undefined);
    const before = generated().length;
    await run('fanuc-macro.insertThreadModule');
    assert.equal(generated().length, before);
    assert.deepEqual(fake.recorded.errors, []);
    assert.equal(fake.answers.inputBox.length, 0);
  });

  it('validates the designation', async () => {
    fake.resetRecorded();
    fake.answers.inputValidation.length = 0;
    fake.answers.inputBox.push('M50x3-5g6H');
    const before = generated().length;
    await run('fanuc-macro.insertThreadModule');
    assert.equal(
      fake.answers.inputValidation[0],
      'M50x3-5g6H: the class 5g6H mixes letter cases (upper case is internal, lower case external)',
    );
    assert.match(fake.recorded.errors[0]?.message ?? '', /mixes letter cases/);
    assert.equal(generated().length, before);
  });

  it('shows the error of the thread module command', async () => {
    fake.resetRecorded();
    fake.answers.inputBox.push('M50x3-6H', '40', '');
    fake.answers.quickPick.push((items) => items[0]);
    serverAnswers.set('fanuc-macro.threadModule', () => ({ error: 'pitch 3 is not standard for M50' }));
    await run('fanuc-macro.insertThreadModule');
    assert.equal(fake.recorded.inserts.length, 0);
    assert.match(fake.recorded.errors[0]?.message ?? '', /pitch 3 is not standard for M50/);
  });

  it('inserts the arc thread program of the defaults, the paper\'s part', async () => {
    fake.resetRecorded();
    const paper = ['93.82, 10, 1.2', '25, 113', '108, 103', '7', '100, 19'];
    fake.answers.inputBox.push(...paper);
    serverAnswers.set('fanuc-macro.arcThread', () => ({
      text: '%\nO0002\nG65 P0003\n%\n',
      summary: { layer_cuts: [7, 7], finishing_cuts: 19, g32_cuts: 33 },
    }));
    await run('fanuc-macro.insertArcThread');
    // The boxes open on the server's defaults, the paper's part.
    assert.deepEqual(
      fake.recorded.inputBoxes.map((b) => b.value),
      paper,
    );
    assert.equal(fake.recorded.inputBoxes[0]?.title, 'Arc Thread Program (1/5)');
    assert.deepEqual(generated().pop()?.params, {
      command: 'fanuc-macro.arcThread',
      // The boxes' answers as the server read them.
      arguments: [
        {
          outer_diameter: 93.82,
          groove_radius: 10,
          tool_radius: 1.2,
          pitch: 25,
          length: 113,
          layers: [108, 103],
          cuts_per_layer: 7,
          finishing_diameter: 100,
          finishing_cuts: 19,
          uri: 'file:///p/O3331.nc',
        },
      ],
    });
    assert.deepEqual(fake.answers.inputValidation.slice(-5), [undefined, undefined, undefined, undefined, undefined]);
    assert.deepEqual(fake.recorded.inserts, [{ position: new fake.Position(4, 0), text: '%\nO0002\nG65 P0003\n%\n' }]);
    assert.deepEqual(fake.recorded.statusMessages, ['FANUC Macro: 33 G32 cuts: 7, 7 per roughing layer, 19 finishing.']);
  });

  it("shows the server's refusal of a drum groove and inserts nothing", async () => {
    fake.resetRecorded();
    fake.answers.inputBox.push(await drumProfile(), '40', '9, 0.8', '1, 0.5');
    serverAnswers.set('fanuc-macro.drumGroove', (args) => {
      assert.equal((args[0] as { pitch: number }).pitch, 40);
      return { error: 'segment 1-2 is steeper than 45 degrees' };
    });
    await run('fanuc-macro.insertDrumGroove');
    assert.equal(fake.recorded.inputBoxes[1]?.value, '');
    assert.equal(fake.recorded.inserts.length, 0);
    assert.match(fake.recorded.errors[0]?.message ?? '', /not generated: segment 1-2 is steeper/);
  });

  it('asks nothing of the server when the drum groove has no pitch', async () => {
    fake.resetRecorded();
    fake.answers.inputValidation.length = 0;
    fake.answers.inputBox.push(await drumProfile(), '');
    const before = generated().length;
    await run('fanuc-macro.insertDrumGroove');
    assert.equal(
      fake.answers.inputValidation[1],
      "pitch is missing: give the groove's pitch (lead) in mm; the paper's is not known, its figure 2 is lost",
    );
    assert.equal(generated().length, before);
  });

  it("uses the Python extension's interpreter when no path is set", async () => {
    fake.setSettings({ ...baseSettings, 'server.path': '' });
    fake.setPythonExtension({
      isActive: true,
      exports: { environments: { getActiveEnvironmentPath: () => ({ id: 'x', path: python }) } },
    });
    await run('fanuc-macro.restartServer');
    const options = lastClient().serverOptions as { run: { command: string; args: string[] } };
    assert.equal(options.run.command, python);
    assert.deepEqual(options.run.args, ['-m', 'fanuc_macro.lsp.server']);
    fake.setPythonExtension(undefined);
  });

  it('restarts when fanuc-macro.server.path changes', async () => {
    const count = clients.length;
    fake.setSettings({ ...baseSettings });
    fake.fireConfigurationChange('fanuc-macro.server.path');
    await run('fanuc-macro.restartServer');
    assert.equal(clients.length, count + 2);
    assert.equal((lastClient().serverOptions as { run: { command: string } }).run.command, server);
  });

  it('looks at fanuc-macro.server.path again when the workspace is trusted', async () => {
    // Started while the restricted setting read as empty; trust makes it readable.
    fake.setSettings({ ...baseSettings, 'server.path': '' });
    await run('fanuc-macro.restartServer');
    const count = clients.length;
    fake.setSettings({ ...baseSettings });
    fake.fireTrustGranted();
    await run('fanuc-macro.restartServer');
    assert.equal(clients.length, count + 2);
    assert.equal((lastClient().serverOptions as { run: { command: string } }).run.command, server);
    // Trust again with the same setting: no restart.
    const after = clients.length;
    fake.fireTrustGranted();
    await new Promise((resolve) => setTimeout(resolve, 50));
    assert.equal(clients.length, after);
  });

  it('says what was tried and offers the setting when no server works', async () => {
    fake.resetRecorded();
    const count = clients.length;
    const savedPath = process.env['PATH'];
    process.env['PATH'] = mkdtempSync(join(dir, 'empty-path-'));
    fake.setSettings({ ...baseSettings, 'server.path': join(dir, 'missing-ls') });
    fake.answers.errorChoice.push('Open Setting');
    try {
      await run('fanuc-macro.restartServer');
      // the error message is shown without blocking the start-up queue
      await new Promise((resolve) => setTimeout(resolve, 50));
    } finally {
      process.env['PATH'] = savedPath;
    }
    assert.equal(clients.length, count);
    const error = fake.recorded.errors[0];
    assert.ok(error);
    assert.match(error.message, /pip install fanuc-macro/);
    assert.match(error.message, /fanuc-macro\.server\.path/);
    assert.match(error.message, /missing-ls: not found/);
    assert.match(error.message, /python3 -m fanuc_macro\.lsp\.server: /);
    assert.deepEqual(error.items, ['Open Setting', 'Show Log']);
    assert.deepEqual(
      fake.recorded.executed.find((e) => e.command === 'workbench.action.openSettings'),
      { command: 'workbench.action.openSettings', args: ['fanuc-macro.server.path'] },
    );
  });

  it('tells the user when a command needs the server and it is not running', async () => {
    fake.resetRecorded();
    fake.window.activeTextEditor = fake.makeEditor('/p/O3331.nc');
    await run('fanuc-macro.showTrace');
    assert.match(fake.recorded.errors[0]?.message ?? '', /not running/);
  });
});
