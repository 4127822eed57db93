import assert from 'node:assert/strict';
import { describe, it } from 'node:test';
import {
  DRUM_PROFILE,
  SERVER_COMMAND_ARC_THREAD,
  SERVER_COMMAND_DRUM_GROOVE,
  arcThreadForm,
  defaultAnswers,
  drumGrooveForm,
  generatedProgram,
  pointsText,
  readAnswers,
  readNumber,
  readNumbers,
  readPoints,
  summaryText,
  validateAnswer,
} from '../src/generatorParameters';

/** The answers of the form's boxes: the defaults, with some replaced by index. */
function answersWith(form: ReturnType<typeof arcThreadForm>, changes: Record<number, string>): string[] {
  return defaultAnswers(form).map((value, i) => changes[i] ?? value);
}

describe('readNumber and readNumbers', () => {
  it('reads decimals with a point', () => {
    assert.equal(readNumber(' 93.82 '), 93.82);
    assert.equal(readNumber('.5'), 0.5);
    assert.equal(readNumber('-3'), -3);
    assert.equal(readNumber('10.'), 10);
  });
  it('refuses a decimal comma or a word, quoting it', () => {
    assert.equal(readNumber('1,2'), '"1,2" is not a number (write decimals with a point, as 1.2).');
    assert.match(String(readNumber('abc')), /^"abc" is not a number/);
    assert.match(String(readNumber('1e3')), /is not a number/);
  });
  it('reads lists apart by commas or spaces, of a given count', () => {
    assert.deepEqual(readNumbers('93.82, 10,1.2', 3, '1, 2, 3'), [93.82, 10, 1.2]);
    assert.deepEqual(readNumbers('108 103 99', undefined, '108, 103'), [108, 103, 99]);
    assert.equal(readNumbers('25', 2, '25, 113'), 'Enter 2 numbers apart by commas, as 25, 113.');
    assert.equal(readNumbers(' ', undefined, '108, 103'), 'Enter one or more numbers apart by commas, as 108, 103.');
    assert.match(String(readNumbers('25, x', 2, '25, 113')), /^"x" is not a number/);
  });
});

describe('readPoints', () => {
  it("reads the paper's profile from its own text", () => {
    assert.equal(DRUM_PROFILE.length, 12);
    assert.ok(pointsText(DRUM_PROFILE).startsWith('298.91,205; 302.104,173; '));
    assert.deepEqual(readPoints(pointsText(DRUM_PROFILE)), DRUM_PROFILE);
  });
  it('takes new lines between points and spaces in a point', () => {
    assert.deepEqual(readPoints('300 10\n310,0\n\n300, -10;'), [
      [300, 10],
      [310, 0],
      [300, -10],
    ]);
  });
  it('says which point is wrong', () => {
    assert.equal(readPoints('300,10; 310'), 'Point 2 "310" is not X,Z.');
    assert.equal(readPoints('300,10'), 'Give 2 to 19 points X,Z apart by semicolons; there are 1.');
    assert.equal(readPoints('300,10; 310,0; 305,5'), 'Z must change in one direction along the profile (points 2 and 3).');
    assert.equal(readPoints('300,10; 310,10'), 'Z must change in one direction along the profile (points 1 and 2).');
    assert.equal(readPoints('-300,10; 310,0'), '-300 is not greater than zero.');
    const twenty = Array.from({ length: 20 }, (_, i) => `300,${-i}`).join(';');
    assert.match(String(readPoints(twenty)), /there are 20/);
  });
});

