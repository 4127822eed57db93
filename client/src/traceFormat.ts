// Turns the answer of the server's `fanuc-macro.trace` command into the text of the trace
// view (client/src/traceView.ts) and the rows that link to the source. Pure: unit-tested
// without VS Code.

/** A position the server sends: the axes known, `{ X: 51, Z: 5.964 }` (a lathe's X a diameter). */
export type TracePosition = Readonly<Record<string, number | null>>;

/** One move of a canned cycle's record. */
export interface TraceMove {
  readonly kind?: string | null;
  readonly start?: TracePosition | null;
  readonly end?: TracePosition | null;
  readonly centre?: TracePosition | null;
  readonly clockwise?: boolean | null;
}

/** One motion block reported by the server. Every field is optional on the wire. */
export interface TraceMotion {
  readonly program?: string | number | null;
  /** 1-based line of the block. */
  readonly line?: number | string | null;
  readonly code?: string | null;
  readonly words?: Readonly<Record<string, number | string | null>> | null;
  /** The block's file (a URI), when it is not the traced document's. */
  readonly path?: string | null;
  readonly start?: TracePosition | null;
  readonly end?: TracePosition | null;
  readonly centre?: TracePosition | null;
  readonly cycle?: string | null;
  readonly moves?: readonly TraceMove[] | null;
  /** What the variables the block reads held when it ran: `{ "#101": 3.5 }`, null vacant. */
  readonly values?: Readonly<Record<string, number | string | null>> | null;
}

/** A place where the toolpath lost track of an axis. */
export interface TraceLost {
  readonly program?: string | number | null;
  readonly line?: number | null;
  readonly axes?: readonly string[] | null;
  readonly reason?: string | null;
  readonly path?: string | null;
}

