// The debugger's pure logic: the adapter's command from the language server's, the launch
// configuration completed from the settings, the hover's variable under the mouse, the block
// the Toolpath view lights on a stop, and the manifest's debugger contribution.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, describe, it } from 'node:test';
import {
  DAP_MODULE,
  DEBUG_TYPE,
  adapterCommand,
  programConfiguration,
  resolveLaunch,
} from '../src/debugConfiguration';
import { isStoppedEvent, samePath, stoppedLine } from '../src/debugFollow';
import { pythonServer } from './fakes/pythonServer';
import { SERVER_MODULE, buildCandidates, type ServerCandidate } from '../src/serverCandidates';

describe('adapterCommand', () => {
  it('runs the DAP module with the interpreter, arguments and environment of the server', () => {
    const bundled: ServerCandidate = {
      command: 'py',
      args: ['-3', '-m', SERVER_MODULE],
      source: 'bundled',
      description: 'py -3 with the bundled server',
      env: { PYTHONPATH: 'C:\\ext\\bundled\\python' },
    };
    assert.deepEqual(adapterCommand(bundled, 'win32'), {
      command: 'py',
      args: ['-3', '-m', DAP_MODULE],
      env: { PYTHONPATH: 'C:\\ext\\bundled\\python' },
    });
  });

  it('follows the candidates buildCandidates makes from a Python setting', () => {
    const [first] = buildCandidates({ settingPath: '/opt/venv/bin/python3', platform: 'linux' });
    assert.ok(first);
    assert.deepEqual(adapterCommand(first, 'linux'), {
      command: '/opt/venv/bin/python3',
      args: ['-m', 'fanuc_macro.dap'],
      env: undefined,
    });
  });

  it('uses the fanuc-macro-dap beside a fanuc-macro-ls executable', () => {
    const at = (command: string, platform: NodeJS.Platform) =>
      adapterCommand({ command, args: [], source: 'setting', description: command }, platform).command;
    assert.equal(at('/home/u/.local/bin/fanuc-macro-ls', 'linux'), '/home/u/.local/bin/fanuc-macro-dap');
    assert.equal(at('C:\\venv\\Scripts\\fanuc-macro-ls.exe', 'win32'), 'C:\\venv\\Scripts\\fanuc-macro-dap.exe');
    assert.equal(at('fanuc-macro-ls', 'linux'), 'fanuc-macro-dap'); // looked up on PATH
    assert.deepEqual(
      adapterCommand({ command: 'fanuc-macro-ls', args: [], source: 'path', description: '' }, 'linux').args,
      [],
    );
  });
});

describe('resolveLaunch', () => {
  const settings = { controller: '0i-MF', stepBudget: 5000 };

  it('debugs the active program when there is no launch.json, stopping on entry', () => {
    const resolved = resolveLaunch({}, { ...settings, activeProgram: '/w/O4009.nc' });
    assert.deepEqual(resolved, {
      ok: true,
      config: {
        type: DEBUG_TYPE,
        request: 'launch',
        name: 'Debug O4009.nc',
        program: '/w/O4009.nc',
        stopOnEntry: true,
        controller: '0i-MF',
        stepBudget: 5000,
      },
    });
  });

  it('fills controller and stepBudget only when the configuration does not give them', () => {
    const given = { type: DEBUG_TYPE, request: 'launch', name: 'x', program: '${file}', controller: '30i', stepBudget: 7 };
    assert.deepEqual(resolveLaunch(given, settings), { ok: true, config: given });
    const bare = resolveLaunch({ type: DEBUG_TYPE, request: 'launch', name: 'x', program: 'a.nc' }, {});
    assert.deepEqual(bare.ok && [bare.config['controller'], bare.config['stepBudget']], [undefined, 300000]);
  });

  it('says why a configuration cannot be launched', () => {
    assert.deepEqual(resolveLaunch({}, settings), { ok: false, problem: 'no-active-program' });
    assert.deepEqual(resolveLaunch({ type: DEBUG_TYPE, request: 'attach', name: 'x', program: 'a.nc' }, settings), {
      ok: false,
      problem: 'not-launch',
    });
    assert.deepEqual(resolveLaunch({ type: DEBUG_TYPE, request: 'launch', name: 'x', program: ' ' }, settings), {
      ok: false,
      problem: 'no-program',
    });
  });

  it('makes the command\'s configuration without a stop on entry', () => {
    assert.deepEqual(programConfiguration('/w/o1000.nc', false), {
      type: DEBUG_TYPE,
      request: 'launch',
      name: 'Debug o1000.nc',
      program: '/w/o1000.nc',
      stopOnEntry: false,
    });
  });
});

