// The debugger's registrations in the extension, against the fakes: the adapter is started with
// what started the language server, launch configurations get the settings, the hover gets the
// whole `#` variable and "Debug This Program" debugs the active file.
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { after, describe, it } from 'node:test';
import type { ExtensionContext } from 'vscode';
import { activate, deactivate } from '../src/extension';
import { ToolpathPanel } from '../src/toolpathView';
import { serverAnswers } from './fakes/languageclient';
import { pythonServer } from './fakes/pythonServer';
import { serverScripts } from './fakes/serverScripts';
import * as fake from './fakes/vscode';

const { dir, server, python, remove } = serverScripts('fanuc-macro-debug-');
const answering = pythonServer();
serverAnswers.set('fanuc-macro.variableAt', (args) => answering.answer('fanuc-macro.variableAt', args));

function registered<T>(map: Map<string, T>): T {
  const found = map.get('fanuc-macro');
  assert.ok(found, 'registered for the fanuc-macro debugger type');
  return found;
}

async function adapter(): Promise<fake.DebugAdapterExecutable> {
  const descriptor = await registered(fake.debuggers.descriptorFactories).createDebugAdapterDescriptor({}, undefined);
  assert.ok(descriptor instanceof fake.DebugAdapterExecutable);
  return descriptor;
}

describe('debugger', { skip: process.platform === 'win32' }, () => {
  const context = { subscriptions: [] as Array<{ dispose(): unknown }> };
  after(async () => {
    await deactivate();
    remove();
    answering.close();
  });

  it('starts fanuc-macro-dap beside the fanuc-macro-ls the server runs', async () => {
    fake.setSettings({ 'server.path': server, controller: '0i-TF', 'analysis.stepBudget': 300000 });
    activate(context as unknown as ExtensionContext);
    const executable = await adapter(); // waits for the server's start-up
    assert.equal(executable.command, join(dir, 'fanuc-macro-dap'));
    assert.deepEqual(executable.args, []);
    assert.equal(executable.options?.env?.['PYTHONUNBUFFERED'], '1');
  });

  it('starts python -m fanuc_macro.dap when the server runs on a Python', async () => {
    fake.setSettings({ 'server.path': python });
    fake.fireConfigurationChange('fanuc-macro.server.path'); // restarts the server
    const executable = await adapter();
    assert.equal(executable.command, python);
    assert.deepEqual(executable.args, ['-m', 'fanuc_macro.dap']);
  });

  it('completes launch configurations from the settings and the active editor', () => {
    fake.setSettings({ 'server.path': python, controller: '0i-MF', 'analysis.stepBudget': 1234 });
    fake.window.activeTextEditor = fake.makeEditor('/w/o4009.nc');
    const provider = registered(fake.debuggers.configurationProviders);
    assert.deepEqual(provider.resolveDebugConfiguration(undefined, {}), {
      type: 'fanuc-macro',
      request: 'launch',
      name: 'Debug o4009.nc',
      program: '/w/o4009.nc',
      stopOnEntry: true,
      controller: '0i-MF',
      stepBudget: 1234,
    });
    fake.window.activeTextEditor = fake.makeEditor('/w/notes.txt', 'plaintext');
    fake.resetRecorded();
    assert.equal(provider.resolveDebugConfiguration(undefined, {}), undefined);
    assert.match(fake.recorded.errors[0]?.message ?? '', /open a FANUC Macro program/);
  });

  it('"Debug This Program" debugs the active file without a stop on entry', async () => {
    fake.window.activeTextEditor = fake.makeEditor('/w/o4009.nc');
    fake.debuggers.started.length = 0;
    await fake.commands.executeCommand('fanuc-macro.debugProgram');
    assert.deepEqual(fake.debuggers.started.map((s) => s.config), [
      { type: 'fanuc-macro', request: 'launch', name: 'Debug o4009.nc', program: '/w/o4009.nc', stopOnEntry: false },
    ]);
  });

  it("gives the debug hover the variable with its #, as the server finds it", async () => {
    const entry = fake.providers.evaluatable.find((p) => p.selector === 'fanuc-macro');
    assert.ok(entry);
    const document = { lineAt: (_line: number) => ({ text: 'G92 X[#100-2*#9] Z#26 F#4' }) };
    const expression = await entry.provider.provideEvaluatableExpression(document, new fake.Position(3, 14));
    assert.deepEqual(expression?.range, new fake.Range(3, 13, 3, 15));
    assert.equal(await entry.provider.provideEvaluatableExpression(document, new fake.Position(3, 1)), undefined);
  });

  it('lets the tracker ignore stops while no Toolpath view is open', async () => {
    const requests: unknown[] = [];
    const session = {
      customRequest: (command: string, args: unknown) => {
        requests.push([command, args]);
        return Promise.resolve({ stackFrames: [] });
      },
    };
    const tracker = registered(fake.debuggers.trackerFactories).createDebugAdapterTracker(session);
    tracker?.onDidSendMessage?.({ type: 'event', event: 'stopped', body: { reason: 'breakpoint', threadId: 1 } });
    await new Promise((resolve) => setImmediate(resolve));
    assert.deepEqual(requests, []); // nothing to light: the stack is not asked for
  });

  it('has the open Toolpath view light the block the run stopped on', async () => {
    const lit: number[] = [];
    // The view's two members the tracker uses (the webview itself is the browser test's).
    const view = { documentPath: '/w/o4009.nc', showStoppedBlock: (line: number) => lit.push(line) };
    ToolpathPanel.current = view as unknown as ToolpathPanel;
    const requests: unknown[] = [];
    const frames = { '/w/o4009.nc': 32, '/w/o9000.nc': 5 };
    let path: keyof typeof frames = '/w/o4009.nc';
    const session = {
      customRequest: (command: string, args: unknown) => {
        requests.push([command, args]);
        return Promise.resolve({ stackFrames: [{ id: 1, name: 'O3331', line: frames[path], source: { path } }] });
      },
    };
    const tracker = registered(fake.debuggers.trackerFactories).createDebugAdapterTracker(session);
    const settle = () => new Promise((resolve) => setImmediate(resolve));
    try {
      tracker?.onDidSendMessage?.({ type: 'event', event: 'output', body: { output: 'DPRNT' } });
      tracker?.onDidSendMessage?.({ type: 'event', event: 'stopped', body: { reason: 'breakpoint', threadId: 1 } });
      await settle();
      path = '/w/o9000.nc'; // a stop in another file's program lights nothing
      tracker?.onDidSendMessage?.({ type: 'event', event: 'stopped', body: { reason: 'step', threadId: 1 } });
      await settle();
    } finally {
      ToolpathPanel.current = undefined;
    }
    assert.deepEqual(requests, [
      ['stackTrace', { threadId: 1, levels: 1 }],
      ['stackTrace', { threadId: 1, levels: 1 }],
    ]);
    assert.deepEqual(lit, [31]);
  });
});
