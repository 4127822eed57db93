import assert from 'node:assert/strict';
import { describe, it } from 'node:test';
import {
  fit,
  hitTest,
  pan,
  projection,
  segmentMiddle,
  segmentsByLine,
  toScreen,
  decodeBase64,
  toSegments,
  toWorld,
  trace,
  zoomAt,
  type PathSink,
  type ToolpathData,
  VIEW_FORMAT,
} from '../webview/toolpathGeometry';
import { TOOLPATH_FORMAT, toolpathError, toolpathHtml } from '../src/toolpathView';
import { LATHE, b64, packed } from './toolpathFixtures';

/** The first G92 pass of O3331 as the server sends it: X as a radius (51 / 2, 49.816 / 2). */
function g92(): ToolpathData {
  const p = (x: number, z: number): (number | null)[] => [x, null, z];
  // Infeed, thread, retract, return: four segments joined through five points.
  const points = [...p(25.5, 5.964), ...p(24.908, 5.964), ...p(24.908, -54.036), ...p(25.5, -54.036), ...p(25.5, 5.964)];
  return packed(LATHE, [0, 2, 0, 0], [40, 40, 40, 41], [0, 0, 0, 0], points, [0, 1, 2, 3]);
}

class Recorder implements PathSink {
  pieces: string[] = [];
  moveTo(x: number, y: number): void {
    this.pieces.push(`M${x.toFixed(1)},${y.toFixed(1)}`);
  }
  lineTo(x: number, y: number): void {
    this.pieces.push(`L${x.toFixed(1)},${y.toFixed(1)}`);
  }
}

describe('the packed segments', () => {
  it('decodes base64 into typed arrays over their own buffers', () => {
    const segments = toSegments(g92());
    assert.equal(segments.count, 4);
    assert.deepEqual([...segments.kind], [0, 2, 0, 0]);
    assert.deepEqual([...segments.line], [40, 40, 40, 41]);
    assert.deepEqual([...segments.point], [0, 1, 2, 3]);
    assert.equal(segments.xyz.length, 15);
    // The thread's start and end, Y unknown (NaN) on the lathe.
    const o = segments.point[1]! * 3;
    assert.deepEqual([segments.xyz[o], segments.xyz[o + 2], segments.xyz[o + 3], segments.xyz[o + 5]], [24.908, 5.964, 24.908, -54.036]);
    assert.ok(Number.isNaN(segments.xyz[o + 1]!));
    // float64 keeps a tenth of a micron at ten metres.
    const far = toSegments(packed(LATHE, [1], [0], [0], [9999.9999, 0, -9999.9999, 9999.9998, 0, 0], [0]));
    assert.deepEqual([...far.xyz.subarray(0, 4)], [9999.9999, 0, -9999.9999, 9999.9998]);
    // A text of 7 bytes: an odd length, still decoded from offset 0 of its own buffer.
    const odd = decodeBase64(Buffer.from([1, 2, 3, 4, 5, 6, 7]).toString('base64'));
    assert.deepEqual([...new Uint8Array(odd)], [1, 2, 3, 4, 5, 6, 7]);
  });
  it('refuses arrays that do not fit together and another format', () => {
    const good = g92();
    const short = { ...good, segments: { ...good.segments, line: b64(Int32Array.from([40, 40, 40])) } };
    assert.throws(() => toSegments(short), /do not match its 4 segments/);
    const torn = { ...good, points: good.points.slice(0, 8) }; // 6 bytes: not a float64
    assert.throws(() => toSegments(torn), /cut short/);
    const beyond = { ...good, segments: { ...good.segments, point: b64(Int32Array.from([0, 1, 2, 4])) } };
    assert.throws(() => toSegments(beyond), /segment 3 has no point 4/);
    assert.throws(() => toSegments({ ...good, format: 1 }), /format 1/);
    assert.equal(TOOLPATH_FORMAT, VIEW_FORMAT);
    const lists = { segments: { kind: [0], line: [1], path: [0], start: [0, 0, 0], end: [1, 0, 0] } };
    assert.match(toolpathError(lists) ?? '', /format 1, this view reads 3/);
  });
});

describe('projection', () => {
  it('draws a lathe Z across and X up, a mill in its planes', () => {
    assert.deepEqual(projection('XZ', true)(25, Number.NaN, -3), [-3, 25]);
    assert.deepEqual(projection('XY', false)(1, 2, 3), [1, 2]);
    assert.deepEqual(projection('XZ', false)(1, 2, 3), [1, 3]);
    assert.deepEqual(projection('YZ', false)(1, 2, 3), [2, 3]);
  });
  it('orbits: seen from the front at pitch 0, from above at 90 degrees', () => {
    const [h, v] = projection('3D', false, 0, 0)(1, 2, 3);
    assert.equal(h, 1);
    assert.equal(v, 3);
    const [h2, v2] = projection('3D', false, 0, Math.PI / 2)(1, 2, 3);
    assert.ok(Math.abs(h2 - 1) < 1e-12 && Math.abs(v2 - 2) < 1e-12);
  });
});

