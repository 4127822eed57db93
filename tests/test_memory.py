"""Memory per block of an analysis: counted by tracemalloc, not read from the RSS.

What Python allocates for analysing a program does not depend on the machine or its load,
so the bound holds on every run. The programs are the benchmarks' (``bench/bench_lsp.py``):
the seeds' style, macro-dense (thread passes computed by macro statements), and CAM output
(distinct plain ``G01 X Y Z`` blocks), 6,000 blocks each. The bounds are bytes per block of
the traced peak: an analysis of them held about 4,500 and 6,100 before the representation was
made lighter, about 2,800 and 4,300 after it (docs/benchmarks.md, "Memory"), and about 2,700
and 3,400 once a constant block kept neither compiled words nor the order of its words and the
words shared their address letters, about 2,500 and 2,650 once the cuts without F were kept by
line, the per-line caches found their entries by text and blocks shared the words of numbers
written alike at the same column, and about 2,130 and 1,650 once blocks of plain words were
kept as their code (``PlainNc``), the line maps' looks held no per-line cache entries and
constants shared their closures.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "bench"
BLOCKS = 6_000

# Run in a new interpreter: the per-line caches are the process's, and what earlier tests left
# in them would change what this analysis allocates.
MEASURE = """
import sys, tracemalloc
sys.path.insert(0, sys.argv[1])
import bench_lsp
from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.syntax.parser import BlockParser
text = getattr(bench_lsp, sys.argv[2])(int(sys.argv[3]))
config = Config(max_blocks=10 * int(sys.argv[3]), max_file_size=100 * len(text))
tracemalloc.start()
analysis = analyse(text, "file:///memory.nc", config, parser=BlockParser())
_, peak = tracemalloc.get_traced_memory()
tracemalloc.stop()
assert analysis.facts is not None
print(peak / len(analysis.doc.blocks))
"""


def _peak_per_block(kind: str) -> float:
    done = subprocess.run(
        [sys.executable, "-c", MEASURE, str(BENCH), kind, str(BLOCKS)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    return float(done.stdout.split()[-1])


@pytest.mark.parametrize(
    ("kind", "bound"),
    [("program", 2_600), ("cam_program", 2_000)],
)
def test_an_analysis_holds_at_most_its_bound_per_block(kind: str, bound: int) -> None:
    per_block = _peak_per_block(kind)
    assert per_block <= bound, f"{per_block:.0f} bytes per block, more than {bound}"