describe('arcThreadForm', () => {
  const form = arcThreadForm();
  it("opens every box on the paper's part and reads it into the generator's keywords", () => {
    assert.equal(form.command, SERVER_COMMAND_ARC_THREAD);
    assert.equal(form.title, 'Arc Thread Program');
    assert.deepEqual(readAnswers(form, defaultAnswers(form)), {
      outer_diameter: 93.82,
      groove_radius: 10,
      tool_radius: 1.2,
      pitch: 25,
      length: 113,
      layers: [108, 103],
      cuts_per_layer: 7,
      finishing_diameter: 100,
      finishing_cuts: 19,
    });
  });
  it('reads an override', () => {
    const read = readAnswers(form, answersWith(form, { 2: '108, 103, 99', 3: '5' }));
    assert.ok(typeof read !== 'string');
    assert.deepEqual(read['layers'], [108, 103, 99]);
    assert.equal(read['cuts_per_layer'], 5);
  });
  it('checks each box as it is typed', () => {
    const [groove, lengths, layers, cuts, finishing] = form.prompts;
    assert.ok(groove && lengths && layers && cuts && finishing);
    assert.equal(validateAnswer(groove, '93.82, 10, 1.2', {}), undefined);
    assert.equal(validateAnswer(groove, '93.82, 10, 10', {}), 'The tool nose radius r 10 must be smaller than the groove radius R 10.');
    assert.equal(validateAnswer(groove, '93.82, 0, 1.2', {}), '0 is not greater than zero.');
    assert.equal(validateAnswer(lengths, '25', {}), 'Enter 2 numbers apart by commas, as 25, 113.');
    assert.equal(validateAnswer(layers, '108, -1', {}), '-1 is not greater than zero.');
    assert.equal(validateAnswer(cuts, '7.5', {}), '7.5 is not a whole number.');
    assert.equal(validateAnswer(cuts, '0', {}), '0 is outside 1-999.');
    assert.equal(validateAnswer(finishing, '100, 1', {}), '1 is outside 2-999.');
  });
  it('gives the first fault of the answers', () => {
    assert.equal(readAnswers(form, answersWith(form, { 1: '25, abc' })), '"abc" is not a number (write decimals with a point, as 1.2).');
  });
});

describe('drumGrooveForm', () => {
  const form = drumGrooveForm();
  it('has no pitch by default: the paper does not give it', () => {
    assert.equal(form.command, SERVER_COMMAND_DRUM_GROOVE);
    assert.deepEqual(defaultAnswers(form), [pointsText(DRUM_PROFILE), '', '9, 0.8', '1, 0.5']);
    assert.equal(readAnswers(form, defaultAnswers(form)), 'Enter the pitch in mm: it has no default.');
    const pitch = form.prompts[1];
    assert.ok(pitch);
    assert.match(pitch.prompt, /lost/);
  });
  it('reads the defaults with a pitch', () => {
    assert.deepEqual(readAnswers(form, answersWith(form, { 1: '40' })), {
      points: DRUM_PROFILE,
      pitch: 40,
      layers: 9,
      radial_step: 0.8,
      cuts_per_layer: 1,
      axial_step: 0.5,
    });
  });
  it('checks the depth against the profile given before', () => {
    const depth = form.prompts[2];
    assert.ok(depth);
    assert.equal(validateAnswer(depth, '9, 0.8', {}), undefined);
    assert.equal(
      validateAnswer(depth, '10, 2', { points: [[30, 10], [40, 0]] }),
      '20 mm deep is more than the radius of the smallest profile diameter 30.',
    );
    assert.equal(validateAnswer(depth, '9.5, 0.8', {}), '9.5 is not a whole number.');
    const cuts = form.prompts[3];
    assert.ok(cuts);
    assert.equal(validateAnswer(cuts, '2, -0.5', {}), '-0.5 is negative.');
    assert.equal(validateAnswer(cuts, '3, 0', {}), undefined);
  });
});

describe('generatedProgram and summaryText', () => {
  it('tells a program from an error or a malformed answer', () => {
    assert.deepEqual(generatedProgram({ text: '%\n', summary: { g32_cuts: 33 } }), { text: '%\n', summary: { g32_cuts: 33 } });
    assert.deepEqual(generatedProgram({ text: '%\n' }), { text: '%\n', summary: {} });
    assert.deepEqual(generatedProgram({ error: 'pitch is missing' }), { error: 'pitch is missing' });
    assert.ok('error' in generatedProgram(null));
    assert.ok('error' in generatedProgram({ text: '' }));
    assert.ok('error' in generatedProgram([]));
  });
  it('says what the run of the program cut', () => {
    assert.equal(
      summaryText(SERVER_COMMAND_ARC_THREAD, { layer_cuts: [7, 7], finishing_cuts: 19, g32_cuts: 33 }),
      '33 G32 cuts: 7, 7 per roughing layer, 19 finishing.',
    );
    assert.equal(
      summaryText(SERVER_COMMAND_DRUM_GROOVE, { passes: 9, segments_per_pass: 11, g32_cuts: 108 }),
      '108 G32 cuts: 9 passes of 11 taper segments and a run-in.',
    );
    assert.equal(summaryText(SERVER_COMMAND_DRUM_GROOVE, { passes: 9 }), undefined);
    assert.equal(summaryText(SERVER_COMMAND_ARC_THREAD, { g32_cuts: 33 }), undefined);
  });
});
