// The prompts of "Insert Arc Thread Program..." and "Insert Drum Groove Program...": what each
// input box asks, its default (the seed papers' part), how its answer is read and checked, and
// the server's answer. Pure logic, no `vscode` import: the UI strings go through the translator
// given (vscode.l10n.t in the extension), so it is unit-tested with node:test. The server
// (ide/generator_requests.py and the generators) has the last word on what can be cut.
import { english, type Translate } from './serverStatus';

/** Server-side commands (workspace/executeCommand). */
export const SERVER_COMMAND_ARC_THREAD = 'fanuc-macro.arcThread';
export const SERVER_COMMAND_DRUM_GROOVE = 'fanuc-macro.drumGroove';

export type Point = readonly [x: number, z: number];

/** The parameters sent to the server: the generators' keyword names. */
export type GeneratorParameters = Readonly<Record<string, number | readonly number[] | readonly Point[]>>;

export interface ParameterPrompt {
  /** What the input box asks. */
  readonly prompt: string;
  /** The text the box opens with: the paper's value ('' where the paper has none). */
  readonly value: string;
  readonly placeHolder: string;
  /** The answer read into parameters, given those of the earlier boxes; or what is wrong. */
  read(input: string, before: GeneratorParameters): GeneratorParameters | string;
}

export interface GeneratorForm {
  /** The input boxes' title, before "(1/5)". */
  readonly title: string;
  readonly command: string;
  readonly prompts: readonly ParameterPrompt[];
}

/** Seed 003's drum profile (X diameter, Z), as the server's DRUM_PROFILE. */
export const DRUM_PROFILE: readonly Point[] = [
  [298.91, 205],
  [302.104, 173],
  [304.83, 140],
  [307.092, 105],
  [308.708, 70],
  [309.677, 35],
  [310, 0],
  [309.677, -35],
  [308.708, -70],
  [307.092, -105],
  [304.83, -140],
  [303.246, -160],
];

/** The most profile points the drum macro holds (#111-#129). */
export const MAX_DRUM_POINTS = 19;

export function pointsText(points: readonly Point[]): string {
  return points.map(([x, z]) => `${x},${z}`).join('; ');
}

const NUMBER = /^[+-]?(?:\d+(?:\.\d*)?|\.\d+)$/;

/** A decimal number as typed (a point, not a comma, before the decimals), or what is wrong. */
export function readNumber(word: string, t: Translate = english): number | string {
  const text = word.trim();
  if (!NUMBER.test(text)) return t('"{0}" is not a number (write decimals with a point, as 1.2).', text);
  return Number(text);
}

function positive(value: number, t: Translate): string | undefined {
  return value > 0 ? undefined : t('{0} is not greater than zero.', value);
}

function whole(value: number, low: number, high: number, t: Translate): string | undefined {
  if (!Number.isInteger(value)) return t('{0} is not a whole number.', value);
  return value >= low && value <= high ? undefined : t('{0} is outside {1}-{2}.', value, low, high);
}

/**
 * The numbers of an answer such as `93.82, 10, 1.2` (commas or spaces between): exactly
 * `count` of them, or one or more when `count` is undefined.
 */
export function readNumbers(input: string, count: number | undefined, example: string, t: Translate = english): number[] | string {
  const words = input.split(/[,\s]+/).filter((w) => w !== '');
  if (count === undefined ? words.length === 0 : words.length !== count) {
    return count === undefined
      ? t('Enter one or more numbers apart by commas, as {0}.', example)
      : t('Enter {0} numbers apart by commas, as {1}.', count, example);
  }
  const values: number[] = [];
  for (const word of words) {
    const value = readNumber(word, t);
    if (typeof value === 'string') return value;
    values.push(value);
  }
  return values;
}

