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
  toSegments,
  toWorld,
  trace,
  zoomAt,
  type PathSink,
  type ToolpathData,
} from '../webview/toolpathGeometry';
import { toolpathError, toolpathHtml } from '../src/toolpathView';

/** The first G92 pass of O3331 as the server sends it: X as a radius (51 / 2, 49.816 / 2). */
function g92(): ToolpathData {
  const p = (x: number, z: number): (number | null)[] => [x, null, z];
  return {
    lathe: true,
    units: 'mm',
    kinds: ['rapid', 'feed', 'thread', 'arc'],
    paths: ['file:///o3331.nc'],
    segments: {
      kind: [0, 2, 0, 0],
      line: [40, 40, 40, 41],
      path: [0, 0, 0, 0],
      start: [...p(25.5, 5.964), ...p(24.908, 5.964), ...p(24.908, -54.036), ...p(25.5, -54.036)],
      end: [...p(24.908, 5.964), ...p(24.908, -54.036), ...p(25.5, -54.036), ...p(25.5, 5.964)],
    },
    lost: [],
    truncated: false,
  };
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
    // 60 mm of Z fill 90% of the width.
    assert.ok(Math.abs(t.scale * 60 - 900) < 1e-6);
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
    const start: number[] = [];
    const end: number[] = [];
    for (let i = 0; i < n; i++) {
      start.push(i * 0.001, 0, 0);
      end.push((i + 1) * 0.001, 0, 0);
    }
    const data: ToolpathData = {
      ...g92(),
      lathe: false,
      segments: { kind: new Array(n).fill(1), line: new Array(n).fill(1), path: new Array(n).fill(0), start, end },
    };
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
