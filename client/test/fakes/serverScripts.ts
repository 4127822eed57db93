// Small shell scripts that stand in for the language server in the tests that probe it for
// real: each answers `--version` as fanuc-macro-ls does (the fake `python3` only to
// `-m fanuc_macro.lsp.server --version`).
import { chmodSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

export interface ServerScripts {
  /** The folder the scripts are in (a fresh temporary one). */
  readonly dir: string;
  /** `fanuc-macro-ls`, printing its version. */
  readonly server: string;
  /** `python3`, running the server's module only for its version. */
  readonly python: string;
  /** Writes another executable script `name` in the folder and returns its path. */
  script(name: string, body: string): string;
  /** Removes the folder. */
  remove(): void;
}

export function serverScripts(prefix: string): ServerScripts {
  const dir = mkdtempSync(join(tmpdir(), prefix));
  const script = (name: string, body: string): string => {
    const path = join(dir, name);
    writeFileSync(path, `#!/bin/sh\n${body}\n`);
    chmodSync(path, 0o755);
    return path;
  };
  return {
    dir,
    script,
    server: script('fanuc-macro-ls', 'echo "fanuc-macro-ls 0.1.0"'),
    python: script(
      'python3',
      'if [ "$1 $2 $3" = "-m fanuc_macro.lsp.server --version" ]; then echo "fanuc-macro-ls 0.1.0"; else exit 2; fi',
    ),
    remove: () => rmSync(dir, { recursive: true, force: true }),
  };
}
