import assert from 'node:assert/strict';
import { describe, it } from 'node:test';
import {
  formatMotionLines,
  formatProgram,
  formatSummary,
  formatTrace,
  formatWordValue,
  formatWords,
  traceResultError,
} from '../src/traceFormat';

describe('formatWordValue', () => {
  it('writes FANUC decimal points', () => {
    assert.equal(formatWordValue('X', 49.816), '49.816');
    assert.equal(formatWordValue('W', -60), '-60.');
    assert.equal(formatWordValue('F', 3), '3.');
    assert.equal(formatWordValue('Z', -0), '0.');
    assert.equal(formatWordValue('Z', 0.1 + 0.2), '0.3');
    assert.equal(formatWordValue('X', -0.0000001), '0.');
    assert.equal(formatWordValue('U', 1e-5), '0.00001');
  });
  it('keeps integer addresses integral', () => {
    assert.equal(formatWordValue('S', 1200), '1200');
    assert.equal(formatWordValue('p', 1000), '1000');
  });
  it('passes strings and vacant values through', () => {
    assert.equal(formatWordValue('X', '#1'), '#1');
    assert.equal(formatWordValue('X', null), '<vacant>');
  });
});

describe('formatProgram', () => {
  it('writes O numbers', () => {
    assert.equal(formatProgram(3331), 'O3331');
    assert.equal(formatProgram('13'), 'O0013');
    assert.equal(formatProgram('O3331'), 'O3331');
    assert.equal(formatProgram('<THREAD>'), '<THREAD>');
    assert.equal(formatProgram(undefined), '');
  });
});

describe('formatWords', () => {
  it('keeps the server order', () => {
    assert.equal(formatWords({ X: 49.816, W: -60, F: 3 }), 'X49.816 W-60. F3.');
    assert.equal(formatWords(undefined), '');
  });
});

describe('formatMotionLines', () => {
  it('formats the example line', () => {
    assert.deepEqual(
      formatMotionLines([{ program: 'O3331', line: 23, code: 'G92', words: { X: 49.816, W: -60, F: 3 } }]),
      ['O3331 line 23  G92  X49.816 W-60. F3.'],
    );
  });
  it('aligns columns', () => {
    assert.deepEqual(
      formatMotionLines([
        { program: 3331, line: 9, code: 'G0', words: { X: 52 } },
        { program: 3331, line: 123, code: 'G92', words: { X: 49.5, W: -60, F: 3 } },
      ]),
      ['O3331 line 9    G0   X52.', 'O3331 line 123  G92  X49.5 W-60. F3.'],
    );
  });
});

describe('formatSummary', () => {
  it('indents nested objects', () => {
    assert.deepEqual(formatSummary({ motions: 2, passes: [0.3, 0.2], limits: { s: 800 } }), [
      '  motions: 2',
      '  passes: 0.3, 0.2',
      '  limits:',
      '    s: 800',
    ]);
  });
  it('marks empty lists and objects', () => {
    assert.deepEqual(formatSummary({ findings: [], by_code: {}, stopped: false }), [
      '  findings: (none)',
      '  by_code: (none)',
      '  stopped: false',
    ]);
  });
  it('lists arrays of objects', () => {
    assert.deepEqual(formatSummary({ warnings: [{ line: 3, message: 'x' }] }), [
      '  warnings:',
      '    - line: 3',
      '      message: x',
    ]);
  });
});

describe('formatTrace', () => {
  it('makes the whole document', () => {
    const text = formatTrace(
      {
        motions: [{ program: 'O3331', line: 23, code: 'G92', words: { X: 49.816, W: -60, F: 3 } }],
        summary: { passes: 1 },
      },
      '/p/O3331.nc',
    );
    assert.equal(
      text,
      'Trace of /p/O3331.nc\n1 motion block\n\nO3331 line 23  G92  X49.816 W-60. F3.\n\nSummary\n  passes: 1\n',
    );
  });
  it('says when there is no motion', () => {
    assert.match(formatTrace({ motions: [] }, 'x'), /\(no motion\)/);
  });
});

describe('traceResultError', () => {
  it('returns the server error', () => {
    assert.equal(traceResultError({ error: 'undefined variable #1' }), 'undefined variable #1');
  });
  it('rejects malformed answers', () => {
    assert.ok(traceResultError(null));
    assert.ok(traceResultError({ motions: 3 }));
  });
  it('accepts a trace', () => {
    assert.equal(traceResultError({ motions: [], summary: {} }), undefined);
  });
});
