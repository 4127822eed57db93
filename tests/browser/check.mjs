// Drives a real VS Code (code-server) in headless Chromium and checks that the
// fanuc-macro extension works in it: language mode, TextMate highlighting,
// diagnostics from the language server, and a hover with a value.
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
  await page.waitForTimeout(300);
}

const editor = page.locator('.editor-instance .monaco-editor').first();

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
    await page.waitForFunction(
      () => [...document.querySelectorAll('.monaco-hover')].some((h) =>
        h.offsetParent !== null && /#1/.test(h.innerText) && /Value[^\n]*93\.82/.test(h.innerText)),
      null,
      { timeout: STEP_MS },
    );
    const text = await page.evaluate(() => [...document.querySelectorAll('.monaco-hover')]
      .filter((h) => h.offsetParent !== null).map((h) => h.innerText).join('\n'));
    record('hover', true, text.split('\n').filter(Boolean).slice(0, 4).join(' | '));
  } catch (e) {
    const text = await page.evaluate(() => [...document.querySelectorAll('.monaco-hover')]
      .map((h) => h.innerText).join('\n')).catch(() => '');
    record('hover', false, `${e.message.split('\n')[0]}; hover text ${JSON.stringify(text.slice(0, 300))}`);
  }
  await shot('hover.png');
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
process.exit(failed || results.length < 4 ? 1 : 0);
