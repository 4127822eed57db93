// Turns the answer of the server's `fanuc-macro.trace` command into a
// plain-text table. Pure: unit-tested without VS Code.

/** One motion block reported by the server. Every field is optional on the wire. */
export interface TraceMotion {
  readonly program?: string | number | null;
  readonly line?: number | string | null;
  readonly code?: string | null;
  readonly words?: Readonly<Record<string, number | string | null>> | null;
}

/** Answer of `workspace/executeCommand` `fanuc-macro.trace`. */
export interface TraceResult {
  readonly motions?: readonly TraceMotion[] | null;
  readonly summary?: unknown;
  readonly error?: string | null;
}

/** Addresses whose values are integers on a FANUC control (no decimal point). */
const INTEGER_ADDRESSES = new Set(['D', 'G', 'H', 'L', 'M', 'N', 'O', 'P', 'S', 'T']);

/** Formats a number like a FANUC word: `49.816`, `-60.`, `3.`; integer addresses without the point. */
export function formatWordValue(address: string, value: number | string | null): string {
  if (value === null) {
    return '<vacant>';
  }
  if (typeof value === 'string') {
    return value;
  }
  if (!Number.isFinite(value)) {
    return String(value);
  }
  let rounded = Number(value.toFixed(6));
  if (Object.is(rounded, -0)) {
    rounded = 0;
  }
  if (Number.isInteger(rounded)) {
    return INTEGER_ADDRESSES.has(address.toUpperCase()) ? String(rounded) : `${rounded}.`;
  }
  // toFixed avoids exponent notation; then drop trailing zeros.
  return rounded.toFixed(6).replace(/0+$/, '');
}

/** `O3331` from 3331, "3331", "O3331" or a program name such as "<THREAD>". */
export function formatProgram(program: string | number | null | undefined): string {
  if (program === null || program === undefined || program === '') {
    return '';
  }
  const text = String(program).trim();
  if (/^\d+$/.test(text)) {
    return `O${text.padStart(4, '0')}`;
  }
  return text;
}

/** The words of a motion in the order the server sent them: `X49.816 W-60. F3.`. */
export function formatWords(words: TraceMotion['words']): string {
  if (words === null || words === undefined) {
    return '';
  }
  return Object.entries(words)
    .map(([address, value]) => `${address}${formatWordValue(address, value)}`)
    .join(' ');
}

function formatScalar(value: unknown): string {
  if (value === null || value === undefined) {
    return '-';
  }
  if (typeof value === 'number') {
    return Number.isInteger(value) ? String(value) : String(Number(value.toFixed(6)));
  }
  if (typeof value === 'string') {
    return value;
  }
  return JSON.stringify(value);
}

function isPlainObject(value: unknown): value is Record<string, unknown> {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}

/** Indented `key: value` lines for the summary object, nested objects indented further. */
export function formatSummary(summary: unknown, indent = '  '): string[] {
  const lines: string[] = [];
  if (!isPlainObject(summary)) {
    if (summary !== undefined && summary !== null) {
      lines.push(`${indent}${formatScalar(summary)}`);
    }
    return lines;
  }
  for (const [key, value] of Object.entries(summary)) {
    if (isPlainObject(value)) {
      if (Object.keys(value).length === 0) {
        lines.push(`${indent}${key}: (none)`);
        continue;
      }
      lines.push(`${indent}${key}:`);
      lines.push(...formatSummary(value, `${indent}  `));
    } else if (Array.isArray(value)) {
      if (value.length === 0) {
        lines.push(`${indent}${key}: (none)`);
      } else if (value.every((v) => !isPlainObject(v) && !Array.isArray(v))) {
        lines.push(`${indent}${key}: ${value.map(formatScalar).join(', ')}`);
      } else {
        lines.push(`${indent}${key}:`);
        for (const item of value) {
          const nested = formatSummary(item, `${indent}    `);
          const first = nested[0];
          if (first !== undefined) {
            nested[0] = `${indent}  - ${first.trimStart()}`;
          }
          lines.push(...nested);
        }
      }
    } else {
      lines.push(`${indent}${key}: ${formatScalar(value)}`);
    }
  }
  return lines;
}

/** One aligned line per motion: `O3331 line 23  G92  X49.816 W-60. F3.`. */
export function formatMotionLines(motions: readonly TraceMotion[]): string[] {
  const rows = motions.map((m) => ({
    program: formatProgram(m.program),
    line: m.line === null || m.line === undefined ? '' : String(m.line),
    code: m.code ?? '',
    words: formatWords(m.words),
  }));
  const programWidth = Math.max(0, ...rows.map((r) => r.program.length));
  const lineWidth = Math.max(0, ...rows.map((r) => r.line.length));
  const codeWidth = Math.max(0, ...rows.map((r) => r.code.length));
  return rows.map((r) => {
    const parts: string[] = [];
    if (programWidth > 0) parts.push(`${r.program.padEnd(programWidth)} `);
    if (lineWidth > 0) parts.push(`line ${r.line.padEnd(lineWidth)}  `);
    if (codeWidth > 0) parts.push(`${r.code.padEnd(codeWidth)}  `);
    parts.push(r.words);
    return parts.join('').trimEnd();
  });
}

/** The whole document shown by "Show Trace of Current Program". */
export function formatTrace(result: TraceResult, source: string): string {
  const motions = result.motions ?? [];
  const out: string[] = [];
  out.push(`Trace of ${source}`);
  out.push(`${motions.length} motion block${motions.length === 1 ? '' : 's'}`);
  out.push('');
  if (motions.length === 0) {
    out.push('(no motion)');
  } else {
    out.push(...formatMotionLines(motions));
  }
  const summaryLines = formatSummary(result.summary);
  if (summaryLines.length > 0) {
    out.push('');
    out.push('Summary');
    out.push(...summaryLines);
  }
  return `${out.join('\n')}\n`;
}

/**
 * Validates the untyped answer of the server. Returns the error text for an
 * `{ error }` answer or an answer of the wrong shape, otherwise undefined.
 */
export function traceResultError(value: unknown): string | undefined {
  if (!isPlainObject(value)) {
    return 'the language server returned no trace';
  }
  const error = value['error'];
  if (typeof error === 'string' && error !== '') {
    return error;
  }
  const motions = value['motions'];
  if (motions !== undefined && motions !== null && !Array.isArray(motions)) {
    return 'the language server returned a trace without a list of motions';
  }
  return undefined;
}
