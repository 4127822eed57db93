// Validation of ISO metric thread designations such as `M50x3-5g6g` for the
// "Insert Symmetric Thread Module..." command. It follows the rules of the
// server's parser (server/fanuc_macro/threads/designation.py) closely enough
// to catch typing mistakes early; the server has the last word.
// Pure: unit-tested without VS Code.

export interface ThreadDesignation {
  /** The designation as sent to the server: as typed, without whitespace. */
  readonly text: string;
  /** Nominal diameter in mm. */
  readonly nominal: number;
  /** Pitch in mm, or undefined for a coarse-pitch designation such as `M10-6g`. */
  readonly pitch: number | undefined;
  /** Starts: lead / pitch of a multi-start designation (`M24xPh4P2`), else 1. */
  readonly starts: number;
  /** A left-hand thread (`LH`). */
  readonly leftHand: boolean;
  /** Tolerance class such as `5g6g` or `6H`, if given. */
  readonly tolerance: string | undefined;
  /**
   * true for an internal thread (upper-case tolerance position, `6H`), false
   * for an external one (lower case, `6g`), null when the designation does
   * not say: no tolerance class, or an all-capital string such as
   * `M50X3-5G6G` (as CNC comments write, the case may be lost) whose class
   * both kinds have in ISO 965-1. An all-capital class
   * only one kind has says that kind: `6E` external, `4H5H` internal.
   */
  readonly internal: boolean | null;
  /**
   * When `internal` is null: the class as each kind writes it, in the case of
   * ISO 965-1 (`5g6g` and `5G6G`; `6g` and `6H` when no class is written).
   */
  readonly classes?: { readonly external: string; readonly internal: string };
}

const NUMBER = String.raw`\d+(?:[.,]\d+)?`;
// ISO 965-1 writes a multi-start thread with its lead and pitch: M16xPh3P1.5.
const HEAD = new RegExp(
  String.raw`^M(${NUMBER})(?:[xX×*](?:Ph(${NUMBER})P(${NUMBER})|(${NUMBER})))?(LH|RH)?$`,
  'i',
);
const CLASS = /^([3-9])([A-Za-z])(?:([3-9])([A-Za-z]))?$/;
// ISO 965-1:1998 as GB/T 197-2003 tabulates it (unverified against the ISO text; the server's
// threads/designation.py): positions e, f, g, h external and G, H internal; pitch-diameter
// grades 3-9 external (Td2) and 4-8 internal (TD2); crest grades 4, 6, 8 external (Td) and
// 4-8 internal (TD1).
const EXTERNAL_POSITIONS = 'efgh';
const INTERNAL_POSITIONS = 'GH';
const PITCH_GRADES = { external: [3, 4, 5, 6, 7, 8, 9], internal: [4, 5, 6, 7, 8] };
const CREST_GRADES = { external: [4, 6, 8], internal: [4, 5, 6, 7, 8] };

/** `5g6g` for grades 5, 6 and position g; `6H` when both grades are 6. */
function classText(pitchGrade: number, crestGrade: number, position: string): string {
  return pitchGrade === crestGrade ? `${pitchGrade}${position}` : `${pitchGrade}${position}${crestGrade}${position}`;
}

/**
 * The kinds whose ISO 965-1 tables have an all-capital class (whose case may be lost), or a
 * message when neither has it.
 */
function kindsWithClass(letter: string, pitchGrade: number, crestGrade: number, tolerance: string): boolean[] | string {
  const byPosition = [false, true].filter((internal) =>
    internal ? INTERNAL_POSITIONS.includes(letter) : EXTERNAL_POSITIONS.includes(letter.toLowerCase()),
  );
  if (byPosition.length < 2) return byPosition;
  const byGrades = byPosition.filter((internal) => {
    const kind = internal ? 'internal' : 'external';
    return PITCH_GRADES[kind].includes(pitchGrade) && CREST_GRADES[kind].includes(crestGrade);
  });
  if (byGrades.length === 0) {
    return `No thread has the class ${tolerance} in ISO 965-1: external threads have pitch-diameter grades 3-9 and crest grades 4, 6, 8, internal ones 4-8.`;
  }
  return byGrades;
}

/**
 * The question that asks the kind of a designation that does not say it (`internal` null):
 * for the quick pick that offers "External thread" and "Internal thread".
 */
