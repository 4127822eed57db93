// Drives a real VS Code (code-server) in headless Chromium and checks that the
// fanuc-macro extension works in it: language mode, TextMate highlighting,
// diagnostics from the language server, a hover with a value, the extension's workbench parts
// (no colour swatch, the status bar item, the rule links, the Settings UI's title), navigation
// (rename, document highlight, folding, workspace symbols), semantic tokens, a code lens,
// signature help, the Toolpath view (webview), the trace view (a read-only document whose
// rows link to the blocks), the debugger (a breakpoint, Debug This Program, the stop) and the
// arc-thread program inserted from the palette with its defaults.
// Every step waits for a condition (a status bar text, a data- attribute), never a fixed delay.
//
// Usage: node check.mjs <code-server base url> <workspace folder> <out dir>
// Exits 0 when every check passed, 1 otherwise. Screenshots go to <out dir>.
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const [baseUrl, workspace, outDir] = process.argv.slice(2);
if (!baseUrl || !workspace || !outDir) {
  console.error('usage: node check.mjs <base url> <workspace folder> <out dir>');
  process.exit(2);
}
const FILE = process.env.CHECK_FILE || 'o2_arc_thread_roughing.nc';
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const STEP_MS = Number(process.env.CHECK_STEP_TIMEOUT_MS || 90_000);
mkdirSync(outDir, { recursive: true });

const t0 = Date.now();
const log = (...a) => console.log(`[${((Date.now() - t0) / 1000).toFixed(1)}s]`, ...a);
const results = [];
function record(name, ok, detail) {
  results.push({ name, ok, detail });
  log(`${ok ? 'PASS' : 'FAIL'} ${name}: ${detail}`);
}

const browser = await chromium.launch({
  executablePath: CHROMIUM,
  headless: true,
  args: ['--no-sandbox', '--disable-dev-shm-usage', '--disable-gpu'],
});
const base = new URL(baseUrl);
const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
page.setDefaultTimeout(STEP_MS);
// Only this machine: every request that is not for code-server is aborted.
const blocked = new Set();
await page.route('**/*', (route) => {
  const u = new URL(route.request().url());
  if (u.protocol === 'data:' || u.protocol === 'blob:' || u.host === base.host) return route.continue();
  blocked.add(u.host);
  return route.abort();
});

async function shot(name) {
  const path = join(outDir, name);
  await page.screenshot({ path });
  log('screenshot', path);
}

async function runCommand(title) {
  await page.keyboard.press('F1');
  const input = page.locator('.quick-input-widget input');
  await input.waitFor({ state: 'visible' });
  await input.fill(`>${title}`);
  await page.locator('.quick-input-list .monaco-list-row', { hasText: title }).first().waitFor();
  await page.keyboard.press('Enter');
}

async function gotoPosition(line, column) {
  await page.keyboard.press('Control+G');
  const input = page.locator('.quick-input-widget input');
  await input.waitFor({ state: 'visible' });
  await input.fill(`:${line}:${column}`);
  await page.keyboard.press('Enter');
  await page.locator('.quick-input-widget').waitFor({ state: 'hidden' });
  await waitStatusLine(line);
}

const editor = page.locator('.editor-instance .monaco-editor').first();

/** The line number the program's editor marks as the cursor's, focused or not. */
async function editorCursorLine() {
  const text = await editor.locator('.line-numbers.active-line-number').first().textContent().catch(() => '');
  return Number(text) || undefined;
}

/** The editor's cursor line (1-based), from the status bar's "Ln 34, Col 1". */
async function statusLine() {
  const text = await page.locator('[id="status.editor.selection"]').innerText().catch(() => '');
  const m = /Ln (\d+)/.exec(text);
  return m ? Number(m[1]) : undefined;
}

async function waitStatusLine(line) {
  await page.waitForFunction(
    (want) => new RegExp(`Ln ${want}\\b`).test(document.getElementById('status.editor.selection')?.innerText || ''),
    line,
    { timeout: STEP_MS },
  );
}

/**
 * The frame whose document has `selector`: a webview is an iframe in an iframe in code-server.
 * Polls the page's frames until one has it.
 */
async function frameWith(selector) {
  const deadline = Date.now() + STEP_MS;
  for (;;) {
    for (const frame of page.frames()) {
      if (frame === page.mainFrame()) continue;
      const found = await frame.locator(selector).count().catch(() => 0);
      if (found > 0) return frame;
    }
    if (Date.now() > deadline) throw new Error(`no frame has ${selector}`);
    await page.waitForTimeout(200);
  }
}

// The Toolpath view of the seed (0-based lines, as the view and the probe count them): a click
// on the first rapid to the thread's start (line 34, `N26 X[#5 - 2 * ...]`, seven passes)
// reveals that block; the cursor on line 39 (`N31 G00 X#24 Z#26`, one move) lights one segment.
const CLICK_LINE = Number(process.env.CHECK_TOOLPATH_CLICK_LINE || 34);
const OTHER_LINE = Number(process.env.CHECK_TOOLPATH_OTHER_LINE || 39);

async function checkToolpath() {
  await editor.click({ position: { x: 200, y: 10 } });
  await gotoPosition(9, 1);
  let frame;
  try {
    await runCommand('FANUC Macro: Show Toolpath');
    frame = await frameWith('canvas#toolpath');
    await frame.waitForFunction(
      (line) => Number(document.getElementById('toolpath')?.dataset.pieces || 0) > 0
        && window.toolpathProbe?.segmentOfLine(line) != null,
      CLICK_LINE - 1,
      { timeout: STEP_MS },
    );
    const data = await frame.locator('canvas#toolpath').evaluate((c) => ({ ...c.dataset }));
    const info = await frame.locator('#summary').innerText();
    record('toolpath view', Number(data.segments) > 0, `segments ${data.segments}, pieces ${data.pieces}; ${info}`);
    await checkBackplot(frame);
  } catch (e) {
    record('toolpath view', false, e.message.split('\n')[0]);
    await shot('toolpath.png');
    return;
  }
  await shot('toolpath.png');

  // A click on a segment reveals its block in the editor.
  try {
    const canvas = frame.locator('canvas#toolpath');
    const at = await frame.evaluate((line) => {
      const p = window.toolpathProbe.segmentOfLine(line);
      const box = document.getElementById('toolpath').getBoundingClientRect();
      return { x: p.x - box.left, y: p.y - box.top };
    }, CLICK_LINE - 1);
    const before = await editorCursorLine();
    await canvas.click({ position: at });
    // The program's editor shows the cursor on the block (its active line number), and has the
    // focus: the status bar says its line.
    await editor.locator('.line-numbers.active-line-number', { hasText: new RegExp(`^${CLICK_LINE}$`) }).waitFor();
    await waitStatusLine(CLICK_LINE);
    await frame.waitForFunction(() => Number(document.getElementById('toolpath').dataset.highlighted) > 0);
    const lit = await canvas.getAttribute('data-highlighted');
    record('toolpath click', true,
      `click at (${at.x.toFixed(0)}, ${at.y.toFixed(0)}): cursor Ln ${before} -> Ln ${await statusLine()}, ${lit} segments lit`);
  } catch (e) {
    record('toolpath click', false,
      `${e.message.split('\n')[0]}; editor's line ${await editorCursorLine()}, status bar Ln ${await statusLine()}`);
    await shot('toolpath-click.png');
    return;
  }

  // The editor's cursor on another block lights that block's segments.
  try {
    const canvas = frame.locator('canvas#toolpath');
    const before = await canvas.getAttribute('data-highlighted');
    const want = await frame.evaluate((line) => window.toolpathProbe.segmentOfLine(line) != null, OTHER_LINE - 1);
    await gotoPosition(OTHER_LINE, 1);
    await waitStatusLine(OTHER_LINE);
    await frame.waitForFunction(
      (old) => document.getElementById('toolpath').dataset.highlighted !== old,
      before,
      { timeout: STEP_MS },
    );
    const after = await canvas.getAttribute('data-highlighted');
    record('toolpath cursor', want && Number(after) > 0,
      `cursor on Ln ${OTHER_LINE}: segments lit ${before} -> ${after}`);
  } catch (e) {
    const lit = await frame.locator('canvas#toolpath').getAttribute('data-highlighted').catch(() => '?');
    record('toolpath cursor', false, `${e.message.split('\n')[0]}; data-highlighted ${lit}`);
  }
  await shot('toolpath-cursor.png');
  await checkStepping(frame);
}

