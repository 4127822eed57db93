"""Rename, document highlight, folding and selection ranges, workspace symbols and the call
hierarchy end to end: a real server process over stdio, driven by pytest-lsp."""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any

import pytest
from lsprotocol import types
from pygls.exceptions import JsonRpcException
from pytest_lsp import LanguageClient

from test_lsp import WAIT, client, open_seed, open_text, start

__all__ = ["client"]  # the fixture, imported for the tests here

LOOPS = "O1 (LOOPS)\n#1=0\nWHILE[#1LT3]DO1\nN5 #1=#1+1\n#2=[#1+1]\nIF[#1EQ2]GOTO5\nEND1\nM30\n"


def doc(uri: str) -> types.TextDocumentIdentifier:
    return types.TextDocumentIdentifier(uri=uri)


def at(line: int, character: int) -> types.Position:
    return types.Position(line=line, character=character)


async def answered(request: Any) -> Any:
    return await asyncio.wait_for(request, WAIT)


def applied(text: str, edits: list[types.TextEdit]) -> str:
    lines = text.split("\n")
    for e in sorted(
        edits, key=lambda e: (e.range.start.line, e.range.start.character), reverse=True
    ):
        start, end = e.range.start, e.range.end
        assert start.line == end.line
        line = lines[start.line]
        lines[start.line] = line[: start.character] + e.new_text + line[end.character :]
    return "\n".join(lines)


