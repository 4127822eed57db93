// The Toolpath view's page (a VS Code webview): a backplot. It draws the segments on a canvas
// over a grid and rulers that follow the zoom, with the origin, a lathe's centre line, the stock
// and the tool; it pans, zooms, fits and orbits; it plays the program back block by block. A
// click on a segment asks the extension to reveal its block, the extension's cursor highlights
// the segments of the block it is on, and a step of the playback moves the editor's cursor.
// The layout's arithmetic is in backplot.ts and toolpathGeometry.ts, tested without a browser.
import {
  blockSteps,
  niceStep,
  positionAtLine,
  readout,
  scaleBar,
  statusNotes,
  stepOf,
  tickText,
  ticks,
  toolOutline,
  tooltipLines,
  viewAxes,
  wordsOf,
  say,
  type Words,
  type Axis,
  type Point3,
  type XMode,
} from './backplot';
import {
  fit,
  hitTest,
  pan,
  projection,
  segmentMiddle,
  segmentsByLine,
  toScreen,
  toSegments,
  toWorld,
  trace,
  zoomAt,
  type Margins,
  type Projection,
  type Segments,
  type ToolpathData,
  type ToolpathThread,
  type Transform,
  type ViewName,
} from './toolpathGeometry';

interface VsCodeApi {
  postMessage(message: unknown): void;
}
declare function acquireVsCodeApi(): VsCodeApi;

type Incoming =
  | { type: 'data'; data: ToolpathData; title: string; words?: Partial<Words> }
  | { type: 'empty'; reason: string; title: string; words?: Partial<Words> }
  | { type: 'error'; message: string }
  | { type: 'cursor'; line: number }
  | { type: 'blockText'; line: number; path?: string; text: string };

const vscode = acquireVsCodeApi();
const element = <T extends HTMLElement>(id: string): T => document.getElementById(id) as T;
const canvas = element<HTMLCanvasElement>('toolpath');
const summary = element<HTMLElement>('summary');
const notesList = element<HTMLUListElement>('notes');
const viewSelect = element<HTMLSelectElement>('view');
const xModeSelect = element<HTMLSelectElement>('xmode');
const xModeGroup = element<HTMLElement>('xmode-group');
const fitButton = element<HTMLButtonElement>('fit');
const playButton = element<HTMLButtonElement>('play');
const speedSelect = element<HTMLSelectElement>('speed');
const readoutBox = element<HTMLElement>('readout');
const tooltipBox = element<HTMLElement>('tooltip');
const emptyBox = element<HTMLElement>('empty');
const emptyReason = element<HTMLElement>('empty-reason');
const context = canvas.getContext('2d') as CanvasRenderingContext2D;

// The rulers' bands at the canvas's left and bottom edges, and the room the fit keeps free.
const RULER_LEFT = 58;
const RULER_BOTTOM = 34;
const INSET_WIDTH = 250;
const INSET_HEIGHT = 170;

/** The canvas's colours, read from VS Code's theme variables (again when the theme changes). */
interface Colours {
  foreground: string;
  muted: string;
  grid: string;
  axis: string;
  background: string;
  ruler: string;
  kinds: Record<string, string>;
  highlight: string;
  tool: string;
  stock: string;
  /** The workbench's fonts (a canvas does not resolve CSS variables). */
  font: string;
  mono: string;
}

function themeColour(name: string, fallback: string): string {
  const value = getComputedStyle(document.documentElement).getPropertyValue(name).trim();
  return value === '' ? fallback : value;
}

function readColours(): Colours {
  return {
    foreground: themeColour('--vscode-editor-foreground', '#333333'),
    muted: themeColour('--vscode-descriptionForeground', '#808080'),
    grid: themeColour('--vscode-editorLineNumber-foreground', '#808080'),
    axis: themeColour('--vscode-editorLineNumber-activeForeground', '#808080'),
    background: themeColour('--vscode-editor-background', '#ffffff'),
    ruler: themeColour('--vscode-editorGutter-background', themeColour('--vscode-editor-background', '#ffffff')),
    kinds: {
      rapid: themeColour('--vscode-descriptionForeground', '#9a9a9a'),
      feed: themeColour('--vscode-charts-blue', '#3b82f6'),
      thread: themeColour('--vscode-charts-red', '#e4572e'),
      arc: themeColour('--vscode-charts-green', '#22a05a'),
    },
    highlight: themeColour('--vscode-charts-yellow', '#ffcc00'),
    tool: themeColour('--vscode-charts-purple', '#b180d7'),
    stock: themeColour('--vscode-charts-orange', '#d18616'),
    font: themeColour('--vscode-font-family', 'sans-serif'),
    mono: themeColour('--vscode-editor-font-family', 'monospace'),
  };
}

