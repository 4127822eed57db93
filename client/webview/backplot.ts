// What the Toolpath view draws around the path, free of the DOM so that node's tests run it: the
// grid's step and the rulers' labels from the zoom, the axes' names by the machine's
// conventions, the scale bar, the readout under the mouse, the playback's steps, the tool's
// outline, a segment's tooltip and the status area's notes.
import type { Segments, ToolpathData, ViewName } from './toolpathGeometry';

/** The smallest step of 1, 2 or 5 times a power of ten that is at least `minPixels` apart. */
export function niceStep(scale: number, minPixels = 56): number {
  if (!(scale > 0) || !Number.isFinite(scale)) return 1;
  const least = minPixels / scale;
  let power = 10 ** Math.floor(Math.log10(least));
  for (;;) {
    for (const m of [1, 2, 5]) {
      if (m * power >= least * (1 - 1e-9)) return m * power;
    }
    power *= 10;
  }
}

/** The multiples of `step` from `lo` to `hi` (at most `limit` of them). */
export function ticks(lo: number, hi: number, step: number, limit = 400): number[] {
  const out: number[] = [];
  if (!(step > 0) || !(hi >= lo)) return out;
  const first = Math.ceil(lo / step - 1e-9);
  for (let k = first; k * step <= hi + step * 1e-9 && out.length < limit; k++) out.push(k * step);
  return out;
}

/** A tick's label: as many decimals as the step has, no "-0". */
export function tickText(value: number, step: number): string {
  const decimals = Math.max(0, Math.min(6, -Math.floor(Math.log10(step) + 1e-9)));
  const text = value.toFixed(decimals);
  return /^-0(\.0*)?$/.test(text) ? text.slice(1) : text;
}

/** How a lathe's X is shown: as the diameter the program writes, or as the radius drawn. */
export type XMode = 'diameter' | 'radius';

/** An axis across or up a view: its name, and the factor from the drawing's geometry to labels. */
export interface Axis {
  name: string;
  factor: number;
  title: string;
}

/**
 * The axes across and up a view: a lathe Z across and X up (X labelled as a diameter or a
 * radius, as the user chose), a mill's planes seen from +Z, -Y and +X; none in 3D.
 */
export function viewAxes(view: ViewName, lathe: boolean, xMode: XMode, units: string): [Axis, Axis] | null {
  const x = (): Axis =>
    lathe
      ? { name: 'X', factor: xMode === 'diameter' ? 2 : 1, title: `X ${xMode === 'diameter' ? 'diameter' : 'radius'} (${units})` }
      : { name: 'X', factor: 1, title: `X (${units})` };
  const plain = (name: string): Axis => ({ name, factor: 1, title: `${name} (${units})` });
  if (view === '3D') return null;
  if (lathe && view === 'XZ') return [plain('Z'), x()];
  if (view === 'XY') return [x(), plain('Y')];
  if (view === 'XZ') return [x(), plain('Z')];
  return [plain('Y'), plain('Z')];
}

/** The coordinates under the mouse, in the axes' labels: `Z 12.345  X Ø50.000`. */
export function readout(axes: [Axis, Axis] | null, h: number, v: number, inch: boolean): string {
  if (axes === null) return '3D: no plane under the mouse';
  const digits = inch ? 4 : 3;
  const one = (axis: Axis, value: number): string => {
    const shown = (value * axis.factor).toFixed(digits).replace(/^-(0\.0+)$/, '$1');
    return `${axis.name} ${axis.name === 'X' && axis.factor === 2 ? 'Ø' : ''}${shown}`;
  };
  return `${one(axes[0], h)}  ${one(axes[1], v)}`;
}

/** The scale bar: a nice length of at most `maxPixels` on the screen. */
export function scaleBar(scale: number, maxPixels = 120): { length: number; pixels: number } {
  let length = niceStep(scale, maxPixels);
  while (length * scale > maxPixels * 1.0001) length = previousNice(length);
  return { length, pixels: length * scale };
}

function previousNice(step: number): number {
  const power = 10 ** Math.floor(Math.log10(step) + 1e-9);
  const m = Math.round(step / power);
  return m === 1 ? 0.5 * power : m === 2 ? power : 2 * power;
}

/**
 * The playback's steps: the first segment of each block's execution (a motion record, else a
 * line of a file), in the order the control runs them, and the segment count after the last.
 */
