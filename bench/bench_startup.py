"""Start-up benchmark (a script, not a test): ``fanuc-macro check`` of a small file and the
language server's answer to ``initialize``, each in a new process, as a user meets them.

    python bench/bench_startup.py               # this checkout, 10 runs of each
    python bench/bench_startup.py --tree DIR    # another checkout (its server/ folder)
    python bench/bench_startup.py --instructions   # instructions executed, under valgrind

The instructions a start executes (valgrind's callgrind, one run of each, the hash seed fixed)
are the same from one run to the next, on a loaded machine too: a comparison of two trees
that wall-clock times, which vary two- to threefold beside other jobs, cannot give.

The interpreter runs with its bytecode cached, as in an installed package: a temporary
``PYTHONPYCACHEPREFIX`` keeps the compiled modules out of the source tree, one run warms it.
The package's cache of generated class code (``code_cache.py``) is kept in a temporary
directory too, warmed by the same run; the runs without it (``FANUC_MACRO_CODE_CACHE=0``,
as a first start after an install or an upgrade) alternate with those with it.
``python -c pass`` is measured too: the interpreter's own start is part of every figure.
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

ROOT = Path(__file__).resolve().parents[1]
SMALL = ROOT / "tests" / "fixtures" / "seeds" / "o2_arc_thread_roughing.nc"


def environment(tree: Path, cache: str, code_cache: bool = True) -> dict[str, str]:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPYCACHEPREFIX"] = cache
    env["PYTHONPATH"] = str(tree / "server")
    env["FANUC_MACRO_CODE_CACHE"] = str(Path(cache) / "fanuc-macro") if code_cache else "0"
    return env


CPU: list[float] = []  # the CPU time (user + system) of each process timed, in order


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


def initialize_round_trip(env: dict[str, str]) -> float:
    """From the start of the server process to the end of its answer to ``initialize`` (and
    the process's CPU time, to its exit)."""
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
    length = 0
    while (line := server.stdout.readline().strip()) != b"":
        if line.lower().startswith(b"content-length:"):
            length = int(line.split(b":")[1])
    answer = json.loads(server.stdout.read(length))
    elapsed = time.perf_counter() - started
    assert answer.get("id") == 1 and "result" in answer, answer
    server.stdin.write(_message({"jsonrpc": "2.0", "id": 2, "method": "shutdown"}))
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
            server = [sys.executable, "-m", "fanuc_macro.lsp.server"]
            for what, command, stdin, envs in (
                ("python -c pass", [sys.executable, "-c", "pass"], b"", (env,)),
                (f"fanuc-macro check {SMALL.name}", check, b"", (env, uncached)),
                (
                    "language server: initialize, shutdown, exit",
                    server,
                    initialize_messages(),
                    (env, uncached),
                ),
            ):
                for run_env in envs:
                    count = instructions(command, run_env, stdin)
                    without = ", without the code cache" if run_env is uncached else ""
                    print(f"{what}{without}: {count / 1e6:,.0f} million instructions")
            return
        runs = range(args.runs)
        CPU.clear()
        report("python -c pass", [timed([sys.executable, "-c", "pass"], env) for _ in runs], CPU)
        for what, start in (
            (f"fanuc-macro check {SMALL.name}", lambda env: timed(check, env)),
            ("language server: start to initialize answered", initialize_round_trip),
        ):
            CPU.clear()
            times: dict[bool, list[float]] = {True: [], False: []}
            cpu: dict[bool, list[float]] = {True: [], False: []}
            for _ in runs:  # alternated, so that a change of load meets both alike
                for cached in (True, False):
                    times[cached].append(start(env if cached else uncached))
                    cpu[cached].append(CPU[-1])
            report(what, times[True], cpu[True])
            report(f"{what}, without the code cache", times[False], cpu[False])


if __name__ == "__main__":
    main()
