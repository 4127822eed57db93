// Bundles the fanuc-macro language server for the .vsix, so that a user who
// has only Python (3.10 or later) and never ran pip gets the server:
//
//   node client/scripts/bundle-server.mjs [OUTPUT_DIR] [--strict]
//
// OUTPUT_DIR (default: bundled/python at the repository root) receives
//   - the pure-Python runtime dependencies of the server (lark, pygls,
//     lsprotocol and what they need), installed with
//     `pip install --target OUTPUT_DIR --no-compile --no-deps` at the versions
//     installed in the Python that runs this script, as universal
//     (py3-none-any) wheels only;
//   - a copy of server/fanuc_macro with the symlinks of its data/ folder
//     replaced by the files they point to, without __pycache__;
//   - fanuc-macro-bundle.json, which lists what was bundled.
// The client runs `python -m fanuc_macro.lsp.server` with OUTPUT_DIR first on
// PYTHONPATH (client/src/serverCandidates.ts).
//
// numpy is not bundled: it is binary and platform-specific.
//
// The Python used to read the versions and run pip is $PYTHON, else python3
// (python on Windows). At the end the script starts the bundled server with
// `--version` in a minimal environment (`python -S -B`, PYTHONPATH=OUTPUT_DIR);
// when that fails it warns, or exits with an error under --strict.
import { spawnSync } from 'node:child_process';
import {
  cpSync,
  existsSync,
  lstatSync,
  mkdirSync,
  readFileSync,
  readdirSync,
  rmSync,
  statSync,
  writeFileSync,
} from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
const MANIFEST = 'fanuc-macro-bundle.json';

/** Distributions the server imports; their requirements are followed from the installed metadata. */
const ROOTS = ['lark', 'pygls', 'lsprotocol'];
/** Binary, platform-specific: never bundled (the server must do without it). */
const EXCLUDED = ['numpy'];
/**
 * Pins for requirements the bundle needs on some Python ≥ 3.10 although this
 * machine's Python does not have them installed (their marker excludes it):
 * cattrs needs exceptiongroup on Python 3.10 only.
 */
const FALLBACK_PINS = { exceptiongroup: '1.3.2' };
/** Oldest Python the bundle is for: pip picks wheels that work there and on every later 3.x. */
const MIN_PYTHON = '3.10';

function usage(message) {
  if (message) console.error(`bundle-server: ${message}`);
  console.error('usage: node client/scripts/bundle-server.mjs [OUTPUT_DIR] [--strict]');
  process.exit(2);
}

function fail(message) {
  console.error(`bundle-server: ${message}`);
  process.exit(1);
}

const positional = [];
let strict = false;
for (const arg of process.argv.slice(2)) {
  if (arg === '--strict') strict = true;
  else if (arg === '-h' || arg === '--help') usage();
  else if (arg.startsWith('-')) usage(`unknown option ${arg}`);
  else positional.push(arg);
}
if (positional.length > 1) usage('give at most one output folder');
const outDir = positional.length === 1 ? resolve(positional[0]) : join(root, 'bundled', 'python');
const python = process.env.PYTHON || (process.platform === 'win32' ? 'python' : 'python3');

function run(command, args, options = {}) {
  const result = spawnSync(command, args, { encoding: 'utf8', maxBuffer: 64 * 1024 * 1024, ...options });
  if (result.error) {
    fail(`cannot run ${command}: ${result.error.message}`);
  }
  return result;
}

// ---- 1. the distributions to bundle, at the versions installed here

const RESOLVE = String.raw`
import json, re, sys
from importlib import metadata

roots, excluded, fallback = (json.loads(a) for a in sys.argv[1:4])

def norm(name):
    return re.sub(r"[-_.]+", "-", name).lower()

excluded = {norm(n) for n in excluded}
fallback = {norm(n): v for n, v in fallback.items()}
found, missing, todo = {}, {}, [(norm(r), "the server") for r in roots]
while todo:
    name, needed_by = todo.pop(0)
    if name in excluded or name in found or name in missing:
        continue
    try:
        dist = metadata.distribution(name)
    except metadata.PackageNotFoundError:
        missing[name] = needed_by
        continue
    found[name] = {"name": dist.metadata["Name"], "version": dist.version}
    for req in dist.requires or []:
        spec, _, marker = req.partition(";")
        if re.search(r"\bextra\s*==", marker):
            continue  # optional feature
        match = re.match(r"\s*([A-Za-z0-9][A-Za-z0-9._-]*)", spec)
        if match:
            todo.append((norm(match.group(1)), dist.metadata["Name"]))
unresolved = {n: by for n, by in missing.items() if n not in fallback}
for n in missing:
    if n in fallback:
        found[n] = {"name": n, "version": fallback[n], "fallback": True}
print(json.dumps({
    "python": sys.version.split()[0],
    "packages": sorted(found.values(), key=lambda d: norm(d["name"])),
    "unresolved": unresolved,
}))
`;