const WIDTHS: Record<string, { dash: number[]; width: number }> = {
  rapid: { dash: [5, 4], width: 1 },
  feed: { dash: [], width: 1.2 },
  thread: { dash: [], width: 1.6 },
  arc: { dash: [], width: 1.2 },
};

let colours = readColours();
let data: ToolpathData | undefined;
let segments: Segments | undefined;
let steps: Int32Array = new Int32Array([0]);
let byLine = new Map<number, number[]>();
let view: ViewName = 'XZ';
let xMode: XMode = 'diameter';
let yaw = -0.6;
let pitch = 0.5;
let transform: Transform | undefined;
let cursorLine = -1;
let pending = false;
/** Playback: how many segments the tool has run (all of them when it is not playing back). */
let position = 0;
let playing = false;
let carried = 0;
let title = '';
/** The words of the notes and tooltips, in the language the extension sends. */
let words: Words = wordsOf(undefined);
const blockTexts = new Map<string, string>();
let hovered = -1;

const inch = (): boolean => data?.units === 'inch';
const unitsLabel = (): string => (data === undefined ? 'mm' : data.units_stated ? data.units : `assumed ${data.units}`);

function currentProjection(): Projection {
  return projection(view, data?.lathe ?? true, yaw, pitch);
}

function currentAxes(): [Axis, Axis] | null {
  return viewAxes(view, data?.lathe ?? true, xMode, unitsLabel());
}

function shownThread(): ToolpathThread | undefined {
  return data?.threads.find((t) => t.profile.length > 1);
}

function margins(): Margins {
  const m = { left: RULER_LEFT + 6, right: 10, top: 34, bottom: RULER_BOTTOM + 6 };
  if (view === '3D') return { left: 10, right: 10, top: 34, bottom: 10 };
  if (shownThread() !== undefined) {
    // The cross-section's inset takes the side the view has most room on.
    if (canvas.clientWidth > canvas.clientHeight) m.right += INSET_WIDTH + 8;
    else m.top += INSET_HEIGHT + 8;
  }
  return m;
}

/** The world points the fit shows besides the path: the stock, and a lathe's centre line. */
function fitExtras(): [number, number, number][] {
  const extras: [number, number, number][] = [];
  const stock = data?.stock;
  if (stock != null) {
    const r = stock.diameter / 2;
    extras.push([r, Number.NaN, stock.front], [0, Number.NaN, stock.back]);
  }
  return extras;
}

function resize(): void {
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth;
  const height = canvas.clientHeight;
  canvas.width = Math.round(width * ratio);
  canvas.height = Math.round(height * ratio);
  context.setTransform(ratio, 0, 0, ratio, 0, 0);
  if (transform !== undefined) transform = { ...transform, width, height };
}

function refit(): void {
  if (segments === undefined) return;
  transform = fit(segments, currentProjection(), canvas.clientWidth, canvas.clientHeight, {
    margins: margins(),
    extra: fitExtras(),
  });
  draw();
}

function draw(): void {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => {
    pending = false;
    paint();
  });
}

function paint(): void {
  const width = canvas.clientWidth;
  const height = canvas.clientHeight;
  context.clearRect(0, 0, width, height);
  if (data === undefined || segments === undefined || transform === undefined) return;
  const project = currentProjection();
  const t = transform;
  const axes = currentAxes();
  if (axes !== null) paintGrid(t, axes);
  paintStock(project, t);
  const pieces = paintPath(project, t, segments, data);
  paintHighlight(project, t, segments);
  paintTool(project, t, segments, data);
  if (axes !== null) {
    paintRulers(t, axes);
    paintScaleBar(t);
  } else {
    paintTriad(project);
  }
  paintThread(t);
  canvas.dataset.pieces = String(pieces);
  canvas.dataset.view = view;
}

