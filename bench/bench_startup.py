"""Start-up benchmark (a script, not a test): ``fanuc-macro check`` of a small file and the
language server's answer to ``initialize``, each in a new process, as a user meets them.

    python bench/bench_startup.py               # this checkout, 10 runs of each
    python bench/bench_startup.py --tree DIR    # another checkout (its server/ folder)
    python bench/bench_startup.py --instructions   # instructions executed, under valgrind

The instructions a start executes (valgrind's callgrind, one run of each, the hash seed fixed)
are the same from one run to the next, on a loaded machine too: a comparison of two trees
that wall-clock times, which vary two- to threefold beside other jobs, cannot give. They count
the server's whole session, to its exit: the loads after its answer too; a last figure counts
its start to its answer to ``initialize`` alone (its first write ends it). Valgrind follows no
``exec``, so the server runs there with ``PYTHONMALLOC=malloc`` and does not start again.

The interpreter runs with its bytecode cached, as in an installed package: a temporary
``PYTHONPYCACHEPREFIX`` keeps the compiled modules out of the source tree, one run warms it.
The package's cache of generated class code (``code_cache.py``) is kept in a temporary
directory too, warmed by the same run; the runs without it (``FANUC_MACRO_CODE_CACHE=0``,
as a first start after an install or an upgrade) alternate with those with it.
``python -c pass`` is measured too: the interpreter's own start is part of every figure.
``python -c "import json"``, run in turn with the server's starts, is the yardstick of the
server's target (issue 31): ``initialize`` answered within 8 times its median. The server's
answer to the request after ``initialize`` (``shutdown``) says when it serves requests.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import IO

ROOT = Path(__file__).resolve().parents[1]
SMALL = ROOT / "tests" / "fixtures" / "seeds" / "o2_arc_thread_roughing.nc"
IMPORT_JSON = [sys.executable, "-c", "import json"]
TARGET_RATIO = 8.0  # the server's start to initialize answered, in starts of IMPORT_JSON


def environment(tree: Path, cache: str, code_cache: bool = True) -> dict[str, str]:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPYCACHEPREFIX"] = cache
    env["PYTHONPATH"] = str(tree / "server")
    env["FANUC_MACRO_CODE_CACHE"] = str(Path(cache) / "fanuc-macro") if code_cache else "0"
    return env


CPU: list[float] = []  # the CPU time (user + system) of each process timed, in order
SERVING: list[float] = []  # each server's start to its answer to the request after initialize


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(command: list[str], env: dict[str, str]) -> float:
    cpu = _children_cpu()
    started = time.perf_counter()
    subprocess.run(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    elapsed = time.perf_counter() - started
    CPU.append(_children_cpu() - cpu)
    return elapsed


def _message(payload: dict[str, object]) -> bytes:
    body = json.dumps(payload).encode()
    return f"Content-Length: {len(body)}\r\n\r\n".encode() + body


def _read_message(stream: IO[bytes]) -> dict[str, object]:
    length = 0
    while (line := stream.readline().strip()) != b"":
        if line.lower().startswith(b"content-length:"):
            length = int(line.split(b":")[1])
    message: dict[str, object] = json.loads(stream.read(length))
    return message


def initialize_round_trip(env: dict[str, str]) -> float:
    """From the start of the server process to the end of its answer to ``initialize`` (and
    the process's CPU time, to its exit; its start to the answer to ``shutdown``, sent after
    the answer to ``initialize``, into SERVING)."""
    cpu = _children_cpu()
    started = time.perf_counter()
    server = subprocess.Popen(
        [sys.executable, "-m", "fanuc_macro.lsp.server"],
        env=env,
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
    )
    assert server.stdin is not None and server.stdout is not None
    params = {"processId": os.getpid(), "rootUri": None, "capabilities": {}}
    server.stdin.write(
        _message({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": params})
    )
    server.stdin.flush()
    answer = _read_message(server.stdout)
    elapsed = time.perf_counter() - started
    assert answer.get("id") == 1 and "result" in answer, answer
    server.stdin.write(_message({"jsonrpc": "2.0", "id": 2, "method": "shutdown"}))
    server.stdin.flush()
    while (answer := _read_message(server.stdout)).get("id") != 2:
        pass  # a notification
    SERVING.append(time.perf_counter() - started)
    server.stdin.write(_message({"jsonrpc": "2.0", "method": "exit"}))
    server.stdin.close()
    try:
        server.wait(10)
    except subprocess.TimeoutExpired:
        server.kill()
        server.wait()
    CPU.append(_children_cpu() - cpu)
    return elapsed


def instructions(command: list[str], env: dict[str, str], stdin: bytes = b"") -> int:
    """The instructions the command executes (valgrind's callgrind "Collected" count)."""
    with tempfile.TemporaryDirectory() as out:
        done = subprocess.run(
            ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}/callgrind.out", *command],
            env={**env, "PYTHONHASHSEED": "0"},
            input=stdin,
            capture_output=True,
        )
    for line in done.stderr.decode(errors="replace").splitlines():
        if "Collected :" in line:
            return int(line.split(":")[-1])
    raise RuntimeError(f"no count from valgrind: {done.stderr[-500:]!r}")