// The backplot around the path (the seed, a lathe, drawn in XZ): the rulers name Z across and X
// up with a grid step, the readout says the coordinates under the mouse, a segment's tooltip
// says its block (line, code, F, S), the fit fills the room, the status area lists every note
// wrapped, and the controls take the theme's colours.
async function checkBackplot(frame) {
  const canvas = frame.locator('canvas#toolpath');
  try {
    await frame.waitForFunction(() => document.getElementById('toolpath').dataset.axes === 'Z,X'
      && Number(document.getElementById('toolpath').dataset.gridStep) > 0);
    const box = await canvas.boundingBox();
    await canvas.hover({ position: { x: box.width * 0.5, y: box.height * 0.4 } });
    await frame.waitForFunction(() => /^Z -?\d+\.\d{3} {2}X Ø-?\d+\.\d{3}$/.test(document.getElementById('toolpath').dataset.readout || ''));
    const d = await canvas.evaluate((c) => ({ ...c.dataset }));
    const shown = await frame.locator('#readout').innerText();
    const fill = await frame.evaluate(() => window.toolpathProbe.fill());
    const filled = Math.max(...fill);
    record('toolpath axes', shown === d.readout && filled > 0.9,
      `axes ${d.axes}, grid step ${d.gridStep}, scale bar ${d.scaleBar}, origin at ${d.origin}; readout "${shown}"; fit fills ${fill.map((f) => f.toFixed(2)).join(' x ')}`);
  } catch (e) {
    record('toolpath axes', false, `${e.message.split('\n')[0]}; ${JSON.stringify(await canvas.evaluate((c) => ({ ...c.dataset })).catch(() => ({})))}`);
  }
  try {
    const at = await frame.evaluate((line) => {
      const p = window.toolpathProbe.segmentOfLine(line);
      const b = document.getElementById('toolpath').getBoundingClientRect();
      return { x: p.x - b.left, y: p.y - b.top };
    }, CLICK_LINE - 1);
    await canvas.hover({ position: at });
    await frame.waitForFunction((line) => document.getElementById('toolpath').dataset.tooltipLine === String(line)
      && /G0\d · /.test(document.getElementById('tooltip').innerText)
      && document.getElementById('tooltip').innerText.split('\n').length >= 3, CLICK_LINE);
    const tip = await frame.locator('#tooltip').innerText();
    record('toolpath tooltip', await frame.locator('#tooltip').isVisible(), tip.replace(/\n/g, ' | '));
    await shot('toolpath-tooltip.png');
  } catch (e) {
    record('toolpath tooltip', false, `${e.message.split('\n')[0]}; ${JSON.stringify(await frame.locator('#tooltip').innerText().catch(() => ''))}`);
    await shot('toolpath-tooltip.png');
  }
  try {
    const status = await frame.evaluate(() => {
      const s = document.getElementById('status');
      return {
        notes: [...s.querySelectorAll('li')].map((li) => li.innerText),
        wraps: getComputedStyle(s.querySelector('li') || s).whiteSpace !== 'nowrap',
        cut: [...s.querySelectorAll('li')].some((li) => li.scrollWidth > li.clientWidth + 1),
      };
    });
    const unit = status.notes.find((n) => n.startsWith('assumed mm')) || '';
    record('toolpath status', status.notes.length >= 3 && status.wraps && !status.cut && unit !== '',
      `${status.notes.length} notes, wrapped ${status.wraps}: ${status.notes.slice(0, 4).join(' | ')}`);
  } catch (e) {
    record('toolpath status', false, e.message.split('\n')[0]);
  }
  try {
    const themed = await frame.evaluate(() => {
      const style = (id) => getComputedStyle(document.getElementById(id));
      const variable = (name) => {
        const probe = document.createElement('div');
        probe.style.backgroundColor = `var(${name})`;
        document.body.append(probe);
        const value = getComputedStyle(probe).backgroundColor;
        probe.remove();
        return value;
      };
      return {
        dark: document.body.classList.contains('vscode-dark'),
        fit: style('fit').backgroundColor,
        button: variable('--vscode-button-background'),
        select: style('view').backgroundColor,
        dropdown: variable('--vscode-dropdown-background'),
        next: style('next').backgroundColor,
        secondary: variable('--vscode-button-secondaryBackground'),
      };
    });
    const ok = themed.fit === themed.button && themed.select === themed.dropdown && themed.next === themed.secondary
      && themed.fit !== 'rgba(0, 0, 0, 0)' && themed.select !== 'rgb(255, 255, 255)' === themed.dark;
    record('toolpath themed controls', ok, JSON.stringify(themed));
  } catch (e) {
    record('toolpath themed controls', false, e.message.split('\n')[0]);
  }
  // In a dark theme the controls and the drawing turn dark with the workbench: VS Code's command
  // that toggles between the light and the dark theme, twice.
  const toggle = async (dark) => {
    await runCommand('Preferences: Toggle between Light/Dark Themes');
    await frame.waitForFunction((want) => document.body.classList.contains(want ? 'vscode-dark' : 'vscode-light'), dark);
  };
  const wasDark = await frame.evaluate(() => document.body.classList.contains('vscode-dark'));
  try {
    await toggle(!wasDark);
    const theme = await frame.evaluate(() => {
      const luminance = (colour) => {
        const [r, g, b] = (colour.match(/\d+(\.\d+)?/g) || ['255', '255', '255']).map(Number);
        return 0.2126 * r + 0.7152 * g + 0.0722 * b;
      };
      const style = (id) => getComputedStyle(document.getElementById(id));
      const page = luminance(getComputedStyle(document.body).backgroundColor) < 128;
      return { select: style('view').backgroundColor, next: style('next').backgroundColor, page: getComputedStyle(document.body).backgroundColor,
        selectDark: luminance(style('view').backgroundColor) < 96, nextDark: luminance(style('next').backgroundColor) < 128, pageDark: page };
    });
    await frame.waitForFunction(() => Number(document.getElementById('toolpath').dataset.pieces) > 0);
    await shot(wasDark ? 'toolpath-light.png' : 'toolpath-dark.png');
    const follows = theme.selectDark === !wasDark && theme.nextDark === !wasDark && theme.pageDark === !wasDark;
    record('toolpath theme switched', follows, `${wasDark ? 'dark -> light' : 'light -> dark'}: ${JSON.stringify(theme)}`);
  } catch (e) {
    record('toolpath theme switched', false, e.message.split('\n')[0]);
    await shot('toolpath-dark.png');
    await page.keyboard.press('Escape');
  }
  try {
    if ((await frame.evaluate(() => document.body.classList.contains('vscode-dark'))) !== wasDark) await toggle(wasDark);
  } catch (e) {
    record('toolpath theme restored', false, e.message.split('\n')[0]);
  }
  await page.mouse.move(5, 5);
  await editor.click({ position: { x: 200, y: 10 } });
}

// Playback: back to the start, then one block at a time: the step count goes up, the tool is
// drawn where the block ends, and the editor's cursor follows the block.
async function checkStepping(frame) {
  const canvas = frame.locator('canvas#toolpath');
  const data = () => canvas.evaluate((c) => ({ ...c.dataset }));
  try {
    await frame.locator('#start').click();
    await frame.waitForFunction(() => document.getElementById('toolpath').dataset.stepIndex === '0');
    // A step sets its index at once and draws the tool in the next frame: both are waited for.
    const drawn = () => frame.waitForFunction(() => {
      const c = document.getElementById('toolpath').dataset;
      return c.toolPosition === c.position;
    });
    await frame.locator('#next').click();
    await frame.waitForFunction(() => document.getElementById('toolpath').dataset.stepIndex === '1');
    await drawn();
    const one = await data();
    await frame.locator('#next').click();
    await frame.waitForFunction(() => document.getElementById('toolpath').dataset.stepIndex === '2');
    await drawn();
    const two = await data();
    // The editor's cursor follows the block of the step (its line number marked active).
    const want = await frame.evaluate(() => window.toolpathProbe.stepLine());
    await editor.locator('.line-numbers.active-line-number', { hasText: new RegExp(`^${want}$`) }).waitFor();
    await shot('toolpath-step.png');
    record('toolpath stepping', one.tool !== '' && one.toolAt !== two.toolAt && Number(two.steps) > 2,
      `step 1 of ${one.steps}: tool ${one.tool} at ${one.toolAt}; step 2: at ${two.toolAt}, editor's cursor at Ln ${await editorCursorLine()}`);
    await frame.locator('#end').click();
    await frame.waitForFunction(() => document.getElementById('toolpath').dataset.stepIndex === document.getElementById('toolpath').dataset.steps);
  } catch (e) {
    record('toolpath stepping', false, `${e.message.split('\n')[0]}; ${JSON.stringify(await data().catch(() => ({})))}`);
    await shot('toolpath-step.png');
  }
  try {
    await frame.locator('#view').selectOption('3D');
    await frame.waitForFunction(() => document.getElementById('toolpath').dataset.axes === '3D'
      && Number(document.getElementById('toolpath').dataset.pieces) > 0);
    await shot('toolpath-3d.png');
    record('toolpath 3D', true, `pieces ${(await data()).pieces}`);
    await frame.locator('#view').selectOption('XZ');
    await frame.waitForFunction(() => document.getElementById('toolpath').dataset.axes === 'Z,X');
  } catch (e) {
    record('toolpath 3D', false, e.message.split('\n')[0]);
  }
}

