import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, describe, it } from 'node:test';
import {
  NO_CONTROLLERS,
  ServerStatus,
  controllerChoices,
  controllerLabel,
  controllersOf,
  documentMachineOf,
  english,
  settingTarget,
  type Controllers,
} from '../src/serverStatus';
import { pythonServer } from './fakes/pythonServer';

const manifest = JSON.parse(readFileSync(join(process.cwd(), 'package.json'), 'utf8')) as {
  contributes: { configuration: Array<{ properties: Record<string, { enum?: string[]; default?: unknown }> }> };
};
const controllerSetting = manifest.contributes.configuration
  .map((c) => c.properties['fanuc-macro.controller'])
  .find((p) => p !== undefined);

const server = pythonServer();
/** The language server's answer to fanuc-macro.controllers. */
let known: Controllers = NO_CONTROLLERS;
before(async () => {
  known = controllersOf(await server.answer('fanuc-macro.controllers', []));
});
after(() => server.close());

describe('controllers', () => {
  it("are the server's, those of the fanuc-macro.controller setting, in its order", () => {
    assert.deepEqual(
      known.list.map((c) => c.id),
      controllerSetting?.enum,
    );
    assert.equal(controllerSetting?.default, '0i-F');
    assert.equal(known.default, '0i-F');
  });

  it('are labelled with the machine they are for', () => {
    assert.equal(controllerLabel('0i-TF', known), '0i-TF lathe');
    assert.equal(controllerLabel('18i-M', known), '18i-M mill');
    assert.equal(controllerLabel('30i', known), '30i lathe and mill');
    assert.equal(controllerLabel('0i-F', known), '0i-F lathe or mill'); // as each program shows
    assert.equal(controllerLabel(undefined, known), '0i-F lathe or mill'); // the setting's default
    assert.equal(controllerLabel('15-T', known), '15-T'); // not one we know: as it is, no kind
    // Before the server has named them: the setting's value, of no kind.
    assert.equal(controllerLabel('0i-TF', NO_CONTROLLERS), '0i-TF');
    assert.deepEqual(controllersOf({ error: 'x' }), NO_CONTROLLERS);
  });

  it('are offered with the current one marked', () => {
    const choices = controllerChoices('0i-MF', known);
    assert.deepEqual(
      choices.filter((c) => c.picked).map((c) => c.label),
      ['$(check) 0i-MF'],
    );
    assert.deepEqual(
      choices.map((c) => [c.id, c.description]),
      [
        ['0i-F', 'lathe or mill'],
        ['0i-TF', 'lathe'],
        ['0i-MF', 'mill'],
        ['16i-T', 'lathe'],
        ['16i-M', 'mill'],
        ['18i-T', 'lathe'],
        ['18i-M', 'mill'],
        ['30i', 'lathe and mill'],
      ],
    );
  });

  it('are written where the setting is set, the most specific place first', () => {
    assert.equal(settingTarget({ workspaceFolderValue: '0i-MF', workspaceValue: '30i' }), 'workspaceFolder');
    assert.equal(settingTarget({ workspaceValue: '30i' }), 'workspace');
    assert.equal(settingTarget({}), 'global');
    assert.equal(settingTarget(undefined), 'global');
  });
});

describe('ServerStatus', () => {
  it('goes from starting to ready to analysing and back', () => {
    let changes = 0;
    const status = new ServerStatus(() => (changes += 1));
    status.controllers = known;
    assert.equal(status.current, 'stopped');
    status.starting();
    assert.equal(status.current, 'starting');
    assert.match(status.view('0i-TF').text, /^\$\(loading~spin\) 0i-TF lathe · starting$/);
    status.ready('0.1.0');
    assert.equal(status.view('0i-TF').text, '$(check) 0i-TF lathe');
    assert.match(status.view('0i-TF').tooltip, /Language server: ready \(fanuc-macro-ls 0\.1\.0\)/);
    status.analysisStarted('file:///a.nc');
    status.analysisStarted('file:///b.nc');
    assert.equal(status.current, 'analysing');
    assert.equal(status.view('0i-MF').text, '$(sync~spin) 0i-MF mill · analysing');
    assert.match(status.view('0i-MF').tooltip, /analysing 2 document\(s\)/);
    status.analysisDone('file:///a.nc');
    assert.equal(status.current, 'analysing');
    status.analysisDone('file:///b.nc');
    assert.equal(status.current, 'ready');
    status.analysisDone('file:///b.nc'); // diagnostics again (a settings change): no change
    assert.equal(changes, 6); // starting, ready, two started, two done
  });

  it('keeps an error and its reason shown until the next start', () => {
    const status = new ServerStatus();
    status.controllers = known;
    status.starting();
    status.failed('spawn python3 ENOENT');
    status.stopped(); // the client's state change after the failure
    assert.equal(status.current, 'error');
    assert.equal(status.error, 'spawn python3 ENOENT');
    const view = status.view('30i');
    assert.equal(view.text, '$(error) 30i lathe and mill · error');
    assert.equal(view.error, true);
    assert.match(view.tooltip, /Controller: FANUC Series 30i\/31i\/32i/);
    assert.match(view.tooltip, /Language server: error: spawn python3 ENOENT/);
    status.starting();
    assert.equal(status.error, undefined);
    assert.equal(status.view('30i').error, false);
  });

  it('forgets the pending analyses of a server that stopped', () => {
    const status = new ServerStatus();
    status.controllers = known;
    status.ready(undefined);
    status.analysisStarted('file:///a.nc');
    status.stopped();
    assert.equal(status.current, 'stopped');
    assert.equal(status.analysing, 0);
    assert.equal(status.view(undefined).text, '$(circle-slash) 0i-F lathe or mill · stopped'); // the default
    status.ready(undefined);
    assert.equal(status.current, 'ready');
  });

  it('translates its words and fills in the placeholders', () => {
    const upper = (message: string, ...args: Array<string | number>) => english(message.toUpperCase(), ...args);
    const status = new ServerStatus();
    status.controllers = known;
    status.failed('boom');
    assert.equal(status.view('0i-TF', upper).text, '$(error) 0i-TF LATHE · ERROR');
    assert.match(status.view('0i-TF', upper).tooltip, /LANGUAGE SERVER: ERROR: boom/);
  });
});

