// The debug adapter through the Debug Adapter Protocol client VS Code's own adapters are tested
// with (@vscode/debugadapter-testsupport): `python -m fanuc_macro.dap` over stdio on the seed
// thread module O4009 (it calls O3331 with M98 P0013331).
//
//   FANUC_MACRO_PYTHON=python3 node --test tests/dap/debug_client.test.mjs
//
// FANUC_MACRO_PYTHON is a Python that imports fanuc_macro (default python3);
// tests/test_dap_node_client.py runs this file under pytest.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { afterEach, beforeEach, describe, it } from 'node:test';
import { fileURLToPath } from 'node:url';
import { DebugClient } from '@vscode/debugadapter-testsupport';

const here = dirname(fileURLToPath(import.meta.url));
const SEED = join(here, '..', 'fixtures', 'thread_variants', 'o4009_clean.nc');
const PYTHON = process.env.FANUC_MACRO_PYTHON || 'python3';
/** A safety net for a broken adapter, not a time the tests measure. */
const WAIT_MS = 60000;

/** The 1-based line of the first line of the seed that holds `text`. */
function lineOf(text) {
  const index = readFileSync(SEED, 'utf8').split(/\r?\n/).findIndex((line) => line.includes(text));
  assert.ok(index >= 0, `${text} is in the seed`);
  return index + 1;
}

const G92 = lineOf('G92');
const M98 = lineOf('M98 P0013331');
const O3331 = lineOf('O3331');

describe('fanuc-macro-dap through DebugClient', () => {
  /** @type {DebugClient} */
  let dc;

  beforeEach(async () => {
    // DebugClient spawns `runtime executable`: one argument, so the module is joined to its -m.
    dc = new DebugClient(PYTHON, '-mfanuc_macro.dap', 'fanuc-macro', { env: { ...process.env } }, true);
    dc.defaultTimeout = WAIT_MS;
    await dc.start();
  });

  afterEach(async () => {
    await dc.stop();
  });

  /** initialize, launch, the breakpoints on the seed's `lines`, configurationDone; the first stop. */
  async function runTo(lines, launch = {}) {
    const initialized = dc.waitForEvent('initialized');
    const stopped = dc.waitForEvent('stopped');
    const init = await dc.initializeRequest({ adapterID: 'fanuc-macro', linesStartAt1: true, columnsStartAt1: true });
    assert.equal(init.body?.supportsConfigurationDoneRequest, true);
    const launched = dc.launchRequest({ program: SEED, ...launch });
    await initialized;
    const set = await dc.setBreakpointsRequest({
      source: { path: SEED },
      breakpoints: lines.map((line) => ({ line })),
    });
    assert.deepEqual(
      set.body.breakpoints.map((b) => [b.verified, b.line]),
      lines.map((line) => [true, line]),
    );
    await dc.configurationDoneRequest();
    await launched;
    return (await stopped).body;
  }

  async function frames() {
    return (await dc.stackTraceRequest({ threadId: 1 })).body.stackFrames;
  }

  /** The evaluate answer of `expression` in the top frame, as the watch view asks it. */
  async function evaluate(expression) {
    const [top] = await frames();
    return (await dc.evaluateRequest({ expression, frameId: top.id, context: 'watch' })).body.result;
  }

  const near = (result, value) => Math.abs(Number.parseFloat(result) - value) < 1e-9;

  it('stops on the first G92 of O3331 with each pass\'s depth in #9', async () => {
    const stop = await runTo([G92]);
    assert.equal(stop.reason, 'breakpoint');
    assert.equal(stop.threadId, 1);
    const first = await frames();
    assert.equal(first[0].line, G92);
    assert.equal(first[0].source.path, SEED);
    assert.ok(near(await evaluate('#9'), 0.092), 'the first pass\'s depth');
    // The next turn of the loop stops on the same block, one pass deeper.
    const again = dc.waitForEvent('stopped');
    await dc.continueRequest({ threadId: 1 });
    assert.equal((await again).body.reason, 'breakpoint');
    assert.equal((await frames())[0].line, G92);
    assert.ok(near(await evaluate('#9'), 0.13), 'the second pass\'s depth');
  });

  it('shows O3331 above the O4009 that called it', async () => {
    await runTo([G92]);
    const stack = await frames();
    assert.deepEqual(
      stack.map((f) => f.name.split(' ')[0]),
      ['O3331', 'O4009'],
    );
    assert.equal(stack[1].line, M98);
    const threads = (await dc.threadsRequest()).body.threads;
    assert.deepEqual(threads.map((t) => t.id), [1]);
  });

  it('evaluates the thread\'s height and the common variables', async () => {
    await runTo([G92]);
    assert.ok(near(await evaluate('#4'), 1.907), 'h, at the control\'s 0.001 mm');
    assert.equal(Number.parseFloat(await evaluate('#101')), 3);
    assert.ok(near(await evaluate('[#100-2*#9]'), 49.816));
  });

  it('steps into O3331 from the M98', async () => {
    const stop = await runTo([M98]);
    assert.equal(stop.reason, 'breakpoint');
    assert.equal((await frames())[0].line, M98);
    const stepped = dc.waitForEvent('stopped');
    await dc.stepInRequest({ threadId: 1 });
    assert.equal((await stepped).body.reason, 'step');
    const stack = await frames();
    assert.equal(stack[0].name.split(' ')[0], 'O3331');
    assert.equal(stack[0].line, O3331);
    assert.equal(stack.length, 2);
  });

  it('stops on the first block when asked, and ends the run after the last', async () => {
    const stop = await runTo([], { stopOnEntry: true });
    assert.equal(stop.reason, 'entry');
    assert.equal((await frames())[0].line, lineOf('O4009'));
    const ended = dc.waitForEvent('terminated');
    await dc.continueRequest({ threadId: 1 });
    await ended;
  });
});