/** The grid and the origin's axes: lines at a nice step of the labels' units. */
function paintGrid(t: Transform, axes: [Axis, Axis]): void {
  const [h0, v1] = toWorld(t, 0, 0);
  const [h1, v0] = toWorld(t, t.width, t.height);
  const stepH = niceStep(t.scale / axes[0].factor) / axes[0].factor;
  const stepV = niceStep(t.scale / axes[1].factor) / axes[1].factor;
  const grid = new Path2D();
  for (const h of ticks(h0, h1, stepH)) {
    const [x] = toScreen(t, h, 0);
    grid.moveTo(Math.round(x) + 0.5, 0);
    grid.lineTo(Math.round(x) + 0.5, t.height);
  }
  for (const v of ticks(v0, v1, stepV)) {
    const [, y] = toScreen(t, 0, v);
    grid.moveTo(0, Math.round(y) + 0.5);
    grid.lineTo(t.width, Math.round(y) + 0.5);
  }
  context.strokeStyle = colours.grid;
  context.lineWidth = 1;
  context.setLineDash([]);
  context.globalAlpha = 0.28;
  context.stroke(grid);
  context.globalAlpha = 1;
  canvas.dataset.gridStep = String(Number((stepH * axes[0].factor).toPrecision(6)));
  // The origin: the work's zero. On a lathe, the horizontal axis is the spindle's centre line.
  const [ox, oy] = toScreen(t, 0, 0);
  const lathe = data?.lathe === true && view === 'XZ';
  context.strokeStyle = colours.axis;
  context.lineWidth = 1;
  context.setLineDash(lathe ? [14, 4, 3, 4] : []);
  context.beginPath();
  context.moveTo(0, oy);
  context.lineTo(t.width, oy);
  context.stroke();
  context.setLineDash([]);
  context.beginPath();
  context.moveTo(ox, 0);
  context.lineTo(ox, t.height);
  context.stroke();
  context.fillStyle = colours.axis;
  context.font = `11px ${colours.font}`;
  context.textBaseline = 'bottom';
  context.textAlign = 'left';
  if (lathe) context.fillText('centre line', RULER_LEFT + 6, oy - 2);
  // The origin's mark: a circle quartered, as drawings mark a datum.
  context.beginPath();
  context.arc(ox, oy, 6, 0, 2 * Math.PI);
  context.stroke();
  context.beginPath();
  context.moveTo(ox, oy);
  context.arc(ox, oy, 6, -Math.PI / 2, 0);
  context.closePath();
  context.moveTo(ox, oy);
  context.arc(ox, oy, 6, Math.PI / 2, Math.PI);
  context.closePath();
  context.fill();
  context.fillText(`${axes[0].name}0 ${axes[1].name}0`, ox + 8, oy - 6);
  canvas.dataset.origin = `${ox.toFixed(0)},${oy.toFixed(0)}`;
}

/** A lathe's bar where the program gives it: its half above the centre line, as the path is. */
function paintStock(project: Projection, t: Transform): void {
  const stock = data?.stock;
  canvas.dataset.stock = stock == null ? '' : `D${stock.diameter}`;
  if (stock == null || view === 'YZ') return;
  const r = stock.diameter / 2;
  const corners: [number, number, number][] = [
    [r, 0, stock.front],
    [r, 0, stock.back],
    [0, 0, stock.back],
    [0, 0, stock.front],
  ];
  const path = new Path2D();
  corners.forEach(([x, y, z], i) => {
    const [h, v] = project(x, y, z);
    const [px, py] = toScreen(t, h, v);
    if (i === 0) path.moveTo(px, py);
    else path.lineTo(px, py);
  });
  path.closePath();
  context.save();
  context.globalAlpha = 0.12;
  context.fillStyle = colours.stock;
  context.fill(path);
  context.globalAlpha = 0.8;
  context.strokeStyle = colours.stock;
  context.setLineDash([2, 3]);
  context.lineWidth = 1;
  context.stroke(path);
  context.restore();
}

function strokeKinds(project: Projection, t: Transform, s: Segments, d: ToolpathData, from: number, to: number): number {
  const paths = d.kinds.map(() => new Path2D());
  const pieces = trace(s, project, t, paths, 0.75, from, to);
  d.kinds.forEach((kind, i) => {
    const style = WIDTHS[kind] ?? WIDTHS.feed!;
    context.strokeStyle = colours.kinds[kind] ?? colours.kinds.feed!;
    context.lineWidth = style.width;
    context.setLineDash(style.dash);
    context.stroke(paths[i]!);
  });
  context.setLineDash([]);
  return pieces;
}

/** The path: what the tool has run in full, what is still to run faint. */
function paintPath(project: Projection, t: Transform, s: Segments, d: ToolpathData): number {
  if (position >= s.count) return strokeKinds(project, t, s, d, 0, s.count);
  context.save();
  context.globalAlpha = 0.22;
  let pieces = strokeKinds(project, t, s, d, position, s.count);
  context.restore();
  pieces += strokeKinds(project, t, s, d, 0, position);
  return pieces;
}

function paintHighlight(project: Projection, t: Transform, s: Segments): void {
  const lit = byLine.get(cursorLine) ?? [];
  if (lit.length > 0) {
    const glow = new Path2D();
    for (const i of lit) {
      const o = s.point[i]! * 3;
      const xyz = s.xyz;
      const [h0, v0] = project(xyz[o]!, xyz[o + 1]!, xyz[o + 2]!);
      const [h1, v1] = project(xyz[o + 3]!, xyz[o + 4]!, xyz[o + 5]!);
      if (Number.isNaN(h0 + v0 + h1 + v1)) continue;
      glow.moveTo(...toScreen(t, h0, v0));
      glow.lineTo(...toScreen(t, h1, v1));
    }
    context.strokeStyle = colours.highlight;
    context.lineWidth = 4;
    context.globalAlpha = 0.8;
    context.stroke(glow);
    context.globalAlpha = 1;
  }
  canvas.dataset.highlighted = String(lit.length);
}

