// The Toolpath view's page (a VS Code webview): draws the segments on a canvas, pans, zooms,
// fits and orbits; a click on a segment asks the extension to reveal its block, and the
// extension's cursor highlights the segments of the block it is on.
import {
  fit,
  hitTest,
  pan,
  projection,
  segmentMiddle,
  segmentsByLine,
  toScreen,
  toSegments,
  trace,
  zoomAt,
  type Projection,
  type Segments,
  type ToolpathData,
  type Transform,
  type ViewName,
} from './toolpathGeometry';

interface VsCodeApi {
  postMessage(message: unknown): void;
}
declare function acquireVsCodeApi(): VsCodeApi;

type Incoming =
  | { type: 'data'; data: ToolpathData; title: string }
  | { type: 'error'; message: string }
  | { type: 'cursor'; line: number };

const vscode = acquireVsCodeApi();
const canvas = document.getElementById('toolpath') as HTMLCanvasElement;
const info = document.getElementById('info') as HTMLElement;
const viewSelect = document.getElementById('view') as HTMLSelectElement;
const fitButton = document.getElementById('fit') as HTMLButtonElement;
const context = canvas.getContext('2d') as CanvasRenderingContext2D;

// Colours of the kinds, in the order of ToolpathData.kinds (rapid, feed, thread, arc).
const STYLES: Record<string, { colour: string; dash: number[]; width: number }> = {
  rapid: { colour: '#9a9a9a', dash: [5, 4], width: 1 },
  feed: { colour: '#3b82f6', dash: [], width: 1.2 },
  thread: { colour: '#e4572e', dash: [], width: 1.6 },
  arc: { colour: '#22a05a', dash: [], width: 1.2 },
};
const HIGHLIGHT = '#ffcc00';

let data: ToolpathData | undefined;
let segments: Segments | undefined;
let byLine = new Map<number, number[]>();
let view: ViewName = 'XZ';
let yaw = -0.6;
let pitch = 0.5;
let transform: Transform | undefined;
let cursorLine = -1;
let pending = false;
let lastPieces = 0;

function currentProjection(): Projection {
  return projection(view, data?.lathe ?? true, yaw, pitch);
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
  transform = fit(segments, currentProjection(), canvas.clientWidth, canvas.clientHeight);
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
  const paths = data.kinds.map(() => new Path2D());
  lastPieces = trace(segments, project, transform, paths);
  data.kinds.forEach((kind, i) => {
    const style = STYLES[kind] ?? STYLES.feed!;
    context.strokeStyle = style.colour;
    context.lineWidth = style.width;
    context.setLineDash(style.dash);
    context.stroke(paths[i]!);
  });
  context.setLineDash([]);
  const lit = byLine.get(cursorLine) ?? [];
  if (lit.length > 0) {
    const glow = new Path2D();
    const xyz = segments.xyz;
    for (const i of lit) {
      const o = segments.point[i]! * 3;
      const [h0, v0] = project(xyz[o]!, xyz[o + 1]!, xyz[o + 2]!);
      const [h1, v1] = project(xyz[o + 3]!, xyz[o + 4]!, xyz[o + 5]!);
      if (Number.isNaN(h0 + v0 + h1 + v1)) continue;
      glow.moveTo(...toScreen(transform, h0, v0));
      glow.lineTo(...toScreen(transform, h1, v1));
    }
    context.strokeStyle = HIGHLIGHT;
    context.lineWidth = 4;
    context.stroke(glow);
  }
  canvas.dataset.highlighted = String(lit.length);
  canvas.dataset.pieces = String(lastPieces);
}

function showInfo(title: string): void {
  if (data === undefined || segments === undefined) return;
  const notes = [`${title}: ${segments.count.toLocaleString('en')} segments, ${data.units}`];
  if (data.lathe) notes.push('X shown as a radius');
  if (data.truncated) notes.push('cut short: the program makes more moves than the view keeps');
  for (const lost of data.lost.slice(0, 3)) {
    notes.push(`line ${lost.line + 1}: ${lost.axes.join(', ')} unknown (${lost.reason})`);
  }
  if (data.lost.length > 3) notes.push(`and ${data.lost.length - 3} more places where the path is not known`);
  info.textContent = notes.join(' · ');
}

window.addEventListener('message', (event: MessageEvent<Incoming>) => {
  const message = event.data;
  if (message.type === 'data') {
    const first = data === undefined;
    const lathe = message.data.lathe;
    let unpacked: Segments;
    try {
      unpacked = toSegments(message.data);
    } catch (err) {
      info.textContent = `${message.title}: ${err instanceof Error ? err.message : String(err)}`;
      return;
    }
    data = message.data;
    segments = unpacked;
    byLine = segmentsByLine(segments);
    canvas.dataset.segments = String(segments.count);
    if (first) {
      view = lathe ? 'XZ' : 'XY';
      viewSelect.value = view;
      refit();
    } else {
      draw(); // the user's pan and zoom stay as they are while the program is edited
    }
    showInfo(message.title);
  } else if (message.type === 'error') {
    info.textContent = message.message;
  } else if (message.type === 'cursor') {
    cursorLine = message.line;
    draw();
  }
});

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
  if (dragFrom === undefined || transform === undefined) return;
  const dx = event.offsetX - dragFrom[0];
  const dy = event.offsetY - dragFrom[1];
  if (!dragged && Math.hypot(dx, dy) < 3) return;
  dragged = true;
  dragFrom = [event.offsetX, event.offsetY];
  if (view === '3D' && !event.shiftKey) {
    yaw += dx * 0.01;
    pitch = Math.max(-Math.PI / 2, Math.min(Math.PI / 2, pitch + dy * 0.01));
  } else {
    transform = pan(transform, dx, dy);
  }
  draw();
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
window.addEventListener('resize', () => {
  resize();
  draw();
});

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
};

resize();
vscode.postMessage({ type: 'ready' });
