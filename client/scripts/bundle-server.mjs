// Bundles the fanuc-macro language server for the .vsix, so that a user who
// has only Python (3.10 or later) and never ran pip gets the server:
//
//   node client/scripts/bundle-server.mjs [OUTPUT_DIR] [--strict]
//
// It needs only node and a Python ≥ 3.10 with its venv module: the Python
// packages are not read from what that Python has installed. The script makes
// a temporary venv, whose pip installs the [project] dependencies of
// pyproject.toml with `pip install --target` as universal
// (py3-none-any) wheels for Python 3.10 and later, from PyPI (or the index pip
// is configured for).
//
// OUTPUT_DIR (default: bundled/python at the repository root) receives
//   - those pure-Python dependencies (lark, pygls, lsprotocol, babel and what they need);
//   - a copy of server/fanuc_macro with the symlinks of its data/ folder
//     replaced by the files they point to, without __pycache__;
//   - fanuc-macro-bundle.json, which lists what was bundled.
// The bundle is built in OUTPUT_DIR.building-<pid> beside it and renamed to
// OUTPUT_DIR only once complete: a failed build leaves the previous bundle.
// The client runs `python -m fanuc_macro.lsp.server` with OUTPUT_DIR first on
// PYTHONPATH (client/src/serverCandidates.ts).
//
// numpy is never bundled: it is binary and platform-specific (the project does not
// depend on it; the build fails if a dependency brings it).
//
// The Python is $PYTHON, else python3 (python on Windows). Before the bundle
// replaces the previous one, the script starts it with `--version` in a minimal
// environment (`python -S -B`, PYTHONPATH=the new bundle); when that fails it
// warns, or under --strict exits with an error and keeps the previous bundle.
import { spawnSync } from 'node:child_process';
import {
  cpSync,
  existsSync,
  lstatSync,
  mkdirSync,
  mkdtempSync,
  readFileSync,
  readdirSync,
  renameSync,
  rmSync,
  statSync,
  writeFileSync,
} from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
const MANIFEST = 'fanuc-macro-bundle.json';

/** Binary, platform-specific: never bundled (the server must do without it). */
const EXCLUDED = ['numpy'];
/**
 * Requirements of the dependencies on the oldest Python only, added by hand: pip evaluates the
 * markers of requirements for the Python running it, not for --python-version. cattrs needs
 * exceptiongroup on Python 3.10 (`exceptiongroup>=1.1.1; python_version < "3.11"`), and the
 * server tomli to read fanuc-macro.toml there (`tomli>=2.0; python_version < '3.11'`).
 */
const OLDEST_PYTHON_NEEDS = ['exceptiongroup>=1.1.1', 'tomli>=2.0'];
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

// ---- 1. the requirements, from pyproject.toml

