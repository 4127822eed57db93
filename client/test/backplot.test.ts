import assert from 'node:assert/strict';
import { describe, it } from 'node:test';
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
  ENGLISH_WORDS,
} from '../webview/backplot';
import { fit, projection, toScreen, toSegments, trace, type PathSink } from '../webview/toolpathGeometry';
import { toolpathHtml, toolpathMessage, toolpathWords } from '../src/toolpathView';
import { LATHE, packed } from './toolpathFixtures';

class Counter implements PathSink {
  lines = 0;
  moveTo(): void {}
  lineTo(): void {
    this.lines++;
  }
}

/** Three blocks of a lathe: a rapid (record 0), a G01 of two segments (record 1), a G01 (record 2). */
function threeBlocks(): ReturnType<typeof toSegments> {
  const p = (x: number, z: number): (number | null)[] => [x, null, z];
  const points = [...p(30, 5), ...p(25, 2), ...p(25, -10), ...p(25, -20), ...p(30, -20)];
  return toSegments(
    packed(LATHE, [0, 1, 1, 1], [3, 4, 4, 5], [0, 0, 0, 0], points, [0, 1, 2, 3], [0, 1, 1, 2], [
      { code: 'G00', feed: Number.NaN, speed: 800 },
      { code: 'G01', feed: 0.2, speed: 180, surface: true },
      { code: 'G01', feed: 0.1, speed: Number.NaN },
    ]),
  );
}

describe('grid and rulers', () => {
  it('steps by 1, 2 or 5 times a power of ten, at least the pixels asked apart', () => {
    assert.equal(niceStep(10, 56), 10); // 10 px a mm: 5.6 mm at least
    assert.equal(niceStep(1, 56), 100);
    assert.equal(niceStep(100, 56), 1);
    assert.equal(niceStep(30, 56), 2);
    assert.equal(niceStep(3000, 56), 0.02);
    // Zooming in by ten makes the step ten times finer.
    for (const scale of [0.37, 4.1, 55, 812]) {
      assert.ok(Math.abs(niceStep(scale * 10) - niceStep(scale) / 10) < 1e-12);
      assert.ok(niceStep(scale) * scale >= 56 - 1e-9);
      assert.ok(niceStep(scale) * scale < 56 * 2.5 + 1e-9);
    }
  });
  it('labels the multiples of the step in the window, with the step\'s decimals', () => {
    assert.deepEqual(ticks(-12, 31, 10), [-10, 0, 10, 20, 30]);
    assert.deepEqual(ticks(0.1, 0.45, 0.1).map((v) => tickText(v, 0.1)), ['0.1', '0.2', '0.3', '0.4']);
    assert.equal(tickText(-0.0001, 0.5), '0.0');
    assert.equal(tickText(150, 50), '150');
    assert.equal(ticks(0, 1e9, 1).length, 400); // never more than the limit
  });
  it('names the axes by the machine: a lathe Z across and X up, as a diameter or a radius', () => {
    const [across, up] = viewAxes('XZ', true, 'diameter', 'mm')!;
    assert.deepEqual([across.name, up.name, up.factor], ['Z', 'X', 2]);
    assert.equal(up.title, 'X diameter (mm)');
    assert.equal(viewAxes('XZ', true, 'radius', 'mm')![1].factor, 1);
    assert.deepEqual(viewAxes('XY', false, 'diameter', 'inch')!.map((a) => a.title), ['X (inch)', 'Y (inch)']);
    assert.deepEqual(viewAxes('YZ', false, 'radius', 'mm')!.map((a) => a.name), ['Y', 'Z']);
    assert.equal(viewAxes('3D', true, 'radius', 'mm'), null);
  });
  it('reads the mouse in the axes\' labels: a lathe\'s X as the diameter', () => {
    const axes = viewAxes('XZ', true, 'diameter', 'mm');
    assert.equal(readout(axes, -12.3456, 25, false), 'Z -12.346  X Ø50.000');
    assert.equal(readout(viewAxes('XZ', true, 'radius', 'mm'), 0, 25, false), 'Z 0.000  X 25.000');
    assert.equal(readout(viewAxes('XY', false, 'radius', 'inch'), 1, -0.00001, true), 'X 1.0000  Y 0.0000');
    assert.match(readout(null, 0, 0, false), /3D/);
  });
  it('draws a scale bar of a nice length no longer than asked', () => {
    const bar = scaleBar(3.3, 120);
    assert.equal(bar.length, 20);
    assert.ok(bar.pixels <= 120 && bar.pixels > 40);
    assert.equal(scaleBar(1000, 120).length, 0.1);
  });
});