describe('transform', () => {
  it('fits every segment in the screen with one scale', () => {
    const segments = toSegments(g92());
    const t = fit(segments, projection('XZ', true), 1000, 500);
    for (let i = 0; i < segments.count; i++) {
      const middle = segmentMiddle(segments, projection('XZ', true), t, i);
      assert.ok(middle !== null);
      assert.ok(middle[0] >= 0 && middle[0] <= 1000 && middle[1] >= 0 && middle[1] <= 500);
    }
    // 60 mm of Z fill 94% of the width.
    assert.ok(Math.abs(t.scale * 60 - 940) < 1e-6);
  });
  it('keeps the pointer on the same world point when zooming, and pans by pixels', () => {
    const t = { scale: 2, centreH: 0, centreV: 0, width: 100, height: 100 };
    const before = toWorld(t, 30, 70);
    const zoomed = zoomAt(t, 30, 70, 3);
    const after = toWorld(zoomed, 30, 70);
    assert.ok(Math.abs(before[0] - after[0]) < 1e-9 && Math.abs(before[1] - after[1]) < 1e-9);
    const moved = pan(t, 10, -4);
    const [x, y] = toScreen(moved, 0, 0);
    assert.deepEqual([x, y], [60, 46]);
  });
});

describe('trace (level of detail)', () => {
  it('sends each kind to its own sink, joining segments that meet', () => {
    const segments = toSegments(g92());
    const t = fit(segments, projection('XZ', true), 1000, 500);
    const sinks = [new Recorder(), new Recorder(), new Recorder(), new Recorder()];
    trace(segments, projection('XZ', true), t, sinks);
    assert.equal(sinks[2]!.pieces.length, 2); // the thread: one move and one line
    assert.equal(sinks[1]!.pieces.length, 0);
    // Three rapids: the infeed, then the retract and the return joined at their corner.
    assert.equal(sinks[0]!.pieces.filter((p) => p.startsWith('M')).length, 2);
    assert.equal(sinks[0]!.pieces.filter((p) => p.startsWith('L')).length, 3);
  });
  it('leaves out what is smaller than a pixel', () => {
    const n = 10_000;
    const points: number[] = [];
    for (let i = 0; i <= n; i++) points.push(i * 0.001, 0, 0);
    const data = packed(
      { ...LATHE, lathe: false },
      new Array<number>(n).fill(1),
      new Array<number>(n).fill(1),
      new Array<number>(n).fill(0),
      points,
      Array.from({ length: n }, (_, i) => i),
    );
    const segments = toSegments(data);
    const t = { scale: 10, centreH: 5, centreV: 0, width: 200, height: 100 }; // 10 mm: 100 px
    const sink = new Recorder();
    const sent = trace(segments, projection('XY', false), t, [new Recorder(), sink]);
    assert.ok(sent < 200, `${sent} pieces for 100 pixels`);
    assert.ok(sent > 50);
  });
});

describe('hit test', () => {
  it('finds the segment under the pointer and its line', () => {
    const segments = toSegments(g92());
    const project = projection('XZ', true);
    const t = fit(segments, project, 1000, 500);
    const middle = segmentMiddle(segments, project, t, 1);
    assert.ok(middle !== null);
    assert.equal(hitTest(segments, project, t, middle[0], middle[1] + 2), 1);
    assert.equal(hitTest(segments, project, t, 5, 5), -1);
    assert.deepEqual(segmentsByLine(segments).get(40), [0, 1, 2]);
  });
});

describe('the view page', () => {
  it('tells errors from data', () => {
    assert.equal(toolpathError({ error: 'the program makes no move: nothing to plot' }), 'the program makes no move: nothing to plot');
    assert.equal(toolpathError(null), 'the server gave no toolpath');
    assert.equal(toolpathError(g92()), undefined);
  });
  it('allows only its own script and styles', () => {
    const html = toolpathHtml('https://webview/toolpath.js', 'https://webview');
    assert.match(html, /default-src 'none'/);
    const nonce = /script-src 'nonce-([A-Za-z0-9]+)'/.exec(html)?.[1];
    assert.ok(nonce !== undefined);
    assert.ok(html.includes(`<script nonce="${nonce}" src="https://webview/toolpath.js">`));
    assert.ok(!/ style="/.test(html), 'inline style attributes are blocked by the policy');
  });
});