def initialize_messages() -> bytes:
    """initialize, shutdown and exit, for a server reading stdin to its end."""
    params = {"processId": None, "rootUri": None, "capabilities": {}}
    return (
        _message({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": params})
        + _message({"jsonrpc": "2.0", "id": 2, "method": "shutdown"})
        + _message({"jsonrpc": "2.0", "method": "exit"})
    )


def report(what: str, times: list[float], cpu: list[float] | None = None) -> None:
    """Wall-clock times; with ``cpu``, the processes' CPU time too, which a loaded machine
    changes less."""
    line = (
        f"{what}: min {min(times) * 1000:.0f} ms, median {statistics.median(times) * 1000:.0f} ms"
    )
    if cpu:
        line += (
            f" (CPU min {min(cpu) * 1000:.0f} ms, median {statistics.median(cpu) * 1000:.0f} ms)"
        )
    print(f"{line}, {len(times)} runs")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--tree", type=Path, default=ROOT, help="the checkout to measure")
    ap.add_argument("--runs", type=int, default=10)
    ap.add_argument(
        "--instructions", action="store_true", help="count instructions (valgrind) instead"
    )
    args = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {platform.python_version()}")
    with tempfile.TemporaryDirectory() as cache:
        env = environment(args.tree.resolve(), cache)
        uncached = environment(args.tree.resolve(), cache, code_cache=False)
        check = [sys.executable, "-m", "fanuc_macro.cli", "check", str(SMALL)]
        timed(check, env)  # compiles the modules into the cache
        initialize_round_trip(env)
        if args.instructions:
            count_instructions(env, uncached, check)
            return
        runs = range(args.runs)
        CPU.clear()
        report("python -c pass", [timed([sys.executable, "-c", "pass"], env) for _ in runs], CPU)
        check_times: dict[bool, list[float]] = {True: [], False: []}
        check_cpu: dict[bool, list[float]] = {True: [], False: []}
        for _ in runs:  # alternated, so that a change of load meets both alike
            for cached in (True, False):
                check_times[cached].append(timed(check, env if cached else uncached))
                check_cpu[cached].append(CPU[-1])
        what = f"fanuc-macro check {SMALL.name}"
        report(what, check_times[True], check_cpu[True])
        report(f"{what}, without the code cache", check_times[False], check_cpu[False])
        time_server(env, uncached, runs)


def time_server(env: dict[str, str], uncached: dict[str, str], runs: range) -> None:
    """The server's starts, with the code cache and without, in turn with the yardstick's."""
    yardstick: list[float] = []
    yardstick_cpu: list[float] = []
    times: dict[bool, list[float]] = {True: [], False: []}
    cpu: dict[bool, list[float]] = {True: [], False: []}
    serving: dict[bool, list[float]] = {True: [], False: []}
    for _ in runs:
        yardstick.append(timed(IMPORT_JSON, env))
        yardstick_cpu.append(CPU[-1])
        for cached in (True, False):
            times[cached].append(initialize_round_trip(env if cached else uncached))
            cpu[cached].append(CPU[-1])
            serving[cached].append(SERVING[-1])
    what = "language server: start to initialize answered"
    report('python -c "import json"', yardstick, yardstick_cpu)
    report(what, times[True], cpu[True])
    report(f"{what}, without the code cache", times[False], cpu[False])
    report("language server: start to the next request answered", serving[True])
    report("language server: the same, without the code cache", serving[False])
    ratio = statistics.median(times[True]) / statistics.median(yardstick)
    met = "met" if ratio <= TARGET_RATIO else "NOT met"
    print(f'start to initialize answered / python -c "import json", medians: {ratio:.1f}x')
    print(f"target (at most {TARGET_RATIO:g}x): {met}")


# The server as `python -m fanuc_macro.lsp.server` starts it, ended by its first write: the
# instructions to the answer to initialize, without what follows it (the analysis's preload,
# the collector's resumption, shutdown).
TO_THE_ANSWER = """
import os, sys
sys.orig_argv = [sys.executable, "-m", "fanuc_macro.lsp.server"]

class Ending:
    def write(self, data):
        os.write(1, data)
        os._exit(0)
    def flush(self):
        pass

class Text:
    buffer = Ending()

sys.stdout = Text()
import fanuc_macro.lsp.server
fanuc_macro.lsp.server.main([])
"""


def count_instructions(env: dict[str, str], uncached: dict[str, str], check: list[str]) -> None:
    # Valgrind follows no exec: the server runs on the C allocator from its start, so it does
    # not start again (one interpreter start less than it takes, about python -c pass).
    no_exec = {**env, "PYTHONMALLOC": "malloc"}
    no_exec_uncached = {**uncached, "PYTHONMALLOC": "malloc"}
    server = [sys.executable, "-m", "fanuc_macro.lsp.server"]
    for what, command, stdin, envs in (
        ("python -c pass", [sys.executable, "-c", "pass"], b"", (env,)),
        ('python -c "import json"', IMPORT_JSON, b"", (env,)),
        (f"fanuc-macro check {SMALL.name}", check, b"", (env, uncached)),
        (
            "language server (PYTHONMALLOC=malloc): initialize, shutdown, exit",
            server,
            initialize_messages(),
            (no_exec, no_exec_uncached),
        ),
        (
            "language server (PYTHONMALLOC=malloc): start to the answer to initialize",
            [sys.executable, "-c", TO_THE_ANSWER],
            initialize_messages(),
            (no_exec,),
        ),
    ):
        for run_env in envs:
            count = instructions(command, run_env, stdin)
            cached = run_env.get("FANUC_MACRO_CODE_CACHE") != "0"
            without = "" if cached else ", without the code cache"
            print(f"{what}{without}: {count / 1e6:,.0f} million instructions")


if __name__ == "__main__":
    main()
