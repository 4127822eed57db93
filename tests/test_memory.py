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
constants shared their closures. Lines of the same code that differ in their comments (the
macro program's passes are numbered in them) now share their statement and its compiled line,
and expressions share their variables' readers and the operations: about 1,450 bytes a block
for it. A program whose blocks are all different (``distinct``) shares none of that: about
3,900 bytes a block, 4,400 before the readers and operations were shared.
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
kind = sys.argv[2]
if kind == "distinct":
    text = bench_lsp.program(int(sys.argv[3]), distinct=True)
else:
    text = getattr(bench_lsp, kind)(int(sys.argv[3]))
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
    [("program", 1_800), ("distinct", 4_600), ("cam_program", 2_000)],
)
def test_an_analysis_holds_at_most_its_bound_per_block(kind: str, bound: int) -> None:
    per_block = _peak_per_block(kind)
    assert per_block <= bound, f"{per_block:.0f} bytes per block, more than {bound}"


# The server's side of an open document, edited once: its own allocations (those made by a
# line of lsp/, the analysis's apart) while its engine holds the document and its result.
SERVER_SIDE = """
import asyncio, sys, tracemalloc
sys.path.insert(0, sys.argv[1])
import bench_lsp
from lsprotocol import types
from fanuc_macro.lsp.engine import Engine

async def main():
    blocks = int(sys.argv[2])
    engine = Engine(lambda doc, result: None, lambda message, kind: None)
    engine.bind_loop(asyncio.get_running_loop())
    engine.configure({"analysis": {"maxBlocks": 10 * blocks, "maxFileSize": 100 * blocks}})
    engine.debounce = 0.0
    text = bench_lsp.program(blocks)
    lines = text.split("\\n")
    uri = "untitled:memory.nc"
    tracemalloc.start()
    engine.open(uri, text, 1)
    assert (await engine.fresh(uri, 300)).version == 1
    line = len(lines) // 2
    at = types.Position(line=line, character=lines[line].index("(") + 1)
    engine.change(uri, 2, [types.TextDocumentContentChangePartial(
        range=types.Range(start=at, end=at), text="x")])
    result = await engine.fresh(uri, 300)
    assert result is not None and result.version == 2 and result.analysis is not None
    own = tracemalloc.take_snapshot().filter_traces(
        [tracemalloc.Filter(True, "*/fanuc_macro/lsp/*")])
    held = sum(stat.size for stat in own.statistics("filename"))
    tracemalloc.stop()
    engine.shutdown()
    text_bytes = sys.getsizeof(engine.docs["untitled:memory.nc"].text)
    print((held - text_bytes) / len(lines))

asyncio.run(main())
"""


