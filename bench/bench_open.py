"""Opening a big file (a script, not a test): the time each stage of the open path takes on a
generated 20,000-block macro program and a 200,000-block CAM file, against the floor of
tokenising the same text with one ``re.finditer``, measured in the same process; and the peak
memory of ``fanuc-macro check`` of each, in a new process.

    python bench/bench_open.py                 # both files, best of 3
    python bench/bench_open.py --cam 1000000   # a posted file of a million blocks too
    python bench/bench_open.py --profile macro # where the macro program's open goes (cProfile)
    python bench/bench_open.py --cpu           # the process's CPU time: for a loaded machine

Targets (issue 31): the macro program's open within 40 times the floor, the CAM file's within
15 times, its ``check`` in at most 250 MB. The figures are ratios to the floor so that two
machines, or one machine under two loads, can be compared.
"""

from __future__ import annotations

import argparse
import cProfile
import gc
import platform
import pstats
import re
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "server"), str(ROOT / "bench")]

from bench_lsp import cam_program, program  # noqa: E402

from fanuc_macro.analysis import analyse  # noqa: E402
from fanuc_macro.config import Config  # noqa: E402
from fanuc_macro.database import Database  # noqa: E402
from fanuc_macro.evaluator import evaluate  # noqa: E402
from fanuc_macro.program.index import build_index  # noqa: E402
from fanuc_macro.program.machine_kind import machine_config  # noqa: E402
from fanuc_macro.syntax.lines import decode_bytes  # noqa: E402
from fanuc_macro.syntax.parser import BlockParser, parse_text, quiet_gc  # noqa: E402

# The floor: every word, number, variable, comment and other character of the text, as a
# tokeniser that knows nothing of blocks would find them.
TOKEN = re.compile(r"\([^)]*\)|#\d+|[A-Z]+|[-+]?(?:\d+\.?\d*|\.\d+)|\S")

TARGETS = {"macro": 40.0, "cam": 15.0}
# The clock of the floor and the stages: wall time, or with --cpu the process's CPU time (on
# a machine shared with other jobs, what the process itself spent).
CLOCK: list[Callable[[], float]] = [time.perf_counter]
CHECK_MEMORY_TARGET_MB = 250


def floor(text: str) -> float:
    started = CLOCK[0]()
    for _ in TOKEN.finditer(text):
        pass
    return CLOCK[0]() - started


def open_stages(data: bytes) -> dict[str, float]:
    """Each stage of opening ``data`` as the command line and the language server do, in a new
    database with a new parser (nothing cached from an earlier run): seconds by stage."""
    with Database().active():
        return _open_stages(data)


def _open_stages(data: bytes) -> dict[str, float]:
    config = Config()
    times: dict[str, float] = {}

    def stage(name: str, fn: Callable[[], object]) -> object:
        started = CLOCK[0]()
        value = fn()
        times[name] = CLOCK[0]() - started
        return value

    decoded = stage("decode", lambda: decode_bytes(data))
    text = decoded.text  # type: ignore[attr-defined]
    parser = BlockParser()
    doc = stage("parse", lambda: parse_text(text, "bench.nc", parser, limits=config.read_limits))
    # The program index, and the machine the program's codes show (a mill for the CAM file),
    # as analyse reads it.
    # As ``Workspace.analyse`` runs them: the machine's reading, the evaluation and the rules
    # in one stretch without the cyclic collector, whose one collection of what they made, at
    # its end, counts with the rules.
    with quiet_gc():
        index, machine = stage("index", lambda: _index_and_machine(doc, config))  # type: ignore[misc]
        facts = stage(
            "evaluate",
            lambda: evaluate([("bench.nc", doc, index)], config=machine),  # type: ignore[list-item]
        )
        rules_started = CLOCK[0]()
        analyse(
            text,
            "bench.nc",
            config,
            parser=parser,
            doc=doc,  # type: ignore[arg-type]
            index=index,  # type: ignore[arg-type]
            facts=facts,  # type: ignore[arg-type]
        )
    gc.collect(0)  # the collection the first allocation after the stretch would start
    times["rules"] = CLOCK[0]() - rules_started
    return times


def _index_and_machine(doc: object, config: Config) -> tuple[object, Config]:
    index = build_index(doc)  # type: ignore[arg-type]
    return index, machine_config(config, doc, index)  # type: ignore[arg-type]


def check_memory(path: Path) -> tuple[float, float]:
    """``fanuc-macro check`` of ``path`` in a new process: (seconds, peak RSS in MB)."""
    code = (
        "import sys\n"
        "from fanuc_macro.cli import main\n"
        "try:\n"
        "    main(['check', '--no-cache', sys.argv[1]])\n"
        "except SystemExit:\n"
        "    pass\n"
        "for line in open('/proc/self/status'):\n"
        "    if line.startswith('VmHWM:'):\n"
        "        print(int(line.split()[1]) / 1024, file=sys.stderr)\n"
    )
    started = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-c", code, str(path)],
        capture_output=True,
        text=True,
        env={"PYTHONPATH": str(ROOT / "server"), "PATH": "/usr/bin:/bin"},
    )
    elapsed = time.perf_counter() - started
    return elapsed, float(done.stderr.strip().splitlines()[-1])


def measure(name: str, text: str, repeat: int) -> None:
    data = text.encode("utf-8")
    best_floor = min(floor(text) for _ in range(repeat))
    runs: list[dict[str, float]] = []
    for _ in range(repeat):
        gc.collect()
        runs.append(open_stages(data))
        best_floor = min(best_floor, floor(text))
    best = min(runs, key=lambda r: sum(r.values()))
    total = sum(best.values())
    blocks = text.count("\n")
    print(
        f"{name}: {blocks:,} lines, {len(text):,} characters; floor (re.finditer) "
        f"{best_floor * 1000:.0f} ms; open {total:.2f} s = {total / best_floor:.1f} x the floor"
    )
    print("  " + ", ".join(f"{stage} {seconds * 1000:.0f} ms" for stage, seconds in best.items()))
    target = TARGETS.get(name.split()[0])
    if target is not None:
        met = "met" if total / best_floor <= target else "NOT met"
        print(f"  target: within {target:.0f} x the floor: {met}")
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "bench.nc"
        path.write_bytes(data)
        seconds, peak = check_memory(path)
    verdict = ""
    if name.startswith("cam"):
        verdict = " (target ≤ 250 MB: " + ("met)" if peak <= CHECK_MEMORY_TARGET_MB else "NOT met)")
    print(f"  fanuc-macro check: {seconds:.2f} s, peak RSS {peak:.0f} MB{verdict}")


def profile(text: str) -> None:
    data = text.encode("utf-8")
    profiler = cProfile.Profile()
    profiler.enable()
    open_stages(data)
    profiler.disable()
    pstats.Stats(profiler).sort_stats("tottime").print_stats(30)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--cam", type=int, default=200_000, help="blocks of the CAM file")
    parser.add_argument("--macro", type=int, default=20_000, help="blocks of the macro program")
    parser.add_argument("--profile", choices=("macro", "cam"))
    parser.add_argument("--cpu", action="store_true", help="CPU time instead of wall time")
    args = parser.parse_args()
    if args.cpu:
        CLOCK[0] = time.process_time
    macro = program(args.macro, distinct=True)
    cam = cam_program(args.cam)
    if args.profile:
        profile(macro if args.profile == "macro" else cam)
        return
    print(f"machine: {platform.machine()}, {platform.python_version()}")
    measure("macro program", macro, args.repeat)
    measure("cam file", cam, args.repeat)


if __name__ == "__main__":
    main()
