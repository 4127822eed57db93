// Validation of ISO metric thread designations such as `M50x3-5g6g` for the
// "Insert Symmetric Thread Module..." command. Pure: unit-tested without VS Code.

export interface ThreadDesignation {
  /** The designation as sent to the server: whitespace removed, `×` written `x`. */
  readonly text: string;
  /** Nominal diameter in mm. */
  readonly nominal: number;
  /** Pitch in mm, or undefined for a coarse-pitch designation such as `M10-6g`. */
  readonly pitch: number | undefined;
  /** Tolerance class such as `5g6g` or `6H`, if given. */
  readonly tolerance: string | undefined;
  /**
   * true for an internal thread (upper-case tolerance position, `6H`), false
   * for an external one (lower case, `6g`), null when the designation has no
   * tolerance class and so does not say.
   */
  readonly internal: boolean | null;
}

const DESIGNATION =
  /^M(\d+(?:\.\d+)?)(?:X(\d+(?:\.\d+)?|\.\d+))?(?:-(([3-9])([a-hA-H])(?:([3-9])([a-hA-H]))?))?((?:-(?:LH|[SNL]))*)$/i;

/** Parses a designation, or returns a message that says what is wrong with it. */
export function parseThreadDesignation(input: string): ThreadDesignation | string {
  const text = input.replace(/\s+/g, '').replace(/×/g, 'x');
  if (text === '') {
    return 'Enter a metric thread designation such as M50x3-5g6g (external) or M50x3-6H (internal).';
  }
  // Match case-insensitively for M and x, but read the tolerance letters as typed.
  const match = DESIGNATION.exec(text);
  if (match === null) {
    return `"${input.trim()}" is not a metric thread designation; write it like M50x3-5g6g (external) or M50x3-6H (internal).`;
  }
  const nominal = Number(match[1]);
  const pitch = match[2] === undefined ? undefined : Number(match[2]);
  if (!(nominal > 0)) {
    return 'The nominal diameter must be greater than zero.';
  }
  if (pitch !== undefined && !(pitch > 0)) {
    return 'The pitch must be greater than zero.';
  }
  if (pitch !== undefined && pitch >= nominal) {
    return 'The pitch must be smaller than the nominal diameter.';
  }
  const tolerance = match[3];
  const first = match[5];
  const second = match[7];
  let internal: boolean | null = null;
  if (first !== undefined) {
    const firstInternal = first === first.toUpperCase();
    if (second !== undefined && (second === second.toUpperCase()) !== firstInternal) {
      return `The tolerance class "${tolerance ?? ''}" mixes an internal (upper-case) and an external (lower-case) position.`;
    }
    const letters = second === undefined ? [first] : [first, second];
    const valid = firstInternal ? /^[EFGH]$/ : /^[efgh]$/;
    if (!letters.every((l) => valid.test(l))) {
      return firstInternal
        ? 'Internal threads use tolerance positions G or H (for example 6H).'
        : 'External threads use tolerance positions e, f, g or h (for example 6g).';
    }
    internal = firstInternal;
  }
  return { text, nominal, pitch, tolerance, internal };
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

/** Arguments of the server command `fanuc-macro.threadModule`. */
export interface ThreadModuleArgs {
  readonly designation: string;
  readonly length: number;
  readonly internal: boolean | null;
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
