"""Formatting, range formatting and "Renumber N labels" through a real server over stdio."""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Sequence

import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient

from test_lsp import ENV, SERVER, WAIT, codes, diagnostics, edit, open_text, start


@pytest_lsp.fixture(config=ClientServerConfig(server_command=SERVER, server_env=ENV))
async def client(lsp_client: LanguageClient) -> AsyncIterator[None]:
    yield
    if lsp_client.capabilities is not None:
        await asyncio.wait_for(lsp_client.shutdown_session(), WAIT)


OPTIONS = types.FormattingOptions(tab_size=4, insert_spaces=True)


def applied(text: str, edits: Sequence[types.TextEdit]) -> str:
    """The text with the edits applied (the lines are ASCII or BMP here: UTF-16 columns are
    code points)."""
    lines = text.split("\n")
    starts = [0]
    for line in lines:
        starts.append(starts[-1] + len(line) + 1)

    def offset(p: types.Position) -> int:
        return starts[p.line] + p.character if p.line < len(lines) else len(text)

    ordered = sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character))
    for e in reversed(ordered):
        text = text[: offset(e.range.start)] + e.new_text + text[offset(e.range.end) :]
    return text


def send(client: LanguageClient, uri: str, version: int, edits: Sequence[types.TextEdit]) -> None:
    """The edits as the client applies them: one change each, the last place first."""
    ordered = sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character))
    changes = [
        types.TextDocumentContentChangePartial(range=e.range, text=e.new_text)
        for e in reversed(ordered)
    ]
    edit(client, uri, version, changes)


async def symbols(client: LanguageClient, uri: str) -> None:
    """A request that waits for the analysis of the document's current version: the
    diagnostics of that version are published before it is answered."""
    await asyncio.wait_for(
        client.text_document_document_symbol_async(
            types.DocumentSymbolParams(text_document=types.TextDocumentIdentifier(uri=uri))
        ),
        WAIT,
    )


async def test_document_formatting(client: LanguageClient) -> None:
    await start(client, None, {"format": {"spaceBetweenWords": "always"}})
    uri = "untitled:format.nc"
    text = "o1000 (Main 主程序)\r\ng01x10.z-5.  \r\n#1=#2+1.\r\nm30\r\n"
    open_text(client, uri, text)
    edits = await asyncio.wait_for(
        client.text_document_formatting_async(
            types.DocumentFormattingParams(
                text_document=types.TextDocumentIdentifier(uri=uri), options=OPTIONS
            )
        ),
        WAIT,
    )
    assert edits is not None
    assert {e.range.start.line for e in edits} == {0, 1, 3}
    assert all("\n" not in e.new_text for e in edits)  # line ends are never touched
    got = applied(text.replace("\r\n", "\n"), edits).replace("\n", "\r\n")
    assert got == "O1000 (Main 主程序)\r\nG01 X10. Z-5.\r\n#1=#2+1.\r\nM30\r\n"


async def test_range_formatting(client: LanguageClient) -> None:
    await start(client, None, {"format": {"spacesAroundAssignment": "always"}})
    uri = "untitled:range.nc"
    text = "o1\n#1=1\n#2=2\n#3=3\nm30\n"
    open_text(client, uri, text)
    edits = await asyncio.wait_for(
        client.text_document_range_formatting_async(
            types.DocumentRangeFormattingParams(
                text_document=types.TextDocumentIdentifier(uri=uri),
                range=types.Range(
                    start=types.Position(line=2, character=1),
                    end=types.Position(line=4, character=0),  # line 4 itself is left
                ),
                options=OPTIONS,
            )
        ),
        WAIT,
    )
    assert edits is not None
    assert applied(text, edits) == "o1\n#1=1\n#2 = 2\n#3 = 3\nm30\n"


async def renumber_actions(
    client: LanguageClient, uri: str, line: int, only: list[str] | None
) -> list[types.CodeAction]:
    result = await asyncio.wait_for(
        client.text_document_code_action_async(
            types.CodeActionParams(
                text_document=types.TextDocumentIdentifier(uri=uri),
                range=types.Range(
                    start=types.Position(line=line, character=0),
                    end=types.Position(line=line, character=0),
                ),
                context=types.CodeActionContext(diagnostics=[], only=only),
            )
        ),
        WAIT,
    )
    return [
        a
        for a in result or []
        if isinstance(a, types.CodeAction) and a.kind == "source.renumber.fanuc-macro"
    ]


LOOP = "O1000 (计数 loop)\nN5 #1=0\nN7 IF[#1GE3]GOTO99\n#1=#1+1\nGOTO7\nN99 M30\n"


async def test_renumber_action_updates_the_jumps(client: LanguageClient) -> None:
    await start(client, None, {"format": {"renumberStep": 100}})
    uri = "untitled:renumber.nc"
    open_text(client, uri, LOOP)
    await diagnostics(client, uri)
    await symbols(client, uri)
    before = client.diagnostics[uri]
    # Offered when asked for: not with the quick fixes.
    assert await renumber_actions(client, uri, 1, [types.CodeActionKind.QuickFix]) == []
    assert await renumber_actions(client, uri, 1, None) == []
    [action] = await renumber_actions(client, uri, 1, [types.CodeActionKind.Source])
    assert action.title == "Renumber N labels of O1000 (step 100)"
    assert action.disabled is None
    assert action.edit is not None and action.edit.changes is not None
    edits = action.edit.changes[uri]
    after = applied(LOOP, edits)
    assert after == (
        "O1000 (计数 loop)\nN100 #1=0\nN200 IF[#1GE3]GOTO300\n#1=#1+1\nGOTO200\nN300 M30\n"
    )
    send(client, uri, 2, edits)
    await symbols(client, uri)
    assert [(d.code, d.range, d.message) for d in client.diagnostics[uri]] == [
        (d.code, d.range, d.message) for d in before
    ]
    # Already so: nothing more to offer.
    assert await renumber_actions(client, uri, 1, ["source.renumber.fanuc-macro"]) == []


async def test_renumber_action_is_disabled_by_a_computed_goto(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:computed.nc"
    open_text(client, uri, "O1\nN1 #2=1\nN2 GOTO#2\nM30\n")
    found = await diagnostics(client, uri)
    assert "MB000" not in codes(found)
    [action] = await renumber_actions(client, uri, 0, [types.CodeActionKind.Source])
    assert action.edit is None
    assert action.disabled is not None and "computed" in action.disabled.reason
    assert "computed" in action.title


async def test_formatting_counts_utf16_columns(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:utf16.nc"
    open_text(client, uri, "O1\n(😀) g01x1.\n")  # the emoji is two UTF-16 code units
    edits = await asyncio.wait_for(
        client.text_document_formatting_async(
            types.DocumentFormattingParams(
                text_document=types.TextDocumentIdentifier(uri=uri), options=OPTIONS
            )
        ),
        WAIT,
    )
    assert edits is not None
    [edit_] = edits
    # "g01x" is at code points 4-8, UTF-16 code units 5-9.
    assert edit_.range == types.Range(
        start=types.Position(line=1, character=5), end=types.Position(line=1, character=9)
    )
    assert edit_.new_text == "G01X"