describe('fit', () => {
  it('fills the room inside the margins along the tighter axis, centred in it', () => {
    const s = threeBlocks();
    const project = projection('XZ', true);
    const margins = { left: 60, right: 10, top: 30, bottom: 40 };
    const t = fit(s, project, 800, 400, { margins });
    // Z spans 25 mm, X 5 mm: 25 mm fill 94% of the 730 pixels across.
    assert.ok(Math.abs(t.scale * 25 - 0.94 * 730) < 1e-6);
    const [left] = toScreen(t, -20, 30);
    const [right] = toScreen(t, 5, 30);
    assert.ok(Math.abs((left + right) / 2 - (60 + 730 / 2)) < 1e-6);
    const [, top] = toScreen(t, 0, 30);
    const [, bottom] = toScreen(t, 0, 25);
    assert.ok(Math.abs((top + bottom) / 2 - (30 + 330 / 2)) < 1e-6);
  });
  it('shows the extra points too: the stock, a lathe\'s centre line', () => {
    const s = threeBlocks();
    const t = fit(s, projection('XZ', true), 800, 400, { extra: [[0, Number.NaN, 0], [40, Number.NaN, -60]] });
    const [x0, y0] = toScreen(t, -60, 0);
    const [x1, y1] = toScreen(t, 5, 40);
    for (const [x, y] of [[x0, y0], [x1, y1]] as const) assert.ok(x >= 0 && x <= 800 && y >= 0 && y <= 400);
  });
  it('sees a helix in 3D as a coil, not a line, and draws a range of the segments', () => {
    const points: number[] = [];
    const n = 144; // two turns of radius 10 going down 4
    for (let i = 0; i <= n; i++) {
      const a = (i / 72) * 2 * Math.PI;
      points.push(10 * Math.cos(a), 10 * Math.sin(a), -4 * (i / n));
    }
    const s = toSegments(
      packed({ ...LATHE, lathe: false }, new Array<number>(n).fill(3), new Array<number>(n).fill(2), new Array<number>(n).fill(0), points, Array.from({ length: n }, (_, i) => i)),
    );
    const project = projection('3D', false, -0.6, 0.5);
    const t = fit(s, project, 600, 600);
    const xs: number[] = [];
    const ys: number[] = [];
    for (let o = 0; o < s.xyz.length; o += 3) {
      const [x, y] = toScreen(t, ...project(s.xyz[o]!, s.xyz[o + 1]!, s.xyz[o + 2]!));
      xs.push(x);
      ys.push(y);
    }
    const spread = (v: number[]): number => Math.max(...v) - Math.min(...v);
    assert.ok(spread(xs) > 300 && spread(ys) > 100, `the coil spans ${spread(xs)} by ${spread(ys)} pixels`);
    const sinks = [new Counter(), new Counter(), new Counter(), new Counter()];
    trace(s, project, t, sinks, 0, 10, 20);
    assert.equal(sinks[3]!.lines, 10);
  });
});

