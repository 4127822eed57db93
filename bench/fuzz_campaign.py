"""A long fuzz campaign of the analysis (a script, not a test): seeded, resumable, in parallel.

    python bench/fuzz_campaign.py --inputs 100000            # seed 1, state in .fuzz/
    python bench/fuzz_campaign.py --inputs 200000 --resume   # goes on where it stopped

Input ``i`` of seed ``s`` is always the same (its choices come from ``Random(f"{s}:{i}")``), so
a finding is reproduced by its number: ``--show 1234`` prints the input and the check's
verdict. The inputs and the checks are those of the test suite's fuzz test
(tests/fuzzing.py): byte, token and grammar-level mutations of the fixtures and the corpus;
no exception or MB000, a result within the time limit, the same result twice, the edit path
equal to a fresh parse, the trace as JSON.

Each input runs in a worker process; one that does not answer within ``--hang`` seconds is
killed and counted as a hang. The figures (inputs run, failures by kind) are written to
``OUT/state.json`` and the failing inputs to ``OUT/failures/``.
"""

from __future__ import annotations

import argparse
import json
import logging
import multiprocessing
import os
import platform
import random
import signal
import sys
import time
from collections import Counter
from multiprocessing.connection import Connection, wait
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "server"))
sys.path.insert(1, str(ROOT / "tests"))

from fuzzing import FuzzInput, RandomDraw, check, digest, make_input, outcome  # noqa: E402

SAVE_EVERY = 500  # inputs between two saves of the state


def input_of(seed: int, index: int) -> FuzzInput:
    return make_input(RandomDraw(random.Random(f"{seed}:{index}")))


def _worker(conn: Connection, seed: int, seconds: float) -> None:
    # MB000 is counted from the diagnostics: its traceback would only flood the terminal.
    logging.getLogger("fanuc_macro").addHandler(logging.NullHandler())
    while True:
        job = conn.recv()
        if job is None:
            return
        index, only_digest = job
        case = input_of(seed, index)
        started = time.perf_counter()
        if only_digest:  # the same input in another process, after other inputs than the first
            conn.send((index, case.level, case.seed, None, 0.0, digest(case)))
            continue
        problem, digested = outcome(case, seconds)
        seconds_taken = time.perf_counter() - started
        conn.send((index, case.level, case.seed, problem, seconds_taken, digested))


class Worker:
    def __init__(self, seed: int, seconds: float) -> None:
        self.conn, child = multiprocessing.Pipe()
        self.process = multiprocessing.Process(
            target=_worker, args=(child, seed, seconds), daemon=True
        )
        self.process.start()
        child.close()
        self.index: int | None = None
        self.only_digest = False
        self.started = 0.0

    def give(self, index: int, only_digest: bool = False) -> None:
        self.index = index
        self.only_digest = only_digest
        self.started = time.monotonic()
        self.conn.send((index, only_digest))

    def kill(self) -> None:
        self.process.kill()
        self.process.join()


def load_state(path: Path, seed: int) -> dict[str, Any]:
    if path.is_file():
        state: dict[str, Any] = json.loads(path.read_text("utf-8"))
        if state["seed"] != seed:
            raise SystemExit(f"{path} is a campaign of seed {state['seed']}, not {seed}")
        return state
    return {
        "seed": seed,
        "next": 0,  # every input below it has run
        "done_above": [],  # inputs above it that have run (they finish out of order)
        "inputs_run": 0,
        "by_level": {},
        "failures": [],
        "failures_by_kind": {},
        "seconds_of_analysis": 0.0,
        "slowest": [],
        "compared_across_processes": 0,  # inputs whose digest a second process computed
        "wall_seconds": 0.0,
        "machine": "",
    }


def save_state(path: Path, state: dict[str, Any]) -> None:
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(state, indent=1) + "\n", "utf-8")
    tmp.replace(path)


def record(state: dict[str, Any], out: Path, result: tuple[Any, ...]) -> None:
    index, level, seed_name, problem, seconds = result[:5]
    state["inputs_run"] += 1
    state["by_level"][level] = state["by_level"].get(level, 0) + 1
    state["seconds_of_analysis"] += seconds
    slowest = state["slowest"]
    slowest.append([round(seconds, 3), index])
    slowest.sort(reverse=True)
    del slowest[5:]
    if problem is not None:
        kind = problem.split(":", 1)[0]
        state["failures_by_kind"][kind] = state["failures_by_kind"].get(kind, 0) + 1
        state["failures"].append({"index": index, "level": level, "seed": seed_name,
                                  "problem": problem[:2000]})  # fmt: skip
        case = input_of(state["seed"], index)
        failures = out / "failures"
        failures.mkdir(parents=True, exist_ok=True)
        (failures / f"{index}.nc").write_text(case.text, "utf-8", errors="surrogatepass")
        (failures / f"{index}.txt").write_text(f"{problem}\n", "utf-8")


def compare_digests(state: dict[str, Any], out: Path, result: tuple[Any, ...], first: str) -> None:
    """The digest another worker process computed for an input, against the first one."""
    state["compared_across_processes"] = state.get("compared_across_processes", 0) + 1
    index, level, seed_name, _, _, second = result
    if second != first:
        problem = f"not deterministic across processes: digest {first} then {second}"
        record(state, out, (index, level, seed_name, problem, 0.0))
        state["inputs_run"] -= 1  # recorded as a failure of an input already counted


