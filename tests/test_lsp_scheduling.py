"""Which open documents an edit reschedules, over stdio: only those whose analysis it can change.

A document's analysis reads the documents it calls and those that call it (the program
numbers they define and call, ``workspace.related_documents``). An edit of a document that
no other reads publishes the edited one alone; a change of a program's number reschedules
the documents that call it, or now call it.
"""

from __future__ import annotations

import asyncio
import collections
import time
from collections.abc import Callable, Sequence
from typing import Any

import pytest
from lsprotocol import types
from pytest_lsp import LanguageClient

from test_lsp import client as client  # the server fixture
from test_lsp import codes, edit, open_text, replace, start

WAIT = 60.0
SETTLE = 1.0  # seconds without a publish: the analyses an edit scheduled are done (debounce 20 ms)

CALLER = "untitled:caller.nc"
CALLED = "untitled:called.nc"
APART = "untitled:apart.nc"


class Publishes(dict[str, Sequence[types.Diagnostic]]):
    """The client's diagnostics by document, counting every publish."""

    def __init__(self) -> None:
        super().__init__()
        self.count: collections.Counter[str] = collections.Counter()

    def __setitem__(self, uri: str, value: Sequence[types.Diagnostic]) -> None:
        self.count[uri] += 1
        super().__setitem__(uri, value)


async def until(check: Callable[[], bool], what: str) -> None:
    deadline = time.monotonic() + WAIT
    while not check():
        if time.monotonic() > deadline:
            raise AssertionError(f"not in {WAIT} s: {what}")
        await asyncio.sleep(0.02)


async def settled(published: Publishes) -> collections.Counter[str]:
    """The publish counts once no publish came for SETTLE seconds."""
    while True:
        before = collections.Counter(published.count)
        await asyncio.sleep(SETTLE)
        if published.count == before:
            return before


async def test_an_edit_reschedules_only_the_documents_it_can_change(
    client: LanguageClient,
) -> None:
    published = Publishes()
    client.diagnostics = published
    await start(client, folder=None)
    open_text(client, CALLER, "O0001\nM98 P0100\nM30\n")
    open_text(client, CALLED, "O0100\nG00 X1.\nM99\n")
    open_text(client, APART, "O0200\nG00 X2.\nM30\n")
    await until(lambda: all(published.count[u] for u in (CALLER, CALLED, APART)), "3 publishes")
    await until(lambda: "MB403" not in codes(published[CALLER]), "O0100 found by its caller")
    counts = await settled(published)

    # A body edit of the called program: it and its caller are analysed again, not the other.
    edit(client, CALLED, 2, [replace(1, 5, 7, "3.")])
    await until(lambda: published.count[CALLED] > counts[CALLED], "the edited one published")
    await until(lambda: published.count[CALLER] > counts[CALLER], "its caller published")
    counts = await settled(published)
    assert published.count[APART] == 1, published.count

    # An edit of the unrelated document publishes it alone.
    edit(client, APART, 2, [replace(1, 5, 7, "4.")])
    await until(lambda: published.count[APART] > counts[APART], "the unrelated one published")
    after = await settled(published)
    assert after[CALLER] == counts[CALLER] and after[CALLED] == counts[CALLED], after

    # The called program's number changes: its caller is rescheduled (O0100 is missing).
    edit(client, CALLED, 3, [replace(0, 1, 5, "0101")])
    await until(lambda: "MB403" in codes(published[CALLER]), "the caller misses O0100")
    counts = await settled(published)
    assert published.count[APART] == after[APART], published.count

    # The unrelated document now defines O0100: the caller, which did not read it, finds it.
    edit(client, APART, 3, [replace(0, 1, 5, "0100")])
    await until(lambda: "MB403" not in codes(published[CALLER]), "the caller finds O0100")
    after = await settled(published)
    assert after[CALLED] == counts[CALLED], after

    # Closed, an untitled document leaves the workspace: its readers alone are analysed again.
    client.text_document_did_close(
        types.DidCloseTextDocumentParams(text_document=types.TextDocumentIdentifier(uri=APART))
    )
    await until(lambda: "MB403" in codes(published[CALLER]), "the caller misses O0100 again")
    final = await settled(published)
    assert final[CALLED] == after[CALLED], final


def test_an_analysis_finds_the_documents_it_reads_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """The engine asks the workspace which documents an analysis reads (to know what cancels
    it) and hands them to the analysis, which does not look for them again."""
    from fanuc_macro import workspace
    from fanuc_macro.lsp.engine import Engine

    looked_up: list[str] = []
    related = workspace.related_documents

    def counted(key: str, indexes: Any, *custom_called: Any) -> list[str] | None:
        looked_up.append(key)
        return related(key, indexes, *custom_called)

    monkeypatch.setattr(workspace, "related_documents", counted)

    async def run() -> None:
        engine = Engine(lambda doc, result: None, lambda message, kind: None)
        engine.bind_loop(asyncio.get_running_loop())
        engine.debounce = 0.0
        try:
            engine.open(CALLED, "O0100\nG00 X1.\nM99\n", 1)
            assert (await engine.fresh(CALLED, WAIT)) is not None
            looked_up.clear()
            engine.change(CALLED, 2, [replace(1, 5, 7, "3.")])
            result = await engine.fresh(CALLED, WAIT)
            assert result is not None and result.version == 2 and result.analysis is not None
            await engine.in_worker(lambda: None)
        finally:
            engine.shutdown()

    asyncio.run(run())
    assert looked_up == [CALLED]