describe('playback', () => {
  it('steps block by block: a motion record is one step, whatever its segments', () => {
    const s = threeBlocks();
    const steps = blockSteps(s);
    assert.deepEqual([...steps], [0, 1, 3, 4]);
    assert.equal(stepOf(steps, 0), 0);
    assert.equal(stepOf(steps, 1), 1);
    assert.equal(stepOf(steps, 2), 1);
    assert.equal(stepOf(steps, 3), 2);
  });
  it('goes to the cursor\'s block: its next execution, else its first, not away from a step', () => {
    // Blocks on lines 3, 4, 5, 4 (a loop runs line 4 twice), one segment each.
    const p = [0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0];
    const s = toSegments(packed({ ...LATHE, lathe: false }, [1, 1, 1, 1], [3, 4, 5, 4], [0, 0, 0, 0], p, [0, 1, 2, 3], [0, 1, 2, 3]));
    const steps = blockSteps(s);
    assert.equal(positionAtLine(s, steps, 0, 4), 2); // the first execution of line 4
    assert.equal(positionAtLine(s, steps, 3, 4), 4); // from after line 5: its second one
    assert.equal(positionAtLine(s, steps, 4, 5), 3); // none after: the first
    assert.equal(positionAtLine(s, steps, 2, 4), 2); // the playback's own block: it stays
    assert.equal(positionAtLine(s, steps, 1, 9), 1); // a line with no move
  });
  it('steps by line and file where a segment has no motion record', () => {
    const p = [0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0];
    const s = toSegments(packed({ ...LATHE, lathe: false }, [1, 1, 1], [7, 7, 8], [0, 0, 0], p, [0, 1, 2]));
    assert.deepEqual([...blockSteps(s)], [0, 2, 3]);
  });
});

describe('the tool', () => {
  const distance = (a: number[], b: number[]): number => Math.hypot(a[0]! - b[0]!, a[2]! - b[2]!);
  it('draws a lathe insert with its nose touching the point and flanks at the included angle', () => {
    const [nose, left, right] = toolOutline(true, [25, 0, -10], 0.8, 60);
    // The nose circle is of the radius, its lowest point the tool's point.
    const lowest = nose!.reduce((a, b) => (b[0] < a[0] ? b : a));
    assert.ok(distance(lowest, [25, 0, -10]) < 1e-9);
    for (const p of nose!) assert.ok(Math.abs(distance(p, [25.8, 0, -10]) - 0.8) < 1e-9);
    // Each flank leaves the circle as its tangent, 30 degrees off the X axis.
    for (const flank of [left!, right!]) {
      const [a, b] = flank;
      assert.ok(Math.abs(distance(a!, [25.8, 0, -10]) - 0.8) < 1e-9);
      const angle = Math.atan2(Math.abs(b![2] - a![2]), b![0] - a![0]);
      assert.ok(Math.abs(angle - Math.PI / 6) < 1e-9);
    }
    // Inside a bore it points up.
    const [inside] = toolOutline(true, [25, 0, -10], 0.8, 60, true);
    assert.ok(Math.max(...inside!.map((p) => p[0])) <= 25 + 1e-9);
  });
  it('draws a mill\'s cutter as a cylinder of the radius, its end at the point', () => {
    const outline = toolOutline(false, [5, 6, -2], 3, 0);
    const [bottom, top] = outline;
    for (const p of bottom!) assert.ok(Math.abs(Math.hypot(p[0] - 5, p[1] - 6) - 3) < 1e-9 && p[2] === -2);
    for (const p of top!) assert.ok(p[2] === 10);
    assert.equal(outline.length, 6);
  });
});

describe('tooltip and status', () => {
  it('says a segment\'s line, code, F and S, and the block\'s text', () => {
    const s = threeBlocks();
    const data = packed(LATHE, [0], [0], [0], [0, 0, 0, 0, 0, 0], [0]);
    const lines = tooltipLines(s, { ...data, codes: ['G00', 'G01'] }, 2, ' N40 G01 Z-20 F0.2 ');
    assert.deepEqual(lines, ['line 5 (feed)', 'N40 G01 Z-20 F0.2', 'G01 · F0.2 · S180 m/min (G96)']);
    assert.deepEqual(tooltipLines(s, { ...data, codes: ['G00', 'G01'] }, 0), ['line 4 (rapid)', 'G00 · rapid · S800 rpm']);
    assert.equal(tooltipLines(s, { ...data, codes: ['G00', 'G01'] }, 3)[1], 'G01 · F0.1 · S not known');
  });
  it('lists every caveat, the unit assumed with its reason, the stock and the tool', () => {
    const s = threeBlocks();
    const lost = Array.from({ length: 18 }, (_, i) => ({ line: i, path: 0, axes: ['X'], reason: `reason ${i}` }));
    const data = {
      ...packed(LATHE, [0], [0], [0], [0, 0, 0, 0, 0, 0], [0]),
      units_stated: false,
      units_note: 'assumed mm: the program states neither G20 nor G21',
      lost,
      truncated: true,
      stock: { diameter: 50, front: 0, back: -60, source: "the major diameter of M50x3", line: 30 },
      tool: { radius: 0.433, angle: 60, source: "the threading tool's nose radius at line 21", line: 20 },
    };
    const notes = statusNotes(data, s, 'diameter');
    assert.equal(notes[0], '4 segments, assumed mm');
    assert.ok(notes.includes('assumed mm: the program states neither G20 nor G21'));
    assert.ok(notes.some((n) => n.startsWith('stock: Ø50 from the major diameter')));
    assert.ok(notes.some((n) => n.startsWith('tool: radius 0.433')));
    assert.ok(notes.some((n) => n.startsWith('cut short')));
    for (let i = 0; i < 18; i++) assert.ok(notes.includes(`line ${i + 1}: X unknown: reason ${i}`));
    const stated = statusNotes({ ...data, units_stated: true }, s, 'radius');
    assert.equal(stated[0], '4 segments, mm');
    assert.ok(stated.includes('X shown as a radius (the program writes diameters)'));
  });
});

