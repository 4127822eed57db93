// The steps of "Insert Symmetric Thread Module...", "Insert Arc Thread Program..." and "Insert
// Drum Groove Program...": what each box asks and the generator's parameters its answer gives.
// The server reads and checks every answer (fanuc-macro.readDesignation, .checkParameters),
// gives the boxes' defaults (.parameterDefaults) and writes the program. Every box opens on its
// default, a text Enter accepts; a placeholder says what an empty box means. Pure: the UI
// strings go through the translator given.
import { english, type Translate } from './serverStatus';

export const SERVER_COMMAND_THREAD_MODULE = 'fanuc-macro.threadModule';
export const SERVER_COMMAND_ARC_THREAD = 'fanuc-macro.arcThread';

/** An input box, or a quick pick when it has `picks`; its answer gives the parameters `names`. */
export interface Step {
  readonly names: readonly string[];
  readonly prompt: string;
  /** What an empty box means, where it is not the default the box opens on. */
  readonly placeHolder?: string;
  readonly picks?: ReadonlyArray<{ readonly label: string; readonly description: string; readonly value: unknown }>;
}

export interface GeneratorForm {
  /** The generator's name in the server's checkParameters and parameterDefaults. */
  readonly generator: 'threadModule' | 'arcThread' | 'drumGroove';
  /** The boxes' title, before "(1/5)". */
  readonly title: string;
  readonly command: string;
  readonly steps: readonly Step[];
  /** The thread module's designation: its boxes' defaults follow it (the length). */
  readonly designation?: string;
}

/** An answer as the server's checkParameters reads it. */
export interface Answer {
  readonly names: readonly string[];
  readonly value: unknown;
}

const box = (names: string[], prompt: string, placeHolder?: string): Step => (placeHolder === undefined ? { names, prompt } : { names, prompt, placeHolder });

/** Seed 002's arc thread: 5 boxes for the 9 values of the part; the rest as the paper. */
export function arcThreadForm(t: Translate = english): GeneratorForm {
  return {
    generator: 'arcThread',
    title: t('Arc Thread Program'),
    command: SERVER_COMMAND_ARC_THREAD,
    steps: [
      box(['outer_diameter', 'groove_radius', 'tool_radius'], t('Thread outer diameter, groove radius R and tool nose radius r in mm')),
      box(['pitch', 'length'], t('Pitch (lead) and length of the thread in mm')),
      box(['layers'], t('Roughing layers: the groove-centre diameter of each layer in mm')),
      box(['cuts_per_layer'], t('Cuts per roughing layer')),
      box(['finishing_diameter', 'finishing_cuts'], t('Finishing: the groove-centre diameter in mm and the number of cuts')),
    ],
  };
}

/** Seed 003's drum groove: the profile, the pitch (which the paper does not give), the layers. */
export function drumGrooveForm(t: Translate = english): GeneratorForm {
  return {
    generator: 'drumGroove',
    title: t('Drum Groove Program'),
    command: 'fanuc-macro.drumGroove',
    steps: [
      box(['points'], t('Profile points X,Z (X a diameter) apart by semicolons, from the start of the groove; the default is the paper\'s drum')),
      box(['pitch'], t('Pitch (lead) of the groove in mm: the paper\'s is lost (its figure 2), so it has no default'), t('required: no default')),
      box(['layers', 'radial_step'], t('Number of layers and radial step per layer in mm (on the radius)')),
      box(['cuts_per_layer', 'axial_step'], t('Cuts per layer and axial step per cut in mm')),
    ],
  };
}

/** A designation as the server read it (fanuc-macro.readDesignation). */
export interface DesignationReading {
  readonly text: string;
  readonly side: 'external' | 'internal' | 'undecided';
  readonly starts: number;
  readonly leftHand: boolean;
  /** When `side` is undecided: which is it? */
  readonly question?: string;
}