def test_the_server_holds_a_document_as_its_text_and_line_starts() -> None:
    """What the language server allocates for an open document beyond the analysis: its text
    (the edited version's, made by the edit) and about 9 bytes a line for the line starts (an
    array of machine integers) shared by the document and its analysis' result. As a list of
    ints they cost about 39 bytes a line; a list of the lines as strings, which the result
    held before, about 130 bytes a line more."""
    done = subprocess.run(
        [sys.executable, "-c", SERVER_SIDE, str(BENCH), str(BLOCKS)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    per_line = float(done.stdout.split()[-1])
    assert per_line <= 20, f"{per_line:.0f} bytes per line besides the text, more than 20"


def test_the_server_gives_freed_memory_back_after_each_analysis(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """After an analysis is delivered the worker trims the C allocator's heaps (glibc), so the
    previous version's freed lists and dicts do not stay in the server's RSS."""
    import asyncio
    import platform

    from fanuc_macro.lsp import engine as engine_module

    if platform.system() == "Linux" and platform.libc_ver()[0] == "glibc":
        assert engine_module.release_memory()
    trims: list[bool] = []
    monkeypatch.setattr(engine_module, "release_memory", lambda: trims.append(True) or True)

    async def run() -> None:
        engine = engine_module.Engine(lambda doc, result: None, lambda message, kind: None)
        engine.bind_loop(asyncio.get_running_loop())
        engine.debounce = 0.0
        engine.open("untitled:trim.nc", "O1\nG01 X1. F1.\nM30\n", 1)
        assert (await engine.fresh("untitled:trim.nc", 60)) is not None
        await engine.in_worker(lambda: None)  # the jobs queued after the analysis
        engine.shutdown()

    asyncio.run(run())
    assert trims == [True]


def test_a_value_read_once_is_summarised_in_two_slots() -> None:
    """Most reads and writes of a program without loops run once: the summary of one value
    (a number, vacant or unknown) holds that value and no spread, 48 bytes with the garbage
    collector's header; one with every field (seven slots, and two infinities of its own
    unless a number replaced them) took 88 to 136."""
    import tracemalloc

    from fanuc_macro.evaluator.facts import ValueSummary
    from fanuc_macro.evaluator.values import UNKNOWN

    count = 3_000
    for value in (1.25, None, UNKNOWN):
        summaries: list[ValueSummary | None] = [None] * count  # the list made before tracing
        tracemalloc.start()
        for i in range(count):
            summary = ValueSummary()
            summary.add(value)
            summaries[i] = summary
        held, _ = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        assert held / count <= 56, f"{held / count:.0f} bytes per summary of {value!r}"
        first = summaries[0]
        assert first is not None and first.count == 1 and first.last is value


# Versions of a document alive after a series of edits, each adding a line in the middle:
# counted among the interpreter's objects (a new process: other tests' documents stay out).
VERSIONS_KEPT = """
import gc, sys
sys.path.insert(0, sys.argv[1])
import bench_lsp
from fanuc_macro.config import Config
from fanuc_macro.syntax.tree import Document
from fanuc_macro.workspace import Workspace

blocks = int(sys.argv[2])
lines = bench_lsp.program(blocks).split("\\n")
workspace = Workspace(Config(max_blocks=10 * blocks, max_file_size=100 * blocks))
uri = "file:///versions.nc"
for edit in range(8):
    lines.insert(len(lines) // 2, f"#{edit + 1}=1. (inserted)")
    workspace.add_text(uri, "\\n".join(lines))
    workspace.analyse(uri)
gc.unfreeze()  # the analysis freezes what it leaves (syntax.parser.quiet_gc)
gc.collect()
print(sum(type(o) is Document for o in gc.get_objects()))
"""


def test_a_workspace_keeps_no_earlier_version_of_an_edited_document() -> None:
    """After edits that move lines (each makes a new block for every line after it, about
    5 MB a version of 100,000 lines), the earlier versions are freed: the cache of line diffs
    (``line_maps.line_diff``) names them by weak reference. It kept the last four pairs."""
    done = subprocess.run(
        [sys.executable, "-c", VERSIONS_KEPT, str(BENCH), "2000"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    assert int(done.stdout.split()[-1]) <= 2


def test_lines_of_the_same_code_share_their_statement_and_compiled_line() -> None:
    """A thread's passes differ in their comments only: their lines share the nodes of the
    statement (immutable, and placed by column, which the comments keep) and so the compiled
    line; another code, or the same code at other columns, has its own."""
    from fanuc_macro.evaluator.machine import compiled
    from fanuc_macro.syntax.parser import BlockParser

    parser = BlockParser()
    first, second, other, moved = (
        parser.parse_line(text)
        for text in (
            "G92 X[#100-0.3] W-[#102+#101] F#101 (pass 1)",
            "G92 X[#100-0.3] W-[#102+#101] F#101 (pass 12)",
            "G92 X[#100-0.4] W-[#102+#101] F#101 (pass 2)",
            " G92 X[#100-0.3] W-[#102+#101] F#101 (pass 3)",
        )
    )
    assert first.statement is second.statement
    assert first.comments[0].text == "pass 1" and second.comments[0].text == "pass 12"
    assert compiled(first) is compiled(second)
    assert other.statement is not first.statement and compiled(other) is not compiled(first)
    assert moved.statement is not None and first.statement is not None
    assert moved.statement.span.start == first.statement.span.start + 1
    assert compiled(moved) is not compiled(first)
