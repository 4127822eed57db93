// The Toolpath view's geometry, free of the DOM so that node's tests run it: the segments the
// server sends (ide/toolpath_view.py), their projection on a plane or an orbiting camera, the
// view transform, the level of detail and the hit test.

/** What the server's `fanuc-macro.toolpath` command answers. */
export interface ToolpathData {
  lathe: boolean;
  units: string;
  kinds: string[];
  paths: string[];
  segments: {
    kind: number[];
    line: number[];
    path: number[];
    start: (number | null)[];
    end: (number | null)[];
  };
  lost: { line: number; path: number; axes: string[]; reason: string }[];
  truncated: boolean;
}

export type ViewName = 'XZ' | 'XY' | 'YZ' | '3D';

/** The segments as typed arrays; an unknown coordinate is NaN. */
export interface Segments {
  count: number;
  kind: Uint8Array;
  line: Int32Array;
  path: Uint16Array;
  /** x, y, z of the start then of the end: 6 numbers per segment. */
  xyz: Float64Array;
}

export function toSegments(data: ToolpathData): Segments {
  const s = data.segments;
  const count = s.kind.length;
  const xyz = new Float64Array(count * 6);
  for (let i = 0; i < count; i++) {
    for (let k = 0; k < 3; k++) {
      xyz[i * 6 + k] = s.start[i * 3 + k] ?? Number.NaN;
      xyz[i * 6 + 3 + k] = s.end[i * 3 + k] ?? Number.NaN;
    }
  }
  return {
    count,
    kind: Uint8Array.from(s.kind),
    line: Int32Array.from(s.line),
    path: Uint16Array.from(s.path),
    xyz,
  };
}

/** Where a point of the world goes across (h) and up (v) in a view. */
export interface Projection {
  (x: number, y: number, z: number): [number, number];
}

/**
 * A lathe is drawn Z across and X up (as the SVG backplot); a mill's planes are seen from +Z,
 * -Y and +X. The 3D view orbits: `yaw` turns about the vertical axis (Z on a mill, X on a
 * lathe), `pitch` lifts the eye (0: seen from the front, 90 degrees: from above).
 */
export function projection(view: ViewName, lathe: boolean, yaw = 0, pitch = 0): Projection {
  if (view === '3D') {
    const ca = Math.cos(yaw);
    const sa = Math.sin(yaw);
    const cb = Math.cos(pitch);
    const sb = Math.sin(pitch);
    return (x, y, z) => {
      // A lathe's world: Z across, Y into the picture, X up; an unknown Y is the centre line.
      const wx = lathe ? z : x;
      const wy = Number.isNaN(y) ? 0 : y;
      const wz = lathe ? x : z;
      const h = wx * ca + wy * sa;
      const depth = -wx * sa + wy * ca;
      return [h, wz * cb + depth * sb];
    };
  }
  if (lathe && view === 'XZ') return (x, _y, z) => [z, x];
  if (view === 'XY') return (x, y) => [x, y];
  if (view === 'XZ') return (x, _y, z) => [x, z];
  return (_x, y, z) => [y, z];
}

/** World (h, v) to screen pixels: one scale for both axes, v drawn upwards. */
export interface Transform {
  scale: number;
  /** The world point at the centre of the screen. */
  centreH: number;
  centreV: number;
  width: number;
  height: number;
}

export function toScreen(t: Transform, h: number, v: number): [number, number] {
  return [(h - t.centreH) * t.scale + t.width / 2, (t.centreV - v) * t.scale + t.height / 2];
}

export function toWorld(t: Transform, px: number, py: number): [number, number] {
  return [(px - t.width / 2) / t.scale + t.centreH, t.centreV - (py - t.height / 2) / t.scale];
}

/** The transform that shows every placed segment, with a margin. */
export function fit(segments: Segments, project: Projection, width: number, height: number): Transform {
  let hMin = Infinity;
  let hMax = -Infinity;
  let vMin = Infinity;
  let vMax = -Infinity;
  const xyz = segments.xyz;
  for (let i = 0; i < segments.count * 2; i++) {
    const [h, v] = project(xyz[i * 3]!, xyz[i * 3 + 1]!, xyz[i * 3 + 2]!);
    if (Number.isNaN(h) || Number.isNaN(v)) continue;
    if (h < hMin) hMin = h;
    if (h > hMax) hMax = h;
    if (v < vMin) vMin = v;
    if (v > vMax) vMax = v;
  }
  if (hMin > hMax) return { scale: 1, centreH: 0, centreV: 0, width, height };
  const span = Math.max(hMax - hMin, vMax - vMin) || 1;
  const spanH = Math.max(hMax - hMin, span / 1000);
  const spanV = Math.max(vMax - vMin, span / 1000);
  const scale = 0.9 * Math.min(width / spanH, height / spanV);
  return { scale, centreH: (hMin + hMax) / 2, centreV: (vMin + vMax) / 2, width, height };
}

/** Zoom by `factor` about the screen point (px, py), which stays where it is. */
export function zoomAt(t: Transform, px: number, py: number, factor: number): Transform {
  const [h, v] = toWorld(t, px, py);
  const scale = t.scale * factor;
  return {
    ...t,
    scale,
    centreH: h - (px - t.width / 2) / scale,
    centreV: v + (py - t.height / 2) / scale,
  };
}