describe('the page\'s messages', () => {
  it('tells a program that makes no move from a failure', () => {
    const reason = 'the program makes no move: no block of it that runs moves an axis';
    assert.deepEqual(toolpathMessage({ error: reason, empty: true }, 'o1.nc'), { type: 'empty', reason, title: 'o1.nc', words: {} });
    assert.deepEqual(toolpathMessage({ error: 'fanuc-macro.toolpath failed' }, 'o1.nc'), {
      type: 'error',
      message: 'o1.nc: fanuc-macro.toolpath failed',
    });
    assert.equal(toolpathMessage(null, 'o1.nc').type, 'error');
    const data = packed(LATHE, [0], [0], [0], [0, 0, 0, 1, 0, 0], [0]);
    assert.deepEqual(toolpathMessage(data, 'o1.nc'), { type: 'data', data, title: 'o1.nc', words: {} });
  });

  it('says the notes and the labels in the words the extension sends', () => {
    // Without a bundle (the test's vscode.l10n), the extension's words are the page's English.
    assert.deepEqual(toolpathWords(), ENGLISH_WORDS);
    const chinese = wordsOf({ segments: '{0} 段，{1}', xShown: 'X 按{0}显示（程序写的是直径）', radius: '半径', extra: 1 });
    const data = packed(LATHE, [0], [0], [0], [0, 0, 0, 0, 0, 0], [0]);
    const notes = statusNotes({ ...data, units_stated: true }, threeBlocks(), 'radius', chinese);
    assert.equal(notes[0], '4 段，mm');
    assert.equal(notes[1], 'X 按半径显示（程序写的是直径）');
    assert.equal(say('line {0}: {1}{2}', 3, 'X ', '?'), 'line 3: X ?');
    const html = toolpathHtml('https://webview/toolpath.js', 'https://webview', (text) => (text === 'Fit' ? '适应' : text));
    assert.match(html, /<button id="fit" [^>]*>适应<\/button>/);
  });
});

describe('the page\'s controls', () => {
  it('take their colours from the theme', () => {
    const html = toolpathHtml('https://webview/toolpath.js', 'https://webview');
    const rule = (selector: string): string => new RegExp(`\\n  ${selector} \\{([^}]*)\\}`).exec(html)?.[1] ?? '';
    assert.match(rule('select'), /background: var\(--vscode-dropdown-background\)/);
    assert.match(rule('select'), /color: var\(--vscode-dropdown-foreground\)/);
    assert.match(rule('button'), /background: var\(--vscode-button-background\)/);
    assert.match(rule('button.secondary'), /var\(--vscode-button-secondaryBackground\)/);
    // No control's colour is written as a literal.
    for (const selector of ['select', 'button', 'button.secondary', '#readout', '#tooltip', '#status']) {
      assert.ok(!/#[0-9a-f]{3,6}\b|rgb\(/i.test(rule(selector)), `${selector} has a literal colour`);
    }
    for (const id of ['fit', 'play', 'next', 'back', 'start', 'end', 'readout', 'tooltip', 'empty', 'status', 'xmode']) {
      assert.ok(html.includes(`id="${id}"`), id);
    }
  });
});
