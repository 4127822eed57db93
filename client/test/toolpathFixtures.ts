// The Toolpath view's answers as the server packs them (ide/toolpath_view.py), for the tests.
import { VIEW_FORMAT, type ToolpathData } from '../webview/toolpathGeometry';

/** Base64 of a typed array's bytes, as the server writes it (little-endian, as node's are). */
export function b64(array: Uint8Array | Uint16Array | Int32Array | Float64Array): string {
  return Buffer.from(array.buffer, array.byteOffset, array.byteLength).toString('base64');
}

export type Base = Omit<ToolpathData, 'count' | 'points' | 'segments' | 'codes' | 'blocks'>;

/** A motion record of the answer's `blocks`: its code, F and S (NaN: not known). */
export interface Record {
  code: string;
  feed: number;
  speed: number;
  surface?: boolean;
}

/**
 * The answer of segments given as lists: per segment its kind, line, file and start point, the
 * points' x, y, z (null unknown), and per segment its motion record in `records` (-1 none).
 */
export function packed(
  base: Base,
  kind: number[],
  line: number[],
  path: number[],
  points: (number | null)[],
  point: number[],
  motion: number[] = kind.map(() => -1),
  records: Record[] = [],
): ToolpathData {
  const codes = [...new Set(records.map((r) => r.code))];
  return {
    ...base,
    count: kind.length,
    points: b64(Float64Array.from(points, (v) => v ?? Number.NaN)),
    segments: {
      kind: b64(Uint8Array.from(kind)),
      line: b64(Int32Array.from(line)),
      path: b64(Uint16Array.from(path)),
      point: b64(Int32Array.from(point)),
      motion: b64(Int32Array.from(motion)),
    },
    codes,
    blocks: {
      code: b64(Uint16Array.from(records, (r) => codes.indexOf(r.code))),
      feed: b64(Float64Array.from(records, (r) => r.feed)),
      speed: b64(Float64Array.from(records, (r) => r.speed)),
      surface: b64(Uint8Array.from(records, (r) => (r.surface ? 1 : 0))),
    },
  };
}

export const LATHE: Base = {
  format: VIEW_FORMAT,
  lathe: true,
  units: 'mm',
  units_stated: true,
  units_note: '',
  kinds: ['rapid', 'feed', 'thread', 'arc'],
  paths: ['file:///o3331.nc'],
  lost: [],
  truncated: false,
  stopped: '',
  stock: null,
  tool: null,
  threads: [],
};
