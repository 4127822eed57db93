// The boxes of "Insert Symmetric Thread Module...", "Insert Arc Thread Program..." and "Insert
// Drum Groove Program...": what each asks and the generator's parameters its answer gives. The
// server reads and checks every answer (fanuc-macro.readDesignation, .checkParameters), gives
// the boxes' defaults (.parameterDefaults) and writes the program. Pure: no `vscode` import,
// the UI strings go through the translator given.
import { english, type Translate } from './serverStatus';

export const SERVER_COMMAND_THREAD_MODULE = 'fanuc-macro.threadModule';
export const SERVER_COMMAND_ARC_THREAD = 'fanuc-macro.arcThread';
export const SERVER_COMMAND_DRUM_GROOVE = 'fanuc-macro.drumGroove';
export const SERVER_COMMAND_READ_DESIGNATION = 'fanuc-macro.readDesignation';
export const SERVER_COMMAND_CHECK = 'fanuc-macro.checkParameters';
export const SERVER_COMMAND_DEFAULTS = 'fanuc-macro.parameterDefaults';

/** An input box: the parameters its answer gives (several: as many numbers apart by commas). */
export interface Box {
  readonly names: readonly string[];
  readonly prompt: string;
  readonly placeHolder?: string;
}

export interface GeneratorForm {
  /** The generator's name in the server's checkParameters and parameterDefaults. */
  readonly generator: 'arcThread' | 'drumGroove';
  /** The input boxes' title, before "(1/5)". */
  readonly title: string;
  readonly command: string;
  readonly boxes: readonly Box[];
}

/** An answer as the server's checkParameters reads it. */
export interface Answer {
  readonly names: readonly string[];
  readonly value: unknown;
}

/** Seed 002's arc thread: 5 boxes for the 9 values of the part; the rest as the paper. */
export function arcThreadForm(t: Translate = english): GeneratorForm {
  return {
    generator: 'arcThread',
    title: t('Arc Thread Program'),
    command: SERVER_COMMAND_ARC_THREAD,
    boxes: [
      {
        names: ['outer_diameter', 'groove_radius', 'tool_radius'],
        prompt: t('Thread outer diameter, groove radius R and tool nose radius r in mm'),
      },
      { names: ['pitch', 'length'], prompt: t('Pitch (lead) and length of the thread in mm') },
      { names: ['layers'], prompt: t('Roughing layers: the groove-centre diameter of each layer in mm') },
      { names: ['cuts_per_layer'], prompt: t('Cuts per roughing layer') },
      {
        names: ['finishing_diameter', 'finishing_cuts'],
        prompt: t('Finishing: the groove-centre diameter in mm and the number of cuts'),
      },
    ],
  };
}

/** Seed 003's drum groove: the profile, the pitch (which the paper does not give), the layers. */
export function drumGrooveForm(t: Translate = english): GeneratorForm {
  return {
    generator: 'drumGroove',
    title: t('Drum Groove Program'),
    command: SERVER_COMMAND_DRUM_GROOVE,
    boxes: [
      {
        names: ['points'],
        prompt: t('Profile points X,Z (X a diameter) apart by semicolons, from the start of the groove; the default is the paper\'s drum'),
        placeHolder: '298.91,205; 302.104,173; 304.83,140',
      },
      {
        names: ['pitch'],
        prompt: t('Pitch (lead) of the groove in mm: the paper\'s is lost (its figure 2), so it has no default'),
        placeHolder: t('required, for example 40'),
      },
      { names: ['layers', 'radial_step'], prompt: t('Number of layers and radial step per layer in mm (on the radius)') },
      { names: ['cuts_per_layer', 'axial_step'], prompt: t('Cuts per layer and axial step per cut in mm') },
    ],
  };
}

/** A box's text from the server's defaults: `93.82, 10, 1.2`; '' where there is none. */
export function boxValue(box: Box, defaults: Readonly<Record<string, string>>): string {
  const known = box.names.map((name) => defaults[name]).filter((v): v is string => v !== undefined);
  return known.length === box.names.length ? known.join(', ') : '';
}

export const isRecord = (value: unknown): value is Record<string, unknown> =>
  typeof value === 'object' && value !== null && !Array.isArray(value);

/** The server's `{ error }` answer, or `error` when the answer is not an object. */
export function refusal(answer: unknown, error: string): string | undefined {
  if (!isRecord(answer)) return error;
  return typeof answer['error'] === 'string' && answer['error'] !== '' ? answer['error'] : undefined;
}

/** A checkParameters answer: the parameters read (with the generator's warning), or its refusal. */
export function checked(answer: unknown): { parameters: Record<string, unknown>; warning?: string } | { error: string } {
  const error = refusal(answer, 'the language server did not check the answers');
  if (error !== undefined) return { error };
  const { parameters, warning } = answer as Record<string, unknown>;
  if (!isRecord(parameters)) return { error: 'the language server did not check the answers' };
  return typeof warning === 'string' ? { parameters, warning } : { parameters };
}

/** A readDesignation answer, or its refusal. */
export interface DesignationReading {
  readonly text: string;
  readonly side: 'external' | 'internal' | 'undecided';
  readonly starts: number;
  readonly leftHand: boolean;
  /** When `side` is undecided: which is it? */
  readonly question?: string;
}

export function designationReading(answer: unknown): DesignationReading | { error: string } {
  const error = refusal(answer, 'the language server did not read the designation');
  if (error !== undefined) return { error };
  const reading = answer as Partial<DesignationReading>;
  if (typeof reading.text !== 'string' || typeof reading.side !== 'string') {
    return { error: 'the language server did not read the designation' };
  }
  return reading as DesignationReading;
}

/** The arguments of fanuc-macro.threadModule: the paper's infeed and no taper left out. */
export function threadModuleArgs(parameters: Record<string, unknown>): Record<string, unknown> {
  const { infeed, taper, ...rest } = parameters;
  return { ...rest, ...(infeed === 'symmetric' ? {} : { infeed }), ...(taper === 0 ? {} : { taper }) };
}

const count = (value: unknown): number | undefined => (typeof value === 'number' && Number.isFinite(value) ? value : undefined);

/** What the inserted program does, from the run the server made of it (undefined: not said). */
export function summaryText(command: string, summary: unknown, t: Translate = english): string | undefined {
  if (!isRecord(summary)) return undefined;
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
