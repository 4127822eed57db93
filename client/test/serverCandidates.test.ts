import assert from 'node:assert/strict';
import { chmodSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, describe, it } from 'node:test';
import { probeCandidate } from '../src/probe';
import {
  SERVER_MODULE,
  buildCandidates,
  candidateFromPath,
  describeAttempts,
  expandPath,
  isPythonInterpreter,
  parseVersionOutput,
  versionArgs,
  type ServerCandidate,
} from '../src/serverCandidates';

describe('isPythonInterpreter', () => {
  for (const path of [
    'python',
    'python3',
    '/usr/bin/python3',
    '/opt/venv/bin/python3.12',
    'C:\\Python312\\python.exe',
    'C:\\venv\\Scripts\\python3.exe',
    'PYTHON.EXE',
    '  /usr/bin/python  ',
  ]) {
    it(`recognises ${path}`, () => assert.equal(isPythonInterpreter(path), true));
  }
  for (const path of [
    'fanuc-macro-ls',
    '/home/u/.local/bin/fanuc-macro-ls',
    'C:\\venv\\Scripts\\fanuc-macro-ls.exe',
    '/usr/bin/python-config',
    '/opt/python3/bin/fanuc-macro-ls',
    'ipython',
  ]) {
    it(`does not take ${path} for an interpreter`, () => assert.equal(isPythonInterpreter(path), false));
  }
});

describe('expandPath', () => {
  it('expands ~ and ${userHome}', () => {
    assert.equal(expandPath('~/venv/bin/python', '/home/u', undefined), '/home/u/venv/bin/python');
    assert.equal(expandPath('${userHome}/x', '/home/u', undefined), '/home/u/x');
    assert.equal(expandPath('~', '/home/u', undefined), '/home/u');
  });
  it('expands ${workspaceFolder} and strips quotes', () => {
    assert.equal(
      expandPath('"${workspaceFolder}/.venv/bin/python"', undefined, '/w'),
      '/w/.venv/bin/python',
    );
  });
  it('leaves other paths alone', () => {
    assert.equal(expandPath(' /a/~b ', '/home/u', '/w'), '/a/~b');
  });
});

describe('candidateFromPath', () => {
  it('runs an interpreter with -m', () => {
    const c = candidateFromPath('/v/bin/python3', 'setting');
    assert.equal(c.command, '/v/bin/python3');
    assert.deepEqual(c.args, ['-m', SERVER_MODULE]);
    assert.deepEqual(versionArgs(c), ['-m', SERVER_MODULE, '--version']);
  });
  it('runs an executable directly', () => {
    const c = candidateFromPath('/v/bin/fanuc-macro-ls', 'setting');
    assert.deepEqual(c.args, []);
    assert.deepEqual(versionArgs(c), ['--version']);
  });
});

describe('buildCandidates', () => {
  const summary = (cs: ServerCandidate[]): string[] => cs.map((c) => [c.source, c.command, ...c.args].join(' '));

  it('has the PATH and python3 fallbacks when nothing is configured', () => {
    assert.deepEqual(summary(buildCandidates({ platform: 'linux' })), [
      'path fanuc-macro-ls',
      `python python3 -m ${SERVER_MODULE}`,
    ]);
  });

  it('tries setting, Python extension, PATH, python3 in this order', () => {
    const cs = buildCandidates({
      platform: 'linux',
      settingPath: '~/bin/fanuc-macro-ls',
      pythonExtensionInterpreter: '/w/.venv/bin/python',
      homeDir: '/home/u',
    });
    assert.deepEqual(summary(cs), [
      'setting /home/u/bin/fanuc-macro-ls',
      `python-extension /w/.venv/bin/python -m ${SERVER_MODULE}`,
      'path fanuc-macro-ls',
      `python python3 -m ${SERVER_MODULE}`,
    ]);
  });

  it('runs a configured interpreter with -m and drops duplicates', () => {
    const cs = buildCandidates({
      platform: 'linux',
      settingPath: '/w/.venv/bin/python',
      pythonExtensionInterpreter: '/w/.venv/bin/python',
    });
    assert.deepEqual(summary(cs), [
      `setting /w/.venv/bin/python -m ${SERVER_MODULE}`,
      'path fanuc-macro-ls',
      `python python3 -m ${SERVER_MODULE}`,
    ]);
  });

  it('ignores blank settings', () => {
    const cs = buildCandidates({ platform: 'linux', settingPath: '   ', pythonExtensionInterpreter: '' });
    assert.equal(cs[0]?.source, 'path');
  });

  it('adds python and py -3 on Windows', () => {
    const cs = buildCandidates({ platform: 'win32' });
    assert.deepEqual(summary(cs), [
      'path fanuc-macro-ls',
      `python python3 -m ${SERVER_MODULE}`,
      `python python -m ${SERVER_MODULE}`,
      `python py -3 -m ${SERVER_MODULE}`,
    ]);
  });
});