/** The thread module's steps after its designation: the kind only when the designation does not say it. */
export function threadModuleForm(designation: DesignationReading, t: Translate = english): GeneratorForm {
  const kind = [designation.starts > 1 ? t('{0} starts', designation.starts) : '', designation.leftHand ? t('left hand') : ''].filter((k) => k !== '');
  const side: Step = {
    names: ['internal'],
    prompt: designation.question ?? '',
    picks: [
      { label: t('External thread'), description: t('bolt, turned on the outside'), value: false },
      { label: t('Internal thread'), description: t('nut, bored on the inside'), value: true },
    ],
  };
  const steps: Step[] = [
    box(['length'], t('Thread length of {0} in mm', designation.text)),
    ...(designation.side === 'undecided' ? [side] : []),
    {
      names: ['infeed'],
      prompt: kind.length > 0
        ? t('How the rough passes of {0} ({1}) go down', designation.text, kind.join(', '))
        : t('How the rough passes of {0} go down', designation.text),
      picks: [
        { label: t('Symmetric'), description: t('both flanks every pass, the paper\'s'), value: 'symmetric' },
        { label: t('Alternate flanks'), description: t('left one pass, right the next'), value: 'alternate' },
        { label: t('Left flank'), description: t('every pass on the -Z flank, as G76'), value: 'left' },
        { label: t('Right flank'), description: t('every pass on the +Z flank'), value: 'right' },
      ],
    },
    box(['taper'], t('Taper as 1:16, or the diameter change per mm; empty for a parallel thread'), t('parallel')),
  ];
  return { generator: 'threadModule', title: t('Symmetric Thread Module'), command: SERVER_COMMAND_THREAD_MODULE, steps, designation: designation.text };
}

/** A box's text from the server's defaults: `93.82, 10, 1.2`; '' where there is none. */
export function boxValue(step: Step, defaults: Readonly<Record<string, string>>): string {
  const known = step.names.map((name) => defaults[name]).filter((v): v is string => v !== undefined);
  return known.length === step.names.length ? known.join(', ') : '';
}

export const isRecord = (value: unknown): value is Record<string, unknown> =>
  typeof value === 'object' && value !== null && !Array.isArray(value);

/** The server's answer, or its `{ error }` (`none` when the answer lacks the field `needed`). */
export function answerOf(answer: unknown, needed: string, none: string): Record<string, unknown> | { error: string } {
  if (isRecord(answer) && typeof answer['error'] === 'string' && answer['error'] !== '') return { error: answer['error'] };
  return isRecord(answer) && answer[needed] !== undefined ? answer : { error: none };
}

/** The arguments of fanuc-macro.threadModule: the paper's infeed and no taper left out; `uri`,
 * the document it goes into, whose program numbers it must not take. */
export function threadModuleArgs(parameters: Record<string, unknown>, uri?: string): Record<string, unknown> {
  const { infeed, taper, ...rest } = parameters;
  return { ...rest, ...(infeed === 'symmetric' ? {} : { infeed }), ...(taper === 0 ? {} : { taper }), ...(uri === undefined ? {} : { uri }) };
}

/** The arguments of fanuc-macro.parameterDefaults for a form. */
export const defaultsArgs = (form: GeneratorForm): unknown[] => (form.designation === undefined ? [form.generator] : [form.generator, form.designation]);

/** What the inserted program does, from the run the server made of it (undefined: not said). */
export function summaryText(command: string, summary: unknown, t: Translate = english): string | undefined {
  const s = isRecord(summary) ? summary : {};
  const [g32, layers, finishing, passes, segments] = ['g32_cuts', 'layer_cuts', 'finishing_cuts', 'passes', 'segments_per_pass'].map((k) => s[k]);
  if (typeof g32 !== 'number') return undefined;
  if (command === SERVER_COMMAND_ARC_THREAD) {
    if (!Array.isArray(layers) || typeof finishing !== 'number') return undefined;
    return t('{0} G32 cuts: {1} per roughing layer, {2} finishing.', g32, layers.join(', '), finishing);
  }
  if (typeof passes !== 'number' || typeof segments !== 'number') return undefined;
  return t('{0} G32 cuts: {1} passes of {2} taper segments and a run-in.', g32, passes, segments);
}
