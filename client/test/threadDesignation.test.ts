import assert from 'node:assert/strict';
import { describe, it } from 'node:test';
import {
  parseThreadDesignation,
  parseThreadLength,
  threadModuleText,
  validateThreadDesignation,
  validateThreadLength,
} from '../src/threadDesignation';

describe('parseThreadDesignation', () => {
  it('reads an external designation', () => {
    assert.deepEqual(parseThreadDesignation('M50x3-5g6g'), {
      text: 'M50x3-5g6g',
      nominal: 50,
      pitch: 3,
      tolerance: '5g6g',
      internal: false,
    });
  });
  it('reads an internal designation', () => {
    const d = parseThreadDesignation(' M20 x 1.5 - 6H ');
    assert.notEqual(typeof d, 'string');
    assert.equal(typeof d !== 'string' && d.internal, true);
    assert.equal(typeof d !== 'string' && d.text, 'M20x1.5-6H');
  });
  it('leaves the kind open without a tolerance class', () => {
    const d = parseThreadDesignation('m10');
    assert.equal(typeof d !== 'string' && d.internal, null);
    assert.equal(typeof d !== 'string' && d.pitch, undefined);
    const e = parseThreadDesignation('M50×3');
    assert.equal(typeof e !== 'string' && e.internal, null);
    assert.equal(typeof e !== 'string' && e.text, 'M50x3');
  });
  it('accepts left hand and length of engagement suffixes', () => {
    assert.equal(validateThreadDesignation('M16x1.5-6g-LH'), undefined);
    assert.equal(validateThreadDesignation('M16x1.5-6H-L-LH'), undefined);
  });
  it('rejects bad designations', () => {
    for (const bad of ['', '50x3', 'M50x', 'M50x3-6', 'M50x3-5g6H', 'M50x3-6k', 'M50x3-6K', 'M3x3-6g', 'Tr40x7-7e']) {
      assert.equal(typeof validateThreadDesignation(bad), 'string', bad);
    }
  });
});

describe('parseThreadLength', () => {
  it('accepts positive numbers', () => {
    assert.equal(parseThreadLength('40'), 40);
    assert.equal(parseThreadLength(' 32.5 '), 32.5);
    assert.equal(parseThreadLength('12,5'), 12.5);
    assert.equal(parseThreadLength('.5'), 0.5);
  });
  it('rejects others', () => {
    for (const bad of ['', '0', '-5', 'abc', '1e3', '0.0']) {
      assert.equal(typeof validateThreadLength(bad), 'string', bad);
    }
  });
});

describe('threadModuleText', () => {
  it('reads text and errors', () => {
    assert.deepEqual(threadModuleText({ text: 'O0001\n' }), { text: 'O0001\n' });
    assert.deepEqual(threadModuleText({ error: 'no such thread' }), { error: 'no such thread' });
    assert.ok('error' in threadModuleText(null));
    assert.ok('error' in threadModuleText({}));
  });
});