/** Profile points `X,Z; X,Z; ...` (`;` or new lines between points), Z in one direction. */
export function readPoints(input: string, t: Translate = english): Point[] | string {
  const items = input
    .split(/[;\n]+/)
    .map((s) => s.trim())
    .filter((s) => s !== '');
  if (items.length < 2 || items.length > MAX_DRUM_POINTS) {
    return t('Give 2 to {0} points X,Z apart by semicolons; there are {1}.', MAX_DRUM_POINTS, items.length);
  }
  const points: Point[] = [];
  for (const [i, item] of items.entries()) {
    const pair = item.split(/[,\s]+/).filter((w) => w !== '');
    if (pair.length !== 2) return t('Point {0} "{1}" is not X,Z.', i + 1, item);
    const x = readNumber(pair[0] ?? '', t);
    if (typeof x === 'string') return x;
    const z = readNumber(pair[1] ?? '', t);
    if (typeof z === 'string') return z;
    const wrong = positive(x, t);
    if (wrong !== undefined) return wrong;
    points.push([x, z]);
  }
  // The macro cuts from point to point along Z: Z must not turn back or stand still.
  const sense = Math.sign((points[0]?.[1] ?? 0) - (points[1]?.[1] ?? 0));
  for (let i = 1; i < points.length; i++) {
    const dz = (points[i - 1]?.[1] ?? 0) - (points[i]?.[1] ?? 0);
    if (dz === 0 || Math.sign(dz) !== sense) {
      return t('Z must change in one direction along the profile (points {0} and {1}).', i, i + 1);
    }
  }
  return points;
}

/** A box of `count` numbers, each checked by `check` (undefined: fine). */
function numbersPrompt(
  t: Translate,
  prompt: string,
  value: string,
  names: readonly string[],
  check: (values: readonly number[], before: GeneratorParameters) => string | undefined,
): ParameterPrompt {
  return {
    prompt,
    value,
    placeHolder: value,
    read(input, before) {
      const values = readNumbers(input, names.length, value, t);
      if (typeof values === 'string') return values;
      const wrong = check(values, before);
      if (wrong !== undefined) return wrong;
      return Object.fromEntries(names.map((name, i) => [name, values[i] ?? 0]));
    },
  };
}

const firstOf = (...messages: Array<string | undefined>): string | undefined => messages.find((m) => m !== undefined);

/** Seed 002's arc thread: 5 boxes for the 9 values of the part; the rest as the paper. */
export function arcThreadForm(t: Translate = english): GeneratorForm {
  return {
    title: t('Arc Thread Program'),
    command: SERVER_COMMAND_ARC_THREAD,
    prompts: [
      numbersPrompt(
        t,
        t('Thread outer diameter, groove radius R and tool nose radius r in mm'),
        '93.82, 10, 1.2',
        ['outer_diameter', 'groove_radius', 'tool_radius'],
        ([od = 0, big = 0, small = 0]) =>
          firstOf(positive(od, t), positive(big, t), positive(small, t)) ??
          (small < big ? undefined : t('The tool nose radius r {0} must be smaller than the groove radius R {1}.', small, big)),
      ),
      numbersPrompt(t, t('Pitch (lead) and length of the thread in mm'), '25, 113', ['pitch', 'length'], (values) =>
        firstOf(...values.map((v) => positive(v, t))),
      ),
      {
        prompt: t('Roughing layers: the groove-centre diameter of each layer in mm'),
        value: '108, 103',
        placeHolder: '108, 103',
        read(input) {
          const values = readNumbers(input, undefined, '108, 103', t);
          if (typeof values === 'string') return values;
          return firstOf(...values.map((v) => positive(v, t))) ?? { layers: values };
        },
      },
      numbersPrompt(t, t('Cuts per roughing layer'), '7', ['cuts_per_layer'], ([cuts = 0]) => whole(cuts, 1, 999, t)),
      numbersPrompt(
        t,
        t('Finishing: the groove-centre diameter in mm and the number of cuts'),
        '100, 19',
        ['finishing_diameter', 'finishing_cuts'],
        ([diameter = 0, cuts = 0]) => firstOf(positive(diameter, t), whole(cuts, 2, 999, t)),
      ),
    ],
  };
}

