// Measures the Toolpath view's level of detail in node (client/webview/toolpathGeometry.ts):
// how many pieces a frame draws of a big toolpath, and how long a frame's geometry takes, at
// fit, zoomed in 10x and 100x about the middle, and in the 3D view. Not a test: the figures
// depend on the machine. The canvas's own drawing is not counted (node has none).
//
//   python bench/bench_plot.py --view-json /tmp/posted.json   # the server's payload, written
//   node bench/bench_view_lod.mjs /tmp/posted.json [--frames 20] [--width 1200 --height 800]
import { readFileSync, rmSync, mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { performance } from 'node:perf_hooks';
import * as esbuild from 'esbuild';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
const option = (name, fallback) => {
  const at = args.indexOf(name);
  return at >= 0 ? Number(args[at + 1]) : fallback;
};
const file = args.find((a) => !a.startsWith('--') && !/^\d+$/.test(a));
if (!file) {
  console.error('usage: node bench/bench_view_lod.mjs PAYLOAD.json [--frames N]');
  process.exit(2);
}
const frames = option('--frames', 20);
const width = option('--width', 1200);
const height = option('--height', 800);

const out = mkdtempSync(join(tmpdir(), 'bench-lod-'));
const bundle = join(out, 'geometry.mjs');
await esbuild.build({
  entryPoints: [join(root, 'client/webview/toolpathGeometry.ts')],
  bundle: true,
  format: 'esm',
  platform: 'node',
  outfile: bundle,
  logLevel: 'warning',
});
const g = await import(pathToFileURL(bundle).href);
rmSync(out, { recursive: true, force: true });

let started = performance.now();
const text = readFileSync(file, 'utf8');
const data = JSON.parse(text);
const parsed = performance.now() - started;
started = performance.now();
const segments = g.toSegments(data);
const converted = performance.now() - started;
console.log(
  `${file}: ${(text.length / 1e6).toFixed(1)} MB, ${segments.count.toLocaleString('en')} segments;` +
    ` JSON.parse ${parsed.toFixed(0)} ms, toSegments ${converted.toFixed(0)} ms`,
);

/** A sink that counts, as a canvas Path2D would take the pieces. */
const counter = () => ({ moves: 0, lines: 0, moveTo() { this.moves++; }, lineTo() { this.lines++; } });

function measure(name, view, transformOf, yaw = 0, pitch = 0) {
  const project = g.projection(view, data.lathe, yaw, pitch);
  const t = transformOf(g.fit(segments, project, width, height));
  const times = [];
  let sent = 0;
  for (let i = 0; i < frames; i++) {
    const sinks = data.kinds.map(counter);
    const begin = performance.now();
    sent = g.trace(segments, project, t, sinks);
    times.push(performance.now() - begin);
  }
  times.sort((a, b) => a - b);
  const median = times[Math.floor(times.length / 2)];
  console.log(
    `  ${name}: ${sent.toLocaleString('en')} pieces drawn of ${segments.count.toLocaleString('en')}` +
      ` segments (${((100 * sent) / (2 * segments.count)).toFixed(1)}% of the points);` +
      ` a frame's geometry min ${times[0].toFixed(1)} ms, median ${median.toFixed(1)} ms`,
  );
}

const plane = data.lathe ? 'XZ' : 'XY';
const middle = (t, factor) => g.zoomAt(t, width / 2, height / 2, factor);
measure(`${plane} at fit`, plane, (t) => t);
measure(`${plane} zoomed 10x`, plane, (t) => middle(t, 10));
measure(`${plane} zoomed 100x`, plane, (t) => middle(t, 100));
measure('3D at fit (yaw 30, pitch 30 degrees)', '3D', (t) => t, Math.PI / 6, Math.PI / 6);
started = performance.now();
const p = g.projection(plane, data.lathe);
const t = g.fit(segments, p, width, height);
const fitted = performance.now() - started;
started = performance.now();
const hit = g.hitTest(segments, p, t, width / 2, height / 2, 6);
console.log(
  `  fit ${fitted.toFixed(1)} ms; hit test at the middle ${(performance.now() - started).toFixed(1)} ms` +
    ` (${hit === undefined || hit === null || hit < 0 ? 'no segment' : `segment ${hit}`})`,
);