describe('parseVersionOutput', () => {
  it('reads the version', () => {
    assert.equal(parseVersionOutput('fanuc-macro-ls 0.1.0\n'), '0.1.0');
    assert.equal(parseVersionOutput('fanuc-macro-ls 1.2.3.dev4+g123'), '1.2.3.dev4+g123');
    assert.equal(parseVersionOutput('fanuc-macro 0.2'), '0.2');
  });
  it('rejects other programs', () => {
    assert.equal(parseVersionOutput('Python 3.11.7'), undefined);
    assert.equal(parseVersionOutput(''), undefined);
  });
});

describe('describeAttempts', () => {
  it('describes each attempt', () => {
    const c = candidateFromPath('fanuc-macro-ls', 'path');
    assert.deepEqual(
      describeAttempts([
        { candidate: c, result: { ok: false, reason: 'not found' } },
        { candidate: c, result: { ok: true, version: '0.1.0' } },
      ]),
      ['fanuc-macro-ls: not found', 'fanuc-macro-ls: found version 0.1.0'],
    );
  });
});

describe('probeCandidate', { skip: process.platform === 'win32' }, () => {
  const dir = mkdtempSync(join(tmpdir(), 'fanuc-macro-probe-'));
  after(() => rmSync(dir, { recursive: true, force: true }));
  const script = (name: string, body: string): string => {
    const path = join(dir, name);
    writeFileSync(path, `#!/bin/sh\n${body}\n`);
    chmodSync(path, 0o755);
    return path;
  };

  it('accepts a server that prints its version', async () => {
    const path = script('fanuc-macro-ls', 'echo "fanuc-macro-ls 0.1.0"');
    assert.deepEqual(await probeCandidate(candidateFromPath(path, 'setting'), 5000), {
      ok: true,
      version: '0.1.0',
    });
  });

  it('passes -m and --version to an interpreter', async () => {
    const path = script('python3', 'if [ "$1 $2 $3" = "-m fanuc_macro.lsp.server --version" ]; then echo "fanuc-macro-ls 0.1.0"; else exit 3; fi');
    const result = await probeCandidate(candidateFromPath(path, 'setting'), 5000);
    assert.deepEqual(result, { ok: true, version: '0.1.0' });
  });

  it('reports a missing program', async () => {
    const result = await probeCandidate(candidateFromPath(join(dir, 'missing-ls'), 'setting'), 5000);
    assert.deepEqual(result, { ok: false, reason: 'not found' });
  });

  it('reports the last line of stderr on failure', async () => {
    const path = script('broken-ls', 'echo "Traceback" >&2; echo "ModuleNotFoundError: No module named fanuc_macro" >&2; exit 1');
    const result = await probeCandidate(candidateFromPath(path, 'setting'), 5000);
    assert.equal(result.ok, false);
    assert.match(!result.ok ? result.reason : '', /exited with code 1: ModuleNotFoundError/);
  });

  it('rejects a program that is not fanuc-macro-ls', async () => {
    const path = script('other-ls', 'echo "other 1.0"');
    const result = await probeCandidate(candidateFromPath(path, 'setting'), 5000);
    assert.equal(result.ok, false);
  });

  it('times out', async () => {
    const path = script('slow-ls', 'exec sleep 10');
    const started = Date.now();
    const result = await probeCandidate(candidateFromPath(path, 'setting'), 300);
    assert.equal(result.ok, false);
    assert.match(!result.ok ? result.reason : '', /within 300 ms/);
    assert.ok(Date.now() - started < 5000);
  });
});

describe('the installed fanuc-macro-ls', { skip: process.platform === 'win32' }, () => {
  it('answers --version as the client expects', async (t) => {
    const result = await probeCandidate(candidateFromPath('fanuc-macro-ls', 'path'), 60000);
    if (!result.ok && result.reason === 'not found') {
      t.skip('fanuc-macro-ls is not installed');
      return;
    }
    if (!result.ok && /No module named '?fanuc_macro\.lsp/.test(result.reason)) {
      t.skip('the fanuc_macro.lsp package is not written yet');
      return;
    }
    assert.equal(result.ok, true, result.ok ? '' : result.reason);
  });
});