// Programs whose codes show a mill, a lathe, and neither (the server's tests read the same).
const MILL = 'O1000\nT1 M06\nG90 G54 G00 X0 Y0\nG43 H1 Z50.\nG91 G28 Z0\nM30\n';
const LATHE = 'O2000\nT0101\nG96 S200 M03\nG00 X50. Z2.\nG01 Z-20. F0.2\nM30\n';
const MACRO = 'O3000\n#1=10\n#2=#1*2\nM30\n';

/** A ready status that has the server's answer to fanuc-macro.machine for each program. */
async function statusWithMachines(settings: Record<string, unknown> = {}): Promise<ServerStatus> {
  const status = new ServerStatus();
  status.controllers = known;
  status.ready('0.1.0');
  for (const [uri, text] of [
    ['file:///mill.nc', MILL],
    ['file:///lathe.nc', LATHE],
    ['file:///macro.nc', MACRO],
  ] as const) {
    status.machineAnswered(uri, status.askingMachine(uri), await server.answer('machineOf', [text, settings]));
  }
  return status;
}

describe('the machine of the active document', () => {
  it('is shown with 0i-F, and its reason in the tooltip', async () => {
    const status = await statusWithMachines();
    const mill = status.view('0i-F', english, 'file:///mill.nc');
    assert.equal(mill.text, '$(check) 0i-F mill');
    assert.equal(
      mill.tooltip.split('\n')[1],
      'Machine: a mill (0i-F read as 0i-MF), from its codes: M06 (tool change) on line 2 and 4 more kinds of mark.',
    );
    assert.equal(status.view(undefined, english, 'file:///lathe.nc').text, '$(check) 0i-F lathe'); // the default
    assert.match(status.view('0i-F', english, 'file:///lathe.nc').tooltip, /\nMachine: a lathe \(0i-F read as 0i-TF\), from its codes: a four-digit T/);
    const macro = status.view('0i-F', english, 'file:///macro.nc');
    assert.equal(macro.text, '$(check) 0i-F lathe?');
    assert.match(macro.tooltip, /\nMachine: not known, no code of the program is a lathe's or a mill's alone\. Read as a lathe/);
    // The server's state goes on showing after the machine.
    status.analysisStarted('file:///mill.nc');
    assert.equal(status.view('0i-F', english, 'file:///mill.nc').text, '$(sync~spin) 0i-F mill · analysing');
    // No program active, or one the server has not answered for: the controller's kind.
    const none = status.view('0i-F', english, undefined);
    assert.equal(none.text, '$(sync~spin) 0i-F lathe or mill · analysing');
    assert.doesNotMatch(none.tooltip, /Machine:/);
    assert.equal(status.view('0i-F', english, 'file:///other.nc').text, '$(sync~spin) 0i-F lathe or mill · analysing');
  });

  it('is not shown with a controller set: the setting says the machine', async () => {
    const status = await statusWithMachines({ controller: '0i-MF' });
    assert.equal(status.machine('file:///lathe.nc')?.kind, 'mill'); // the setting wins over the codes
    const view = status.view('0i-MF', english, 'file:///lathe.nc');
    assert.equal(view.text, '$(check) 0i-MF mill');
    assert.doesNotMatch(view.tooltip, /Machine:/);
    // An answer read with 0i-F, shown with a controller set since: the controller's label.
    const byCodes = await statusWithMachines();
    assert.equal(byCodes.view('0i-TF', english, 'file:///mill.nc').text, '$(check) 0i-TF lathe');
  });

  it('keeps the newest answer, and forgets a refused, a closed and every document', async () => {
    const status = await statusWithMachines();
    const uri = 'file:///mill.nc';
    const older = status.askingMachine(uri);
    const newer = status.askingMachine(uri);
    status.machineAnswered(uri, newer, await server.answer('machineOf', [LATHE, {}]));
    status.machineAnswered(uri, older, await server.answer('machineOf', [MILL, {}])); // too late
    assert.equal(status.view('0i-F', english, uri).text, '$(check) 0i-F lathe');
    status.machineAnswered(uri, status.askingMachine(uri), { error: `${uri} is not open` });
    assert.equal(status.view('0i-F', english, uri).text, '$(check) 0i-F lathe or mill');
    status.forgetMachines('file:///lathe.nc');
    assert.equal(status.machine('file:///lathe.nc'), undefined);
    assert.equal(status.machine('file:///macro.nc')?.kind, 'unknown');
    status.forgetMachines();
    assert.equal(status.machine('file:///macro.nc'), undefined);
    assert.equal(documentMachineOf({ controller: '0i-MF', kind: 'drill', text: 'x' }), undefined);
    assert.equal(documentMachineOf(undefined), undefined);
  });

  it('translates the kind', async () => {
    const upper = (message: string, ...args: Array<string | number>) => english(message.toUpperCase(), ...args);
    const status = await statusWithMachines();
    assert.equal(status.view('0i-F', upper, 'file:///macro.nc').text, '$(check) 0i-F LATHE?');
    assert.equal(status.view('0i-F', upper, 'file:///mill.nc').text, '$(check) 0i-F MILL');
  });
});
