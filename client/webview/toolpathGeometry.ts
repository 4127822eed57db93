// The Toolpath view's geometry, free of the DOM so that node's tests run it: the segments the
// server sends (ide/toolpath_view.py), their projection on a plane or an orbiting camera, the
// view transform, the level of detail and the hit test.

/** The layout of the server's answer this view reads (ide/toolpath_view.py VIEW_FORMAT). */
export const VIEW_FORMAT = 3;

/**
 * What the server's `fanuc-macro.toolpath` command answers. The arrays are base64 of
 * little-endian typed arrays: `points` float64 x, y, z per point (NaN unknown); per segment
 * `kind` uint8 (indexes `kinds`), `line` int32 (0-based), `path` uint16 (indexes `paths`) and
 * `point` int32, the segment's start point (its end is the next point), `motion` int32, its
 * motion record (-1 none). Per motion record (`blocks`): `code` uint16 (indexes `codes`), `feed`
 * and `speed` float64 (NaN not known), `surface` uint8 (1: the speed is G96's surface speed).
 */
export interface ToolpathData {
  format: number;
  lathe: boolean;
  units: string;
  /** The program has G20 or G21; else `units_note` says why the unit is assumed. */
  units_stated: boolean;
  units_note: string;
  kinds: string[];
  paths: string[];
  count: number;
  points: string;
  segments: {
    kind: string;
    line: string;
    path: string;
    point: string;
    motion: string;
  };
  codes: string[];
  blocks: { code: string; feed: string; speed: string; surface: string };
  lost: { line: number; path: number; axes: string[]; reason: string }[];
  truncated: boolean;
  stopped: string;
  /** A lathe's bar: its diameter from Z `front` to `back`. */
  stock: { diameter: number; front: number; back: number; source: string; line: number } | null;
  tool: { radius: number; angle: number; source: string; line: number } | null;
  threads: ToolpathThread[];
}

/** A thread's simulated cross-section over one lead: (offset along the lead, radius) pairs. */
export interface ToolpathThread {
  name: string;
  line: number;
  internal: boolean;
  pitch: number | null;
  major: number | null;
  passes: number;
  profile: [number, number][];
  band: [number, number] | null;
}

/** Per motion record: what a segment's tooltip says of its block. */
export interface Blocks {
  code: Uint16Array;
  feed: Float64Array;
  speed: Float64Array;
  surface: Uint8Array;
}

export type ViewName = 'XZ' | 'XY' | 'YZ' | '3D';

/** The segments as typed arrays; an unknown coordinate is NaN. */
export interface Segments {
  count: number;
  kind: Uint8Array;
  line: Int32Array;
  path: Uint16Array;
  /** Each segment's start point in `xyz` (an index of points); its end is the next point. */
  point: Int32Array;
  /** Each segment's motion record (an index of `blocks`; -1 none). */
  motion: Int32Array;
  blocks: Blocks;
  /** x, y, z per point. */
  xyz: Float64Array;
}

const LITTLE_ENDIAN = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

