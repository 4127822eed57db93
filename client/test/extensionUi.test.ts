// The extension's workbench parts against the fakes: the status bar item (controller and
// server state, a click switches the controller), the diagnostics' rule links to the shipped
// documentation, the check task and the walkthrough's sample.
import assert from 'node:assert/strict';
import { chmodSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, describe, it } from 'node:test';
import type { ExtensionContext } from 'vscode';
import { activate, deactivate } from '../src/extension';
import { clients, serverAnswers, startFailures, type LanguageClient } from './fakes/languageclient';
import { pythonServer } from './fakes/pythonServer';
import * as fake from './fakes/vscode';

// The controllers and their kinds are the language server's answer.
const python = pythonServer();
serverAnswers.set('fanuc-macro.controllers', (args) => python.answer('fanuc-macro.controllers', args));

const root = process.cwd();
const dir = mkdtempSync(join(tmpdir(), 'fanuc-macro-ui-'));
const server = join(dir, 'fanuc-macro-ls');
writeFileSync(server, '#!/bin/sh\necho "fanuc-macro-ls 0.1.0"\n');
chmodSync(server, 0o755);
const extensionDir = join(dir, 'extension');
for (const path of ['docs/rules.md', 'samples/o1000_walkthrough.nc']) {
  fake.files.set(`${extensionDir}/${path}`, readFileSync(join(root, path), 'utf8'));
}

function lastClient(): LanguageClient {
  const client = clients[clients.length - 1];
  assert.ok(client);
  return client;
}

function item(): fake.FakeStatusBarItem {
  const found = fake.statusBarItems.find((i) => i.id === 'fanuc-macro.status');
  assert.ok(found, 'the status bar item was created');
  return found;
}

interface Middleware {
  didOpen(document: { uri: fake.Uri }, next: (d: unknown) => Promise<void>): Promise<void>;
  didChange(
    event: { document: { uri: fake.Uri }; contentChanges: unknown[] },
    next: (e: unknown) => Promise<void>,
  ): Promise<void>;
  didClose(document: { uri: fake.Uri }, next: (d: unknown) => Promise<void>): Promise<void>;
  handleDiagnostics(uri: fake.Uri, diagnostics: unknown[], next: (u: fake.Uri, d: unknown[]) => void): void;
}