const resolved = run(python, [
  '-c',
  RESOLVE,
  JSON.stringify(ROOTS),
  JSON.stringify(EXCLUDED),
  JSON.stringify(FALLBACK_PINS),
]);
if (resolved.status !== 0) {
  fail(`${python} could not read the installed versions:\n${resolved.stderr}`);
}
const plan = JSON.parse(resolved.stdout);
const unresolved = Object.entries(plan.unresolved);
if (unresolved.length > 0) {
  fail(
    `not installed in ${python} (Python ${plan.python}): ` +
      unresolved.map(([name, by]) => `${name} (needed by ${by})`).join(', ') +
      '. Install the server with its dependencies first (pip install -e .), or set PYTHON.',
  );
}
const pins = plan.packages.map((p) => `${p.name}==${p.version}`);

// ---- 2. a clean output folder

if (existsSync(outDir)) {
  if (!statSync(outDir).isDirectory()) fail(`${outDir} exists and is not a folder`);
  const entries = readdirSync(outDir);
  if (entries.length > 0 && !entries.includes(MANIFEST)) {
    fail(`${outDir} is not empty and holds no ${MANIFEST}: refusing to delete it`);
  }
  rmSync(outDir, { recursive: true, force: true });
}
mkdirSync(outDir, { recursive: true });

// ---- 3. the dependencies, as universal wheels

console.log(`bundle-server: Python ${plan.python} (${python}); installing ${pins.join(' ')}`);
const pip = run(
  python,
  [
    '-m',
    'pip',
    'install',
    '--target',
    outDir,
    '--no-compile',
    '--no-deps',
    '--no-input',
    '--quiet',
    '--disable-pip-version-check',
    // only pure-Python wheels that work on every CPython/PyPy ≥ MIN_PYTHON
    '--only-binary=:all:',
    '--platform',
    'any',
    '--implementation',
    'py',
    '--abi',
    'none',
    '--python-version',
    MIN_PYTHON,
    ...pins,
  ],
  { stdio: ['ignore', 'inherit', 'inherit'], env: { ...process.env, PIP_ROOT_USER_ACTION: 'ignore' } },
);
if (pip.status !== 0) {
  fail(`pip install failed (exit ${pip.status})`);
}
// console scripts are of no use on PYTHONPATH
rmSync(join(outDir, 'bin'), { recursive: true, force: true });

// ---- 4. the server package, symlinks followed

const packageDir = join(root, 'server', 'fanuc_macro');
cpSync(packageDir, join(outDir, 'fanuc_macro'), {
  recursive: true,
  dereference: true,
  filter: (source) => {
    const name = basename(source);
    return name !== '__pycache__' && !name.endsWith('.pyc') && !name.endsWith('.pyo');
  },
});

// Check: no symlinks, no bytecode anywhere in the bundle.
let files = 0;
let bytes = 0;
function walk(dir) {
  for (const name of readdirSync(dir)) {
    const path = join(dir, name);
    const stat = lstatSync(path);
    if (stat.isSymbolicLink()) fail(`${path} is a symlink`);
    if (name === '__pycache__' || name.endsWith('.pyc')) fail(`${path}: bytecode in the bundle`);
    if (stat.isDirectory()) walk(path);
    else {
      files += 1;
      bytes += stat.size;
    }
  }
}
walk(outDir);

const versionMatch = /__version__\s*=\s*["']([^"']+)["']/.exec(
  readFileSync(join(packageDir, '__init__.py'), 'utf8'),
);
writeFileSync(
  join(outDir, MANIFEST),
  `${JSON.stringify(
    {
      server: { name: 'fanuc-macro', version: versionMatch?.[1] ?? 'unknown' },
      requiresPython: `>=${MIN_PYTHON}`,
      packages: plan.packages.map(({ name, version }) => ({ name, version })),
      notBundled: EXCLUDED,
      builtWith: `Python ${plan.python}`,
    },
    null,
    2,
  )}\n`,
);
console.log(
  `bundle-server: ${outDir}: fanuc_macro ${versionMatch?.[1] ?? '?'} + ${plan.packages.length} packages, ` +
    `${files + 1} files, ${(bytes / 1024 / 1024).toFixed(1)} MiB` +
    `; not bundled: ${EXCLUDED.join(', ')}`,
);

// ---- 5. does it start without anything installed?

const minimalEnv = { PYTHONPATH: outDir, PYTHONDONTWRITEBYTECODE: '1' };
for (const name of ['PATH', 'SYSTEMROOT', 'SystemRoot', 'TEMP', 'TMP', 'TMPDIR']) {
  if (process.env[name] !== undefined) minimalEnv[name] = process.env[name];
}
const check = run(python, ['-S', '-B', '-m', 'fanuc_macro.lsp.server', '--version'], {
  cwd: tmpdir(),
  env: minimalEnv,
  timeout: 60000,
});
const answer = `${check.stdout ?? ''}`.trim();
if (check.status === 0 && /^fanuc-macro-ls \S+$/m.test(answer)) {
  console.log(`bundle-server: the bundled server starts: ${answer}`);
} else {
  const lines = `${check.stderr ?? ''}`.trim().split(/\r?\n/);
  const message =
    `the bundled server does not start with only the bundle on the path ` +
    `(${python} -S -B -m fanuc_macro.lsp.server --version: exit ${check.status ?? check.signal}): ` +
    (lines[lines.length - 1] || answer || 'no output');
  if (strict) fail(message);
  console.warn(`bundle-server: WARNING: ${message}`);
}