describe("the server's variable under the hover (fanuc-macro.variableAt)", () => {
  const server = pythonServer();
  after(() => server.close());
  /** The text of the expression under the first `^` of `marker`, on `line`. */
  const under = async (line: string, marker: string) => {
    const range = (await server.answer('fanuc-macro.variableAt', [line, marker.indexOf('^')])) as { start?: number; end?: number };
    return range.start === undefined ? undefined : line.slice(range.start, range.end);
  };
  const line = '#1=#[#2+1]*#101 (RADIUS #5)';

  it('keeps the # of a numbered variable', async () => {
    assert.equal(await under(line, '^'), '#1');
    assert.equal(await under(line, ' ^'), '#1');
    assert.equal(await under(line, '            ^'), '#101');
    assert.equal(await under('G00 X#24 Z#26;', '      ^'), '#24');
  });

  it('gives the innermost variable of an indirection, and the whole one between', async () => {
    assert.equal(await under(line, '     ^'), '#2');
    assert.equal(await under(line, '       ^'), '#[#2+1]');
    assert.equal(await under(line, '   ^'), '#[#2+1]');
    assert.equal(await under('#[#[#1]+2]', '   ^'), '#[#1]');
  });

  it('reads system variable names', async () => {
    assert.equal(await under('#_UI[2]=1', ' ^'), '#_UI[2]');
    assert.equal(await under('#<TOOLNO>=1', '  ^'), '#<TOOLNO>');
  });

  it('gives nothing off a variable, in a comment or for an unclosed bracket', async () => {
    assert.equal(await under(line, '  ^'), undefined); // the =
    assert.equal(await under(line, '                        ^'), undefined); // #5 in the comment
    assert.equal(await under('#[#2+1', '^'), undefined);
    assert.equal(await under('G65 P9000 A#', '           ^'), undefined);
  });
});

describe('stoppedLine', () => {
  const body = (path: string, line: number) => ({ stackFrames: [{ id: 1, name: 'O3331', line, source: { path } }] });

  it('is the top frame\'s line, 0-based, in the view\'s document', () => {
    assert.equal(stoppedLine(body('/w/o4009.nc', 32), '/w/o4009.nc', 'linux'), 31);
    assert.equal(stoppedLine(body('C:\\w\\O4009.NC', 1), 'c:/w/o4009.nc', 'win32'), 0);
  });

  it('is nothing for another file or an answer without frames', () => {
    assert.equal(stoppedLine(body('/w/O4009.nc', 32), '/w/o4009.nc', 'linux'), undefined);
    assert.equal(stoppedLine(body('/w/o9000.nc', 3), '/w/o4009.nc', 'linux'), undefined);
    assert.equal(stoppedLine({ stackFrames: [] }, '/w/o4009.nc', 'linux'), undefined);
    assert.equal(stoppedLine(undefined, '/w/o4009.nc', 'linux'), undefined);
    assert.equal(stoppedLine(body('/w/o4009.nc', 0), '/w/o4009.nc', 'linux'), undefined);
  });

  it('compares paths as the platform does', () => {
    assert.equal(samePath('/a/B.nc', '/a/b.nc', 'linux'), false);
    assert.equal(samePath('/a/B.nc', '/a/b.nc', 'darwin'), true);
  });

  it('reacts to stopped events only', () => {
    assert.equal(isStoppedEvent({ type: 'event', event: 'stopped', body: { reason: 'breakpoint' } }), true);
    assert.equal(isStoppedEvent({ type: 'event', event: 'output' }), false);
    assert.equal(isStoppedEvent({ type: 'response', command: 'stopped' }), false);
  });
});

describe('the manifest\'s debugger', () => {
  const manifest = JSON.parse(readFileSync(join(process.cwd(), 'package.json'), 'utf8')) as {
    contributes: {
      debuggers: Array<{
        type: string;
        languages: string[];
        configurationAttributes: { launch: { required: string[]; properties: Record<string, unknown> } };
        initialConfigurations: Array<Record<string, unknown>>;
      }>;
      breakpoints: Array<{ language: string }>;
      commands: Array<{ command: string; icon?: string }>;
      menus: Record<string, Array<{ command: string; when?: string }>>;
    };
  };
  const [debuggerEntry] = manifest.contributes.debuggers;

  it('describes every launch argument the adapter reads', () => {
    assert.ok(debuggerEntry);
    assert.equal(debuggerEntry.type, DEBUG_TYPE);
    assert.deepEqual(debuggerEntry.languages, ['fanuc-macro']);
    assert.deepEqual(Object.keys(debuggerEntry.configurationAttributes.launch.properties).sort(), [
      'arguments',
      'commons',
      'controller',
      'entry',
      'program',
      'stepBudget',
      'stopOnEntry',
    ]);
    assert.deepEqual(debuggerEntry.configurationAttributes.launch.required, ['program']);
    assert.deepEqual(debuggerEntry.initialConfigurations[0]?.['program'], '${file}');
    assert.equal(debuggerEntry.initialConfigurations[0]?.['stopOnEntry'], true);
  });

  it('lets breakpoints be set in programs and puts the command in the editor title', () => {
    assert.deepEqual(manifest.contributes.breakpoints, [{ language: 'fanuc-macro' }]);
    const command = manifest.contributes.commands.find((c) => c.command === 'fanuc-macro.debugProgram');
    assert.equal(command?.icon, '$(debug-alt)');
    const title = manifest.contributes.menus['editor/title']?.find((m) => m.command === 'fanuc-macro.debugProgram');
    assert.match(title?.when ?? '', /resourceLangId == fanuc-macro/);
  });
});