export function sideQuestion(designation: ThreadDesignation): string {
  const classes = designation.classes;
  if (designation.tolerance === undefined) {
    const kinds = classes === undefined ? '' : ` (${classes.external} or ${classes.internal})`;
    return `${designation.text} has no tolerance class: is it an external or an internal thread${kinds}?`;
  }
  if (classes === undefined) return `Is ${designation.text} an external or an internal thread?`;
  return `${designation.text}: the class ${designation.tolerance} fits an external (${classes.external}) or an internal (${classes.internal}) thread: which is it?`;
}

function toNumber(text: string): number {
  return Number(text.replace(',', '.'));
}

const EXAMPLE = 'write it like M50x3-5g6g (external) or M50x3-6H (internal)';

/**
 * Parses an ISO metric thread designation (`M50x3-5g6g`, `M20x1.5LH-6H`,
 * `M10-6g`, `M50X3-5G6G`), or returns a message that says what is wrong.
 */
export function parseThreadDesignation(input: string): ThreadDesignation | string {
  const text = input.replace(/\s+/g, '');
  if (text === '') {
    return `Enter a metric thread designation: ${EXAMPLE}.`;
  }
  const [head = '', ...tail] = text.split('-');
  const match = HEAD.exec(head);
  if (match === null) {
    return `"${input.trim()}" is not an ISO metric thread designation; ${EXAMPLE}.`;
  }
  const nominal = toNumber(match[1] ?? '');
  const pitchText = match[3] ?? match[4];
  const pitch = pitchText === undefined ? undefined : toNumber(pitchText);
  let starts = 1;
  if (match[2] !== undefined && pitch !== undefined) {
    const ratio = toNumber(match[2]) / pitch;
    starts = Math.round(ratio);
    if (!(pitch > 0) || Math.abs(ratio - starts) > 1e-9 || starts < 1) {
      return `The lead Ph${match[2]} must be a whole number of pitches P${pitchText ?? ''}.`;
    }
    if (starts > 9) {
      return `Ph${match[2]}P${pitchText ?? ''} has ${starts} starts: the module cuts 1 to 9.`;
    }
  }
  let leftHand = (match[5] ?? '').toUpperCase() === 'LH';
  if (!(nominal > 0)) {
    return 'The nominal diameter must be greater than zero.';
  }
  if (pitch !== undefined && !(pitch > 0)) {
    return 'The pitch must be greater than zero.';
  }
  if (pitch !== undefined && pitch >= nominal) {
    return 'The pitch must be smaller than the nominal diameter.';
  }
  let tolerance: string | undefined;
  let classMatch: RegExpExecArray | null = null;
  for (const part of tail) {
    if (/^(LH|RH|S|N|L)$/i.test(part)) {
      leftHand ||= part.toUpperCase() === 'LH';
      continue;
    }
    const m = CLASS.exec(part);
    if (m !== null && tolerance === undefined) {
      tolerance = part;
      classMatch = m;
      continue;
    }
    return part === ''
      ? `"${input.trim()}" has an empty part between dashes; ${EXAMPLE}.`
      : `"${input.trim()}": unexpected part "${part}"; ${EXAMPLE}.`;
  }
  let internal: boolean | null = null;
  let classes: { external: string; internal: string } | undefined;
  if (classMatch === null) {
    // GB/T 197: the medium classes are not written (5H/6h up to 1.4 mm, else 6H/6g).
    classes = nominal <= 1.4 ? { external: '6h', internal: '5H' } : { external: '6g', internal: '6H' };
  } else {
    const letters = [classMatch[2], classMatch[4]].filter((l): l is string => l !== undefined);
    const [first = '', second = first] = letters;
    const onePosition = `The pitch-diameter and crest classes of "${tolerance ?? ''}" must share one tolerance position.`;
    // Case tells internal from external only if the writer could use lower case.
    const caseMeaningful = /[a-z]/.test(text) || text.includes('×');
    if (caseMeaningful) {
      const upper = letters.map((l) => l === l.toUpperCase());
      if (upper.some((u) => u !== upper[0])) {
        return `The tolerance class "${tolerance ?? ''}" mixes an internal (upper-case) and an external (lower-case) position.`;
      }
      internal = upper[0] ?? null;
      const allowed = internal ? INTERNAL_POSITIONS : EXTERNAL_POSITIONS;
      if (!letters.every((l) => allowed.includes(l))) {
        return internal
          ? 'Internal threads use tolerance positions G or H (for example 6H).'
          : 'External threads use tolerance positions e, f, g or h (for example 6g).';
      }
      if (first !== second) return onePosition;
    } else {
      if (!letters.every((l) => 'EFGH'.includes(l))) {
        return 'Tolerance positions are e, f, g, h (external) or G, H (internal), for example 6g or 6H.';
      }
      if (first !== second) return onePosition;
      // All capitals: the case may be lost. A class only one kind has in ISO 965-1 says that
      // kind (E and F are external positions only; 4H5H internal, no external crest grade 5);
      // one both kinds have is asked, never guessed.
      const pitchGrade = Number(classMatch[1]);
      const crestGrade = classMatch[3] === undefined ? pitchGrade : Number(classMatch[3]);
      const kinds = kindsWithClass(first, pitchGrade, crestGrade, tolerance ?? '');
      if (typeof kinds === 'string') return kinds;
      if (kinds.length === 1) {
        internal = kinds[0] ?? null;
      } else {
        classes = {
          external: classText(pitchGrade, crestGrade, first.toLowerCase()),
          internal: classText(pitchGrade, crestGrade, first.toUpperCase()),
        };
      }
    }
  }
  const asked = internal === null && classes !== undefined ? { classes } : {};
  return { text, nominal, pitch, starts, leftHand, tolerance, internal, ...asked };
}

