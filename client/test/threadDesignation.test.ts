import assert from 'node:assert/strict';
import { describe, it } from 'node:test';
import {
  parseTaper,
  parseThreadDesignation,
  sideQuestion,
  parseThreadLength,
  threadModuleText,
  validateTaper,
  validateThreadDesignation,
  validateThreadLength,
} from '../src/threadDesignation';

describe('parseThreadDesignation', () => {
  it('reads an external designation', () => {
    assert.deepEqual(parseThreadDesignation('M50x3-5g6g'), {
      text: 'M50x3-5g6g',
      nominal: 50,
      pitch: 3,
      starts: 1,
      leftHand: false,
      tolerance: '5g6g',
      internal: false,
    });
  });
  it('reads the starts of a multi-start designation and the hand', () => {
    const d = parseThreadDesignation('M24xPh4P2-6g');
    assert.equal(typeof d !== 'string' && d.starts, 2);
    assert.equal(typeof d !== 'string' && d.pitch, 2);
    const e = parseThreadDesignation('M24XPH6P2-6H-LH');
    assert.equal(typeof e !== 'string' && e.starts, 3);
    assert.equal(typeof e !== 'string' && e.leftHand, true);
    const f = parseThreadDesignation('M20x2LH-6g');
    assert.equal(typeof f !== 'string' && f.leftHand, true);
    for (const bad of ['M24xPh5P2-6g', 'M24xPh20P2-6g', 'M24xPh4-6g', 'M24xPhP2-6g']) {
      assert.equal(typeof validateThreadDesignation(bad), 'string', bad);
    }
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
    assert.equal(typeof e !== 'string' && e.text, 'M50×3');
  });
  it('does not read the case of an all-capital designation', () => {
    const d = parseThreadDesignation('M50X3-5G6G');
    assert.equal(typeof d !== 'string' && d.internal, null);
    assert.deepEqual(typeof d !== 'string' && d.classes, { external: '5g6g', internal: '5G6G' });
    const e = parseThreadDesignation('M50X3-6E');
    assert.equal(typeof e !== 'string' && e.internal, false);
    const f = parseThreadDesignation('M50×3-6H');
    assert.equal(typeof f !== 'string' && f.internal, true);
  });
  it('leaves the kind of an all-capital class both kinds have open, never guessed', () => {
    for (const text of ['M50X3-5G6G', 'M20X1.5-6H', 'M10-6H', 'M50X3-7H6H', 'M20X1.5-6G-LH']) {
      const d = parseThreadDesignation(text);
      assert.equal(typeof d !== 'string' && d.internal, null, text);
    }
  });
  it('reads an all-capital class only one kind has in ISO 965-1 as that kind', () => {
    // The seed paper's M50X3-4H5H: no external crest grade 5 (Td grades 4, 6, 8).
    const paper = parseThreadDesignation('M50X3-4H5H');
    assert.equal(typeof paper !== 'string' && paper.internal, true);
    assert.equal(typeof paper !== 'string' && paper.classes, undefined);
    const seven = parseThreadDesignation('M20X1.5-7H'); // no Td grade 7
    assert.equal(typeof seven !== 'string' && seven.internal, true);
    const three = parseThreadDesignation('M20X1.5-3G4G'); // no TD2 grade 3
    assert.equal(typeof three !== 'string' && three.internal, false);
    assert.match(validateThreadDesignation('M50X3-9H') ?? '', /No thread has the class 9H/);
  });
  it('asks the kind in the words of the designation', () => {
    const capitals = parseThreadDesignation('M50X3-5G6G');
    assert.ok(typeof capitals !== 'string');
    assert.equal(
      sideQuestion(capitals),
      'M50X3-5G6G: the class 5G6G fits an external (5g6g) or an internal (5G6G) thread: which is it?',
    );
    const bare = parseThreadDesignation('M50x3');
    assert.ok(typeof bare !== 'string');
    assert.equal(sideQuestion(bare), 'M50x3 has no tolerance class: is it an external or an internal thread (6g or 6H)?');
  });
  it('accepts the other forms the server reads', () => {
    for (const good of ['M16x1.5-6g-LH', 'M16x1.5-6H-L-LH', 'M20x1.5LH-6H', 'M20x2-7g6g-L', 'M50*3-6g', 'M10,5x1-6h', 'M10-6g']) {
      assert.equal(validateThreadDesignation(good), undefined, good);
    }
  });
  it('rejects bad designations', () => {
    for (const bad of ['', '50x3', 'M50x', 'M50x3-6', 'M50x3-5g6H', 'M50x3-6k', 'M50x3-6E', 'M50X3-6K', 'M3x3-6g', 'Tr40x7-7e', 'M50x3--6g', 'M50x3-6g-6g', 'M50x3-5g6h', 'M50X3-5G6H']) {
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

describe('parseTaper', () => {
  it('reads ratios and changes per mm', () => {
    assert.equal(parseTaper(''), 0);
    assert.equal(parseTaper('0'), 0);
    assert.equal(parseTaper('1:16'), 0.0625);
    assert.equal(parseTaper(' 1 : 16 '), 0.0625);
    assert.equal(parseTaper('-1:32'), -0.03125);
    assert.equal(parseTaper('0,0625'), 0.0625);
  });
  it('rejects others, and cones steeper than 1:2', () => {
    for (const bad of ['1:x', 'steep', '0.6', '1:1', '1:0']) {
      assert.equal(typeof validateTaper(bad), 'string', bad);
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
