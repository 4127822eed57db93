import assert from 'node:assert/strict';
import { describe, it } from 'node:test';
import {
  formatMacroValue,
  formatPosition,
  formatProgram,
  formatSummary,
  formatTraceView,
  formatValues,
  formatWordValue,
  formatWords,
  rowAt,
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

describe('formatPosition', () => {
  it('writes the axes known', () => {
    assert.equal(formatPosition({ X: 51, Z: 5.964 }), 'X51. Z5.964');
    assert.equal(formatPosition({ X: 94.274, Y: null, Z: -113 }), 'X94.274 Z-113.');
    assert.equal(formatPosition({}), '?');
    assert.equal(formatPosition(undefined), '?');
  });
});

describe('formatMacroValue', () => {
  it('shows 8 significant digits as the control does', () => {
    assert.equal(formatMacroValue(51.24902500375539), '51.249025');
    assert.equal(formatMacroValue(0.09205804890977895), '0.092058049');
    assert.equal(formatMacroValue(150), '150.');
    assert.equal(formatMacroValue(-0), '0.');
    assert.equal(formatMacroValue(-1.25), '-1.25');
  });
  it('marks vacant and unknown values', () => {
    assert.equal(formatMacroValue(null), '<vacant>');
    assert.equal(formatMacroValue('depends on #500'), '(depends on #500)');
  });
});

describe('formatValues', () => {
  it('keeps the order the block names them', () => {
    assert.equal(formatValues({ '#6': 50, '#4': 10, '#18': 1.2, '#16': 51.249025 }), '#6=50. #4=10. #18=1.2 #16=51.249025');
    assert.equal(formatValues({ '#1': null }), '#1=<vacant>');
    assert.equal(formatValues(undefined), '');
  });
});

describe('formatTraceView', () => {
  const result = {
    motions: [
      {
        program: 'O0003',
        line: 33,
        code: 'G00',
        words: { Z: 55.508 },
        start: { X: 150, Z: 100 },
        end: { X: 150, Z: 55.508 },
        values: { '#6': 50, '#16': 51.24902500375539 },
      },
      {
        program: 'O3331',
        line: 32,
        code: 'G92',
        words: { X: 49.816, W: -60, F: 3 },
        path: 'file:///p/O3331.nc',
        start: { X: 51, Z: 5.964 },
        end: { X: 51, Z: 5.964 },
        moves: [
          { kind: 'rapid', start: { X: 51, Z: 5.964 }, end: { X: 49.816, Z: 5.964 } },
          { kind: 'thread', start: { X: 49.816, Z: 5.964 }, end: { X: 49.816, Z: -54.036 } },
        ],
      },
    ],
    toolpath: { units: 'mm', lost: [{ program: 'O0003', line: 32, axes: ['X', 'Z'], reason: 'not known' }] },
    summary: { blocks_executed: 143, stopped: null },
  };
  const view = formatTraceView(result, '/p/o2.nc');
  const lines = view.text.split('\n');

  it('writes a row per block with its positions and the values it read', () => {
    assert.equal(lines[0], 'Trace of /p/o2.nc');
    assert.equal(lines[1], '2 motion blocks, 143 blocks executed, positions in mm');
    const header = lines.findIndex((l) => l.startsWith('block '));
    assert.equal(
      lines[header + 1],
      'O0003 line 33  G00   Z55.508            X150. Z100. -> X150. Z55.508  #6=50. #16=51.249025',
    );
    assert.equal(lines[header + 2], 'O3331 line 32  G92   X49.816 W-60. F3.  X51. Z5.964 -> X51. Z5.964');
    assert.deepEqual(lines.slice(header + 3, header + 6), [
      '    2 moves:',
      '      rapid  X51. Z5.964 -> X49.816 Z5.964',
      '      thread X49.816 Z5.964 -> X49.816 Z-54.036',
    ]);
    // The columns line up under the header.
    assert.equal(lines[header]!.indexOf('from -> to'), lines[header + 1]!.indexOf('X150.'));
    assert.equal(lines[header]!.indexOf('values read'), lines[header + 1]!.indexOf('#6='));
  });

  it('links every row of a block to its line, in its own file', () => {
    const header = lines.findIndex((l) => l.startsWith('block '));
    const first = rowAt(view, header + 1);
    assert.deepEqual(first, { line: header + 1, sourceLine: 32, link: { start: 0, end: 13 }, label: 'O0003 line 33' });
    assert.equal(lines[header + 1]!.slice(first!.link!.start, first!.link!.end), 'O0003 line 33');
    const cycle = rowAt(view, header + 2);
    assert.equal(cycle?.path, 'file:///p/O3331.nc');
    assert.equal(cycle?.sourceLine, 31);
    // The moves under it lead to the same block, without a link of their own.
    assert.deepEqual(rowAt(view, header + 4), { line: header + 4, sourceLine: 31, path: 'file:///p/O3331.nc', label: 'O3331 line 32' });
    assert.equal(rowAt(view, 0), undefined);
    assert.equal(rowAt(view, header), undefined);
    // Where the path is not known links to its block too.
    const lost = lines.indexOf('  O0003 line 32: X, Z not known');
    assert.ok(lost > header);
    assert.deepEqual(rowAt(view, lost)?.link, { start: 2, end: 15 });
    assert.deepEqual(
      view.rows.map((r) => r.line),
      [...view.rows.map((r) => r.line)].sort((a, b) => a - b),
    );
  });

  it('says when there is no motion', () => {
    const empty = formatTraceView({ motions: [] }, 'x');
    assert.match(empty.text, /\(no motion\)/);
    assert.deepEqual(empty.rows, []);
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