/** "Show Toolpath" for the active editor; resolves with the view's frame once `ready` holds. */
async function showToolpath(ready, arg) {
  await runCommand('FANUC Macro: Show Toolpath');
  const frame = await frameWith('canvas#toolpath');
  await frame.waitForFunction(ready, arg, { timeout: STEP_MS });
  return frame;
}

// A threading program shows its thread's simulated cross-section and its stock; an untitled
// program that makes no move says why nothing is drawn; a mill's helical bore and drilling cycle
// are drawn in 3D. Then the view is on the seed again, for the debugger's check.
async function checkToolpathPrograms() {
  const THREAD_FILE = 'o4009_external_m50x3.nc';
  await editor.click({ position: { x: 200, y: 10 } });
  try {
    await openFile(THREAD_FILE);
    const frame = await showToolpath(() => Number(document.getElementById('toolpath').dataset.threads) > 0
      && document.getElementById('toolpath').dataset.stock !== '');
    const d = await frame.locator('canvas#toolpath').evaluate((c) => ({ ...c.dataset }));
    record('toolpath thread section', true, `threads ${d.threads}, stock ${d.stock}, tool ${d.tool}, segments ${d.segments}`);
    await shot('toolpath-thread.png');
  } catch (e) {
    record('toolpath thread section', false, e.message.split('\n')[0]);
    await shot('toolpath-thread.png');
  }
  const input = page.locator('.quick-input-widget input');
  const untitled = async (lines) => {
    await runCommand('File: New Untitled Text File');
    await page.locator('.editor-group-container.active .tab.active', { hasText: 'Untitled' }).first().waitFor();
    await runCommand('Change Language Mode');
    await page.waitForFunction(
      () => /language/i.test(document.querySelector('.quick-input-widget input')?.getAttribute('placeholder') || ''),
      null,
      { timeout: STEP_MS },
    );
    await input.fill('FANUC Macro B');
    await page.locator('.quick-input-list .monaco-list-row', { hasText: 'FANUC Macro B' }).first().waitFor();
    await page.keyboard.press('Enter');
    await waitActiveEditor('Untitled', 'FANUC Macro B');
    const active = page.locator('.editor-group-container.active .editor-instance .monaco-editor').first();
    await active.click({ position: { x: 200, y: 10 } });
    for (const [i, line] of lines.entries()) {
      await page.keyboard.type(line);
      await page.keyboard.press('Escape');
      if (i < lines.length - 1) await page.keyboard.press('Enter');
    }
  };
  const close = async () => {
    if (await page.locator('.editor-group-container.active .tab.active', { hasText: 'Untitled' }).count()) {
      await runCommand('View: Revert and Close Editor').catch(() => {});
    }
  };
  try {
    await untitled(['O7100', '#1=2', 'M30']);
    const frame = await showToolpath(() => document.getElementById('toolpath').dataset.empty === '1');
    const said = await frame.locator('#empty').innerText();
    record('toolpath empty state', await frame.locator('#empty').isVisible() && /no move/.test(said), said.replace(/\n/g, ' | '));
    await shot('toolpath-empty.png');
  } catch (e) {
    record('toolpath empty state', false, e.message.split('\n')[0]);
    await shot('toolpath-empty.png');
  }
  await close();
  try {
    await untitled(['O7200', 'G17 G21 G90 G54', 'G43 H1 Z20.', 'G00 X10. Y0', 'Z2.', 'G01 Z0 F300', 'G03 I-10. Z-2.',
      'G03 I-10. Z-4.', 'G03 I-10.', 'G00 Z20.', 'G81 X0 Y20. Z-10. R2. F100', 'G80', 'M30']);
    const frame = await showToolpath(() => Number(document.getElementById('toolpath').dataset.segments) > 100);
    await frame.locator('#view').selectOption('3D');
    await frame.waitForFunction(() => document.getElementById('toolpath').dataset.axes === '3D');
    await shot('toolpath-helix-3d.png');
    // Each plane of the mill, its axes named as seen from +Z, -Y and +X.
    for (const [plane, axes] of [['XZ', 'X,Z'], ['YZ', 'Y,Z'], ['XY', 'X,Y']]) {
      await frame.locator('#view').selectOption(plane);
      await frame.waitForFunction((want) => document.getElementById('toolpath').dataset.axes === want, axes);
      await shot(`toolpath-helix-${plane.toLowerCase()}.png`);
    }
    const d = await frame.locator('canvas#toolpath').evaluate((c) => ({ ...c.dataset }));
    record('toolpath mill', d.units === 'mm' && d.tool.startsWith('cylinder'), `segments ${d.segments}, units ${d.units}, tool ${d.tool}`);
  } catch (e) {
    record('toolpath mill', false, e.message.split('\n')[0]);
    await shot('toolpath-helix-3d.png');
  }
  await close();
  try {
    await openFile(FILE);
    await showToolpath(() => document.getElementById('toolpath').dataset.empty === '0'
      && Number(document.getElementById('toolpath').dataset.segments) > 0 && document.getElementById('toolpath').dataset.threads === '0'
      && document.getElementById('toolpath').dataset.axes === 'Z,X');
  } catch (e) {
    record('toolpath back on the seed', false, e.message.split('\n')[0]);
  }
  // The mouse away from the tabs, whose hover would cover the editor's first line.
  await page.mouse.move(5, 5);
  await page.keyboard.press('Escape');
}