export function pan(t: Transform, dx: number, dy: number): Transform {
  return { ...t, centreH: t.centreH - dx / t.scale, centreV: t.centreV + dy / t.scale };
}

/** Something that takes a polyline's pieces: a canvas Path2D, or a test's recorder. */
export interface PathSink {
  moveTo(x: number, y: number): void;
  lineTo(x: number, y: number): void;
}

/**
 * Sends the segments of each kind to its sink, in screen pixels, leaving out what would not
 * show: a segment off the screen, and a point less than `minPixels` from the last one drawn
 * (200,000 segments of a CAM file at full view are mostly that). Returns how many pieces were
 * sent, the level of detail's measure.
 */
export function trace(
  segments: Segments,
  project: Projection,
  t: Transform,
  sinks: PathSink[],
  minPixels = 0.75,
): number {
  const xyz = segments.xyz;
  const last = new Float64Array(sinks.length * 2).fill(Number.NaN);
  const min2 = minPixels * minPixels;
  let sent = 0;
  const w = t.width;
  const hgt = t.height;
  for (let i = 0; i < segments.count; i++) {
    const kind = segments.kind[i]!;
    const sink = sinks[kind];
    if (sink === undefined) continue;
    const o = i * 6;
    const [h0, v0] = project(xyz[o]!, xyz[o + 1]!, xyz[o + 2]!);
    const [h1, v1] = project(xyz[o + 3]!, xyz[o + 4]!, xyz[o + 5]!);
    if (Number.isNaN(h0 + v0 + h1 + v1)) continue;
    const [x0, y0] = toScreen(t, h0, v0);
    const [x1, y1] = toScreen(t, h1, v1);
    if ((x0 < 0 && x1 < 0) || (x0 > w && x1 > w) || (y0 < 0 && y1 < 0) || (y0 > hgt && y1 > hgt)) {
      last[kind * 2] = Number.NaN;
      continue;
    }
    const lx = last[kind * 2]!;
    const ly = last[kind * 2 + 1]!;
    const joined = (lx - x0) ** 2 + (ly - y0) ** 2 <= min2;
    if (!joined) {
      sink.moveTo(x0, y0);
      last[kind * 2] = x0;
      last[kind * 2 + 1] = y0;
      sent++;
    }
    if ((last[kind * 2]! - x1) ** 2 + (last[kind * 2 + 1]! - y1) ** 2 > min2) {
      sink.lineTo(x1, y1);
      last[kind * 2] = x1;
      last[kind * 2 + 1] = y1;
      sent++;
    }
  }
  return sent;
}

function distanceToSegment(px: number, py: number, x0: number, y0: number, x1: number, y1: number): number {
  const dx = x1 - x0;
  const dy = y1 - y0;
  const length2 = dx * dx + dy * dy;
  const f = length2 === 0 ? 0 : Math.max(0, Math.min(1, ((px - x0) * dx + (py - y0) * dy) / length2));
  return Math.hypot(px - (x0 + f * dx), py - (y0 + f * dy));
}

/** The segment nearest the screen point, within `tolerance` pixels; -1 when none is. */
export function hitTest(
  segments: Segments,
  project: Projection,
  t: Transform,
  px: number,
  py: number,
  tolerance = 6,
): number {
  let best = -1;
  let bestDistance = tolerance;
  const xyz = segments.xyz;
  for (let i = 0; i < segments.count; i++) {
    const o = i * 6;
    const [h0, v0] = project(xyz[o]!, xyz[o + 1]!, xyz[o + 2]!);
    const [h1, v1] = project(xyz[o + 3]!, xyz[o + 4]!, xyz[o + 5]!);
    if (Number.isNaN(h0 + v0 + h1 + v1)) continue;
    const [x0, y0] = toScreen(t, h0, v0);
    const [x1, y1] = toScreen(t, h1, v1);
    const d = distanceToSegment(px, py, x0, y0, x1, y1);
    if (d <= bestDistance) {
      best = i;
      bestDistance = d;
    }
  }
  return best;
}

/** The segments of each source line, for highlighting the cursor's block. */
export function segmentsByLine(segments: Segments, path = 0): Map<number, number[]> {
  const byLine = new Map<number, number[]>();
  for (let i = 0; i < segments.count; i++) {
    if (segments.path[i] !== path) continue;
    const line = segments.line[i]!;
    let list = byLine.get(line);
    if (list === undefined) {
      list = [];
      byLine.set(line, list);
    }
    list.push(i);
  }
  return byLine;
}

/** The middle of a segment on the screen (where a test clicks), or null if it is not placed. */
export function segmentMiddle(
  segments: Segments,
  project: Projection,
  t: Transform,
  index: number,
): [number, number] | null {
  const xyz = segments.xyz;
  const o = index * 6;
  const [h0, v0] = project(xyz[o]!, xyz[o + 1]!, xyz[o + 2]!);
  const [h1, v1] = project(xyz[o + 3]!, xyz[o + 4]!, xyz[o + 5]!);
  if (Number.isNaN(h0 + v0 + h1 + v1)) return null;
  return toScreen(t, (h0 + h1) / 2, (v0 + v1) / 2);
}
