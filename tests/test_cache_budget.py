"""The caches of a long session: bounded in bytes, freed when a document closes.

Two interfaces: the workspace in this process (its database's caches, measured by
tracemalloc, deterministic), and the language server over stdio (its RSS after typing 5,000
distinct lines into a document and closing it, read from /proc).
"""

from __future__ import annotations

import gc
import time
import tracemalloc
from collections.abc import Iterator
from pathlib import Path

import pytest

from fanuc_macro import analysis
from fanuc_macro.analysis import cache_bytes
from fanuc_macro.database import Database
from fanuc_macro.workspace import Workspace
from raw_stdio import RawLspClient

CORPUS = Path(__file__).resolve().parents[2] / "shared" / "corpus"


def program(n: int, lines: int = 120) -> str:
    """A program of ``lines`` blocks no other program here has (distinct numbers)."""
    body = "".join(
        f"#{100 + i % 30}=[#{101 + (i * 7) % 30}+{n}.{i}]*SIN[{(n + i) % 360}]\n"
        f"G01 X[#{100 + i % 30}+{n * lines + i}.] Z-{i}.{n % 10} F0.{i % 9 + 1}\n"
        for i in range(lines // 2)
    )
    return f"O{1000 + n % 8000}\n#101=1.\n{body}M30\n"


def traced_after_collect() -> int:
    gc.collect()
    return tracemalloc.get_traced_memory()[0]


def test_closing_a_document_frees_the_caches_it_filled() -> None:
    workspace = Workspace(db=Database())
    workspace.add_text("warm.nc", "O1\n#1=1\nG0X#1\nM30\n")
    workspace.analyse("warm.nc")
    tracemalloc.start()
    try:
        before = traced_after_collect()
        for n in range(40):  # 40 versions of one document, 4,800 distinct lines
            workspace.add_text("typed.nc", program(n))
            workspace.analyse("typed.nc")
        with workspace.db.active():
            held = cache_bytes(workspace.parser)
        grown = traced_after_collect() - before
        workspace.remove("typed.nc")
        left = traced_after_collect() - before
    finally:
        tracemalloc.stop()
    assert grown > 2_000_000, grown  # the caches held the document's lines
    assert held > 1_000_000, held
    assert left < 300_000, left  # what is left is the warm document's, not the closed one's
    with workspace.db.active():
        assert cache_bytes(workspace.parser) == 0


def test_the_estimate_follows_the_bytes_the_caches_hold() -> None:
    # The caches of a workspace whose documents are gone but for their caches: the bytes
    # tracemalloc finds against those the estimate gives, within a factor of 1.6.
    workspace = Workspace(db=Database())
    tracemalloc.start()
    try:
        before = traced_after_collect()
        for n in range(30):
            workspace.add_text(f"p{n}.nc", program(n))
            workspace.analyse(f"p{n}.nc")
        workspace._entries.clear()  # the documents go, their lines stay in the caches
        workspace._facts.clear()
        workspace._indexes = {}
        held = traced_after_collect() - before
    finally:
        tracemalloc.stop()
    with workspace.db.active():
        estimate = cache_bytes(workspace.parser)
    assert held / 1.6 < estimate < held * 1.6, (estimate, held)


def test_the_caches_stay_within_their_budget_in_bytes(monkeypatch: pytest.MonkeyPatch) -> None:
    # Distinct programs analysed one after the other in one document, as a day of editing:
    # the caches are dropped whenever they pass the budget, so memory levels off.
    budget = 3_000_000
    monkeypatch.setattr(analysis, "CACHE_BUDGET", budget)
    workspace = Workspace(db=Database())
    tracemalloc.start()
    try:
        base = traced_after_collect()
        levels = []
        for n in range(150):
            workspace.add_text("day.nc", program(n))
            workspace.analyse("day.nc")
            with workspace.db.active():
                # Over the budget by at most what one analysis adds (it is checked before).
                assert cache_bytes(workspace.parser) < budget + 1_500_000
            levels.append(traced_after_collect() - base)
    finally:
        tracemalloc.stop()
    # The document, its analysis and the caches rise to the budget and drop, again and again:
    # the highest of the last 50 analyses is no higher than that of the first 50.
    first, last = max(levels[:50]), max(levels[100:])
    assert last < first * 1.2, (first, last)
    assert last < 3 * budget, (first, last)


# ---- the language server's RSS -----------------------------------------------------------------


@pytest.fixture
def server() -> Iterator[RawLspClient]:
    started = RawLspClient()
    yield started
    started.close()


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="RSS read from /proc")
def test_the_server_gives_back_what_5000_typed_lines_held(server: RawLspClient) -> None:
    server.initialize()
    server.notify("initialized", {})
    warm = {"uri": "untitled:warm.nc", "languageId": "fanuc-macro", "version": 1}
    server.notify("textDocument/didOpen", {"textDocument": {**warm, "text": "O1\n#1=1\nM30\n"}})
    server.published("untitled:warm.nc", 1)
    time.sleep(1.0)
    start = server.rss_mb()
    uri = "untitled:typed.nc"
    opened = {"uri": uri, "languageId": "fanuc-macro", "version": 1, "text": "O1000\nM30\n"}
    server.notify("textDocument/didOpen", {"textDocument": opened})
    version = 1
    for i in range(5000):  # a keystroke a line, each line a new one, at the end of the program
        version += 1
        line = f"#{100 + i % 400}=[#{100 + (i * 7) % 400}+{i}.{i % 97}]*SIN[{i % 360}]\n"
        at = {"line": 1 + i, "character": 0}
        server.notify(
            "textDocument/didChange",
            {
                "textDocument": {"uri": uri, "version": version},
                "contentChanges": [{"range": {"start": at, "end": at}, "text": line}],
            },
        )
        if i % 250 == 249:
            server.published(uri, version)  # the analyses keep up, as in an editor
    server.published(uri, version)
    peak = server.rss_mb()
    server.notify("textDocument/didClose", {"textDocument": {"uri": uri}})
    # A request answered after the close's work: then the memory has been given back.
    time.sleep(2.0)
    server.send({"jsonrpc": "2.0", "id": 2, "method": "workspace/symbol", "params": {"query": ""}})
    server.answer(2)
    time.sleep(1.0)
    end = server.rss_mb()
    print(f"RSS: {start:.1f} MB at the start, {peak:.1f} MB typed, {end:.1f} MB closed")
    assert peak > start + 5, (start, peak)  # the document and its analysis took memory
    assert end < start + 20, (start, peak, end)


