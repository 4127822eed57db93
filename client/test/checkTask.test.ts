import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, it } from 'node:test';
import { checkTaskCommand, cliCommand, isCheckTaskDefinition } from '../src/checkTask';

const root = process.cwd();
const manifest = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8')) as {
  contributes: {
    problemMatchers: Array<{
      name: string;
      owner: string;
      fileLocation: unknown;
      pattern: { regexp: string; file: number; line: number; column: number; code: number; severity: number; message: number };
    }>;
    taskDefinitions: Array<{ type: string; required: string[] }>;
  };
};
const matcher = manifest.contributes.problemMatchers.find((m) => m.name === 'fanuc-macro');

/** `fanuc-macro check` of the seeds, in text and JSON, from this checkout's server package. */
function runCheck(format: 'text' | 'json'): string {
  const python = process.env['PYTHON'] || (process.platform === 'win32' ? 'python' : 'python3');
  const result = spawnSync(
    python,
    ['-m', 'fanuc_macro.cli', 'check', '--format', format, 'tests/fixtures/seeds', 'samples'],
    { cwd: root, encoding: 'utf8', env: { ...process.env, PYTHONPATH: join(root, 'server') } },
  );
  assert.equal(result.error, undefined);
  assert.ok(result.status === 0 || result.status === 1, result.stderr);
  return result.stdout;
}

describe('the $fanuc-macro problem matcher', () => {
  it('reads every line of the CLI text output as the JSON output gives it', () => {
    assert.ok(matcher, 'package.json contributes the fanuc-macro problem matcher');
    assert.equal(matcher.owner, 'fanuc-macro');
    assert.deepEqual(matcher.fileLocation, ['autoDetect', '${workspaceFolder}']);
    const regexp = new RegExp(matcher.pattern.regexp);
    const lines = runCheck('text').split('\n').filter((l) => l !== '');
    const expected = JSON.parse(runCheck('json')) as Array<{
      path: string;
      line: number;
      column: number;
      code: string;
      severity: string;
      message: string;
    }>;
    assert.ok(expected.length >= 3, `only ${expected.length} problems`);
    assert.equal(lines.length, expected.length);
    const { file, line, column, code, severity, message } = matcher.pattern;
    const read = lines.map((text) => {
      const m = regexp.exec(text);
      assert.ok(m, `the matcher does not read ${JSON.stringify(text)}`);
      return {
        path: m[file],
        line: Number(m[line]),
        column: Number(m[column]),
        code: m[code],
        severity: m[severity],
        message: m[message],
      };
    });
    assert.deepEqual(
      read,
      expected.map((d) => ({
        path: d.path,
        line: d.line,
        column: d.column,
        code: d.code,
        severity: d.severity,
        message: d.message,
      })),
    );
    // A message that holds ": " and a path in it still splits at the first location.
    assert.ok(read.some((d) => d.message.includes(': ')));
  });

  it('is what the task definition uses', () => {
    const definition = manifest.contributes.taskDefinitions.find((d) => d.type === 'fanuc-macro');
    assert.deepEqual(definition?.required, ['paths']);
  });
});

describe('the check task command', () => {
  it('runs the CLI module of the Python that runs the server', () => {
    assert.deepEqual(cliCommand({ command: '/usr/bin/python3', args: ['-m', 'fanuc_macro.lsp.server'] }), {
      command: '/usr/bin/python3',
      args: ['-m', 'fanuc_macro.cli'],
    });
    assert.deepEqual(cliCommand({ command: 'py', args: ['-3', '-m', 'fanuc_macro.lsp.server'] }), {
      command: 'py',
      args: ['-3', '-m', 'fanuc_macro.cli'],
    });
  });

  it('runs the fanuc-macro beside a fanuc-macro-ls executable', () => {
    assert.deepEqual(cliCommand({ command: '/venv/bin/fanuc-macro-ls', args: [] }), {
      command: '/venv/bin/fanuc-macro',
      args: [],
    });
    assert.deepEqual(cliCommand({ command: 'fanuc-macro-ls', args: [] }), { command: 'fanuc-macro', args: [] });
    assert.deepEqual(cliCommand({ command: '/opt/server', args: [] }), { command: 'fanuc-macro', args: [] });
    assert.deepEqual(cliCommand(undefined), { command: 'fanuc-macro', args: [] });
  });

  it('gives the paths, then the options of tasks.json', () => {
    assert.deepEqual(
      checkTaskCommand(
        { command: 'python3', args: ['-m', 'fanuc_macro.lsp.server'] },
        { paths: ['programs', 'O4009.nc'], args: ['--controller', '0i-MF'] },
      ),
      {
        command: 'python3',
        args: ['-m', 'fanuc_macro.cli', 'check', '--format', 'text', 'programs', 'O4009.nc', '--controller', '0i-MF'],
      },
    );
    assert.deepEqual(checkTaskCommand(undefined, { paths: [] }).args, ['check', '--format', 'text', '.']);
  });

  it('accepts only well-formed definitions', () => {
    assert.equal(isCheckTaskDefinition({ type: 'fanuc-macro', paths: ['.'] }), true);
    assert.equal(isCheckTaskDefinition({ type: 'fanuc-macro', paths: ['.'], args: ['--verbose'] }), true);
    assert.equal(isCheckTaskDefinition({ type: 'fanuc-macro', paths: '.' }), false);
    assert.equal(isCheckTaskDefinition({ type: 'shell', paths: ['.'] }), false);
    assert.equal(isCheckTaskDefinition({ type: 'fanuc-macro', paths: ['.'], args: [1] }), false);
    assert.equal(isCheckTaskDefinition(null), false);
  });
});
