// The language server's own answers for the client tests: one Python process of this
// checkout's package (server/) answers the editor commands (lsp/commands.py EDITOR_COMMANDS)
// as the server does, so that the client is tested against what the server says, not a copy.
import { spawn, type ChildProcessWithoutNullStreams } from 'node:child_process';
import { join } from 'node:path';
import { createInterface } from 'node:readline';

const SCRIPT = `
import asyncio, json, sys
from fanuc_macro.lsp.commands import EDITOR_COMMANDS, _machine_json, _trace_view_json
from fanuc_macro.ide.trace_view import view_of_trace

def machine_of(text, settings):
    # fanuc-macro.machine of a program analysed with the settings, without a workspace
    from fanuc_macro.analysis import analyse
    from fanuc_macro.config import Config
    from fanuc_macro.ide import View, document_machine
    config = Config.from_settings(settings)
    return _machine_json(document_machine(View("o.nc", analyse(text, "o.nc", config), config)))

async def answer(command, args):
    if command == "viewOfTrace":  # the view of a trace given, without a workspace
        return _trace_view_json(view_of_trace(args[0], args[1]))
    if command == "machineOf":
        return machine_of(args[0], args[1])
    return await EDITOR_COMMANDS[command](None, tuple(args))

for line in sys.stdin:
    command, args = json.loads(line)
    print(json.dumps(asyncio.run(answer(command, args))), flush=True)
`;

export interface PythonServer {
  /** The server's answer to `command` with `args`. */
  answer(command: string, args: unknown[]): Promise<unknown>;
  close(): void;
}

export function pythonServer(): PythonServer {
  const root = process.cwd();
  const child: ChildProcessWithoutNullStreams = spawn(process.env['PYTHON'] ?? 'python3', ['-c', SCRIPT], {
    env: { ...process.env, PYTHONPATH: join(root, 'server') },
  });
  const waiting: Array<(line: string) => void> = [];
  let stderr = '';
  child.stderr.on('data', (chunk: Buffer) => (stderr += chunk.toString()));
  createInterface({ input: child.stdout }).on('line', (line) => waiting.shift()?.(line));
  let exited = false;
  const failure = () => JSON.stringify({ error: `the server's Python exited: ${stderr}` });
  child.on('exit', () => {
    exited = true;
    for (const resolve of waiting.splice(0)) resolve(failure());
  });
  return {
    answer: (command, args) =>
      new Promise((resolve) => {
        if (exited) return resolve(JSON.parse(failure()));
        waiting.push((line) => resolve(JSON.parse(line)));
        child.stdin.write(`${JSON.stringify([command, args])}\n`);
      }),
    close: () => child.stdin.end(),
  };
}