/** Answer of `workspace/executeCommand` `fanuc-macro.trace`. */
export interface TraceResult {
  readonly motions?: readonly TraceMotion[] | null;
  readonly toolpath?: { readonly lost?: readonly TraceLost[] | null; readonly units?: string | null } | null;
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

/** A position as the control writes it: `X51. Z5.964`; `?` when no axis is known. */
export function formatPosition(position: TracePosition | null | undefined): string {
  if (position === null || position === undefined) return '?';
  const text = Object.entries(position)
    .filter((entry): entry is [string, number] => typeof entry[1] === 'number')
    .map(([axis, value]) => `${axis}${formatWordValue(axis, value)}`)
    .join(' ');
  return text === '' ? '?' : text;
}

/**
 * A macro variable's value as the control's display shows it, 8 significant digits at most:
 * `51.249025`, `150.`; `<vacant>`; a value the analysis cannot compute in parentheses.
 */
export function formatMacroValue(value: number | string | null | undefined): string {
  if (value === null || value === undefined) return '<vacant>';
  if (typeof value === 'string') return `(${value})`;
  if (!Number.isFinite(value)) return String(value);
  let rounded = Number(value.toPrecision(8));
  if (Object.is(rounded, -0)) rounded = 0;
  if (Number.isInteger(rounded) && Math.abs(rounded) < 1e15) return `${rounded}.`;
  return String(rounded);
}

/** `#6=50. #16=51.249025`, in the order the server sent them (the order the block names them). */
export function formatValues(values: TraceMotion['values']): string {
  if (values === null || values === undefined) return '';
  return Object.entries(values)
    .map(([name, value]) => `${name.startsWith('#') ? name : `#${name}`}=${formatMacroValue(value)}`)
    .join(' ');
}

/** A row of the trace view that leads to a block: its line in the view, the block's line. */
export interface TraceRow {
  /** 0-based line of the row in the trace view. */
  readonly line: number;
  /** 0-based line of the block in its file. */
  readonly sourceLine: number;
  /** The block's file (a URI) when it is not the traced document. */
  readonly path?: string;
  /** Columns of the row's link (the `O0003 line 33` part), when it has one. */
  readonly link?: { readonly start: number; readonly end: number };
  /** What the link says it opens. */
  readonly label: string;
}

/** The trace view's text and the rows that lead to the source, in the order of the text. */
export interface TraceView {
  readonly text: string;
  readonly rows: readonly TraceRow[];
}

/** A column is padded to the widest of its cells, up to this many characters. */
const MAX_COLUMN = 40;

function pad(text: string, width: number): string {
  return text.padEnd(Math.min(width, MAX_COLUMN));
}

function sourceLineOf(line: TraceMotion['line']): number | undefined {
  const n = typeof line === 'number' ? line : typeof line === 'string' ? Number(line) : NaN;
  return Number.isInteger(n) && n >= 1 ? n - 1 : undefined;
}

function formatMove(move: TraceMove): string {
  let text = `${(move.kind ?? 'move').padEnd(6)} ${formatPosition(move.start)} -> ${formatPosition(move.end)}`;
  if (move.centre !== null && move.centre !== undefined) {
    text += `  centre ${formatPosition(move.centre)}${move.clockwise === true ? ' CW' : move.clockwise === false ? ' CCW' : ''}`;
  }
  return text;
}

/**
 * The document "Show Trace of Current Program" shows: a header, one row per motion block
 * (where it is, its code and words, where the tool goes from and to, the values the block
 * read), a canned cycle's moves under its row, where the path is not known, and the summary.
 * Every row of a block is in `rows`, for its link and its definition.
 */
export function formatTraceView(result: TraceResult, source: string): TraceView {
  const motions = result.motions ?? [];
  const out: string[] = [];
  const rows: TraceRow[] = [];
  const summary = isPlainObject(result.summary) ? result.summary : {};
  const executed = summary['blocks_executed'];
  out.push(`Trace of ${source}`);
  out.push(
    `${motions.length} motion block${motions.length === 1 ? '' : 's'}` +
      (typeof executed === 'number' ? `, ${executed} block${executed === 1 ? '' : 's'} executed` : '') +
      (typeof result.toolpath?.units === 'string' ? `, positions in ${result.toolpath.units}` : ''),
  );
  out.push('Ctrl+click a block (O0001 line 12) to open it in its program, or press F12 on its row.');
  out.push('');
  if (motions.length === 0) {
    out.push('(no motion)');
  } else {
    const cells = motions.map((m) => {
      const program = formatProgram(m.program);
      const line = m.line === null || m.line === undefined ? '' : `line ${String(m.line)}`;
      return {
        block: program === '' ? line : `${program} ${line}`.trimEnd(),
        code: m.code ?? '',
        words: formatWords(m.words),
        path:
          m.start === undefined && m.end === undefined ? '' : `${formatPosition(m.start)} -> ${formatPosition(m.end)}`,
        values: formatValues(m.values),
      };
    });
    const width = (key: keyof (typeof cells)[number], title: string) =>
      Math.max(title.length, ...cells.map((c) => c[key].length));
    const widths = {
      block: width('block', 'block'),
      code: width('code', 'code'),
      words: width('words', 'words'),
      path: width('path', 'from -> to'),
    };
    const row = (c: { block: string; code: string; words: string; path: string; values: string }) =>
      `${pad(c.block, widths.block)}  ${pad(c.code, widths.code)}  ${pad(c.words, widths.words)}  ${pad(c.path, widths.path)}  ${c.values}`.trimEnd();
    out.push(row({ block: 'block', code: 'code', words: 'words', path: 'from -> to', values: 'values read' }));
    motions.forEach((m, i) => {
      const c = cells[i]!;
      const sourceLine = sourceLineOf(m.line);
      const at = out.length;
      out.push(row(c));
      if (sourceLine !== undefined) {
        const path = typeof m.path === 'string' && m.path !== '' ? m.path : undefined;
        rows.push({
          line: at,
          sourceLine,
          ...(path === undefined ? {} : { path }),
          link: { start: 0, end: c.block.length },
          label: c.block,
        });
      }
      if (m.centre !== null && m.centre !== undefined) {
        out.push(`${' '.repeat(4)}centre ${formatPosition(m.centre)}`);
      }
      const moves = m.moves ?? [];
      if (moves.length > 0) {
        const cycle = typeof m.cycle === 'string' && m.cycle !== '' ? ` (${m.cycle})` : '';
        out.push(`${' '.repeat(4)}${moves.length} move${moves.length === 1 ? '' : 's'}${cycle}:`);
      }
      for (const move of moves) out.push(`${' '.repeat(6)}${formatMove(move)}`);
      if (sourceLine !== undefined) {
        // The lines under a block's row lead to it too (F12), without a link of their own.
        const path = typeof m.path === 'string' && m.path !== '' ? m.path : undefined;
        for (let line = at + 1; line < out.length; line++) {
          rows.push({ line, sourceLine, ...(path === undefined ? {} : { path }), label: c.block });
        }
      }
    });
  }
  const lost = result.toolpath?.lost ?? [];
  if (lost.length > 0) {
    out.push('');
    out.push('Where the path is not known');
    for (const place of lost) {
      const program = formatProgram(place.program);
      const line = typeof place.line === 'number' ? `line ${place.line}` : '';
      const block = `${program} ${line}`.trim();
      const sourceLine = sourceLineOf(place.line);
      const at = out.length;
      out.push(`  ${block}: ${(place.axes ?? []).join(', ')} ${place.reason ?? ''}`.trimEnd());
      if (sourceLine !== undefined) {
        const path = typeof place.path === 'string' && place.path !== '' ? place.path : undefined;
        rows.push({ line: at, sourceLine, ...(path === undefined ? {} : { path }), link: { start: 2, end: 2 + block.length }, label: block });
      }
    }
  }
  const summaryLines = formatSummary(result.summary);
  if (summaryLines.length > 0) {
    out.push('');
    out.push('Summary');
    out.push(...summaryLines);
  }
  return { text: `${out.join('\n')}\n`, rows };
}

/** The row on a line of the trace view, if that line leads to a block. */
export function rowAt(view: TraceView, line: number): TraceRow | undefined {
  // Rows are in the order of the text: a binary search.
  let lo = 0;
  let hi = view.rows.length - 1;
  while (lo <= hi) {
    const mid = (lo + hi) >> 1;
    const row = view.rows[mid]!;
    if (row.line === line) return row;
    if (row.line < line) lo = mid + 1;
    else hi = mid - 1;
  }
  return undefined;
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