/** Where the tool is: the end of the last segment it has run (the first one's start before). */
function toolPoint(s: Segments): Point3 | undefined {
  if (s.count === 0) return undefined;
  for (let i = Math.min(position, s.count) - 1; i >= -1; i--) {
    const o = i < 0 ? s.point[0]! * 3 : s.point[i]! * 3 + 3;
    const p: Point3 = [s.xyz[o]!, s.xyz[o + 1]!, s.xyz[o + 2]!];
    const known = data?.lathe ? !Number.isNaN(p[0] + p[2]) : !Number.isNaN(p[0] + p[1] + p[2]);
    if (known) return data?.lathe ? [p[0], Number.isNaN(p[1]) ? 0 : p[1], p[2]] : p;
  }
  return undefined;
}

function paintTool(project: Projection, t: Transform, s: Segments, d: ToolpathData): void {
  const at = toolPoint(s);
  if (at === undefined) {
    canvas.dataset.tool = '';
    canvas.dataset.toolPosition = String(position);
    return;
  }
  // Without a radius the program gives, a nominal 6 pixels: a marker, not a size.
  const radius = d.tool?.radius ?? 6 / t.scale;
  const inside = d.threads.some((th) => th.internal) && d.threads.every((th) => th.internal);
  const outline = toolOutline(d.lathe, at, radius, d.tool?.angle ?? 0, inside);
  const path = new Path2D();
  for (const line of outline) {
    line.forEach(([x, y, z], i) => {
      const [h, v] = project(x, y, z);
      const [px, py] = toScreen(t, h, v);
      if (i === 0) path.moveTo(px, py);
      else path.lineTo(px, py);
    });
  }
  context.strokeStyle = colours.tool;
  context.lineWidth = 1.5;
  context.setLineDash([]);
  context.stroke(path);
  const [h, v] = project(...at);
  const [px, py] = toScreen(t, h, v);
  context.fillStyle = colours.tool;
  context.beginPath();
  context.arc(px, py, 2.5, 0, 2 * Math.PI);
  context.fill();
  canvas.dataset.tool = `${d.lathe ? 'insert' : 'cylinder'} r${Number(radius.toPrecision(4))}`;
  canvas.dataset.toolAt = `${px.toFixed(0)},${py.toFixed(0)}`;
  // The playback's position this drawing shows: the frame comes after the step that asked it.
  canvas.dataset.toolPosition = String(position);
}

/** The rulers at the left and bottom edges: the labels of the grid's lines, the axes' titles. */
function paintRulers(t: Transform, axes: [Axis, Axis]): void {
  const [h0, v1] = toWorld(t, RULER_LEFT, 0);
  const [h1, v0] = toWorld(t, t.width, t.height - RULER_BOTTOM);
  context.fillStyle = colours.ruler;
  context.globalAlpha = 0.92;
  context.fillRect(0, 0, RULER_LEFT, t.height);
  context.fillRect(0, t.height - RULER_BOTTOM, t.width, RULER_BOTTOM);
  context.globalAlpha = 1;
  context.strokeStyle = colours.axis;
  context.lineWidth = 1;
  context.beginPath();
  context.moveTo(RULER_LEFT + 0.5, 0);
  context.lineTo(RULER_LEFT + 0.5, t.height - RULER_BOTTOM + 0.5);
  context.lineTo(t.width, t.height - RULER_BOTTOM + 0.5);
  context.stroke();
  context.fillStyle = colours.foreground;
  context.font = `11px ${colours.mono}`;
  const labelStepH = niceStep(t.scale / axes[0].factor);
  const labelStepV = niceStep(t.scale / axes[1].factor);
  context.textAlign = 'center';
  context.textBaseline = 'top';
  const tick = new Path2D();
  for (const h of ticks(h0, h1, labelStepH / axes[0].factor)) {
    const [x] = toScreen(t, h, 0);
    tick.moveTo(x, t.height - RULER_BOTTOM);
    tick.lineTo(x, t.height - RULER_BOTTOM + 4);
    context.fillText(tickText(h * axes[0].factor, labelStepH), x, t.height - RULER_BOTTOM + 5);
  }
  context.textAlign = 'right';
  context.textBaseline = 'middle';
  for (const v of ticks(v0, v1, labelStepV / axes[1].factor)) {
    const [, y] = toScreen(t, 0, v);
    tick.moveTo(RULER_LEFT - 4, y);
    tick.lineTo(RULER_LEFT, y);
    context.fillText(tickText(v * axes[1].factor, labelStepV), RULER_LEFT - 6, y);
  }
  context.stroke(tick);
  // The axes' titles: across at the bottom right, up at the top left.
  context.font = `bold 11px ${colours.font}`;
  context.textAlign = 'right';
  context.textBaseline = 'bottom';
  context.fillText(`${axes[0].title} →`, t.width - 6, t.height - 2);
  context.textAlign = 'left';
  context.textBaseline = 'top';
  context.fillText(`↑ ${axes[1].title}`, 4, 4);
  canvas.dataset.axes = `${axes[0].name},${axes[1].name}`;
  canvas.dataset.rulerStep = `${labelStepH},${labelStepV}`;
}

