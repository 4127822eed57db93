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
    assert.equal(controllerSetting?.default, '0i-TF');
    assert.equal(known.default, '0i-TF');
  });

  it('are labelled with the machine they are for', () => {
    assert.equal(controllerLabel('0i-TF', known), '0i-TF lathe');
    assert.equal(controllerLabel('18i-M', known), '18i-M mill');
    assert.equal(controllerLabel('30i', known), '30i lathe and mill');
    assert.equal(controllerLabel(undefined, known), '0i-TF lathe'); // the setting's default
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
    assert.equal(status.view(undefined).text, '$(circle-slash) 0i-TF lathe · stopped');
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
