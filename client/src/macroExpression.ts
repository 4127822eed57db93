// The Macro B variable under the mouse, for the debugger's hover: VS Code's default word would
// be `123` of `#123` and drop the `#`, so the extension gives it the whole variable. Pure logic,
// unit-tested with node:test.

/** Columns of a piece of a line: `start` included, `end` excluded. */
export interface ColumnRange {
  readonly start: number;
  readonly end: number;
}

/** The end of the `[...]` that opens at `open`, nested brackets included, or -1 when unclosed. */
function closingBracket(line: string, open: number): number {
  let depth = 0;
  for (let i = open; i < line.length; i++) {
    const ch = line[i];
    if (ch === '[') depth++;
    else if (ch === ']') {
      depth--;
      if (depth === 0) return i + 1;
    } else if (ch === '(') return -1; // a comment: Macro B brackets are only [ ]
  }
  return -1;
}

/**
 * The variable that starts at the `#` at `hash`: `#123`, `#[expression]` or a system variable
 * name such as `#_UI[2]` or `#<NAME>`; undefined when nothing follows the `#`.
 */
function variableAt(line: string, hash: number): ColumnRange | undefined {
  let end = hash + 1;
  const next = line[end];
  if (next === '[') {
    const close = closingBracket(line, end);
    return close < 0 ? undefined : { start: hash, end: close };
  }
  if (next === '<') {
    const close = line.indexOf('>', end);
    return close < 0 ? undefined : { start: hash, end: close + 1 };
  }
  if (next !== undefined && /\d/.test(next)) {
    while (end < line.length && /\d/.test(line[end] ?? '')) end++;
    return { start: hash, end };
  }
  if (next === '_') {
    while (end < line.length && /[A-Za-z0-9_]/.test(line[end] ?? '')) end++;
    if (line[end] === '[') {
      const close = closingBracket(line, end);
      if (close > 0) end = close;
    }
    return end > hash + 2 ? { start: hash, end } : undefined;
  }
  return undefined;
}

/** Columns of the line that are in a `( ... )` comment. */
function commentColumns(line: string): boolean[] {
  const inComment = new Array<boolean>(line.length).fill(false);
  let depth = 0;
  for (let i = 0; i < line.length; i++) {
    const ch = line[i];
    if (ch === '(') depth++;
    if (depth > 0) inComment[i] = true;
    if (ch === ')' && depth > 0) depth--;
  }
  return inComment;
}

/**
 * The variable under `character` of `line`: of the variables that hold that column the shortest,
 * so that `#1` of `#[#1+1]` is `#1` and the `+` is the whole `#[#1+1]`. Undefined off a variable
 * and in comments.
 */
export function macroExpressionAt(line: string, character: number): ColumnRange | undefined {
  const comments = commentColumns(line);
  if (comments[character] === true) return undefined;
  let best: ColumnRange | undefined;
  for (let hash = line.indexOf('#'); hash >= 0; hash = line.indexOf('#', hash + 1)) {
    if (comments[hash] === true) continue;
    const range = variableAt(line, hash);
    if (range === undefined || character < range.start || character >= range.end) continue;
    if (best === undefined || range.end - range.start < best.end - best.start) best = range;
  }
  return best;
}