function paintScaleBar(t: Transform): void {
  const bar = scaleBar(t.scale, 120);
  const right = t.width - 14;
  const y = t.height - RULER_BOTTOM - 12;
  context.strokeStyle = colours.foreground;
  context.lineWidth = 2;
  context.beginPath();
  context.moveTo(right - bar.pixels, y - 4);
  context.lineTo(right - bar.pixels, y);
  context.lineTo(right, y);
  context.lineTo(right, y - 4);
  context.stroke();
  context.fillStyle = colours.foreground;
  context.font = `11px ${colours.font}`;
  context.textAlign = 'center';
  context.textBaseline = 'bottom';
  context.fillText(`${bar.length} ${data?.units ?? 'mm'}`, right - bar.pixels / 2, y - 5);
  canvas.dataset.scaleBar = String(bar.length);
}

/** In 3D, the axes' directions at the bottom left. */
function paintTriad(project: Projection): void {
  const [oh, ov] = project(0, 0, 0);
  const cx = 40;
  const cy = canvas.clientHeight - 40;
  context.lineWidth = 1.5;
  context.font = `bold 11px ${colours.font}`;
  context.textAlign = 'center';
  context.textBaseline = 'middle';
  const ends: [string, Point3, string][] = [
    ['X', [1, 0, 0], colours.kinds.thread!],
    ['Y', [0, 1, 0], colours.kinds.arc!],
    ['Z', [0, 0, 1], colours.kinds.feed!],
  ];
  for (const [name, [x, y, z], colour] of ends) {
    const [h, v] = project(x, y, z);
    const dx = (h - oh) * 26;
    const dy = -(v - ov) * 26;
    context.strokeStyle = colour;
    context.fillStyle = colour;
    context.beginPath();
    context.moveTo(cx, cy);
    context.lineTo(cx + dx, cy + dy);
    context.stroke();
    context.fillText(name, cx + dx * 1.3, cy + dy * 1.3);
  }
  canvas.dataset.axes = '3D';
  canvas.dataset.gridStep = '';
}

/** A threading program's cross-section (threads/cross_section.py): the cut over one lead. */
function paintThread(t: Transform): void {
  const thread = shownThread();
  canvas.dataset.threads = String(thread === undefined ? 0 : data?.threads.length ?? 0);
  if (thread === undefined) return;
  const wide = t.width > t.height;
  const x0 = wide ? t.width - INSET_WIDTH - 8 : t.width - INSET_WIDTH - 8;
  const y0 = wide ? 34 : 34;
  context.fillStyle = colours.background;
  context.globalAlpha = 0.94;
  context.fillRect(x0, y0, INSET_WIDTH, INSET_HEIGHT);
  context.globalAlpha = 1;
  context.strokeStyle = colours.axis;
  context.lineWidth = 1;
  context.strokeRect(x0 + 0.5, y0 + 0.5, INSET_WIDTH, INSET_HEIGHT);
  context.fillStyle = colours.foreground;
  context.font = `bold 11px ${colours.font}`;
  context.textAlign = 'left';
  context.textBaseline = 'top';
  context.fillText(`${thread.name}: the cut over one lead`, x0 + 6, y0 + 4);
  const us = thread.profile.map((p) => p[0]);
  const rs = thread.profile.map((p) => p[1]);
  const band = thread.band;
  const rLo = Math.min(...rs, ...(band ? band.map((d) => d / 2) : []));
  const rHi = Math.max(...rs, ...(band ? band.map((d) => d / 2) : []));
  const uLo = Math.min(...us);
  const uHi = Math.max(...us);
  const boxW = INSET_WIDTH - 16;
  const boxH = INSET_HEIGHT - 48;
  const k = Math.min(boxW / Math.max(uHi - uLo, 1e-9), boxH / Math.max(rHi - rLo, 1e-9));
  const px = (u: number): number => x0 + 8 + (u - uLo) * k + (boxW - (uHi - uLo) * k) / 2;
  const py = (r: number): number => y0 + 22 + boxH - (r - rLo) * k - (boxH - (rHi - rLo) * k) / 2;
  // The metal left: under the profile outside, over it inside.
  const metal = new Path2D();
  const edge = thread.internal ? rHi : rLo;
  metal.moveTo(px(uLo), py(edge));
  for (const [u, r] of thread.profile) metal.lineTo(px(u), py(r));
  metal.lineTo(px(uHi), py(edge));
  metal.closePath();
  context.globalAlpha = 0.25;
  context.fillStyle = colours.stock;
  context.fill(metal);
  context.globalAlpha = 1;
  context.strokeStyle = colours.kinds.thread!;
  context.lineWidth = 1.4;
  const outline = new Path2D();
  thread.profile.forEach(([u, r], i) => (i === 0 ? outline.moveTo(px(u), py(r)) : outline.lineTo(px(u), py(r))));
  context.stroke(outline);
  if (band !== null) {
    context.strokeStyle = colours.kinds.feed!;
    context.setLineDash([4, 3]);
    context.beginPath();
    for (const d of band) {
      context.moveTo(px(uLo), py(d / 2));
      context.lineTo(px(uHi), py(d / 2));
    }
    context.stroke();
    context.setLineDash([]);
  }
  context.fillStyle = colours.muted;
  context.font = `11px ${colours.font}`;
  context.textBaseline = 'bottom';
  const what = `${thread.passes} passes${band !== null ? `, pitch Ø ${band[0].toFixed(3)}-${band[1].toFixed(3)} dashed` : ''}`;
  context.fillText(what, x0 + 6, y0 + INSET_HEIGHT - 4);
}