async def test_rename_of_a_label_over_the_protocol(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    prepared = await answered(
        client.text_document_prepare_rename_async(
            types.PrepareRenameParams(text_document=doc(uri), position=at(40, 21))
        )
    )
    assert isinstance(prepared, types.PrepareRenamePlaceholder)
    assert prepared.placeholder == "10" and prepared.range.start == at(40, 20)
    edit = await answered(
        client.text_document_rename_async(
            types.RenameParams(text_document=doc(uri), position=at(40, 21), new_name="N15")
        )
    )
    assert edit is not None and edit.changes is not None
    [(changed, edits)] = edit.changes.items()
    assert changed == uri
    assert [(e.range.start.line, e.new_text) for e in edits] == [(30, "15"), (40, "15")]


async def test_rename_refusals_are_errors_with_their_reason(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:computed.nc"
    open_text(client, uri, "O1\nN10 #1=10\nGOTO#1\nGOTO10\nM30\n")

    async def refused(line: int, character: int, new_name: str | None = None) -> str:
        with pytest.raises(JsonRpcException) as error:
            if new_name is None:
                await answered(
                    client.text_document_prepare_rename_async(
                        types.PrepareRenameParams(
                            text_document=doc(uri), position=at(line, character)
                        )
                    )
                )
            else:
                await answered(
                    client.text_document_rename_async(
                        types.RenameParams(
                            text_document=doc(uri), position=at(line, character), new_name=new_name
                        )
                    )
                )
        assert error.value.code == types.LSPErrorCodes.RequestFailed
        return error.value.message

    assert "computed GOTO" in await refused(2, 1)
    assert "is a variable number" in await refused(1, 4)
    assert "has a computed GOTO (line 3)" in await refused(3, 5, "20")
    other = "untitled:plain.nc"
    open_text(client, other, "O1\nN10 G00 X0\nGOTO10\nM30\n")
    uri = other
    assert "out of range" in await refused(2, 4, "123456")
    nothing = await answered(
        client.text_document_prepare_rename_async(
            types.PrepareRenameParams(text_document=doc(other), position=at(1, 5))
        )
    )
    assert nothing is None  # G00


async def test_rename_of_a_program_in_a_workspace(client: LanguageClient, tmp_path: Path) -> None:
    (tmp_path / "main.nc").write_text("O1000\nM98 P1234\nG65 P1234 A1.\nM30\n", "utf-8")
    (tmp_path / "other.nc").write_text("O1001\nG66 P1234 A2.\nM30\n", "utf-8")
    (tmp_path / "sub.nc").write_text("%\nO1234 (SUB)\n#100=#1\nM99\n%\n", "utf-8")
    await start(client, tmp_path)
    main = (tmp_path / "main.nc").as_uri()
    open_text(client, main, (tmp_path / "main.nc").read_text("utf-8"))
    edit = None
    for _ in range(100):  # the workspace scan finds the other files
        edit = await answered(
            client.text_document_rename_async(
                types.RenameParams(text_document=doc(main), position=at(1, 6), new_name="O2000")
            )
        )
        if edit is not None and edit.changes is not None and len(edit.changes) == 3:
            break
        await asyncio.sleep(0.1)
    assert edit is not None and edit.changes is not None
    texts = {
        uri: applied((tmp_path / Path(uri).name).read_text("utf-8"), edits)
        for uri, edits in edit.changes.items()
    }
    assert texts == {
        main: "O1000\nM98 P2000\nG65 P2000 A1.\nM30\n",
        (tmp_path / "other.nc").as_uri(): "O1001\nG66 P2000 A2.\nM30\n",
        (tmp_path / "sub.nc").as_uri(): "%\nO2000 (SUB)\n#100=#1\nM99\n%\n",
    }


async def test_document_highlight_of_a_variable_and_a_label(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:loops.nc"
    open_text(client, uri, LOOPS)
    found = await answered(
        client.text_document_document_highlight_async(
            types.DocumentHighlightParams(text_document=doc(uri), position=at(3, 7))
        )
    )
    assert found is not None
    kinds = [(h.range.start.line, h.range.start.character, h.kind) for h in found]
    read, write = types.DocumentHighlightKind.Read, types.DocumentHighlightKind.Write
    assert kinds == [
        (1, 0, write),
        (2, 6, read),
        (3, 3, write),
        (3, 6, read),
        (4, 4, read),
        (5, 3, read),
    ]
    label = await answered(
        client.text_document_document_highlight_async(
            types.DocumentHighlightParams(text_document=doc(uri), position=at(3, 1))
        )
    )
    assert label is not None
    assert [(h.range.start.line, h.kind) for h in label] == [
        (3, types.DocumentHighlightKind.Text),
        (5, types.DocumentHighlightKind.Text),
    ]


async def test_folding_and_selection_ranges(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:folds.nc"
    open_text(client, uri, "(ONE)\n(TWO)\n" + LOOPS)
    folds = await answered(
        client.text_document_folding_range_async(types.FoldingRangeParams(text_document=doc(uri)))
    )
    assert folds is not None
    assert [(f.start_line, f.end_line, f.kind) for f in folds] == [
        (0, 1, types.FoldingRangeKind.Comment),
        (2, 9, types.FoldingRangeKind.Region),
        (4, 7, types.FoldingRangeKind.Region),
    ]
    [selection] = await answered(
        client.text_document_selection_range_async(
            types.SelectionRangeParams(text_document=doc(uri), positions=[at(6, 5)])
        )
    )
    chain = []
    node: types.SelectionRange | None = selection
    while node is not None:
        chain.append(
            (
                node.range.start.line,
                node.range.start.character,
                node.range.end.line,
                node.range.end.character,
            )
        )
        node = node.parent
    # #1, #1+1, [#1+1], the block, the loop's body, the loop, the program.
    assert chain == [
        (6, 4, 6, 6),
        (6, 4, 6, 8),
        (6, 3, 6, 9),
        (6, 0, 6, 9),
        (5, 0, 7, 14),
        (4, 0, 8, 4),
        (2, 0, 9, 3),
    ]


async def test_workspace_symbols_over_the_protocol(client: LanguageClient) -> None:
    await start(client)
    open_seed(client, "o4009_external_m50x3.nc")
    found: list[Any] = []
    for _ in range(100):
        found = list(
            await answered(client.workspace_symbol_async(types.WorkspaceSymbolParams(query="o333")))
            or []
        )
        if len(found) == 2:  # the scan has reached both files
            break
        await asyncio.sleep(0.1)
    # Both seeds' subprograms, in the order of their files; the first comment beside each.
    assert [(s.name, s.container_name) for s in found] == [
        ("O3331", "外螺纹子程序"),
        ("O3330", "内螺纹子程序"),
    ]
    symbol = found[0]
    assert symbol.kind == types.SymbolKind.Function
    assert symbol.location.uri.endswith("o4009_external_m50x3.nc")
    assert symbol.location.range.start.line == 17
    labels = await answered(client.workspace_symbol_async(types.WorkspaceSymbolParams(query="N20")))
    assert any(s.container_name == "O3331" for s in labels or [])


async def test_call_hierarchy_across_files(client: LanguageClient, tmp_path: Path) -> None:
    (tmp_path / "main.nc").write_text("O1000 (MAIN)\nM98 P1234\nG65 P1234 A1.\nM30\n", "utf-8")
    (tmp_path / "sub.nc").write_text("O1234 (SUB)\nM98 P2000\nM99\n%\nO2000 (LEAF)\nM99\n", "utf-8")
    await start(client, tmp_path)
    main = (tmp_path / "main.nc").as_uri()
    sub = (tmp_path / "sub.nc").as_uri()
    open_text(client, main, (tmp_path / "main.nc").read_text("utf-8"))
    items: list[types.CallHierarchyItem] = []
    for _ in range(100):
        items = list(
            await answered(
                client.text_document_prepare_call_hierarchy_async(
                    types.CallHierarchyPrepareParams(text_document=doc(main), position=at(1, 6))
                )
            )
            or []
        )
        if items and items[0].uri == sub:
            break
        await asyncio.sleep(0.1)
    [item] = items
    assert (item.name, item.uri, item.detail) == ("O1234", sub, "SUB")
    incoming = await answered(
        client.call_hierarchy_incoming_calls_async(
            types.CallHierarchyIncomingCallsParams(item=item)
        )
    )
    assert incoming is not None
    [caller] = incoming
    assert caller.from_.name == "O1000" and caller.from_.uri == main
    assert [r.start.line for r in caller.from_ranges] == [1, 2]
    outgoing = await answered(
        client.call_hierarchy_outgoing_calls_async(
            types.CallHierarchyOutgoingCallsParams(item=item)
        )
    )
    assert outgoing is not None
    [callee] = outgoing
    assert callee.to.name == "O2000" and callee.to.uri == sub
    assert [(r.start.line, r.start.character, r.end.character) for r in callee.from_ranges] == [
        (1, 0, 9)
    ]


async def test_definition_of_a_common_variable_is_where_the_caller_sets_it(
    client: LanguageClient, tmp_path: Path
) -> None:
    seed = Path(__file__).resolve().parent / "fixtures" / "seeds" / "o4009_external_m50x3.nc"
    lines = seed.read_text("utf-8").splitlines(keepends=True)
    (tmp_path / "main.nc").write_text("".join(lines[:17]), "utf-8")  # % and O4009
    (tmp_path / "sub.nc").write_text("".join(lines[17:]), "utf-8")  # O3331 and %
    await start(client, tmp_path)
    uri = (tmp_path / "sub.nc").as_uri()
    open_text(client, uri, (tmp_path / "sub.nc").read_text("utf-8"))
    found = await answered(
        client.text_document_definition_async(
            types.DefinitionParams(text_document=doc(uri), position=at(12, 8))  # X[#100+1.]
        )
    )
    assert [(loc.uri, loc.range.start.line) for loc in found] == [
        ((tmp_path / "main.nc").as_uri(), 5)  # #100=50. in O4009, before M98 P0013331
    ]