/** Seed 003's drum groove: the profile, the pitch (which the paper does not give), the layers. */
export function drumGrooveForm(t: Translate = english): GeneratorForm {
  return {
    title: t('Drum Groove Program'),
    command: SERVER_COMMAND_DRUM_GROOVE,
    prompts: [
      {
        prompt: t('Profile points X,Z (X a diameter) apart by semicolons, from the start of the groove; the default is the paper\'s drum'),
        value: pointsText(DRUM_PROFILE),
        placeHolder: '298.91,205; 302.104,173; 304.83,140',
        read(input) {
          const points = readPoints(input, t);
          return typeof points === 'string' ? points : { points };
        },
      },
      {
        prompt: t('Pitch (lead) of the groove in mm: the paper\'s is lost (its figure 2), so it has no default'),
        value: '',
        placeHolder: t('required, for example 40'),
        read(input) {
          if (input.trim() === '') return t('Enter the pitch in mm: it has no default.');
          const pitch = readNumber(input, t);
          if (typeof pitch === 'string') return pitch;
          return positive(pitch, t) ?? { pitch };
        },
      },
      numbersPrompt(
        t,
        t('Number of layers and radial step per layer in mm (on the radius)'),
        '9, 0.8',
        ['layers', 'radial_step'],
        ([layers = 0, step = 0], before) => {
          const wrong = firstOf(whole(layers, 1, 999, t), positive(step, t));
          if (wrong !== undefined) return wrong;
          const points = before['points'] as readonly Point[] | undefined;
          const smallest = Math.min(...(points ?? DRUM_PROFILE).map(([x]) => x));
          const depth = Number((layers * step).toFixed(6));
          return 2 * depth < smallest
            ? undefined
            : t('{0} mm deep is more than the radius of the smallest profile diameter {1}.', depth, smallest);
        },
      ),
      numbersPrompt(
        t,
        t('Cuts per layer and axial step per cut in mm'),
        '1, 0.5',
        ['cuts_per_layer', 'axial_step'],
        ([cuts = 0, step = 0]) => firstOf(whole(cuts, 1, 999, t), step >= 0 ? undefined : t('{0} is negative.', step)),
      ),
    ],
  };
}

/** For `showInputBox.validateInput`: undefined when the answer reads, else the message. */
export function validateAnswer(prompt: ParameterPrompt, input: string, before: GeneratorParameters): string | undefined {
  const read = prompt.read(input, before);
  return typeof read === 'string' ? read : undefined;
}

/** Every box's answer read in turn into the server command's parameters, or the first fault. */
export function readAnswers(form: GeneratorForm, answers: readonly string[]): GeneratorParameters | string {
  let parameters: GeneratorParameters = {};
  for (const [i, prompt] of form.prompts.entries()) {
    const read = prompt.read(answers[i] ?? '', parameters);
    if (typeof read === 'string') return read;
    parameters = { ...parameters, ...read };
  }
  return parameters;
}

/** The answers the boxes open with: the paper's part. */
export function defaultAnswers(form: GeneratorForm): string[] {
  return form.prompts.map((p) => p.value);
}

export interface GeneratedProgram {
  readonly text: string;
  readonly summary: Readonly<Record<string, unknown>>;
}

/** Validates the untyped answer `{ text, summary }` / `{ error }` of the server command. */
export function generatedProgram(value: unknown): GeneratedProgram | { error: string } {
  if (typeof value !== 'object' || value === null || Array.isArray(value)) {
    return { error: 'the language server returned no program' };
  }
  const record = value as Record<string, unknown>;
  const error = record['error'];
  if (typeof error === 'string' && error !== '') return { error };
  const text = record['text'];
  if (typeof text !== 'string' || text === '') {
    return { error: 'the language server returned a program without text' };
  }
  const summary = record['summary'];
  const known = typeof summary === 'object' && summary !== null && !Array.isArray(summary);
  return { text, summary: known ? (summary as Record<string, unknown>) : {} };
}

const count = (value: unknown): number | undefined => (typeof value === 'number' && Number.isFinite(value) ? value : undefined);

/** What the inserted program does, from the run the server made of it (undefined: not said). */
export function summaryText(command: string, summary: Readonly<Record<string, unknown>>, t: Translate = english): string | undefined {
  const g32 = count(summary['g32_cuts']);
  if (g32 === undefined) return undefined;
  if (command === SERVER_COMMAND_ARC_THREAD) {
    const layers = summary['layer_cuts'];
    const finishing = count(summary['finishing_cuts']);
    if (!Array.isArray(layers) || finishing === undefined) return undefined;
    return t('{0} G32 cuts: {1} per roughing layer, {2} finishing.', g32, layers.join(', '), finishing);
  }
  const passes = count(summary['passes']);
  const segments = count(summary['segments_per_pass']);
  if (passes === undefined || segments === undefined) return undefined;
  return t('{0} G32 cuts: {1} passes of {2} taper segments and a run-in.', g32, passes, segments);
}