describe('extension UI', { skip: process.platform === 'win32' }, () => {
  const context = {
    subscriptions: [] as Array<{ dispose(): unknown }>,
    extensionPath: extensionDir,
    extensionUri: fake.Uri.file(extensionDir),
  };
  after(async () => {
    await deactivate();
    rmSync(dir, { recursive: true, force: true });
    python.close();
  });

  it('shows the controller and the server state in the status bar', async () => {
    fake.setSettings({ 'server.path': server, controller: '0i-TF' });
    fake.window.activeTextEditor = fake.makeEditor('/p/O1.nc');
    activate(context as unknown as ExtensionContext);
    await fake.commands.executeCommand('fanuc-macro.restartServer'); // waits for the start-up
    assert.equal(item().text, '$(check) 0i-TF lathe');
    // The kind of machine comes with the server's controllers, once it runs.
    assert.deepEqual(item().texts.slice(0, 4), [
      '$(circle-slash) 0i-TF · stopped', // before the first start
      '$(loading~spin) 0i-TF · starting',
      '$(check) 0i-TF',
      '$(check) 0i-TF lathe',
    ]);
    assert.match(String(item().tooltip), /ready \(fanuc-macro-ls 0\.1\.0\)/);
    assert.equal(item().command, 'fanuc-macro.selectController');
    assert.equal(item().visible, true);
    // The server bit: the snippets are the extension's.
    assert.equal((lastClient().clientOptions['initializationOptions'] as Record<string, unknown>)['contributesSnippets'], true);
  });

  it('says "analysing" from an opened document until its diagnostics, whose rule links it rewrites', async () => {
    const middleware = lastClient().clientOptions['middleware'] as Middleware;
    const uri = fake.Uri.file('/p/O1.nc');
    await middleware.didOpen({ uri }, () => Promise.resolve());
    assert.equal(item().text, '$(sync~spin) 0i-TF lathe · analysing');
    const web = 'https://github.com/fanuc-macro/fanuc-macro/blob/main/docs/rules.md#mb601-m-not-integer';
    const other = fake.Uri.parse('https://example.com/x');
    const delivered: unknown[][] = [];
    middleware.handleDiagnostics(
      uri,
      [
        { message: 'M gets 2.5', code: { value: 'MB601', target: fake.Uri.parse(web) } },
        { message: 'other', code: { value: 'XX001', target: other } },
        { message: 'plain', code: 'MB101' },
      ],
      (_u, d) => delivered.push(d),
    );
    assert.equal(item().text, '$(check) 0i-TF lathe');
    const [first, second, third] = (delivered[0] ?? []) as Array<{ code: unknown }>;
    const code = first?.code as { value: string; target: fake.Uri };
    assert.equal(code.value, 'MB601');
    assert.equal(code.target.toString(), 'command:fanuc-macro.openRuleDocumentation?%5B%22mb601-m-not-integer%22%5D');
    assert.equal((second?.code as { target: fake.Uri }).target, other);
    assert.equal(third?.code, 'MB101');

    // A change of the text is analysed again; a change of nothing (a save) is not; a closed
    // document is analysed no more.
    const next = () => Promise.resolve();
    await middleware.didChange({ document: { uri }, contentChanges: [] }, next);
    assert.equal(item().text, '$(check) 0i-TF lathe');
    await middleware.didChange({ document: { uri }, contentChanges: [{ text: 'M30' }] }, next);
    assert.equal(item().text, '$(sync~spin) 0i-TF lathe · analysing');
    await middleware.didClose({ uri }, next);
    assert.equal(item().text, '$(check) 0i-TF lathe');

    // The command opens the shipped page at the rule's heading.
    fake.resetRecorded();
    await fake.commands.executeCommand('fanuc-macro.openRuleDocumentation', 'mb601-m-not-integer');
    const lines = readFileSync(join(root, 'docs/rules.md'), 'utf8').split('\n');
    const heading = lines.findIndex((l) => l.startsWith('## MB601 '));
    assert.ok(heading > 0);
    assert.deepEqual(fake.recorded.revealed, [{ line: heading, type: fake.TextEditorRevealType.AtTop }]);
    assert.equal(fake.recorded.shownDocuments[0]?.content, lines.join('\n'));
  });

  it('switches the controller from the quick pick, where the setting is set', async () => {
    fake.resetRecorded();
    fake.settingScopes['controller'] = 'workspace';
    fake.answers.quickPick.push((items) => items.find((i) => i.label === '18i-M'));
    await fake.commands.executeCommand('fanuc-macro.selectController');
    assert.deepEqual(fake.recorded.settingUpdates, [
      { key: 'controller', value: '18i-M', target: fake.ConfigurationTarget.Workspace },
    ]);
    assert.equal(item().text, '$(check) 18i-M mill');

    // Dismissed, or the same controller again: nothing is written.
    fake.answers.quickPick.push(() => undefined);
    await fake.commands.executeCommand('fanuc-macro.selectController');
    fake.answers.quickPick.push((items) => items.find((i) => i.label === '$(check) 18i-M'));
    await fake.commands.executeCommand('fanuc-macro.selectController');
    assert.equal(fake.recorded.settingUpdates.length, 1);
  });

  it('provides a check task with the server package and the problem matcher', () => {
    fake.workspace.workspaceFolders = [{ uri: fake.Uri.file('/work/programs') }];
    const provider = fake.taskProviders.get('fanuc-macro');
    assert.ok(provider);
    const [task] = provider.provideTasks();
    assert.equal(task?.name, 'check .');
    assert.deepEqual(task?.problemMatchers, ['$fanuc-macro']);
    assert.equal(task?.execution.process, join(dir, 'fanuc-macro'));
    assert.deepEqual(task?.execution.args, ['check', '--format', 'text', '.']);
    assert.equal(task?.execution.options?.cwd, '/work/programs');
    const resolved = provider.resolveTask({
      definition: { type: 'fanuc-macro', paths: ['O4009.nc'], args: ['--controller', '0i-MF'] },
      scope: fake.TaskScope.Workspace,
    });
    assert.deepEqual(resolved?.execution.args, ['check', '--format', 'text', 'O4009.nc', '--controller', '0i-MF']);
    assert.equal(provider.resolveTask({ definition: { type: 'fanuc-macro' } }), undefined);
  });

  it('opens the walkthrough sample as an untitled program', async () => {
    fake.resetRecorded();
    await fake.commands.executeCommand('fanuc-macro.openSample');
    const sample = readFileSync(join(root, 'samples/o1000_walkthrough.nc'), 'utf8');
    assert.deepEqual(fake.recorded.openedDocuments, [{ content: sample, language: 'fanuc-macro' }]);
    assert.equal(fake.recorded.shownDocuments[0]?.content, sample);
  });

  it('shows a start failure with its reason until the next start', async () => {
    startFailures.push(new Error('spawn /p/python3 EACCES'));
    fake.answers.errorChoice.push(undefined);
    await fake.commands.executeCommand('fanuc-macro.restartServer');
    assert.equal(item().text, '$(error) 18i-M mill · error');
    assert.equal(item().backgroundColor?.id, 'statusBarItem.errorBackground');
    assert.match(String(item().tooltip), /Language server: error: spawn \/p\/python3 EACCES/);
    assert.match(fake.recorded.errors.at(-1)?.message ?? '', /failed to start: spawn \/p\/python3 EACCES/);
    await fake.commands.executeCommand('fanuc-macro.restartServer');
    assert.equal(item().text, '$(check) 18i-M mill');
    assert.equal(item().backgroundColor, undefined);
  });

  it("shows with 0i-F the machine the active document was read as, once its diagnostics come", async () => {
    // The server's answer for each document: its program analysed with the settings.
    const programs: Record<string, string> = {
      'file:///p/O1.nc': 'O1\nT1 M06\nG43 H1 Z50.\nG91 G28 Z0\nM30\n',
      'file:///p/O2.nc': 'O2\nT0101\nG96 S200 M03\nM30\n',
    };
    serverAnswers.set('fanuc-macro.machine', (args) =>
      python.answer('machineOf', [programs[String(args[0])] ?? '', { controller: fake.settings['controller'] }]),
    );
    const middleware = lastClient().clientOptions['middleware'] as Middleware;
    const asked = () =>
      lastClient()
        .requests.filter((r) => r.params.command === 'fanuc-macro.machine')
        .map((r) => r.params.arguments[0]);
    fake.setSettings({ ...fake.settings, controller: '0i-F' });
    fake.fireConfigurationChange('fanuc-macro.controller');
    assert.equal(item().text, '$(check) 0i-F lathe or mill');

    const uri = fake.Uri.file('/p/O1.nc'); // the active editor's
    middleware.handleDiagnostics(uri, [], () => undefined);
    await until(() => item().text === '$(check) 0i-F mill');
    assert.match(String(item().tooltip), /\nMachine: a mill \(0i-F read as 0i-MF\), from its codes: M06 \(tool change\) on line 2/);
    // Another document's diagnostics: not asked, the active one's machine stays.
    middleware.handleDiagnostics(fake.Uri.file('/p/O2.nc'), [], () => undefined);
    assert.deepEqual(asked(), ['file:///p/O1.nc']);

    // Another program made active: asked at once.
    fake.setActiveEditor(fake.makeEditor('/p/O2.nc'));
    await until(() => item().text === '$(check) 0i-F lathe');
    assert.deepEqual(asked(), ['file:///p/O1.nc', 'file:///p/O2.nc']);
    fake.setActiveEditor(fake.makeEditor('/p/O1.nc'));
    await until(() => item().text === '$(check) 0i-F mill');

    // A controller set: its label, the codes not asked about.
    fake.setSettings({ ...fake.settings, controller: '0i-TF' });
    fake.fireConfigurationChange('fanuc-macro.controller');
    assert.equal(item().text, '$(check) 0i-TF lathe');
    assert.doesNotMatch(String(item().tooltip), /Machine:/);
    // Closed: its machine is forgotten.
    fake.setSettings({ ...fake.settings, controller: '0i-F' });
    middleware.handleDiagnostics(uri, [], () => undefined);
    await until(() => item().text === '$(check) 0i-F mill');
    await middleware.didClose({ uri }, () => Promise.resolve());
    assert.equal(item().text, '$(check) 0i-F lathe or mill');
  });
});

/** Waits until `done` holds (the server's answers come asynchronously). */
async function until(done: () => boolean, ms = 10000): Promise<void> {
  const deadline = Date.now() + ms;
  while (!done()) {
    if (Date.now() > deadline) throw new Error(`not so after ${ms} ms: the status bar says ${item().text}`);
    await new Promise((resolve) => setTimeout(resolve, 10));
  }
}