// Navigation in an untitled program typed in (no seed has a WHILE loop), closed unsaved after:
// F2 on a GOTO's label renames the label and the GOTO, the cursor on a variable shows its
// writes and reads (`.wordHighlightStrong` / `.wordHighlight`: the server's Write and Read
// kinds; VS Code's own word matching marks `.wordHighlightText` only), folding controls on the
// O line (only the server folds a program: the language configuration's markers fold the
// WHILE alone) and the WHILE, and Ctrl+T lists an O program of the workspace.
async function checkNavigation() {
  // The last line is written in lower case for the formatting check.
  const NAV_LINES = ['O7001', '#1=0', 'IF[#1GT5]GOTO20', 'WHILE[#1LT3]DO1', '#1=#1+1', 'END1', 'N20 #2=#1', 'M30', 'g01 x1. f0.2'];
  const nav = page.locator('.editor-group-container.active .editor-instance .monaco-editor').first();
  const input = page.locator('.quick-input-widget input');
  // A click on the quick input's row whose label is `label` itself: Enter would take the first
  // row, which for "File: New Untitled Text File" is "File: Compare New Untitled Text Files".
  const pickRow = async (label) => {
    const rows = page.locator('.quick-input-list .monaco-list-row', { hasText: label });
    await rows.first().waitFor();
    const texts = await rows.allInnerTexts();
    const at = texts.findIndex((t) => t.replace(/\u00a0/g, ' ').split('\n')
      .some((l) => l.trim() === label || l.trim().startsWith(`${label} (`)));
    await rows.nth(Math.max(at, 0)).click();
  };
  const command = async (title) => {
    await page.keyboard.press('F1');
    await input.waitFor({ state: 'visible' });
    await input.fill(`>${title}`);
    await pickRow(title);
  };
  // The untitled program closed unsaved: the seed's editor is the active one again.
  const closeUntitled = async () => {
    try {
      if (await page.locator('.editor-group-container.active .tab.active', { hasText: 'Untitled' }).count()) {
        await command('View: Revert and Close Editor');
      }
      await waitActiveEditor(FILE, 'FANUC Macro B');
    } catch (e) {
      record('navigation cleanup', false, e.message.split('\n')[0]);
    }
  };

  try {
    await command('File: New Untitled Text File');
    await page.locator('.editor-group-container.active .tab.active', { hasText: 'Untitled' }).first().waitFor();
    await command('Change Language Mode');
    // The language picker, not the command palette still closing.
    await page.waitForFunction(
      () => /language/i.test(document.querySelector('.quick-input-widget input')?.getAttribute('placeholder') || ''),
      null,
      { timeout: STEP_MS },
    );
    await input.fill('FANUC Macro B');
    await pickRow('FANUC Macro B');
    await waitActiveEditor('Untitled', 'FANUC Macro B');
    await nav.click({ position: { x: 200, y: 10 } });
    for (const [i, line] of NAV_LINES.entries()) {
      await page.keyboard.type(line);
      await page.keyboard.press('Escape'); // a completion list must not take the Enter
      if (i < NAV_LINES.length - 1) await page.keyboard.press('Enter');
    }
    await page.waitForFunction(
      () => /N20 #2=#1/.test((document.querySelector('.editor-group-container.active .monaco-editor .view-lines')
        ?.innerText || '').replace(/\u00a0/g, ' ')),
      null,
      { timeout: STEP_MS },
    );
  } catch (e) {
    record('navigation program', false, `${e.message.split('\n')[0]}; ${JSON.stringify((await activeEditorText()).slice(0, 300))}`);
    await shot('navigation.png');
    await closeUntitled();
    return;
  }

  // The cursor on #1 of `#1=#1+1`: its writes (lines 2, 5) and reads (lines 3, 4, 5, 7), before the rename edits the program.
  try {
    await gotoPosition(5, 2);
    await page.waitForFunction(
      () => {
        const view = document.querySelector('.editor-group-container.active .monaco-editor');
        return view && view.querySelectorAll('.wordHighlightStrong').length >= 2
          && view.querySelectorAll('.wordHighlight').length >= 3;
      },
      null,
      { timeout: STEP_MS },
    );
    const counts = await nav.evaluate((el) => ({
      write: el.querySelectorAll('.wordHighlightStrong').length,
      read: el.querySelectorAll('.wordHighlight').length,
    }));
    record('document highlight', true, `#1: ${counts.write} write and ${counts.read} read decorations`);
  } catch (e) {
    const classes = await nav.evaluate((el) =>
      [...new Set([...el.querySelectorAll('[class*="wordHighlight"]')].map((d) => d.className))]).catch(() => []);
    record('document highlight', false, `${e.message.split('\n')[0]}; decorations ${JSON.stringify(classes)}`);
    await shot('highlight.png');
  }

  // Folding controls in the gutter beside the O line (1) and the WHILE (4).
  try {
    await page.waitForFunction(
      () => {
        const view = document.querySelector('.editor-group-container.active .monaco-editor');
        if (!view) return false;
        const tops = (n) => [...view.querySelectorAll('.line-numbers')]
          .filter((el) => Number(el.textContent) === n).map((el) => el.getBoundingClientRect().top);
        const folds = [...view.querySelectorAll('.margin-view-overlays [class*="codicon-folding-"]')]
          .map((el) => el.getBoundingClientRect().top);
        const at = (n) => tops(n).some((t) => folds.some((f) => Math.abs(f - t) < 3));
        return at(1) && at(4);
      },
      null,
      { timeout: STEP_MS },
    );
    const count = await nav.locator('.margin-view-overlays [class*="codicon-folding-"]').count();
    record('folding', true, `folding controls on the O line and the WHILE (${count} in the gutter)`);
  } catch (e) {
    const count = await nav.locator('.margin-view-overlays [class*="codicon-folding-"]').count().catch(() => -1);
    record('folding', false, `${e.message.split('\n')[0]}; ${count} folding controls`);
    await shot('folding.png');
  }

  // F2 on the 20 of GOTO20: N20 and GOTO20 become 30.
  try {
    const column = NAV_LINES[2].indexOf('GOTO20') + 6; // on the "0" of 20 (1-based column)
    await gotoPosition(3, column);
    await page.keyboard.press('F2');
    // Type only into the rename box: keys sent before it has the focus would edit the program.
    await page.waitForFunction(
      () => Boolean(document.activeElement?.closest('.rename-box')),
      null,
      { timeout: STEP_MS },
    );
    const offered = await page.evaluate(() => {
      const el = document.activeElement;
      return el && 'value' in el ? el.value : el?.textContent;
    });
    await page.keyboard.press('Control+A');
    await page.keyboard.type('30');
    await page.keyboard.press('Enter');
    await page.waitForFunction(
      () => {
        const t = (document.querySelector('.editor-group-container.active .monaco-editor .view-lines')?.innerText || '')
          .replace(/\u00a0/g, ' ');
        return /GOTO30/.test(t) && /N30 #2=#1/.test(t) && !/GOTO20|N20/.test(t);
      },
      null,
      { timeout: STEP_MS },
    );
    record('rename', true, `F2 on GOTO20 offered ${JSON.stringify(offered)}; renamed to 30: GOTO30 and N30`);
  } catch (e) {
    const focus = await page.evaluate(() => document.activeElement?.className || '').catch(() => '');
    record('rename', false, `${e.message.split('\n')[0]}; focus on ${JSON.stringify(focus)}; ${JSON.stringify((await activeEditorText()).slice(0, 300))}`);
    await shot('rename.png');
  }

  // Selection ranges: from the second #1 of `#1=#1+1` (line 5) the selection grows to `#1+1`,
  // the expression, which neither the word nor the bracket selection of VS Code gives.
  try {
    await gotoPosition(5, 5);
    const sizes = [];
    for (let i = 0; i < 4 && !sizes.includes(4); i++) {
      await page.keyboard.press('Shift+Alt+ArrowRight');
      await page.waitForFunction(
        (before) => (document.getElementById('status.editor.selection')?.innerText || '') !== before,
        await page.locator('[id="status.editor.selection"]').innerText(),
        { timeout: 10_000 },
      ).catch(() => {});
      const text = await page.locator('[id="status.editor.selection"]').innerText();
      const m = /\((\d+) selected\)/.exec(text);
      sizes.push(m ? Number(m[1]) : 0);
    }
    record('selection ranges', sizes.includes(4), `Expand Selection from #1 of #1=#1+1: ${sizes.join(' -> ')} characters`);
    await page.keyboard.press('Escape');
  } catch (e) {
    record('selection ranges', false, e.message.split('\n')[0]);
    await shot('selection.png');
  }

  // Format Document: the lower-case last line comes out in upper case, the rest as it was.
  try {
    await command('Format Document');
    await page.waitForFunction(
      () => {
        const t = (document.querySelector('.editor-group-container.active .monaco-editor .view-lines')?.innerText || '')
          .replace(/\u00a0/g, ' ');
        return /G01 X1\. F0\.2/.test(t) && /IF\[#1GT5\]GOTO30/.test(t);
      },
      null,
      { timeout: STEP_MS },
    );
    record('formatting', true, 'Format Document: "g01 x1. f0.2" -> "G01 X1. F0.2", the other lines kept');
  } catch (e) {
    record('formatting', false, `${e.message.split('\n')[0]}; ${JSON.stringify((await activeEditorText()).slice(0, 300))}`);
    await shot('formatting.png');
  }

  // Ctrl+T: the workspace's programs, O4009 among them (the seeds' folder, scanned).
  try {
    await nav.click({ position: { x: 200, y: 10 } });
    await page.keyboard.press('Control+T');
    const input = page.locator('.quick-input-widget input');
    let how = 'Ctrl+T';
    try {
      await input.waitFor({ state: 'visible', timeout: 10_000 });
    } catch {
      how = 'Go to Symbol in Workspace (Ctrl+T did not open it)';
      await command('Go to Symbol in Workspace');
      await input.waitFor({ state: 'visible' });
    }
    await input.fill('#O40');
    const row = page.locator('.quick-input-list .monaco-list-row', { hasText: 'O4009' }).first();
    await row.waitFor();
    record('workspace symbols', true, `${how} "O40": ${(await row.innerText()).replace(/\s+/g, ' ')}`);
    await page.keyboard.press('Escape');
  } catch (e) {
    const rows = await page.locator('.quick-input-list').innerText().catch(() => '');
    record('workspace symbols', false, `${e.message.split('\n')[0]}; ${JSON.stringify(rows.slice(0, 300))}`);
    await shot('workspace-symbols.png');
    await page.keyboard.press('Escape');
  }

  await closeUntitled();

  // The call hierarchy of O3 in the seed (line 8): O0002 calls it (N1 M98 P3).
  try {
    await gotoPosition(8, 2);
    await command('Calls: Show Call Hierarchy');
    await page.waitForFunction(
      () => /O0*2\b/.test(document.querySelector('.part.sidebar')?.innerText || ''),
      null,
      { timeout: STEP_MS },
    );
    const shown = await page.locator('.part.sidebar').innerText();
    record('call hierarchy', true, `O3: ${shown.split('\n').filter((l) => /O0*[23]\b/.test(l)).slice(0, 4).join(' | ')}`);
  } catch (e) {
    const shown = await page.locator('.part.sidebar').innerText().catch(() => '');
    record('call hierarchy', false, `${e.message.split('\n')[0]}; sidebar ${JSON.stringify(shown.slice(0, 300))}`);
    await shot('call-hierarchy.png');
  }
  await page.keyboard.press('Escape');
}

/** Waits until the active group's active tab says `name` and the active editor's language is `mode`. */
async function waitActiveEditor(name, mode) {
  await page.locator('.editor-group-container.active .tab.active', { hasText: name }).first().waitFor();
  await page.waitForFunction(
    (want) => document.getElementById('status.editor.mode')?.innerText.trim() === want,
    mode,
    { timeout: STEP_MS },
  );
}

/** The text of the active editor's visible lines, spaces as spaces. */
async function activeEditorText() {
  return page.evaluate(() =>
    (document.querySelector('.editor-group-container.active .monaco-editor .view-lines')?.innerText || '')
      .replace(/\u00a0/g, ' '));
}