function showNotes(): void {
  if (data === undefined || segments === undefined) return;
  const notes = statusNotes(data, segments, xMode, words);
  summary.textContent = `${title}: ${notes[0]}`;
  notesList.replaceChildren(
    ...notes.slice(1).map((note) => {
      const item = document.createElement('li');
      item.textContent = note;
      return item;
    }),
  );
  summary.title = notes.join('\n');
  notesList.dataset.notes = String(notes.length - 1);
}

/** The block the playback is at: the last one it ran. */
function currentStep(): number {
  return position <= 0 || segments === undefined ? -1 : stepOf(steps, position - 1);
}

function showStep(follow: boolean): void {
  if (segments === undefined) return;
  const step = currentStep();
  canvas.dataset.stepIndex = String(step + 1);
  canvas.dataset.steps = String(steps.length - 1);
  canvas.dataset.position = String(position);
  playButton.textContent = playing ? '❚❚' : '▶︎';
  if (step < 0 || !follow) return;
  const first = steps[step]!;
  const line = segments.line[first]!;
  const path = segments.path[first]!;
  if (path === 0) cursorLine = line;
  // The editor follows the block, keeping the focus where it is.
  vscode.postMessage(path === 0 ? { type: 'reveal', line, follow: true } : { type: 'reveal', line, path: data?.paths[path], follow: true });
}

function stepTo(next: number, follow = true): void {
  if (segments === undefined) return;
  position = Math.max(0, Math.min(segments.count, next));
  showStep(follow);
  draw();
}

function stepForward(): void {
  if (segments === undefined || position >= segments.count) return;
  stepTo(steps[stepOf(steps, position) + 1]!);
}

function stepBack(): void {
  if (segments === undefined || position <= 0) return;
  stepTo(steps[stepOf(steps, position - 1)]!);
}

