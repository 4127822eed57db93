"""Debugger benchmark (a script, not a test): what single-blocking costs.

    python bench/bench_debug.py                  # 100,000 executed blocks, 200 steps
    python bench/bench_debug.py --blocks 300000 --steps 500

1. A run to its end with no breakpoint under the debugger's session (the stepper consulted
   before every block), against the checker's own run of the same program: CPU seconds of
   this process (``time.process_time``), the best of three.
2. A step over the Debug Adapter Protocol, the adapter a subprocess on stdio: ``next``, its
   ``stopped`` event and what an editor asks then (the stack, the scopes, the locals), wall
   clock, the median and the slowest.
"""

from __future__ import annotations

import argparse
import platform
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "server"))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from dap_client import DapClient
from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.debugger import Ended, Listener, Output, Session, Stop, read_launch


def program(blocks: int) -> str:
    """A WHILE loop of six blocks a turn (five and its END): about ``blocks`` executed."""
    turns = max(1, blocks // 6)
    return (
        "%\nO7000 (BENCH)\n#1=0\n"
        f"WHILE[#1 LT {turns}] DO1\n"
        "#2=#1*0.5\n#3=SQRT[#2+1.]\nG01 X[#3] Z[-#2] F0.2\n#1=#1+1\nEND1\nM30\n%\n"
    )


class _Quiet(Listener):
    def __init__(self) -> None:
        self.done = threading.Event()
        self.ended_with: Ended | None = None

    def stopped(self, stop: Stop) -> None:
        pass

    def output(self, output: Output) -> None:
        pass

    def ended(self, ended: Ended) -> None:
        self.ended_with = ended
        self.done.set()


def run_times(path: Path, blocks: int) -> tuple[float, float, str]:
    budget = max(blocks * 2, Config().step_budget)
    config = Config(step_budget=budget, time_limit=600.0)
    text = path.read_text()
    checked = debugged = float("inf")
    said = ""
    for _ in range(3):
        started = time.process_time()
        analyse(text, str(path), config)
        checked = min(checked, time.process_time() - started)
        listener = _Quiet()
        session = Session(read_launch({"program": str(path), "stepBudget": budget}), listener)
        started = time.process_time()
        session.start()
        listener.done.wait()
        debugged = min(debugged, time.process_time() - started)
        said = listener.ended_with.message if listener.ended_with else ""
    return checked, debugged, said


def step_times(path: Path, steps: int) -> list[float]:
    dap = DapClient()
    try:
        dap.start({"program": str(path), "stopOnEntry": True})
        dap.stopped()
        times: list[float] = []
        for _ in range(steps):
            started = time.perf_counter()
            dap.ok("next", {"threadId": 1})
            dap.stopped()
            # What an editor asks at each stop: the stack, the top frame's scopes, its locals.
            frame = dap.ok("stackTrace", {"threadId": 1})["stackFrames"][0]
            scopes = dap.ok("scopes", {"frameId": frame["id"]})["scopes"]
            dap.ok("variables", {"variablesReference": scopes[0]["variablesReference"]})
            times.append(time.perf_counter() - started)
        dap.ok("disconnect")
        return times
    finally:
        dap.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--blocks", type=int, default=100_000)
    parser.add_argument("--steps", type=int, default=200)
    args = parser.parse_args()
    print(f"{platform.machine()} {platform.processor() or ''} CPython {platform.python_version()}")
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "o7000.nc"
        path.write_text(program(args.blocks))
        checked, debugged, said = run_times(path, args.blocks)
        print(
            f"run of about {args.blocks:,} blocks: checker {checked:.3f} s CPU, debugger "
            f"{debugged:.3f} s CPU ({debugged / checked:.1f}x); {said}"
        )
        times = step_times(path, args.steps)
        print(
            "a step over DAP (next, stack, scopes, locals): median "
            f"{statistics.median(times) * 1000:.2f} ms, max {max(times) * 1000:.2f} ms "
            f"({len(times)} steps)"
        )


if __name__ == "__main__":
    main()