// The trace view: a read-only document of its own language beside the program, one row per
// motion block with where the tool goes, S and F, the values the block read under it; Ctrl+click on a row's
// "O0003 line 34" opens that block, and so does F12 on a row.
async function checkTrace() {
  await editor.click({ position: { x: 200, y: 10 } });
  await gotoPosition(9, 1);
  const title = `Trace of ${FILE}`;
  try {
    await runCommand('FANUC Macro: Show Trace of Current Program');
    await waitActiveEditor(title, 'FANUC Macro Trace');
    // N26 X[#5 - 2 * [#4 - #18] * SIN[#16]] of the first pass: #16 = 51.249025 (N16-N21),
    // under the block's row.
    await page.waitForFunction(
      () => /O0003 line 34 [^\n]*\n +#5=108\. #4=10\. #18=1\.2 #16=51\.249025/.test(
        (document.querySelector('.editor-group-container.active .monaco-editor .view-lines')?.innerText || '')
          .replace(/\u00a0/g, ' ')),
      null,
      { timeout: STEP_MS },
    );
    const lines = (await activeEditorText()).split('\n');
    const at = lines.findIndex((l) => l.startsWith('O0003 line 34'));
    const row = lines[at];
    const readOnly = await page.locator('.editor-group-container.active .monaco-editor textarea')
      .first().getAttribute('aria-readonly').catch(() => null);
    record('trace view', true, `${title}: ${row?.replace(/ +/g, ' ')} / ${lines[at + 1]?.trim()}${readOnly ? `; aria-readonly ${readOnly}` : ''}`);
  } catch (e) {
    record('trace view', false, `${e.message.split('\n')[0]}; ${JSON.stringify((await activeEditorText()).slice(0, 300))}`);
    await shot('trace.png');
    return;
  }
  await shot('trace.png');
  await checkTraceLayout();

  // F12 (Go to Definition) on a row of the trace opens its block: the first G32 (line 35).
  try {
    const row = await lineNumberOf('O0003 line 35');
    if (row < 0) throw new Error('no row of O0003 line 35 on the screen');
    await gotoPosition(row, 30);
    await page.keyboard.press('F12');
    await waitActiveEditor(FILE, 'FANUC Macro B');
    await waitStatusLine(35);
    record('trace definition', true, `F12 on Ln ${row} of the trace: ${FILE} at Ln ${await statusLine()}`);
  } catch (e) {
    record('trace definition', false, `${e.message.split('\n')[0]}; status bar Ln ${await statusLine()}`);
    await shot('trace-definition.png');
    return;
  }

  // The command again, from the program, shows the trace again; Ctrl+click on the link of the
  // first "O0003 line 34" opens the program at line 34.
  try {
    await runCommand('FANUC Macro: Show Trace of Current Program');
    await waitActiveEditor(title, 'FANUC Macro Trace');
    await page.waitForFunction(
      () => document.querySelector('.editor-group-container.active .monaco-editor .detected-link') !== null,
      null,
      { timeout: STEP_MS },
    );
    const line = page.locator('.editor-group-container.active .monaco-editor .view-line', { hasText: /^O0003\s+line\s+34\s/ }).first();
    const box = await line.boundingBox();
    await page.keyboard.down('Control');
    await page.mouse.move(box.x + 20, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.up();
    await page.keyboard.up('Control');
    await waitActiveEditor(FILE, 'FANUC Macro B');
    await waitStatusLine(34);
    record('trace link', true, `Ctrl+click on "O0003 line 34": ${FILE} at Ln ${await statusLine()}`);
  } catch (e) {
    record('trace link', false, `${e.message.split('\n')[0]}; status bar Ln ${await statusLine()}`);
    await shot('trace-link.png');
  }
}

// The trace view's header is not program text: its title and the hint under it have none of
// the colours a row's G code and addresses have (the hint's "F12" is no F word). Its columns,
// S, F and the time a block starts at among them, fit beside the program, and the values a
// block read are under its row.
// The 1400-pixel window is narrower than a programmer's screen: the side bar is closed for
// this check, as the two editors then share what a 1920-pixel screen gives them with it open.
async function checkTraceLayout() {
  const sidebar = page.locator('.part.sidebar');
  try {
    if (await sidebar.isVisible()) {
      await runCommand('View: Close Primary Side Bar');
      await sidebar.waitFor({ state: 'hidden' });
    }
    // The trace editor takes the room the side bar left.
    await page.waitForFunction(
      () => (document.querySelector('.editor-group-container.active .monaco-editor .editor-scrollable')?.getBoundingClientRect().width || 0) > 480,
      null,
      { timeout: STEP_MS },
    );
    const seen = await page.evaluate(() => {
      const view = document.querySelector('.editor-group-container.active .monaco-editor');
      const lines = [...(view?.querySelectorAll('.view-line') || [])];
      const text = (l) => l.innerText.replace(/\u00a0/g, ' ');
      const colours = (line, test) => [...line.querySelectorAll('span span')]
        .filter((s) => test(s.textContent.replace(/\u00a0/g, ' ')))
        .map((s) => getComputedStyle(s).color);
      const title = lines.find((l) => text(l).startsWith('Trace of'));
      const hint = lines.find((l) => text(l).includes('F12'));
      const columns = lines.find((l) => /^block\s+code\s+words/.test(text(l)));
      const row = lines.find((l) => /^O0003 line 3\d\s/.test(text(l)));
      // The text's width (each line's span is as wide as its text) and the room for it: the
      // scrollable part of the editor, without its gutter and minimap.
      const room = view?.querySelector('.editor-scrollable');
      return {
        title: title ? colours(title, (t) => t.trim() !== '') : [],
        hint: hint ? colours(hint, (t) => t.trim() !== '') : [],
        columns: columns ? text(columns).trim().split(/\s+/) : [],
        code: row ? colours(row, (t) => /^G\d+$/.test(t.trim())) : [],
        address: row ? colours(row, (t) => /^[XZ]$/.test(t.trim())) : [],
        width: Math.max(0, ...lines.map((l) => l.firstElementChild?.getBoundingClientRect().width || 0)),
        room: room ? room.getBoundingClientRect().width : 0,
      };
    });
    const program = new Set([...seen.code, ...seen.address]);
    if (seen.title.length === 0 || seen.code.length === 0 || seen.address.length === 0) {
      throw new Error(`no title, G code or address tokens on screen: ${JSON.stringify(seen)}`);
    }
    const coloured = [...seen.title, ...seen.hint].filter((c) => program.has(c));
    if (coloured.length > 0) throw new Error(`the header has a program text's colour ${coloured[0]}: ${JSON.stringify(seen)}`);
    if (seen.columns.join(' ') !== 'block code words to S F time') throw new Error(`columns ${seen.columns.join(' ')}`);
    if (seen.width === 0 || seen.width > seen.room + 1) throw new Error(`the rows are ${seen.width}px wide beside ${seen.room}px of editor`);
    record('trace layout', true,
      `header ${seen.title[0]} / ${seen.hint[0]}, program text ${[...program].join(' ')}; columns ${seen.columns.join(' ')}; ${Math.round(seen.width)} of ${Math.round(seen.room)} px`);
    await shot('trace-layout.png');
  } catch (e) {
    record('trace layout', false, e.message.split('\n')[0]);
    await shot('trace-layout.png');
  }
  if (!(await sidebar.isVisible())) await runCommand('View: Toggle Primary Side Bar Visibility').catch(() => {});
}

// The debugger: a breakpoint toggled on O3's G32 (line 35, reached in the first pass of the
// first layer), "FANUC Macro: Debug This Program" runs fanuc-macro-dap on the language server's
// Python; the run stops there: the debug toolbar, the editor's stopped-line highlight and the
// Variables view with #2 = 113. (set on line 10); the Toolpath view, still open, lights the
// stopped block. Then the session is stopped.
const DEBUG_LINE = 35;