/** The `dependencies = [...]` of pyproject.toml's [project] table (Python 3.10 has no tomllib). */
function projectDependencies(text) {
  const table = /^\[project\]\s*$([\s\S]*?)(?=^\[|(?![\s\S]))/m.exec(text);
  const list = table && /^dependencies\s*=\s*\[([\s\S]*?)\]/m.exec(table[1]);
  if (!list) fail('pyproject.toml has no [project] dependencies list');
  // A comment's words are not requirements (an apostrophe in one would open a string).
  const items = list[1].replace(/#.*$/gm, '');
  return [...items.matchAll(/"([^"]+)"|'([^']+)'/g)].map((m) => m[1] ?? m[2]);
}

function requirementName(requirement) {
  return (/^\s*([A-Za-z0-9][A-Za-z0-9._-]*)/.exec(requirement)?.[1] ?? requirement)
    .replace(/[-_.]+/g, '-')
    .toLowerCase();
}

const requirements = [
  ...projectDependencies(readFileSync(join(root, 'pyproject.toml'), 'utf8')).filter(
    (requirement) => !EXCLUDED.includes(requirementName(requirement)),
  ),
  ...OLDEST_PYTHON_NEEDS,
];

// ---- 2. a temporary venv: its pip resolves them, whatever the Python running this has installed

const work = mkdtempSync(join(tmpdir(), 'fanuc-macro-bundle-'));
process.on('exit', () => rmSync(work, { recursive: true, force: true }));
const venv = join(work, 'venv');
const made = run(python, ['-m', 'venv', venv]);
if (made.status !== 0) {
  fail(
    `${python} -m venv failed (exit ${made.status}): ${made.stderr.trim()}\n` +
      'The bundle needs Python 3.10 or later with its venv module (on Debian/Ubuntu: apt install python3-venv).',
  );
}
const venvPython =
  process.platform === 'win32' ? join(venv, 'Scripts', 'python.exe') : join(venv, 'bin', 'python');
const version = run(venvPython, ['-c', 'import sys; print("%d.%d.%d" % sys.version_info[:3])']);
const pythonVersion = version.stdout.trim();
const [major, minor] = pythonVersion.split('.').map(Number);
if (version.status !== 0 || major !== 3 || minor < 10) {
  fail(`${python} is Python ${pythonVersion || '?'}: the server needs Python ${MIN_PYTHON} or later`);
}

// ---- 3. the dependencies, as universal wheels, into a folder beside OUTPUT_DIR

if (existsSync(outDir)) {
  if (!statSync(outDir).isDirectory()) fail(`${outDir} exists and is not a folder`);
  const entries = readdirSync(outDir);
  if (entries.length > 0 && !entries.includes(MANIFEST)) {
    fail(`${outDir} is not empty and holds no ${MANIFEST}: refusing to replace it`);
  }
}
// Built beside OUTPUT_DIR (same file system, so it can be renamed), which stays as it is until
// the new bundle is complete and starts.
mkdirSync(dirname(outDir), { recursive: true });
const building = `${outDir}.building-${process.pid}`;
rmSync(building, { recursive: true, force: true });
process.on('exit', () => rmSync(building, { recursive: true, force: true }));

console.log(`bundle-server: Python ${pythonVersion} (${python}); installing ${requirements.join(' ')}`);
const pip = run(
  venvPython,
  [
    '-m',
    'pip',
    'install',
    '--target',
    building,
    '--no-compile',
    '--no-input',
    '--quiet',
    '--disable-pip-version-check',
    // only pure-Python wheels that work on every CPython/PyPy ≥ MIN_PYTHON; markers are
    // evaluated for MIN_PYTHON, so what an older Python needs is there too
    '--only-binary=:all:',
    '--platform',
    'any',
    '--implementation',
    'py',
    '--abi',
    'none',
    '--python-version',
    MIN_PYTHON,
    ...requirements,
  ],
  { stdio: ['ignore', 'inherit', 'inherit'], env: { ...process.env, PIP_ROOT_USER_ACTION: 'ignore' } },
);
if (pip.status !== 0) {
  fail(`pip install failed (exit ${pip.status}); ${outDir} is left as it was`);
}
// console scripts are of no use on PYTHONPATH
rmSync(join(building, 'bin'), { recursive: true, force: true });

/** What pip installed: the name and version of each *.dist-info folder's METADATA. */
function installedPackages(dir) {
  const packages = [];
  for (const name of readdirSync(dir).filter((n) => n.endsWith('.dist-info')).sort()) {
    const metadata = readFileSync(join(dir, name, 'METADATA'), 'utf8');
    const field = (key) => new RegExp(`^${key}:\\s*(.+)$`, 'm').exec(metadata)?.[1]?.trim();
    packages.push({ name: field('Name') ?? name, version: field('Version') ?? '?' });
  }
  return packages.sort((a, b) => requirementName(a.name).localeCompare(requirementName(b.name)));
}
const packages = installedPackages(building);
const binary = packages.filter((p) => EXCLUDED.includes(requirementName(p.name)));
if (binary.length > 0) fail(`a binary package would be bundled: ${binary.map((p) => p.name).join(', ')}`);

// ---- 4. the server package, symlinks followed

const packageDir = join(root, 'server', 'fanuc_macro');
cpSync(packageDir, join(building, 'fanuc_macro'), {
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
walk(building);

const versionMatch = /__version__\s*=\s*["']([^"']+)["']/.exec(
  readFileSync(join(packageDir, '__init__.py'), 'utf8'),
);
writeFileSync(
  join(building, MANIFEST),
  `${JSON.stringify(
    {
      server: { name: 'fanuc-macro', version: versionMatch?.[1] ?? 'unknown' },
      requiresPython: `>=${MIN_PYTHON}`,
      requirements,
      packages,
      notBundled: EXCLUDED,
      builtWith: `Python ${pythonVersion}`,
    },
    null,
    2,
  )}\n`,
);
console.log(
  `bundle-server: fanuc_macro ${versionMatch?.[1] ?? '?'} + ${packages.length} packages ` +
    `(${packages.map((p) => `${p.name} ${p.version}`).join(', ')}), ` +
    `${files + 1} files, ${(bytes / 1024 / 1024).toFixed(1)} MiB` +
    `; not bundled: ${EXCLUDED.join(', ')}`,
);

// ---- 5. does it start without anything installed?

const minimalEnv = { PYTHONPATH: building, PYTHONDONTWRITEBYTECODE: '1' };
for (const name of ['PATH', 'SYSTEMROOT', 'SystemRoot', 'TEMP', 'TMP', 'TMPDIR']) {
  if (process.env[name] !== undefined) minimalEnv[name] = process.env[name];
}
const check = run(python, ['-S', '-B', '-m', 'fanuc_macro.lsp.server', '--version'], {
  cwd: work,
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
  if (strict) fail(`${message}; ${outDir} is left as it was`);
  console.warn(`bundle-server: WARNING: ${message}`);
}

// ---- 6. the new bundle replaces the previous one

const previous = `${outDir}.previous-${process.pid}`;
if (existsSync(outDir)) renameSync(outDir, previous);
renameSync(building, outDir);
rmSync(previous, { recursive: true, force: true });
console.log(`bundle-server: ${outDir} is the new bundle`);