function play(): void {
  if (segments === undefined) return;
  if (playing) {
    playing = false;
    showStep(true);
    return;
  }
  if (position >= segments.count) position = 0;
  playing = true;
  carried = 0;
  showStep(false);
  const frame = (): void => {
    if (!playing || segments === undefined) return;
    // A few blocks a second at "normal", whatever the program's length, a second or two for
    // a short one.
    const rate = Number(speedSelect.value) * Math.max(0.25, segments.count / 4000);
    carried += rate;
    const whole = Math.floor(carried);
    carried -= whole;
    position = Math.min(segments.count, position + whole);
    if (position >= segments.count) playing = false;
    showStep(!playing);
    draw();
    if (playing) requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
}

function showEmpty(reason: string, name: string): void {
  data = undefined;
  segments = undefined;
  transform = undefined;
  playing = false;
  emptyBox.style.display = 'flex';
  emptyReason.textContent = reason.charAt(0).toUpperCase() + reason.slice(1) + (/[\u3000-\u9fff]$/u.test(reason) ? '。' : '.');
  summary.textContent = say(words.nothingToDraw, name);
  summary.title = reason;
  notesList.replaceChildren();
  canvas.dataset.empty = '1';
  canvas.dataset.segments = '0';
  context.clearRect(0, 0, canvas.clientWidth, canvas.clientHeight);
}

window.addEventListener('message', (event: MessageEvent<Incoming>) => {
  const message = event.data;
  if (message.type === 'data' || message.type === 'empty') words = wordsOf(message.words);
  if (message.type === 'data') {
    const lathe = message.data.lathe;
    // Another program, or the same one read on another machine: its own view, fitted.
    const first = data === undefined || message.title !== title || lathe !== data.lathe;
    let unpacked: Segments;
    try {
      unpacked = toSegments(message.data);
    } catch (err) {
      summary.textContent = `${message.title}: ${err instanceof Error ? err.message : String(err)}`;
      return;
    }
    const wasAtEnd = first || segments === undefined || position >= segments.count;
    data = message.data;
    segments = unpacked;
    title = message.title;
    steps = blockSteps(segments);
    byLine = segmentsByLine(segments);
    blockTexts.clear();
    emptyBox.style.display = 'none';
    canvas.dataset.empty = '0';
    canvas.dataset.segments = String(segments.count);
    canvas.dataset.units = unitsLabel();
    xModeGroup.style.display = lathe ? '' : 'none';
    if (wasAtEnd) position = segments.count;
    position = Math.min(position, segments.count);
    if (first) {
      view = lathe ? 'XZ' : 'XY';
      viewSelect.value = view;
      refit();
    } else {
      draw(); // the user's pan and zoom stay as they are while the program is edited
    }
    showNotes();
    showStep(false);
  } else if (message.type === 'empty') {
    showEmpty(message.reason, message.title);
  } else if (message.type === 'error') {
    summary.textContent = message.message;
    summary.title = message.message;
  } else if (message.type === 'cursor') {
    cursorLine = message.line;
    // While the program is played back, the tool goes to the cursor's block.
    if (segments !== undefined && position < segments.count && !playing) {
      position = positionAtLine(segments, steps, position, message.line);
      showStep(false);
    }
    draw();
  } else if (message.type === 'blockText') {
    blockTexts.set(`${message.path ?? ''}:${message.line}`, message.text);
    if (hovered >= 0 && segments !== undefined && segments.line[hovered] === message.line) showTooltip(hovered);
  }
});

let tooltipAt: [number, number] = [0, 0];

function showTooltip(index: number): void {
  if (segments === undefined || data === undefined) return;
  const path = segments.path[index]!;
  const key = `${path === 0 ? '' : data.paths[path]}:${segments.line[index]}`;
  const text = blockTexts.get(key);
  if (text === undefined) {
    vscode.postMessage(path === 0 ? { type: 'blockText', line: segments.line[index] } : { type: 'blockText', line: segments.line[index], path: data.paths[path] });
  }
  tooltipBox.textContent = tooltipLines(segments, data, index, text, words).join('\n');
  tooltipBox.style.display = 'block';
  const stage = canvas.getBoundingClientRect();
  const [x, y] = tooltipAt;
  const left = Math.min(x + 14, stage.width - tooltipBox.offsetWidth - 4);
  const top = y + 18 + tooltipBox.offsetHeight > stage.height ? y - tooltipBox.offsetHeight - 8 : y + 18;
  tooltipBox.style.left = `${Math.max(0, left)}px`;
  tooltipBox.style.top = `${Math.max(0, top)}px`;
  canvas.dataset.tooltipLine = String(segments.line[index]! + 1);
}

function hideTooltip(): void {
  hovered = -1;
  tooltipBox.style.display = 'none';
  canvas.dataset.tooltipLine = '';
}

let hoverPending = false;
function hover(x: number, y: number): void {
  tooltipAt = [x, y];
  if (transform !== undefined) {
    const [h, v] = toWorld(transform, x, y);
    const text = readout(currentAxes(), h, v, inch());
    readoutBox.textContent = text;
    canvas.dataset.readout = text;
  }
  if (hoverPending) return;
  hoverPending = true;
  requestAnimationFrame(() => {
    hoverPending = false;
    if (segments === undefined || transform === undefined) return;
    const [hx, hy] = tooltipAt;
    const hit = hitTest(segments, currentProjection(), transform, hx, hy);
    if (hit < 0) {
      hideTooltip();
      return;
    }
    hovered = hit;
    showTooltip(hit);
  });
}

// Pointer: drag pans (orbits in 3D; shift-drag pans there), the wheel zooms about the pointer,
// a click without a drag reveals the block of the segment under it.
let dragFrom: [number, number] | undefined;
let dragged = false;
// A press on the canvas does not focus the view: a click reveals a block, and the editor is to
// have the focus then. The view's focus, when it came after the reveal, kept the keyboard and the
// status bar's "Ln" from the editor (the browser test saw it on a loaded machine).
canvas.addEventListener('mousedown', (event) => event.preventDefault());
canvas.addEventListener('pointerdown', (event) => {
  dragFrom = [event.offsetX, event.offsetY];
  dragged = false;
  canvas.setPointerCapture(event.pointerId);
});
canvas.addEventListener('pointermove', (event) => {
  if (dragFrom === undefined || transform === undefined) {
    hover(event.offsetX, event.offsetY);
    return;
  }
  const dx = event.offsetX - dragFrom[0];
  const dy = event.offsetY - dragFrom[1];
  if (!dragged && Math.hypot(dx, dy) < 3) return;
  dragged = true;
  hideTooltip();
  dragFrom = [event.offsetX, event.offsetY];
  if (view === '3D' && !event.shiftKey) {
    yaw += dx * 0.01;
    pitch = Math.max(-Math.PI / 2, Math.min(Math.PI / 2, pitch + dy * 0.01));
  } else {
    transform = pan(transform, dx, dy);
  }
  draw();
});
canvas.addEventListener('pointerleave', () => {
  hideTooltip();
  readoutBox.textContent = '';
});
canvas.addEventListener('pointerup', (event) => {
  canvas.releasePointerCapture(event.pointerId);
  const click = !dragged;
  dragFrom = undefined;
  if (!click || segments === undefined || transform === undefined || data === undefined) return;
  const hit = hitTest(segments, currentProjection(), transform, event.offsetX, event.offsetY);
  if (hit < 0) return;
  // Path 0 is the view's own document; another is a called program's file (its URI).
  const path = segments.path[hit]!;
  vscode.postMessage(
    path === 0 ? { type: 'reveal', line: segments.line[hit] } : { type: 'reveal', line: segments.line[hit], path: data.paths[path] },
  );
});
canvas.addEventListener(
  'wheel',
  (event) => {
    if (transform === undefined) return;
    event.preventDefault();
    transform = zoomAt(transform, event.offsetX, event.offsetY, Math.exp(-event.deltaY * 0.0015));
    draw();
  },
  { passive: false },
);
fitButton.addEventListener('click', refit);
viewSelect.addEventListener('change', () => {
  view = viewSelect.value as ViewName;
  refit();
});
xModeSelect.addEventListener('change', () => {
  xMode = xModeSelect.value as XMode;
  showNotes();
  draw();
});
element<HTMLButtonElement>('start').addEventListener('click', () => {
  playing = false;
  stepTo(0, false);
});
element<HTMLButtonElement>('back').addEventListener('click', () => {
  playing = false;
  stepBack();
});
element<HTMLButtonElement>('next').addEventListener('click', () => {
  playing = false;
  stepForward();
});
element<HTMLButtonElement>('end').addEventListener('click', () => {
  playing = false;
  if (segments !== undefined) stepTo(segments.count, false);
});
playButton.addEventListener('click', play);
window.addEventListener('keydown', (event) => {
  if (event.target instanceof HTMLSelectElement) return;
  if (event.key === ' ') play();
  else if (event.key === 'ArrowRight') stepForward();
  else if (event.key === 'ArrowLeft') stepBack();
  else return;
  event.preventDefault();
});
// The canvas's size follows the view's and the status area's (whose notes change its height):
// its pixels are sized again whenever its box changes.
new ResizeObserver(() => {
  resize();
  draw();
}).observe(canvas);
// VS Code changes the body's class with the theme: the canvas's colours are read again.
new MutationObserver(() => {
  colours = readColours();
  draw();
}).observe(document.body, { attributes: true, attributeFilter: ['class'] });

// For the browser test: where a block's first segment is on the screen, in page pixels.
(window as unknown as { toolpathProbe: unknown }).toolpathProbe = {
  segmentOfLine(line: number): { x: number; y: number } | null {
    if (segments === undefined || transform === undefined) return null;
    const first = byLine.get(line)?.[0];
    if (first === undefined) return null;
    const middle = segmentMiddle(segments, currentProjection(), transform, first);
    if (middle === null) return null;
    const box = canvas.getBoundingClientRect();
    return { x: box.left + middle[0], y: box.top + middle[1] };
  },
  /** The 1-based line of the block the playback is at (0 before the first). */
  stepLine(): number {
    const step = currentStep();
    return step < 0 || segments === undefined ? 0 : segments.line[steps[step]!]! + 1;
  },
  /** The share of the room inside the margins the drawing's box fills, across and up. */
  fill(): [number, number] | null {
    if (segments === undefined || transform === undefined) return null;
    const project = currentProjection();
    const m = margins();
    let lo = [Infinity, Infinity];
    let hi = [-Infinity, -Infinity];
    const xyz = segments.xyz;
    for (let o = 0; o < xyz.length; o += 3) {
      const [h, v] = project(xyz[o]!, xyz[o + 1]!, xyz[o + 2]!);
      if (Number.isNaN(h + v)) continue;
      const [x, y] = toScreen(transform, h, v);
      lo = [Math.min(lo[0]!, x), Math.min(lo[1]!, y)];
      hi = [Math.max(hi[0]!, x), Math.max(hi[1]!, y)];
    }
    return [(hi[0]! - lo[0]!) / (transform.width - m.left - m.right), (hi[1]! - lo[1]!) / (transform.height - m.top - m.bottom)];
  },
};

resize();
vscode.postMessage({ type: 'ready' });