async function checkDebug() {
  const text = () => page.evaluate(() => (document.querySelector('.part.sidebar')?.innerText || '').replace(/\u00a0/g, ' '));
  try {
    await openFile(FILE);
    await editor.click({ position: { x: 200, y: 10 } });
    await gotoPosition(DEBUG_LINE, 1);
    await runCommand('Debug: Toggle Breakpoint');
    await editor.locator('.codicon-debug-breakpoint').first().waitFor();
    // The cursor elsewhere, so that a lit block in the Toolpath view is the stop's, not the cursor's.
    await gotoPosition(9, 1);
    await runCommand('FANUC Macro: Debug This Program');
    await page.locator('.debug-toolbar').first().waitFor({ state: 'visible' });
    await editor.locator('.debug-top-stack-frame-line').first().waitFor();
    // VS Code leaves the scopes collapsed here (code-server 4.139): open the locals.
    const locals = page.locator('.part.sidebar .monaco-list-row', { hasText: 'Locals #1-#33' }).first();
    await locals.waitFor();
    if ((await locals.getAttribute('aria-expanded')) !== 'true') await locals.click();
    await page.waitForFunction(
      () => /#2\W+113\b/.test((document.querySelector('.part.sidebar')?.innerText || '').replace(/\u00a0/g, ' ')),
      null,
      { timeout: STEP_MS },
    );
    const stack = (await text()).split('\n').filter((l) => /^O0*[23]\b/.test(l.trim())).slice(0, 2).join(' | ');
    const row = (await text()).split('\n').find((l) => /#2\W+113\b/.test(l));
    record('debug', true, `stopped on Ln ${DEBUG_LINE} (editor at Ln ${await statusLine()}): ${stack}; Variables ${row?.trim()}`);
    await shot('debug.png');
  } catch (e) {
    record('debug', false, `${e.message.split('\n')[0]}; sidebar ${JSON.stringify((await text().catch(() => '')).slice(0, 300))}`);
    await shot('debug.png');
  }
  try {
    const frame = await frameWith('canvas#toolpath');
    const want = await frame.evaluate((line) => window.toolpathProbe?.segmentOfLine(line) != null, DEBUG_LINE - 1);
    await frame.waitForFunction(() => Number(document.getElementById('toolpath').dataset.highlighted) > 0, null, { timeout: STEP_MS });
    const lit = await frame.locator('canvas#toolpath').getAttribute('data-highlighted');
    record('debug toolpath', want, `stopped on Ln ${DEBUG_LINE}, editor cursor at Ln ${await statusLine()}: ${lit} segments lit`);
  } catch (e) {
    record('debug toolpath', false, e.message.split('\n')[0]);
  }
  try {
    // The toolbar's Stop button: the palette's first row for "Debug: Stop" was another command.
    await page.locator('.debug-toolbar .codicon-debug-stop').first().click();
    await page.locator('.debug-toolbar').first().waitFor({ state: 'hidden' });
    await gotoPosition(DEBUG_LINE, 1);
    await runCommand('Debug: Toggle Breakpoint');
  } catch (e) {
    record('debug stop', false, e.message.split('\n')[0]);
  }
}

// "Insert Arc Thread Program..." from the command palette, in the walkthrough's sample (an
// untitled program, so nothing on disk changes): each of its input boxes opens on the paper's
// value and Enter accepts it; the server's program (main O0002, G65 P0003 per roughing layer)
// is inserted at the cursor. Then the sample is closed unsaved.
async function checkGenerators() {
  const quick = page.locator('.quick-input-widget');
  const input = quick.locator('input').first();
  const defaults = [];
  try {
    await runCommand('FANUC Macro: Open Walkthrough Sample Program');
    await waitActiveEditor('Untitled', 'FANUC Macro B');
    await runCommand('FANUC Macro: Insert Arc Thread Program');
    for (let n = 1; n <= 5; n++) {
      await quick.locator('.quick-input-title', { hasText: `Arc Thread Program (${n}/5)` }).waitFor();
      defaults.push(await input.inputValue());
      await page.keyboard.press('Enter');
    }
    await page.waitForFunction(
      () => /O0002 \(ARC THREAD BY THE FITTING METHOD[^\n]*\n\s*G65 P0003 A93\.82 /.test(
        (document.querySelector('.editor-group-container.active .monaco-editor .view-lines')?.innerText || '')
          .replace(/\u00a0/g, ' ')),
      null,
      { timeout: STEP_MS },
    );
    const lines = (await activeEditorText()).split('\n');
    const call = lines.find((l) => l.startsWith('G65 P0003'))?.replace(/ +/g, ' ');
    const said = await page.locator('.statusbar', { hasText: 'G32 cuts' }).first().innerText().catch(() => '');
    record('arc thread program', true,
      `defaults ${defaults.join(' | ')}; ${call?.slice(0, 120)}; ${said.split('\n').find((l) => l.includes('G32 cuts')) ?? ''}`);
  } catch (e) {
    record('arc thread program', false,
      `${e.message.split('\n')[0]}; defaults ${defaults.join(' | ')}; ${JSON.stringify((await activeEditorText()).slice(0, 300))}`);
  }
  await shot('arc-thread.png');
  await page.keyboard.press('Escape');
  await runCommand('View: Revert and Close Editor').catch(() => {});
  await checkThreadModuleOptions();
  await checkThreadModuleDefaults();
}

// "Insert Symmetric Thread Module..." with its options: a two-start left-hand designation,
// the left flank infeed picked, a 1:16 taper typed; the server's module (lead in #105, taper
// in #106, the sub-program's left-flank infeed) is inserted at the cursor of a new program.
async function checkThreadModuleOptions() {
  const quick = page.locator('.quick-input-widget');
  const input = quick.locator('input').first();
  const title = (step) => quick.locator('.quick-input-title', { hasText: `Symmetric Thread Module (${step}/4)` });
  try {
    await runCommand('FANUC Macro: Open Walkthrough Sample Program');
    await waitActiveEditor('Untitled', 'FANUC Macro B');
    await runCommand('FANUC Macro: Insert Symmetric Thread Module');
    await title(1).waitFor();
    await input.fill('M24xPh4P2-6g-LH');
    await page.keyboard.press('Enter');
    await title(2).waitFor();
    await input.fill('30');
    await page.keyboard.press('Enter');
    await title(3).waitFor();
    await input.fill('Left flank');
    await quick.locator('.monaco-list-row', { hasText: 'Left flank' }).first().waitFor();
    await page.keyboard.press('Enter');
    await title(4).waitFor();
    await input.fill('1:16');
    await page.keyboard.press('Enter');
    // The module lands at the cursor, the sample's first line: its top is shown from the
    // file's start, whichever way the editor scrolled after the insertion.
    const until = Date.now() + STEP_MS;
    let text = '';
    while (!(text.includes('LEFT FLANK INFEED, LEFT HAND') && text.includes('#105='))) {
      if (Date.now() > until) throw new Error('the module did not appear in the editor');
      await page.waitForTimeout(500);
      await page.keyboard.press('Control+Home');
      text = await activeEditorText();
    }
    const lines = text.split('\n').map((l) => l.replace(/ +/g, ' '));
    const lead = lines.find((l) => l.startsWith('#105='));
    const taper = lines.find((l) => l.startsWith('#106='));
    if (lead === undefined || taper === undefined) throw new Error('no #105 or #106 in the module');
    record('thread module options', true, `${lead}; ${taper}`);
  } catch (e) {
    record('thread module options', false,
      `${e.message.split('\n')[0]}; ${JSON.stringify((await activeEditorText()).slice(0, 300))}`);
  }
  await shot('thread-module.png');
  await page.keyboard.press('Escape');
  await runCommand('View: Revert and Close Editor').catch(() => {});
}

// "Insert Symmetric Thread Module..." answered with Enter in every box after the designation:
// the length box opens on one nominal diameter (24 for M24x3), the taper box empty with the
// placeholder "parallel". Inserted twice into the same program: the second module takes the
// numbers the program does not have yet (O4010 and O3332, its M98 too), and a notification says
// which.
async function checkThreadModuleDefaults() {
  const quick = page.locator('.quick-input-widget');
  const input = quick.locator('input').first();
  const title = (step) => quick.locator('.quick-input-title', { hasText: `Symmetric Thread Module (${step}/4)` });
  const seen = [];
  const insert = async () => {
    await runCommand('FANUC Macro: Insert Symmetric Thread Module');
    await title(1).waitFor();
    await input.fill('M24x3-6g');
    await page.keyboard.press('Enter');
    await title(2).waitFor();
    await page.waitForFunction(() => document.querySelector('.quick-input-widget input')?.value !== 'M24x3-6g', null, { timeout: STEP_MS });
    seen.push(`length ${JSON.stringify(await input.inputValue())}`);
    await page.keyboard.press('Enter');
    await title(3).waitFor();
    await quick.locator('.monaco-list-row', { hasText: 'Symmetric' }).first().waitFor();
    await page.keyboard.press('Enter');
    await title(4).waitFor();
    seen.push(`taper ${JSON.stringify(await input.inputValue())} (${await input.getAttribute('placeholder')})`);
    await page.keyboard.press('Enter');
  };
  const moduleText = async (want) => {
    const until = Date.now() + STEP_MS;
    let text = '';
    while (!want.every((w) => text.includes(w))) {
      if (Date.now() > until) throw new Error(`no ${want.join(', ')} in the editor`);
      await page.waitForTimeout(500);
      await page.keyboard.press('Control+Home');
      text = await activeEditorText();
    }
    return text;
  };
  try {
    await runCommand('FANUC Macro: Open Walkthrough Sample Program');
    await waitActiveEditor('Untitled', 'FANUC Macro B');
    await insert();
    if (seen[0] !== 'length "24"' || seen[1] !== 'taper "" (parallel)') throw new Error(`the boxes opened on ${seen.join(', ')}`);
    await moduleText(['O4009 (MAIN - EXTERNAL THREAD M24x3-6g L=24)', 'M98 P0013331']);
    await page.keyboard.press('Control+Home');
    await insert();
    const text = await moduleText(['O4010 (MAIN - EXTERNAL THREAD M24x3-6g L=24)', 'M98 P0013332']);
    const subs = text.split('\n').filter((l) => /^O333[12] /.test(l)).length;
    const toast = page.locator('.notifications-toasts', { hasText: 'in the file already' }).first();
    await toast.waitFor({ timeout: STEP_MS });
    const said = (await toast.innerText()).split('\n').find((l) => l.includes('in the file already'));
    record('thread module defaults', true, `${seen.slice(0, 2).join(', ')}; the second module O4010 / M98 P0013332${subs ? ` (${subs} sub-program lines on screen)` : ''}; ${said}`);
  } catch (e) {
    record('thread module defaults', false,
      `${e.message.split('\n')[0]}; ${seen.join(', ')}; ${JSON.stringify((await activeEditorText()).slice(0, 300))}`);
  }
  await shot('thread-module-defaults.png');
  await page.keyboard.press('Escape');
  await runCommand('View: Revert and Close Editor').catch(() => {});
}

/**
 * Opens `name` of the workspace through Quick Open and waits for its editor. F1, then the name
 * without `>`: Ctrl+P did not reach the workbench once the status bar item had been clicked.
 */
async function openFile(name) {
  await page.keyboard.press('F1');
  const input = page.locator('.quick-input-widget input');
  await input.waitFor({ state: 'visible' });
  await input.fill(name);
  await page.locator('.quick-input-list .monaco-list-row', { hasText: name }).first().waitFor();
  await page.keyboard.press('Enter');
  await waitActiveEditor(name, 'FANUC Macro B');
  await editor.locator('.view-lines').waitFor();
}

// The extension's workbench parts: no colour swatch on `#101` (VS Code would read it as a hex
// colour), the status bar item with the controller and the program's machine (a click offers the
// others), the rule code's
// link in the Problems panel opening the shipped rules page, and the Settings UI's group title.
async function checkExtensionUi() {
  const SWATCH_FILE = 'o4009_external_m50x3.nc'; // line 7: `#101=3.`
  // The default controller, 0i-F, with the machine the open program's codes show (a lathe's).
  const status = page.locator('.statusbar-item', { hasText: /0i-F lathe(?! or|\?)/ }).first();
  try {
    await openFile(SWATCH_FILE);
    await gotoPosition(7, 1);
    await editor.locator('.view-line', { hasText: '#101=3.' }).first().waitFor();
    // The server has analysed the file (its state back to ready) before the swatches are counted.
    await page.waitForFunction(
      () => [...document.querySelectorAll('.statusbar-item')].some((e) =>
        /0i-F lathe(?! or|\?)/.test(e.innerText) && !/analysing|starting/.test(e.innerText)
        && e.querySelector('.codicon-check') !== null),
      null,
      { timeout: STEP_MS },
    );
    const swatches = await editor.locator('.colorpicker-color-decoration').count();
    record('no colour swatch', swatches === 0, `${SWATCH_FILE} line 7 "#101=3.": ${swatches} colour decorations`);
  } catch (e) {
    record('no colour swatch', false, e.message.split('\n')[0]);
    await shot('swatch.png');
  }

  try {
    const text = (await status.innerText()).trim();
    const tooltip = await status.locator('a, [role="button"]').first().getAttribute('aria-label').catch(() => null);
    await status.click();
    const rows = page.locator('.quick-input-list .monaco-list-row');
    await rows.filter({ hasText: '18i-M' }).first().waitFor();
    const offered = (await rows.allInnerTexts()).map((t) => t.split('\n')[0].trim()).slice(0, 8);
    await page.keyboard.press('Escape');
    await page.locator('.quick-input-widget').waitFor({ state: 'hidden' });
    record('status bar controller', /0i-F lathe(?! or|\?)/.test(text) && offered.length >= 8,
      `${JSON.stringify(text)} (${tooltip ?? 'no label'}); a click offers ${offered.join(', ')}`);
  } catch (e) {
    record('status bar controller', false, e.message.split('\n')[0]);
    await shot('status.png');
  }

  // The rule code of a diagnostic in the Problems panel links to the shipped documentation.
  try {
    await openFile(FILE);
    // Ctrl+Shift+M toggles the panel: pressed only when it is not shown (it is, since (b)).
    if (!(await page.locator('.markers-panel').isVisible())) await page.keyboard.press('Control+Shift+M');
    const link = page.locator('.markers-panel a', { hasText: 'MB601' }).first();
    await link.waitFor();
    const href = await link.getAttribute('href');
    await link.click();
    await page.locator('.editor-group-container.active .tab.active', { hasText: 'rules.md' }).first().waitFor();
    await page.waitForFunction(
      () => /^## MB601 /m.test((document.querySelector('.editor-group-container.active .monaco-editor .view-lines')?.innerText || '')
        .replace(/\u00a0/g, ' ')),
      null,
      { timeout: STEP_MS },
    );
    record('rule documentation link', (href || '').startsWith('command:fanuc-macro.openRuleDocumentation'),
      `${href}: rules.md open at ${JSON.stringify((await activeEditorText()).split('\n').find((l) => l.startsWith('## MB601')))}`);
  } catch (e) {
    record('rule documentation link', false, e.message.split('\n')[0]);
    await shot('rule-link.png');
  }

  // The Settings UI: the extension's settings under its title.
  try {
    await runCommand('Preferences: Open Settings (UI)');
    await page.locator('.settings-editor .settings-header').waitFor();
    // The search box has the focus when the editor opens.
    await page.keyboard.type('fanuc-macro');
    const item = page.locator('.settings-editor .setting-item-contents', { hasText: 'Controller' }).first();
    await item.waitFor();
    const label = (await item.locator('.setting-item-title').innerText()).replace(/\s+/g, ' ').trim();
    const toc = (await page.locator('.settings-editor .settings-toc-container').innerText().catch(() => '')).replace(/\s+/g, ' ').trim();
    const groups = (await page.locator('.settings-editor .settings-group-title-label').allInnerTexts()).map((t) => t.trim());
    await shot('settings.png');
    record('settings title', groups.includes('FANUC Macro B') || toc.includes('FANUC Macro B'),
      `group titles ${JSON.stringify(groups)}; contents ${JSON.stringify(toc)}; the setting reads ${JSON.stringify(label)}`);
  } catch (e) {
    record('settings title', false, e.message.split('\n')[0]);
    await shot('settings.png');
  }
  // The program again, for the checks after this one (the other editors stay open, inactive).
  // code-server shows the Settings editor as a modal: Escape (twice: the first may only clear
  // its search box) closes it.
  try {
    for (let i = 0; i < 3 && (await page.locator('.settings-editor').isVisible()); i++) {
      await page.keyboard.press('Escape');
      await page.locator('.settings-editor').waitFor({ state: 'hidden', timeout: 2000 }).catch(() => {});
    }
    await openFile(FILE);
  } catch (e) {
    record('program reopened', false, e.message.split('\n')[0]);
    await shot('reopen.png');
  }
}

/** The line number of the active editor's visible line that starts with `prefix`, or -1. */
async function lineNumberOf(prefix) {
  return page.evaluate((want) => {
    const view = document.querySelector('.editor-group-container.active .monaco-editor');
    if (!view) return -1;
    const line = [...view.querySelectorAll('.view-line')]
      .find((l) => l.innerText.replace(/\u00a0/g, ' ').startsWith(want));
    if (!line) return -1;
    // The gutter's number at the same height (the lines' DOM order need not be theirs).
    const top = line.getBoundingClientRect().top;
    const number = [...view.querySelectorAll('.line-numbers')]
      .find((n) => Math.abs(n.getBoundingClientRect().top - top) < 2);
    return number ? Number(number.textContent) : -1;
  }, prefix);
}

/**
 * The language server's semantic tokens, code lenses and signature help in the editor: the token
 * inspector names a semantic token type for `#1` (line 9), a lens over `O3` (line 8) counts its
 * caller, and typing a G65 call on a new line opens the parameter hints, then the typing is
 * undone.
 */
async function checkTokensAndLenses() {
  await editor.click({ position: { x: 200, y: 10 } });
  await gotoPosition(9, 6);
  try {
    await runCommand('Developer: Inspect Editor Tokens and Scopes');
    await page.waitForFunction(
      () => /semantic token type\s*variable/.test(document.querySelector('.token-inspect-widget')?.innerText || ''),
      null,
      { timeout: STEP_MS },
    );
    const text = await page.locator('.token-inspect-widget').innerText();
    record('semantic tokens', true, text.split('\n').filter((l) => /semantic|modifiers/.test(l)).join(' | '));
    await shot('semantic-tokens.png');
  } catch (e) {
    const text = await page.locator('.token-inspect-widget').innerText().catch(() => '');
    record('semantic tokens', false, `${e.message.split('\n')[0]}; inspector ${JSON.stringify(text.slice(0, 400))}`);
  }
  await page.keyboard.press('Escape');

  try {
    await page.waitForFunction(
      () => [...document.querySelectorAll('.codelens-decoration')].some((d) => /called from O0002/.test(d.innerText)),
      null,
      { timeout: STEP_MS },
    );
    const lenses = await page.evaluate(() => [...document.querySelectorAll('.codelens-decoration')]
      .map((d) => d.innerText.trim()).filter(Boolean));
    record('code lens', true, lenses.slice(0, 4).join(' | '));
  } catch (e) {
    const lenses = await page.evaluate(() => [...document.querySelectorAll('.codelens-decoration')]
      .map((d) => d.innerText.trim())).catch(() => []);
    record('code lens', false, `${e.message.split('\n')[0]}; lenses ${JSON.stringify(lenses)}`);
  }

  // A new line after line 3 (`N1 M98 P3 ...`), a G65 call typed on it.
  await editor.click({ position: { x: 200, y: 10 } });
  await gotoPosition(3, 1);
  await page.keyboard.press('End');
  await page.keyboard.press('Enter');
  await page.keyboard.type('G65 P3 A1. B', { delay: 30 });
  try {
    await page.waitForFunction(
      // Shown: a box of some size (the widget is fixed-positioned, so offsetParent is null).
      () => [...document.querySelectorAll('.parameter-hints-widget')].some((w) =>
        w.getBoundingClientRect().height > 0 && /G65 P3/.test(w.innerText) && /B=#2/.test(w.innerText)),
      null,
      { timeout: STEP_MS },
    );
    const text = await page.locator('.parameter-hints-widget').first().innerText();
    record('signature help', true, text.split('\n').filter(Boolean).slice(0, 3).join(' | '));
    await shot('signature-help.png');
  } catch (e) {
    const text = await page.evaluate(() => [...document.querySelectorAll('.parameter-hints-widget')]
      .map((w) => w.innerText).join('\n')).catch(() => '');
    record('signature help', false, `${e.message.split('\n')[0]}; widget ${JSON.stringify(text.slice(0, 300))}`);
  }
  await page.keyboard.press('Escape');
  // Undo the typing (the session made no edit before it, so undoing too often changes nothing).
  for (let i = 0; i < 30 && ((await lineNumberOf('G65 P3')) !== -1 || (await lineNumberOf('N2 M98')) !== 4); i++) {
    await page.keyboard.press('Control+Z');
  }
  const restored = (await lineNumberOf('G65 P3')) === -1 && (await lineNumberOf('N2 M98')) === 4;
  record('signature help undone', restored, restored ? 'the typed line is gone' : 'the typed line is still there');
}

try {
  const url = `${baseUrl.replace(/\/$/, '')}/?folder=${encodeURIComponent(workspace)}`;
  await page.goto(url);
  await page.locator('.monaco-workbench').waitFor();
  await page.locator('.explorer-folders-view').waitFor();
  log('workbench loaded');

  // Open the program through Quick Open, as a person would.
  await page.keyboard.press('Control+P');
  await page.locator('.quick-input-widget input').waitFor({ state: 'visible' });
  await page.keyboard.type(FILE);
  await page.locator('.quick-input-list .monaco-list-row', { hasText: FILE }).first().waitFor();
  await page.keyboard.press('Enter');
  await page.locator('.tab.active', { hasText: FILE }).waitFor();
  await editor.locator('.view-lines').waitFor();
  log('editor open');

  // (a) language mode in the status bar.
  const mode = page.locator('[id="status.editor.mode"]');
  try {
    await page.waitForFunction(
      () => document.getElementById('status.editor.mode')?.innerText.includes('FANUC Macro B'),
      null,
      { timeout: STEP_MS },
    );
    record('language mode', true, await mode.innerText());
  } catch {
    record('language mode', false, `status bar shows ${JSON.stringify(await mode.innerText().catch(() => ''))}`);
  }

  // (a') TextMate highlighting: the token inspector reports the grammar's scopes
  // for `#1` on line 9 (`N01 #1 = 93.82 ...`).
  await editor.click({ position: { x: 200, y: 10 } });
  await gotoPosition(9, 6);
  try {
    await runCommand('Developer: Inspect Editor Tokens and Scopes');
    const widget = page.locator('.token-inspect-widget');
    await page.waitForFunction(
      () => /variable.*fanuc-macro/.test(document.querySelector('.token-inspect-widget')?.innerText || ''),
      null,
      { timeout: STEP_MS },
    );
    const text = await widget.innerText();
    const scopes = text.split('\n').filter((l) => l.includes('fanuc-macro'));
    record('syntax highlighting', scopes.some((l) => l.includes('source.fanuc-macro')), scopes.join(' | '));
    await shot('tokens.png');
    await page.keyboard.press('Escape');
  } catch (e) {
    const classes = await editor.evaluate((el) =>
      [...new Set([...el.querySelectorAll('.view-lines span span')].map((s) => s.className.split(' ')[0]))]);
    record('syntax highlighting', false, `token inspector failed (${e.message.split('\n')[0]}); token classes ${classes}`);
  }

  // (b) diagnostics from the language server, in the Problems panel.
  await page.keyboard.press('Control+Shift+M');
  const markers = page.locator('.markers-panel');
  try {
    await page.waitForFunction(
      () => {
        const t = document.querySelector('.markers-panel')?.innerText || '';
        return t.includes('MB601') && t.includes('93.82');
      },
      null,
      { timeout: STEP_MS },
    );
    const rows = (await markers.innerText()).split('\n').filter((l) => l.includes('93.82') || l.includes('MB601'));
    record('diagnostics', true, rows.slice(0, 3).join(' | '));
  } catch {
    record('diagnostics', false, `Problems panel: ${JSON.stringify((await markers.innerText().catch(() => '')).slice(0, 400))}`);
  }
  await shot('problems.png');

  // (c) hover on `#1` (line 9, column 6) shows its value.
  await editor.click({ position: { x: 200, y: 10 } });
  await gotoPosition(9, 6);
  try {
    const cursor = editor.locator('.cursors-layer .cursor').first();
    const box = await cursor.boundingBox();
    await page.mouse.move(box.x - 3, box.y + box.height / 2);
    await page.mouse.move(box.x - 2, box.y + box.height / 2);
    // The value first: `#1 = 93.82`, then its meaning in a line.
    await page.waitForFunction(
      () => [...document.querySelectorAll('.monaco-hover')].some((h) =>
        h.offsetParent !== null && /^#1 = 93\.82\b/.test(h.innerText.replace(/\u00a0/g, ' ').trim())),
      null,
      { timeout: STEP_MS },
    );
    const text = await page.evaluate(() => [...document.querySelectorAll('.monaco-hover')]
      .filter((h) => h.offsetParent !== null).map((h) => h.innerText).join('\n'));
    // It fits in 12 lines of the editor's font, with no scroll bar of its own.
    const fit = await page.evaluate(() => {
      const hover = [...document.querySelectorAll('.monaco-hover')].find((h) => h.offsetParent !== null);
      const line = document.querySelector('.monaco-editor .view-line')?.getBoundingClientRect().height || 19;
      const contents = hover?.querySelector('.monaco-hover-content') || hover;
      const height = contents?.getBoundingClientRect().height || 0;
      return { lines: height / line, scrolls: (contents?.scrollHeight || 0) > (contents?.clientHeight || 0) + 1 };
    });
    if (fit.lines > 12 || fit.scrolls) throw new Error(`the hover takes ${fit.lines.toFixed(1)} lines${fit.scrolls ? ' and scrolls' : ''}`);
    record('hover', true, `${fit.lines.toFixed(1)} lines: ${text.split('\n').filter(Boolean).slice(0, 4).join(' | ')}`);
  } catch (e) {
    const text = await page.evaluate(() => [...document.querySelectorAll('.monaco-hover')]
      .map((h) => h.innerText).join('\n')).catch(() => '');
    record('hover', false, `${e.message.split('\n')[0]}; hover text ${JSON.stringify(text.slice(0, 300))}`);
  }
  await shot('hover.png');
  await page.keyboard.press('Escape');

  await checkExtensionUi();
  await checkNavigation();
  await checkTokensAndLenses();
  await checkToolpath();
  await checkToolpathPrograms();
  await checkTrace();
  await checkDebug();
  await checkGenerators();
} catch (e) {
  record('session', false, e.stack || String(e));
  await shot('failure.png').catch(() => {});
} finally {
  await browser.close();
}

if (blocked.size) log('blocked requests to', [...blocked].join(', '));
writeFileSync(join(outDir, 'results.json'), JSON.stringify(results, null, 2));
const failed = results.filter((r) => !r.ok).length;
const passed = results.length - failed;
// Not in the "N passed, N failed" form, which CI may read as a test runner's closing line.
console.log(`check.mjs: ${passed} of ${results.length} checks passed`);
process.exit(failed || results.length < 10 ? 1 : 0);
