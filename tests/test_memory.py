"""Memory per block of an analysis: counted by tracemalloc, not read from the RSS.

What Python allocates for analysing a program does not depend on the machine or its load,
so the bound holds on every run. The programs are the benchmarks' (``bench/bench_lsp.py``):
the seeds' style, macro-dense (thread passes computed by macro statements), and CAM output
(distinct plain ``G01 X Y Z`` blocks), 6,000 blocks each. The bounds are bytes per block of
the traced peak: an analysis of them held about 4,500 and 6,100 before the representation was
made lighter, about 2,800 and 4,300 after it (docs/benchmarks.md, "Memory").
"""

from __future__ import annotations

import importlib.util
import sys
import tracemalloc
from pathlib import Path
from types import ModuleType

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.parser import BlockParser

BENCH = Path(__file__).resolve().parents[1] / "bench" / "bench_lsp.py"
BLOCKS = 6_000


def _generators() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_lsp_programs", BENCH)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def _peak_per_block(text: str) -> float:
    config = Config(max_blocks=10 * BLOCKS, max_file_size=100 * len(text))
    tracemalloc.start()
    try:
        analysis = analyse(text, "file:///memory.nc", config, parser=BlockParser())
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert analysis.facts is not None
    return peak / len(analysis.doc.blocks)


@pytest.mark.parametrize(
    ("kind", "bound"),
    [("program", 3_300), ("cam_program", 5_000)],
)
def test_an_analysis_holds_at_most_its_bound_per_block(kind: str, bound: int) -> None:
    text = getattr(_generators(), kind)(BLOCKS)
    per_block = _peak_per_block(text)
    assert per_block <= bound, f"{per_block:.0f} bytes per block, more than {bound}"