/** The bytes of a base64 text, in a buffer of their own (so aligned for any typed array). */
export function decodeBase64(text: string): ArrayBuffer {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

type Typed = Uint8Array | Uint16Array | Int32Array | Float64Array;

function unpack<T extends Typed>(
  text: string,
  make: (buffer: ArrayBuffer) => T,
  read: (view: DataView, offset: number) => number,
  name: string,
): T {
  const buffer = decodeBase64(text);
  const array = make(buffer);
  if (array.byteLength !== buffer.byteLength) throw new Error(`the toolpath's ${name} is cut short`);
  if (!LITTLE_ENDIAN && array.BYTES_PER_ELEMENT > 1) {
    const view = new DataView(buffer.slice(0));
    for (let i = 0; i < array.length; i++) array[i] = read(view, i * array.BYTES_PER_ELEMENT);
  }
  return array;
}

/** The answer's arrays as typed arrays; throws when they do not fit together. */
export function toSegments(data: ToolpathData): Segments {
  if (data.format !== VIEW_FORMAT) throw new Error(`the server's toolpath is of format ${data.format}, the view reads ${VIEW_FORMAT}`);
  const s = data.segments;
  const length = (buffer: ArrayBuffer, size: number): number => Math.floor(buffer.byteLength / size);
  const kind = unpack(s.kind, (b) => new Uint8Array(b), (v, o) => v.getUint8(o), 'kinds');
  const line = unpack(s.line, (b) => new Int32Array(b, 0, length(b, 4)), (v, o) => v.getInt32(o, true), 'lines');
  const path = unpack(s.path, (b) => new Uint16Array(b, 0, length(b, 2)), (v, o) => v.getUint16(o, true), 'paths');
  const point = unpack(s.point, (b) => new Int32Array(b, 0, length(b, 4)), (v, o) => v.getInt32(o, true), 'points');
  const xyz = unpack(data.points, (b) => new Float64Array(b, 0, length(b, 8)), (v, o) => v.getFloat64(o, true), 'positions');
  const motion = unpack(s.motion, (b) => new Int32Array(b, 0, length(b, 4)), (v, o) => v.getInt32(o, true), 'motions');
  const b = data.blocks;
  const blocks: Blocks = {
    code: unpack(b.code, (x) => new Uint16Array(x, 0, length(x, 2)), (v, o) => v.getUint16(o, true), 'codes'),
    feed: unpack(b.feed, (x) => new Float64Array(x, 0, length(x, 8)), (v, o) => v.getFloat64(o, true), 'feeds'),
    speed: unpack(b.speed, (x) => new Float64Array(x, 0, length(x, 8)), (v, o) => v.getFloat64(o, true), 'speeds'),
    surface: unpack(b.surface, (x) => new Uint8Array(x), (v, o) => v.getUint8(o), 'speeds'),
  };
  const records = blocks.code.length;
  if ([blocks.feed, blocks.speed, blocks.surface].some((a) => a.length !== records)) {
    throw new Error(`the toolpath's blocks do not match its ${records} motion records`);
  }
  const count = data.count;
  if ([kind, line, path, point, motion].some((a) => a.length !== count) || xyz.length % 3 !== 0) {
    throw new Error(`the toolpath's arrays do not match its ${count} segments`);
  }
  const points = xyz.length / 3;
  for (let i = 0; i < count; i++) {
    const p = point[i]!;
    if (p < 0 || p + 1 >= points) throw new Error(`the toolpath's segment ${i} has no point ${p}`);
  }
  return { count, kind, line, path, point, motion, blocks, xyz };
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

/** Pixels at the screen's edges the fit leaves to the rulers and the insets. */
export interface Margins {
  left: number;
  right: number;
  top: number;
  bottom: number;
}

export interface FitOptions {
  margins?: Margins;
  /** Points of the world the fit shows too: the stock's corners, a lathe's centre line. */
  extra?: [number, number, number][];
  /** The share of the room inside the margins the drawing fills along its tighter axis. */
  fill?: number;
}

/**
 * The transform that shows every placed segment (and the extra points) as large as the room
 * inside the margins allows, centred in that room.
 */
export function fit(segments: Segments, project: Projection, width: number, height: number, options: FitOptions = {}): Transform {
  const margins = options.margins ?? { left: 0, right: 0, top: 0, bottom: 0 };
  const fill = options.fill ?? 0.94;
  let hMin = Infinity;
  let hMax = -Infinity;
  let vMin = Infinity;
  let vMax = -Infinity;
  const take = (x: number, y: number, z: number): void => {
    const [h, v] = project(x, y, z);
    if (Number.isNaN(h) || Number.isNaN(v)) return;
    if (h < hMin) hMin = h;
    if (h > hMax) hMax = h;
    if (v < vMin) vMin = v;
    if (v > vMax) vMax = v;
  };
  const xyz = segments.xyz;
  for (let o = 0; o < xyz.length; o += 3) take(xyz[o]!, xyz[o + 1]!, xyz[o + 2]!);
  for (const [x, y, z] of options.extra ?? []) take(x, y, z);
  if (hMin > hMax) return { scale: 1, centreH: 0, centreV: 0, width, height };
  const roomH = Math.max(1, width - margins.left - margins.right);
  const roomV = Math.max(1, height - margins.top - margins.bottom);
  const span = Math.max(hMax - hMin, vMax - vMin) || 1;
  const spanH = Math.max(hMax - hMin, span / 1000);
  const spanV = Math.max(vMax - vMin, span / 1000);
  const scale = fill * Math.min(roomH / spanH, roomV / spanV);
  // The room's centre on the screen is where the drawing's centre goes.
  const offsetX = (margins.left - margins.right) / 2;
  const offsetY = (margins.top - margins.bottom) / 2;
  return {
    scale,
    centreH: (hMin + hMax) / 2 - offsetX / scale,
    centreV: (vMin + vMax) / 2 + offsetY / scale,
    width,
    height,
  };
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
 * (200,000 segments of a CAM file at full view are mostly that); only the segments `from` up to
 * `to` (the playback's part). Returns how many pieces were sent, the level of detail's measure.
 */
export function trace(
  segments: Segments,
  project: Projection,
  t: Transform,
  sinks: PathSink[],
  minPixels = 0.75,
  from = 0,
  to = segments.count,
): number {
  const xyz = segments.xyz;
  const last = new Float64Array(sinks.length * 2).fill(Number.NaN);
  const min2 = minPixels * minPixels;
  let sent = 0;
  const w = t.width;
  const hgt = t.height;
  for (let i = Math.max(0, from); i < Math.min(to, segments.count); i++) {
    const kind = segments.kind[i]!;
    const sink = sinks[kind];
    if (sink === undefined) continue;
    const o = segments.point[i]! * 3;
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
    const o = segments.point[i]! * 3;
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
  const o = segments.point[index]! * 3;
  const [h0, v0] = project(xyz[o]!, xyz[o + 1]!, xyz[o + 2]!);
  const [h1, v1] = project(xyz[o + 3]!, xyz[o + 4]!, xyz[o + 5]!);
  if (Number.isNaN(h0 + v0 + h1 + v1)) return null;
  return toScreen(t, (h0 + h1) / 2, (v0 + v1) / 2);
}
