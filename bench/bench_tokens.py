"""Semantic tokens benchmark (a script, not a test): the tokens of a whole program, as the
editor asks for them after every edit, the first time and again (the lines' tokens kept).

    python bench/bench_tokens.py                 # 2,000 and 20,000 blocks
    python bench/bench_tokens.py --blocks 25000 --distinct

Figures are CPU seconds of this process (``time.process_time``), the best of a few runs.
"""

from __future__ import annotations

import argparse
import platform
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "server"))

from bench_lsp import program

from fanuc_macro import database
from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.ide import semantic
from fanuc_macro.ide.view import View


def measure(blocks: int, distinct: bool, runs: int) -> tuple[float, float, int]:
    config = Config(max_blocks=max(blocks + 10, Config().max_blocks))
    view = View("bench.nc", analyse(program(blocks, distinct), "bench.nc", config), config)
    first = again = float("inf")
    count = 0
    for _ in range(runs):
        database.current().table(semantic.LINE_TOKENS).clear()
        started = time.process_time()
        count = len(semantic.semantic_tokens(view))
        first = min(first, time.process_time() - started)
        started = time.process_time()
        semantic.semantic_tokens(view)
        again = min(again, time.process_time() - started)
    return first, again, count


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--blocks", type=int, action="append", help="program size (repeatable)")
    parser.add_argument("--distinct", action="store_true", help="no two blocks alike")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    print(f"{platform.processor() or platform.machine()}, Python {platform.python_version()}")
    for blocks in args.blocks or [2_000, 20_000]:
        first, again, count = measure(blocks, args.distinct, args.runs)
        print(
            f"{blocks:>7} blocks{' (distinct)' if args.distinct else ''}: {count} tokens, "
            f"first {first * 1000:.0f} ms, again {again * 1000:.0f} ms CPU"
        )


if __name__ == "__main__":
    main()
