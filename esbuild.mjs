// Build script for the VS Code client.
//
//   node esbuild.mjs               bundle client/src/extension.ts -> client/out/extension.js
//                                  and the Toolpath view's page client/webview/toolpath.ts
//                                  -> client/out/webview/toolpath.js
//   node esbuild.mjs --production  the same, minified and without source maps
//   node esbuild.mjs --test        bundle client/test/*.test.ts -> client/out/test/*.test.js
//                                  and run them with node's built-in test runner
import { spawnSync } from 'node:child_process';
import { readdirSync, rmSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import * as esbuild from 'esbuild';

const root = dirname(fileURLToPath(import.meta.url));
const args = new Set(process.argv.slice(2));
const production = args.has('--production');
const test = args.has('--test');

const common = {
  bundle: true,
  platform: 'node',
  format: 'cjs',
  target: 'node18',
  external: ['vscode'],
  logLevel: 'warning',
};

async function buildExtension() {
  await esbuild.build({
    ...common,
    entryPoints: [join(root, 'client/src/extension.ts')],
    outfile: join(root, 'client/out/extension.js'),
    minify: production,
    sourcemap: !production,
    sourcesContent: false,
  });
  await esbuild.build({
    bundle: true,
    platform: 'browser',
    format: 'iife',
    target: 'es2022',
    logLevel: 'warning',
    entryPoints: [join(root, 'client/webview/toolpath.ts')],
    outfile: join(root, 'client/out/webview/toolpath.js'),
    minify: production,
    sourcemap: !production,
    sourcesContent: false,
  });
}

async function buildAndRunTests() {
  const testDir = join(root, 'client/test');
  const outDir = join(root, 'client/out/test');
  const entries = readdirSync(testDir)
    .filter((name) => name.endsWith('.test.ts'))
    .sort();
  if (entries.length === 0) {
    console.error('no unit tests found in client/test');
    process.exit(1);
  }
  rmSync(outDir, { recursive: true, force: true });
  await esbuild.build({
    ...common,
    // The tests run the client against small fakes of the VS Code API.
    external: [],
    alias: {
      vscode: './client/test/fakes/vscode.ts',
      'vscode-languageclient/node': './client/test/fakes/languageclient.ts',
    },
    absWorkingDir: root,
    entryPoints: entries.map((name) => join(testDir, name)),
    outdir: outDir,
    sourcemap: 'inline',
  });
  const files = entries.map((name) => join(outDir, name.replace(/\.ts$/, '.js')));
  const result = spawnSync(process.execPath, ['--enable-source-maps', '--test', ...files], {
    stdio: 'inherit',
    cwd: root,
  });
  if (result.error) {
    throw result.error;
  }
  process.exit(result.status ?? 1);
}

try {
  if (test) {
    await buildAndRunTests();
  } else {
    await buildExtension();
  }
} catch (err) {
  console.error(err instanceof Error ? err.message : err);
  process.exit(1);
}