def test_workspaces_dropped_leave_nothing_behind() -> None:
    # A parser's closures and a workspace's database hold cycles: the collector must be free
    # to collect them (no gc.freeze), or every dropped workspace stays for good.
    def one(n: int) -> None:
        workspace = Workspace(db=Database())
        workspace.add_text("p.nc", program(n, 20))
        workspace.analyse("p.nc")

    one(0)
    tracemalloc.start()
    try:
        before = traced_after_collect()
        for n in range(1, 21):
            one(n)
        left = traced_after_collect() - before
    finally:
        tracemalloc.stop()
    assert left < 500_000, left  # a parser's tables alone are 240 KB


def test_no_module_freezes_the_collector() -> None:
    package = Path(analysis.__file__).parent
    freezing = [
        str(path.relative_to(package))
        for path in sorted(package.rglob("*.py"))
        if "gc.freeze(" in path.read_text("utf-8")
    ]
    assert not freezing


@pytest.mark.parametrize(
    ("argv", "server"),
    [
        (["python3", "-m", "fanuc_macro.lsp.server"], True),
        (["python3", "-m", "fanuc_macro.lsp.server", "--stdio"], True),
        (["/usr/bin/python3", "/venv/bin/fanuc-macro-ls"], True),
        (["/usr/bin/python3", "/venv/bin/fanuc-macro-ls", "--log-level", "DEBUG"], True),
        (["python3", "-m", "pytest"], False),
        (["python3", "-c", "import fanuc_macro.lsp"], False),
        (["/venv/bin/fanuc-macro"], False),
    ],
)
def test_the_server_is_recognised_by_its_command_line(argv: list[str], server: bool) -> None:
    from fanuc_macro.lsp import _started_as_server

    assert _started_as_server(argv) is server


@pytest.mark.skipif(not Path("/proc/self/environ").exists(), reason="environment from /proc")
def test_the_server_runs_on_the_c_allocator(server: RawLspClient) -> None:
    server.initialize()  # started again, then answering: the environment is the final one
    environ = Path(f"/proc/{server.proc.pid}/environ").read_bytes().split(b"\0")
    assert b"PYTHONMALLOC=malloc" in environ