/** For `showInputBox.validateInput`: undefined when valid, else the message. */
export function validateThreadDesignation(input: string): string | undefined {
  const parsed = parseThreadDesignation(input);
  return typeof parsed === 'string' ? parsed : undefined;
}

/** Parses a thread length in mm (a positive number; `,` is accepted as decimal separator). */
export function parseThreadLength(input: string): number | string {
  const text = input.trim().replace(',', '.');
  if (!/^(\d+(\.\d*)?|\.\d+)$/.test(text)) {
    return 'Enter the thread length in mm as a positive number, for example 40 or 32.5.';
  }
  const value = Number(text);
  if (!(value > 0) || !Number.isFinite(value)) {
    return 'The thread length must be greater than zero.';
  }
  return value;
}

/** For `showInputBox.validateInput`: undefined when valid, else the message. */
export function validateThreadLength(input: string): string | undefined {
  const parsed = parseThreadLength(input);
  return typeof parsed === 'string' ? parsed : undefined;
}

/** How the module's rough passes go down (server: thread_generator.INFEEDS). */
export const INFEEDS = ['symmetric', 'alternate', 'left', 'right'] as const;
export type Infeed = (typeof INFEEDS)[number];

/**
 * Parses a taper: empty or `0` for a parallel thread, `1:16` (diameter change per length, as
 * pipe threads give it), `-1:16`, or the change per mm (`0.0625`); at most 1:2, as the server.
 */
export function parseTaper(input: string): number | string {
  const text = input.trim().replace(',', '.');
  if (text === '' || text === '0') return 0;
  const ratio = /^(-?)\s*1\s*:\s*(\d+(?:\.\d*)?)$/.exec(text);
  let value: number;
  if (ratio !== null) {
    value = 1 / Number(ratio[2]);
    if (ratio[1] === '-') value = -value;
  } else if (/^-?(\d+(\.\d*)?|\.\d+)$/.test(text)) {
    value = Number(text);
  } else {
    return 'Enter the taper as 1:16, or as the diameter change per mm (0.0625); empty for a parallel thread.';
  }
  if (!Number.isFinite(value) || Math.abs(value) > 0.5) {
    return 'The taper must be at most 1:2 (0.5 mm of diameter per mm).';
  }
  return value;
}

/** For `showInputBox.validateInput`: undefined when valid, else the message. */
export function validateTaper(input: string): string | undefined {
  const parsed = parseTaper(input);
  return typeof parsed === 'string' ? parsed : undefined;
}

/** Arguments of the server command `fanuc-macro.threadModule`. */
export interface ThreadModuleArgs {
  readonly designation: string;
  readonly length: number;
  readonly internal: boolean | null;
  /** Left out: the paper's symmetric infeed. */
  readonly infeed?: Infeed;
  /** Diameter change per mm; left out: a parallel thread. */
  readonly taper?: number;
}

/** Validates the untyped answer `{ text }` / `{ error }` of `fanuc-macro.threadModule`. */
export function threadModuleText(value: unknown): { text: string } | { error: string } {
  if (typeof value !== 'object' || value === null || Array.isArray(value)) {
    return { error: 'the language server returned no thread module' };
  }
  const record = value as Record<string, unknown>;
  const error = record['error'];
  if (typeof error === 'string' && error !== '') {
    return { error };
  }
  const text = record['text'];
  if (typeof text !== 'string') {
    return { error: 'the language server returned a thread module without text' };
  }
  return { text };
}