export function blockSteps(segments: Segments): Int32Array {
  const starts: number[] = [];
  for (let i = 0; i < segments.count; i++) {
    const record = segments.motion[i]!;
    if (
      i === 0
      || record !== segments.motion[i - 1]
      || (record < 0 && (segments.line[i] !== segments.line[i - 1] || segments.path[i] !== segments.path[i - 1]))
    ) {
      starts.push(i);
    }
  }
  starts.push(segments.count);
  return Int32Array.from(starts);
}

/** The step whose segments hold segment `index` (the last step for the end). */
export function stepOf(steps: Int32Array, index: number): number {
  let lo = 0;
  let hi = steps.length - 2;
  if (hi < 0) return 0;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (steps[mid]! <= index) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

/**
 * Where the playback goes when the editor's cursor moves to `line` (of the view's own file):
 * past the next execution of that block after `position`, else its first one; `position` as it
 * is when the block is the one the playback is at (the editor following a step) or has no
 * segment.
 */
export function positionAtLine(segments: Segments, steps: Int32Array, position: number, line: number): number {
  if (position > 0) {
    const at = steps[stepOf(steps, position - 1)]!;
    if (segments.path[at] === 0 && segments.line[at] === line) return position;
  }
  let first = -1;
  for (let k = 0; k < steps.length - 1; k++) {
    const i = steps[k]!;
    if (segments.path[i] !== 0 || segments.line[i] !== line) continue;
    if (i >= position) return steps[k + 1]!;
    if (first < 0) first = steps[k + 1]!;
  }
  return first < 0 ? position : first;
}

/** A point of the world: x, y, z (a lathe's X as the radius drawn). */
export type Point3 = [number, number, number];

/**
 * The tool's outline about the point it is at, as polylines of world points. A lathe's insert:
 * its nose a circle of `radius` whose lowest point is the tool's point, and two flanks at the
 * included `angle` going up from it (the insert seen from above, cutting towards the axis; a
 * tool inside a bore points up). A mill's cutter: a cylinder of `radius` about the spindle's
 * axis (Z), its end at the point, `4 * radius` long.
 */
export function toolOutline(lathe: boolean, at: Point3, radius: number, angle: number, inside = false): Point3[][] {
  const [x, y, z] = at;
  const circle = (n: number, f: (t: number) => Point3): Point3[] =>
    Array.from({ length: n + 1 }, (_, k) => f((2 * Math.PI * k) / n));
  if (lathe) {
    const up = inside ? -1 : 1;
    const half = ((angle > 0 ? angle : 55) * Math.PI) / 360;
    const length = radius * 12;
    const cx = x + up * radius;
    const nose = circle(36, (t) => [cx + radius * Math.sin(t), y, z + radius * Math.cos(t)]);
    // The flanks leave the nose where they are its tangents.
    const flank = (side: number): Point3[] => {
      const sx = cx - up * radius * Math.sin(half);
      const sz = z + side * radius * Math.cos(half);
      return [[sx, y, sz], [sx + up * length * Math.cos(half), y, sz + side * length * Math.sin(half)]];
    };
    const top = [flank(-1)[1]!, flank(1)[1]!];
    return [nose, flank(-1), flank(1), top];
  }
  const height = radius * 4;
  const bottom = circle(36, (t) => [x + radius * Math.cos(t), y + radius * Math.sin(t), z]);
  const top = circle(36, (t) => [x + radius * Math.cos(t), y + radius * Math.sin(t), z + height]);
  const sides: Point3[][] = [0, Math.PI / 2, Math.PI, (3 * Math.PI) / 2].map((t) => [
    [x + radius * Math.cos(t), y + radius * Math.sin(t), z],
    [x + radius * Math.cos(t), y + radius * Math.sin(t), z + height],
  ]);
  return [bottom, top, ...sides];
}

/**
 * The words the view says, as templates whose {0}, {1} the values fill: English here; the
 * extension sends them in the user's language (client/src/toolpathView.ts `toolpathWords`).
 */
export const ENGLISH_WORDS = {
  notKnown: 'not known',
  line: 'line {0} ({1})',
  rapid: 'rapid',
  feedNotKnown: 'F not known',
  speedNotKnown: 'S not known',
  assumed: 'assumed {0}',
  segments: '{0} segments, {1}',
  xShown: 'X shown as a {0} (the program writes diameters)',
  diameter: 'diameter',
  radius: 'radius',
  stock: 'stock: Ø{0} from {1}',
  noStockLathe: 'stock: not given by the program (no stock removal cycle, no thread blank)',
  noStock: 'stock: not given by the program',
  tool: 'tool: radius {0}, {1}',
  noTool: 'tool: its radius is not given by the program: drawn at a nominal size',
  cutShort: 'cut short: the program makes more moves than the view keeps',
  unknownAxes: '{0} unknown: ',
  lost: 'line {0}: {1}{2}',
  nothingToDraw: '{0}: nothing to draw',
};
export type Words = typeof ENGLISH_WORDS;

/** `template` with its {0}, {1}... filled by `values` (one left out stays as it is). */
export function say(template: string, ...values: Array<string | number>): string {
  return template.replace(/\{(\d+)\}/g, (found, index: string) => {
    const value = values[Number(index)];
    return value === undefined ? found : String(value);
  });
}

/** The words a message gives, English for any it lacks. */
export function wordsOf(given: unknown): Words {
  const words = { ...ENGLISH_WORDS };
  if (given === null || typeof given !== 'object') return words;
  for (const key of Object.keys(words) as Array<keyof Words>) {
    const text = (given as Record<string, unknown>)[key];
    if (typeof text === 'string') words[key] = text;
  }
  return words;
}

function number(value: number, digits: number, words: Words = ENGLISH_WORDS): string {
  return Number.isFinite(value) ? String(Number(value.toFixed(digits))) : words.notKnown;
}

/** What a segment's tooltip says: its file and line, the block's code, F and S, and the block. */
export function tooltipLines(
  segments: Segments,
  data: ToolpathData,
  index: number,
  text?: string,
  words: Words = ENGLISH_WORDS,
): string[] {
  const line = segments.line[index]!;
  const path = segments.path[index]!;
  const file = path === 0 ? '' : `${(data.paths[path] ?? '').split('/').pop()}: `;
  const kind = data.kinds[segments.kind[index]!] ?? 'move';
  const out = [`${file}${say(words.line, line + 1, kind)}`];
  if (text !== undefined && text.trim() !== '') out.push(text.trim().slice(0, 120));
  const record = segments.motion[index]!;
  const blocks = segments.blocks;
  if (record >= 0 && record < blocks.code.length) {
    const inch = data.units === 'inch';
    const code = data.codes[blocks.code[record]!] ?? '';
    const feed = blocks.feed[record]!;
    const speed = blocks.speed[record]!;
    const surface = blocks.surface[record] === 1;
    const f = Number.isFinite(feed) ? `F${number(feed, 4, words)}` : words.feedNotKnown;
    const s = Number.isFinite(speed)
      ? surface
        ? `S${number(speed, 1, words)} ${inch ? 'ft' : 'm'}/min (G96)`
        : `S${number(speed, 1, words)} rpm`
      : words.speedNotKnown;
    out.push(`${code} · ${kind === 'rapid' ? words.rapid : f} · ${s}`);
  }
  return out;
}

/** The status area's notes: what is drawn, in which unit and why, and every caveat. */
export function statusNotes(data: ToolpathData, segments: Segments, xMode: XMode, words: Words = ENGLISH_WORDS): string[] {
  const units = data.units_stated ? data.units : say(words.assumed, data.units);
  const notes = [say(words.segments, segments.count.toLocaleString('en'), units)];
  if (data.lathe) notes.push(say(words.xShown, words[xMode]));
  if (!data.units_stated && data.units_note) notes.push(data.units_note);
  if (data.stock !== null) notes.push(say(words.stock, number(data.stock.diameter, 3, words), data.stock.source));
  else notes.push(data.lathe ? words.noStockLathe : words.noStock);
  if (data.tool !== null) notes.push(say(words.tool, number(data.tool.radius, 4, words), data.tool.source));
  else notes.push(words.noTool);
  if (data.truncated) notes.push(words.cutShort);
  if (data.stopped) notes.push(data.stopped);
  for (const lost of data.lost) {
    const file = lost.path === 0 ? '' : `${(data.paths[lost.path] ?? '').split('/').pop()}: `;
    const axes = lost.axes.length > 0 ? say(words.unknownAxes, lost.axes.join(', ')) : '';
    notes.push(`${file}${say(words.lost, lost.line + 1, axes, lost.reason)}`);
  }
  return notes;
}