def advance(state: dict[str, Any], finished: int) -> None:
    above = set(state["done_above"])
    above.add(finished)
    while state["next"] in above:
        above.discard(state["next"])
        state["next"] += 1
    state["done_above"] = sorted(above)


def _stop(signum: int, frame: object) -> None:
    raise KeyboardInterrupt  # the state is saved on the way out


def campaign(args: argparse.Namespace) -> int:
    # A campaign run in the background has SIGINT ignored: SIGTERM stops it the same way.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, _stop)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    state_path = out / "state.json"
    if not args.resume and state_path.exists():
        raise SystemExit(f"{state_path} exists: --resume to go on, or another --out")
    state = load_state(state_path, args.seed)
    state["machine"] = (
        f"{platform.machine()}, {os.cpu_count()} CPUs, Python {platform.python_version()}, "
        f"{args.workers} workers"
    )
    done = set(state["done_above"])
    todo = (i for i in range(state["next"], args.inputs) if i not in done)
    workers = [Worker(args.seed, args.seconds) for _ in range(args.workers)]
    started = time.monotonic()
    wall_before = state["wall_seconds"]
    since_save = 0
    hangs = Counter[int]()
    # Checked inputs waiting for their digest from another worker: index -> (digest, pid).
    waiting: dict[int, tuple[str, int]] = {}

    def give_next(w: Worker) -> None:
        pid = w.process.pid or 0
        other = next((i for i, (_, by) in waiting.items() if by != pid), None)
        if other is not None:
            w.give(other, only_digest=True)
            return
        index = next(todo, None)
        if index is not None:
            w.give(index)

    try:
        for w in workers:
            give_next(w)
        while any(w.index is not None for w in workers):
            ready = wait([w.conn for w in workers if w.index is not None], timeout=1.0)
            now = time.monotonic()
            for w in list(workers):
                index, only_digest = w.index, w.only_digest
                if index is None:
                    continue
                if w.conn in ready:
                    try:
                        result = w.conn.recv()
                    except EOFError:  # the worker died (killed for its memory, say)
                        problem = f"crash: the worker died (exit {w.process.exitcode})"
                        result = (index, "?", "?", problem, 0.0, "")
                        w.kill()
                        workers[workers.index(w)] = w = Worker(args.seed, args.seconds)
                elif now - w.started > args.hang:
                    hangs[index] += 1
                    result = (index, "?", "?", f"hang: over {args.hang:g} s", 0.0, "")
                    w.kill()
                    workers[workers.index(w)] = w = Worker(args.seed, args.seconds)
                else:
                    continue
                w.index = None
                if only_digest:
                    first = waiting.pop(index)[0]
                    if result[3] is None:
                        compare_digests(state, out, result, first)
                    else:  # counted when it was checked: recorded as a failure only
                        record(state, out, result[:5])
                        state["inputs_run"] -= 1
                    give_next(w)
                    continue
                record(state, out, result[:5])
                if args.workers > 1 and result[5]:
                    waiting[index] = (result[5], w.process.pid or 0)
                advance(state, index)
                give_next(w)
                since_save += 1
            for w in workers:  # an idle worker takes a digest the other one left
                if w.index is None:
                    give_next(w)
            if since_save >= SAVE_EVERY:
                state["wall_seconds"] = wall_before + time.monotonic() - started
                save_state(state_path, state)
                since_save = 0
                print(
                    f"{state['inputs_run']} inputs, {len(state['failures'])} failures, "
                    f"{state['wall_seconds']:.0f} s",
                    flush=True,
                )
    except KeyboardInterrupt:
        print("stopped: --resume goes on from here", flush=True)
    finally:
        for w in workers:
            if w.index is None:
                w.conn.send(None)
            w.kill()
        state["wall_seconds"] = wall_before + time.monotonic() - started
        save_state(state_path, state)
    print(json.dumps({k: state[k] for k in ("inputs_run", "by_level", "failures_by_kind",
                                             "wall_seconds", "slowest")}, indent=1))  # fmt: skip
    return 1 if state["failures"] else 0


def show(args: argparse.Namespace) -> int:
    logging.basicConfig(level=logging.ERROR)  # the traceback of an MB000, if there is one
    case = input_of(args.seed, args.show)
    print(f"input {args.show} of seed {args.seed}: {case.level} mutation of {case.seed}")
    print(case.text)
    problem = check(case, args.seconds)
    print(f"check: {problem or 'passes'}")
    return 0 if problem is None else 1


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--inputs", type=int, default=100_000, help="run inputs 0 to N-1")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default=".fuzz", help="folder of the state and the failures")
    ap.add_argument("--resume", action="store_true", help="go on with the state in --out")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--seconds", type=float, default=10.0, help="an analysis longer is slow")
    ap.add_argument("--hang", type=float, default=60.0, help="a worker silent longer hangs")
    ap.add_argument("--show", type=int, metavar="INDEX", help="print one input and its check")
    args = ap.parse_args()
    if args.show is not None:
        return show(args)
    return campaign(args)


if __name__ == "__main__":
    sys.exit(main())
