"""The language server end to end: a real server process over stdio, driven by pytest-lsp."""

from __future__ import annotations

import asyncio
import concurrent.futures
import importlib.util
import math
import os
import random
import re
import subprocess
import sys
import time
import uuid
from collections.abc import AsyncIterator, Callable, Sequence
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest
import pytest_lsp
from lsprotocol import types
from pygls.exceptions import JsonRpcException, JsonRpcInternalError, JsonRpcInvalidParams
from pytest_lsp import ClientServerConfig, LanguageClient

from view_payload import unpacked

ROOT = Path(__file__).resolve().parents[1]
SEEDS = ROOT / "tests" / "fixtures" / "seeds"
FAULT = "@@fanuc-macro-test-crash@@"
FEATURE_FAULT = "@@fanuc-macro-test-feature-crash@@"
SERVER = [sys.executable, "-m", "fanuc_macro.lsp.server"]
ENV = {
    **os.environ,
    "PYTHONPATH": os.pathsep.join(
        p for p in (str(ROOT / "server"), os.environ.get("PYTHONPATH", "")) if p
    ),
    "FANUC_MACRO_LS_FAULT": FAULT,
    "FANUC_MACRO_LS_FEATURE_FAULT": FEATURE_FAULT,
}
WAIT = 60.0  # seconds: generous for a loaded 2-core machine

CAPABILITIES = types.ClientCapabilities(
    general=types.GeneralClientCapabilities(position_encodings=[types.PositionEncodingKind.Utf16]),
    text_document=types.TextDocumentClientCapabilities(
        hover=types.HoverClientCapabilities(
            content_format=[types.MarkupKind.Markdown, types.MarkupKind.PlainText]
        ),
        completion=types.CompletionClientCapabilities(
            completion_item=types.ClientCompletionItemOptions(
                snippet_support=True,
                documentation_format=[types.MarkupKind.Markdown, types.MarkupKind.PlainText],
            )
        ),
        publish_diagnostics=types.PublishDiagnosticsClientCapabilities(
            related_information=True, version_support=True, code_description_support=True
        ),
    ),
    workspace=types.WorkspaceClientCapabilities(configuration=False),
)


@pytest_lsp.fixture(config=ClientServerConfig(server_command=SERVER, server_env=ENV))
async def client(lsp_client: LanguageClient) -> AsyncIterator[None]:
    yield
    if lsp_client.capabilities is not None:
        await asyncio.wait_for(lsp_client.shutdown_session(), WAIT)


async def start(
    client: LanguageClient,
    folder: Path | None = SEEDS,
    options: dict[str, Any] | None = None,
    capabilities: types.ClientCapabilities = CAPABILITIES,
    locale: str | None = None,
) -> None:
    settings = {"analysis": {"debounceMs": 20}, **(options or {})}
    await asyncio.wait_for(
        client.initialize_session(
            types.InitializeParams(
                capabilities=capabilities,
                root_uri=folder.as_uri() if folder else None,
                workspace_folders=(
                    [types.WorkspaceFolder(uri=folder.as_uri(), name=folder.name)]
                    if folder
                    else None
                ),
                initialization_options=settings,
                locale=locale,
            )
        ),
        WAIT,
    )


def uri_of(name: str) -> str:
    return (SEEDS / name).as_uri()


def open_text(client: LanguageClient, uri: str, text: str, version: int = 1) -> None:
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(
                uri=uri, language_id="fanuc-macro", version=version, text=text
            )
        )
    )


def open_seed(client: LanguageClient, name: str) -> str:
    uri = uri_of(name)
    open_text(client, uri, (SEEDS / name).read_text("utf-8"))
    return uri


def edit(client: LanguageClient, uri: str, version: int, changes: Sequence[Any]) -> None:
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
            content_changes=list(changes),
        )
    )


def replace(line: int, start: int, end: int, text: str) -> types.TextDocumentContentChangePartial:
    return types.TextDocumentContentChangePartial(
        range=types.Range(
            start=types.Position(line=line, character=start),
            end=types.Position(line=line, character=end),
        ),
        text=text,
    )


async def diagnostics(
    client: LanguageClient,
    uri: str,
    until: Callable[[Sequence[types.Diagnostic]], bool] = lambda d: True,
    timeout: float = WAIT,
) -> Sequence[types.Diagnostic]:
    deadline = time.monotonic() + timeout
    while True:
        found = client.diagnostics.get(uri)
        if found is not None and until(found):
            return found
        if time.monotonic() > deadline:
            raise AssertionError(f"no such diagnostics for {uri} in {timeout} s: {found}")
        await asyncio.sleep(0.02)


async def hover(client: LanguageClient, uri: str, line: int, character: int) -> str:
    result = await asyncio.wait_for(
        client.text_document_hover_async(
            types.HoverParams(
                text_document=types.TextDocumentIdentifier(uri=uri),
                position=types.Position(line=line, character=character),
            )
        ),
        WAIT,
    )
    if result is None:
        return ""
    assert isinstance(result.contents, types.MarkupContent)
    return result.contents.value


def codes(found: Sequence[types.Diagnostic]) -> set[str]:
    return {str(d.code) for d in found}


# ---- the executable --------------------------------------------------------------------------


def test_version() -> None:
    done = subprocess.run(
        [*SERVER, "--version"], env=ENV, capture_output=True, text=True, timeout=WAIT
    )
    assert done.returncode == 0
    assert done.stdout.strip() == "fanuc-macro-ls 0.1.0"


# ---- diagnostics -----------------------------------------------------------------------------


async def test_diagnostics_of_arc_thread(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o2_arc_thread_roughing.nc")
    found = await diagnostics(client, uri, lambda d: "MB601" in codes(d))
    mb601 = [d for d in found if d.code == "MB601" and d.range.start.line == 29]
    assert mb601, found
    diag = mb601[0]
    assert "93.82" in diag.message
    assert diag.source == "fanuc-macro"
    assert diag.severity == types.DiagnosticSeverity.Error
    assert diag.code_description is not None
    assert diag.code_description.href.endswith(
        "docs/rules.md#mb601-" + diag.code_description.href.rsplit("#mb601-", 1)[1]
    )
    assert diag.related_information, "the assignment of #1 is related"
    assert diag.related_information[0].location.uri == uri
    assert diag.related_information[0].location.range.start.line == 8


async def test_edit_updates_diagnostics(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:edit.nc"
    open_text(client, uri, "O1000\nGOTO 99\nN10 M30\n")
    found = await diagnostics(client, uri, lambda d: "MB101" in codes(d))
    assert any(d.range.start.line == 1 for d in found if d.code == "MB101")
    edit(client, uri, 2, [replace(1, 5, 7, "10")])  # GOTO 99 -> GOTO 10
    await diagnostics(client, uri, lambda d: "MB101" not in codes(d))


async def test_the_first_keystroke_in_an_empty_document(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:new.nc"
    open_text(client, uri, "")
    assert not await diagnostics(client, uri)  # the empty version analysed first
    edit(client, uri, 2, [replace(0, 0, 0, "G")])
    found = await diagnostics(client, uri, lambda d: bool(d))
    assert codes(found) == {"MB001"}, found  # the incomplete word, no internal error (MB000)


async def edited_as_fresh(
    client: LanguageClient,
    name: str,
    text: str,
    change: types.TextDocumentContentChangePartial,
    edited: str,
    done: Callable[[Sequence[types.Diagnostic]], bool],
) -> Sequence[types.Diagnostic]:
    """Open ``text``, make ``change`` (which gives ``edited``) and wait for ``done``; the
    diagnostics must be those of ``edited`` opened fresh. Returns them."""
    uri = f"untitled:{name}.nc"
    open_text(client, uri, text)
    await diagnostics(client, uri)
    edit(client, uri, 2, [change])
    found = await diagnostics(client, uri, done)
    fresh_uri = f"untitled:{name}-fresh.nc"
    open_text(client, fresh_uri, edited)
    fresh = await diagnostics(client, fresh_uri, lambda d: bool(d))
    assert [(d.code, d.range) for d in found] == [(d.code, d.range) for d in fresh]
    return found


async def test_an_edit_that_makes_a_failed_block_assign_is_analysed_again(
    client: LanguageClient,
) -> None:
    # Both versions of line 3 fail to parse, but only the second plainly assigns #9: the run
    # changes (#9 is set before G0 reads it), so the earlier run's facts must not be kept.
    await start(client, None)
    text = "O1000\n#5=2.\n#7=3\n#9BCD#5*0.[#7]\nG0X#9Z5.\nM30\n"
    change = replace(3, 2, 5, "=")  # #9BCD#5*0.[#7] -> #9=#5*0.[#7]
    edited = text.replace("BCD", "=")
    await edited_as_fresh(client, "assign", text, change, edited, lambda d: "MB904" not in codes(d))


async def test_lines_added_after_a_call_run_when_the_call_returns(client: LanguageClient) -> None:
    # The earlier run returned from O2000 to "G00 X100.", and met the new run inside O2000:
    # resuming there skipped the block added after the M98 (MB702 for it, no alarm).
    await start(client, None)
    body = "".join(f"G01 X{10 + i}. Z-{i}.5 F0.1\n" for i in range(60))
    text = "O1000\nM98 P2000\nG00 X100.\nM30\nO2000\n#1=0\nWHILE[#1LT20]DO1\n"
    text += body + "#1=#1+1\nEND1\nM99\n"
    change = replace(2, 0, 0, "#3000=1(STOP)\n")
    edited = text.replace("M98 P2000\n", "M98 P2000\n#3000=1(STOP)\n")
    found = await edited_as_fresh(
        client, "call-return", text, change, edited, lambda d: "MB503" in codes(d)
    )
    assert "MB702" not in codes(found)


async def test_never_executed_is_unnecessary(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:dead.nc"
    open_text(client, uri, "O1000\n#1=1\nGOTO 10\n#2=2\nN10 M30\n")
    found = await diagnostics(client, uri, lambda d: "MB702" in codes(d))
    dead = next(d for d in found if d.code == "MB702")
    assert dead.range.start.line == 3
    assert list(dead.tags or []) == [types.DiagnosticTag.Unnecessary]


async def test_settings_from_did_change_configuration(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o2_arc_thread_roughing.nc")
    await diagnostics(client, uri, lambda d: "MB601" in codes(d))
    client.workspace_did_change_configuration(
        types.DidChangeConfigurationParams(
            settings={"fanuc-macro": {"rules": {"disabled": ["MB601"]}}}
        )
    )
    await diagnostics(client, uri, lambda d: "MB601" not in codes(d))


async def test_endless_loop_is_reported_in_time(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:endless.nc"
    started = time.monotonic()
    open_text(client, uri, "O1000\n#1=0\nWHILE[1EQ1]DO1\n#1=#1+1\nEND1\nM30\n")
    await diagnostics(client, uri, lambda d: "MB703" in codes(d))
    elapsed = time.monotonic() - started
    print(f"endless loop: diagnostics after {elapsed:.2f} s")
    assert elapsed < 10.0  # the step budget of 300,000 blocks: well under a second here


# ---- hover -----------------------------------------------------------------------------------


async def test_hover_on_an_assignment_shows_value_and_formula(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    text = await hover(client, uri, 21, 1)  # #4=[7./8.]*SIN[60]*#101-#3+#103/2.+#104/4.
    assert "#4" in text
    # O3331 is called by M98 only: its locals hold no G65 arguments.
    assert "argument" not in text
    # At the control's increment, 0.001 mm, in the value and the formula.
    assert "**#4** = **1.907**" in text and "1.906804" not in text
    assert "= [0.875]*SIN[60]*3.-0.433+0.048/2.+0.17/4.\n```" in text
    assert "h, thread height, radius — *计算外螺纹牙高*" in text
    # The paper as a short link to its citation, never the project's file number; its
    # formula and the variable's kind after the rule.
    lead, more = text.split("\n\n---\n\n")
    assert "Deng" not in lead and "[Deng Ronggang, table 3](" in more
    assert "docs/papers.md#deng-ronggang)" in more
    assert "7H/8 − r + es/2 + Td2/4" in more and "Local variable" in more
    assert "seed paper" not in text and "宏指令" not in text
    # Every digit the control keeps, on request.
    client.workspace_did_change_configuration(
        types.DidChangeConfigurationParams(
            settings={"fanuc-macro": {"hover": {"fullPrecision": True}}}
        )
    )
    for _ in range(200):
        text = await hover(client, uri, 21, 1)
        if "1.906804" in text:
            break
        await asyncio.sleep(0.05)
    assert "**#4** = **1.906804**" in text
    assert "[0.875]*SIN[60]*3.-0.4330127+0.048/2.+0.17/4.\n```" in text


async def test_hover_on_a_read_shows_the_values_over_the_passes(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    text = await hover(client, uri, 31, 14)  # #9 in G92 X[#100-2.*#9] ...
    assert "#9" in text
    assert "0.092 → 1.885 (88 times, min 0.092, max 1.885)" in text
    assert "计算总切削深度" in text  # the comment of its assignment
    assert "Σap(n), total depth after pass n" in text  # the module's parameter table
    main = await hover(client, uri, 6, 2)  # #101=3. in O4009, which calls O3331
    assert "P, pitch" in main and "table 2" in main


async def test_hover_on_codes_labels_and_calls(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    assert "Threading cycle" in await hover(client, uri, 31, 1)  # G92 on a lathe
    assert "Subprogram call" in await hover(client, uri, 10, 1)  # M98
    program = await hover(client, uri, 10, 6)  # P0013331
    assert "O3331" in program and "外螺纹子程序" in program
    label = await hover(client, uri, 30, 1)  # N10
    assert "GOTO10" in label and "taken 87 of 88" in label
    goto = await hover(client, uri, 40, 18)  # GOTO10
    assert "line 31" in goto
    assert "Square root" in await hover(client, uri, 22, 15)  # SQRT


VARIANTS = ROOT / "tests" / "fixtures" / "thread_variants"


async def test_threading_verdicts_and_the_thread_in_the_hover(client: LanguageClient) -> None:
    await start(client, VARIANTS)
    path = VARIANTS / "o3331_height_typo.nc"
    uri = path.as_uri()
    open_text(client, uri, path.read_text("utf-8"))
    found = await diagnostics(client, uri, lambda d: {"MB808", "MB801"} <= codes(d))
    height = next(d for d in found if d.code == "MB808")
    assert height.range.start.line == 21  # #4=... with the typo, the line to fix
    assert "#103 is taken ×2 where the formula has es/2" in height.message
    assert height.related_information  # where the thread is known from
    text = await hover(client, uri, 31, 1)  # G92 X[#100-2.*#9] ... in O3331
    assert "Threading cycle" in text
    assert "**Thread M50x3**, external" in text and "known from the cuts" in text
    assert "root X46.101" in text and "class 5g" in text
    renumbered = ROOT / "tests" / "fixtures" / "rules" / "MB808_thread-height.nc"
    open_text(client, renumbered.as_uri(), renumbered.read_text("utf-8"))
    await diagnostics(client, renumbered.as_uri(), lambda d: "MB808" in codes(d))
    radius = await hover(client, renumbered.as_uri(), 12, 1)  # #3 of O3001: no comment
    assert "r, tool nose radius" in radius and "O3001, recognised by its formulas" in radius
    plain = VARIANTS / "g92_clean.nc"
    open_text(client, plain.as_uri(), plain.read_text("utf-8").replace("(M24X3-6G)", ""))
    await diagnostics(client, plain.as_uri())
    unknown = await hover(client, plain.as_uri(), 5, 1)
    # The example names a thread and its side: in the case of ISO 965-1.
    assert "not identified" in unknown and "(M50x3-5g6g)" in unknown


async def test_hover_counts_utf16_columns(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:astral.nc"
    # The emoji is two UTF-16 units but one character: "#1" starts at unit 5, not 4.
    open_text(client, uri, "O1000\n(\U0001f600) #1=2.5\nGOTO 99 (\U0001f600)\nM30\n")
    found = await diagnostics(client, uri, lambda d: "MB101" in codes(d))
    assert "#1" in await hover(client, uri, 1, 5)
    result = await client.text_document_hover_async(
        types.HoverParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=types.Position(line=1, character=6),
        )
    )
    assert result is not None and result.range is not None
    assert (result.range.start.character, result.range.end.character) == (5, 7)
    assert found


async def test_utf8_position_encoding(client: LanguageClient) -> None:
    capabilities = types.ClientCapabilities(
        general=types.GeneralClientCapabilities(
            position_encodings=[types.PositionEncodingKind.Utf8, types.PositionEncodingKind.Utf16]
        )
    )
    result = await client.initialize_session(
        types.InitializeParams(capabilities=capabilities, initialization_options={})
    )
    assert result.capabilities.position_encoding == types.PositionEncodingKind.Utf8
    uri = "untitled:utf8.nc"
    open_text(client, uri, "O1000\n(螺纹) #1=2.5\nM30\n")
    # "(螺纹) " is 4 characters but 1 + 3 + 3 + 1 + 1 = 9 bytes: "#1" starts at byte 9.
    text = await hover(client, uri, 1, 9)
    assert text.startswith("**#1**")


# ---- navigation ------------------------------------------------------------------------------


async def definition(client: LanguageClient, uri: str, line: int, character: int) -> list[Any]:
    result = await asyncio.wait_for(
        client.text_document_definition_async(
            types.DefinitionParams(
                text_document=types.TextDocumentIdentifier(uri=uri),
                position=types.Position(line=line, character=character),
            )
        ),
        WAIT,
    )
    if result is None:
        return []
    return list(result) if isinstance(result, list) else [result]


async def test_definition_of_goto_and_call(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    [label] = await definition(client, uri, 40, 18)  # GOTO10
    assert label.uri == uri and label.range.start.line == 30  # N10 G01 W[-#10]
    [program] = await definition(client, uri, 10, 6)  # M98 P0013331
    assert program.uri == uri and program.range.start.line == 17  # O3331
    writes = await definition(client, uri, 31, 14)  # #9: its assignments
    assert {loc.range.start.line for loc in writes} == {26, 37, 38}


async def test_definition_across_files(client: LanguageClient, tmp_path: Path) -> None:
    (tmp_path / "main.nc").write_text("O1000\nM98 P1234\nM30\n", "utf-8")
    (tmp_path / "sub.nc").write_text("%\nO1234 (SUB)\n#1=1\nM99\n%\n", "utf-8")
    await start(client, tmp_path)
    uri = (tmp_path / "main.nc").as_uri()
    open_text(client, uri, (tmp_path / "main.nc").read_text("utf-8"))
    [target] = await definition(client, uri, 1, 5)
    assert target.uri == (tmp_path / "sub.nc").as_uri()
    assert target.range.start.line == 1


async def test_a_file_without_o_line_is_known_by_its_name(
    client: LanguageClient, tmp_path: Path
) -> None:
    (tmp_path / "main.nc").write_text("O1000\nM98 P8501\nG65 P8502 A1.\nM30\n", "utf-8")
    (tmp_path / "O8501.NC").write_text("%\n(ROUGHING)\nG00 X100.\nM99\n%\n", "utf-8")
    await start(client, tmp_path)
    uri = (tmp_path / "main.nc").as_uri()
    open_text(client, uri, (tmp_path / "main.nc").read_text("utf-8"))
    found = await diagnostics(client, uri, lambda d: "MB410" in codes(d))
    # O8501 is the file O8501.NC; nothing is named O8502 (a resident program's number: MB410).
    assert [d.message.split(",")[0] for d in found if d.code == "MB410"] == ["G65 calls O8502"]
    [target] = await definition(client, uri, 1, 5)
    assert target.uri == (tmp_path / "O8501.NC").as_uri() and target.range.start.line == 2
    assert "no O line: the number is the file name's" in await hover(client, uri, 1, 5)
    # Opened, the file says where its number comes from, as a hint.
    sub = (tmp_path / "O8501.NC").as_uri()
    open_text(client, sub, (tmp_path / "O8501.NC").read_text("utf-8"))
    notes = await diagnostics(client, sub, lambda d: "MB010" in codes(d))
    [hint] = [d for d in notes if d.code == "MB010"]
    assert hint.severity == types.DiagnosticSeverity.Hint
    assert hint.message.startswith("program number 8501 taken from the file name 'O8501.NC'")
    # A file saved under that number, created later, answers the other call.
    later = tmp_path / "O8502 FINISH.nc"
    later.write_text("G00 X#1\nM99\n", "utf-8")
    client.workspace_did_change_watched_files(
        types.DidChangeWatchedFilesParams(
            changes=[types.FileEvent(uri=later.as_uri(), type=types.FileChangeType.Created)]
        )
    )
    await diagnostics(client, uri, lambda d: "MB410" not in codes(d))


async def test_references_of_a_local(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    result = await client.text_document_references_async(
        types.ReferenceParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=types.Position(line=31, character=14),
            context=types.ReferenceContext(include_declaration=True),
        )
    )
    assert result is not None
    lines = sorted(loc.range.start.line for loc in result)
    assert lines == [26, 27, 31, 33, 37, 38, 38, 39, 40]


async def test_document_symbols(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    result = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(text_document=types.TextDocumentIdentifier(uri=uri))
    )
    assert result is not None
    symbols = {s.name: s for s in result if isinstance(s, types.DocumentSymbol)}
    assert set(symbols) == {"O4009", "O3331"}
    assert symbols["O3331"].kind == types.SymbolKind.Function
    children = [c.name for c in symbols["O3331"].children or []]
    assert children == ["N10", "N20"]
    loop_uri = "untitled:loops.nc"
    open_text(
        client, loop_uri, "O1\n#1=0\nWHILE[#1LT3]DO1\nN5 #1=#1+1\nIF[#1EQ2]GOTO5\nEND1\nM30\n"
    )
    loops = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(text_document=types.TextDocumentIdentifier(uri=loop_uri))
    )
    assert loops is not None
    [program] = loops
    assert isinstance(program, types.DocumentSymbol)
    [loop] = program.children or []
    assert loop.name == "WHILE[#1LT3]DO1"
    assert (loop.range.start.line, loop.range.end.line) == (2, 5)
    assert [c.name for c in loop.children or []] == ["N5"]


async def test_inlay_hints(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    result = await client.text_document_inlay_hint_async(
        types.InlayHintParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            range=types.Range(
                start=types.Position(line=0, character=0),
                end=types.Position(line=48, character=0),
            ),
        )
    )
    assert result is not None
    labels = {h.position.line: h.label for h in result}
    assert labels[21] == "= 1.907"
    assert labels[35] == "= 2. → 89. ×88"
    assert 0 not in labels and 1 not in labels
    # #100=50., #7=1., #12=8.0: the line shows the value; every other hint keeps a gap.
    assert not {5, 24, 28} & set(labels)
    assert all(h.padding_left for h in result)


async def test_completion(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:complete.nc"
    open_text(client, uri, "O1\n#1=SQ\nG9\n#30\n")
    await diagnostics(client, uri)

    async def complete(line: int, character: int) -> list[types.CompletionItem]:
        result = await client.text_document_completion_async(
            types.CompletionParams(
                text_document=types.TextDocumentIdentifier(uri=uri),
                position=types.Position(line=line, character=character),
            )
        )
        assert isinstance(result, types.CompletionList)
        return list(result.items)

    items = {i.label: i for i in await complete(1, 5)}
    sqrt = items["SQRT"]
    assert sqrt.insert_text_format == types.InsertTextFormat.Snippet
    assert isinstance(sqrt.text_edit, types.TextEdit)
    assert sqrt.text_edit.new_text == "SQRT[$1]"
    assert sqrt.text_edit.range.start.character == 3  # replaces "SQ"
    assert "WHILE" in items and "while" in items  # keyword and snippet
    g_codes = {i.label: i.detail for i in await complete(2, 2)}
    assert g_codes["G92"] == "Threading cycle"
    variables = {i.label: i.detail for i in await complete(3, 3)}
    assert "#3000" in variables and "#5221" in variables


async def test_completion_offers_the_thread_module_of_the_document(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:main-only.nc"
    main = (
        "O4009 (M50X3-5G6G)\r\nT0101\r\nG00 X55. Z0.\r\nG97 S400 M03\r\n#100=50.\r\n"
        "#101=3.\r\n#102=50.\r\n#103=0.048\r\n#104=0.170\r\nthr\r\nM30\r\n%\r\n"
    )
    open_text(client, uri, main)
    await diagnostics(client, uri)
    result = await client.text_document_completion_async(
        types.CompletionParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=types.Position(line=9, character=3),
        )
    )
    assert isinstance(result, types.CompletionList)
    module = next(i for i in result.items if (i.label or "").startswith("thread module"))
    assert module.filter_text == "thread"
    assert isinstance(module.text_edit, types.TextEdit)
    assert module.text_edit.range.start.character == 0  # replaces "thr"
    assert module.text_edit.new_text.startswith("M98 P0013331 (CALL O3331: 186 G92 CUTS")
    (sub,) = module.additional_text_edits or []
    assert sub.range.start == types.Position(line=11, character=0)  # before the closing %
    assert sub.new_text.startswith("O3331 (EXTERNAL THREAD SUB")
    assert "H=1.907" in sub.new_text and "88 ROUGH PASSES" in sub.new_text
    assert "\r\n" in sub.new_text and "\n" not in sub.new_text.replace("\r\n", "")
    assert "#100=" not in sub.new_text


async def test_completion_offers_both_kinds_when_the_document_does_not_tell(
    client: LanguageClient,
) -> None:
    await start(client, None)
    uri = "untitled:capitals.nc"
    # All capitals, a class both kinds have, no es/EI, no word or program number that tells.
    open_text(client, uri, "O0001 (M10X1.5-6G)\n#100=10.\n#102=20.\nthr\nM30\n")
    await diagnostics(client, uri)
    result = await client.text_document_completion_async(
        types.CompletionParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=types.Position(line=3, character=3),
        )
    )
    assert isinstance(result, types.CompletionList)
    labels = sorted(i.label for i in result.items if i.label.startswith("thread module"))
    assert [label.split(",")[0] for label in labels] == [
        "thread module M10x1.5-6G internal",
        "thread module M10x1.5-6g external",
    ]


async def test_snippets_are_left_to_an_extension_that_contributes_them(
    client: LanguageClient,
) -> None:
    await start(client, None, {"contributesSnippets": True})
    uri = "untitled:snippets.nc"
    open_text(client, uri, "O1\nwh\nM30\n")
    await diagnostics(client, uri)
    result = await client.text_document_completion_async(
        types.CompletionParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=types.Position(line=1, character=2),
        )
    )
    assert isinstance(result, types.CompletionList)
    kinds = {i.label: i.kind for i in result.items}
    assert kinds["WHILE"] == types.CompletionItemKind.Keyword
    assert types.CompletionItemKind.Snippet not in kinds.values()


# ---- code actions ----------------------------------------------------------------------------


async def code_actions(
    client: LanguageClient, uri: str, found: Sequence[types.Diagnostic]
) -> list[types.CodeAction]:
    result = await client.text_document_code_action_async(
        types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            range=found[0].range,
            context=types.CodeActionContext(diagnostics=list(found)),
        )
    )
    return [a for a in result or [] if isinstance(a, types.CodeAction)]


def apply(client: LanguageClient, uri: str, action: types.CodeAction, version: int) -> None:
    assert action.edit is not None and action.edit.changes is not None
    edits = action.edit.changes[uri]
    changes = [
        types.TextDocumentContentChangePartial(range=e.range, text=e.new_text) for e in edits
    ]
    edit(client, uri, version, changes)


async def test_code_action_inserts_the_missing_end(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:noend.nc"
    open_text(client, uri, "O1000\n#1=0\nWHILE[#1LT3]DO1\n#1=#1+1\nM30\n")
    found = await diagnostics(client, uri, lambda d: "MB201" in codes(d))
    mb201 = [d for d in found if d.code == "MB201"]
    actions = await code_actions(client, uri, mb201)
    fix = next(a for a in actions if a.title.startswith("Insert END1"))
    assert fix.edit is not None and fix.edit.changes is not None
    [text_edit] = fix.edit.changes[uri]
    assert text_edit.new_text == "END1\n" and text_edit.range.start.line == 4
    apply(client, uri, fix, 2)
    await diagnostics(client, uri, lambda d: "MB201" not in codes(d))


async def test_code_action_brackets_a_logic_operand(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:probe.nc"
    # A character outside the BMP before the condition: the edit's columns are UTF-16 units.
    text = "O9060\n(\U0001f600) IF [#1 AND #2 LT 0] GOTO 90\nM99\nN90 #3000=1(OUT OF TOLERANCE)\n"
    open_text(client, uri, text)
    found = await diagnostics(client, uri, lambda d: "MB305" in codes(d))
    mb305 = [d for d in found if d.code == "MB305"]
    assert mb305[0].range.start == types.Position(line=1, character=9)  # 8 characters
    actions = await code_actions(client, uri, mb305)
    fixes = [a for a in actions if a.title.startswith("Bracket the condition")]
    assert [a.is_preferred for a in fixes] == [True, None]
    edits = []
    for fix in fixes:
        assert fix.edit is not None and fix.edit.changes is not None
        [text_edit] = fix.edit.changes[uri]
        assert text_edit.range == mb305[0].range
        edits.append(text_edit.new_text)
    assert edits == ["[#1 LT 0] AND [#2 LT 0]", "[#1 AND #2] LT 0"]
    apply(client, uri, fixes[0], 2)
    await diagnostics(client, uri, lambda d: "MB305" not in codes(d))


RULE_FIXTURES = ROOT / "tests" / "fixtures" / "rules"

# A rule's quick fix in its fixture: the fixture, the code, the diagnostic's line, the edit
# (range on that line and its new text), and whether the client is told it is the one to take.
RULE_FIXES = [
    ("MB003_nested-comment.nc", "MB003", 3, (0, 25, "(TOOL T0101 BORING BAR)"), True),
    ("MB004_unclosed-comment.nc", "MB004", 2, (45, 45, ")"), True),
    ("MB101_goto-missing-label.nc", "MB101", 8, (14, 15, "2"), None),
    ("MB404_argument-without-decimal-point.nc", "MB404", 2, (13, 13, "."), True),
    ("MB601_address-not-integer_suggested.nc", "MB601", 6, (1, 3, "#13"), True),
]


@pytest.mark.parametrize(("name", "code", "line", "change", "preferred"), RULE_FIXES)
async def test_code_action_applies_the_rule_fix(
    client: LanguageClient,
    name: str,
    code: str,
    line: int,
    change: tuple[int, int, str],
    preferred: bool | None,
) -> None:
    await start(client, None)
    uri = f"untitled:{name}"
    text = (RULE_FIXTURES / name).read_text("utf-8")
    open_text(client, uri, text)
    found = await diagnostics(client, uri, lambda d: code in codes(d))
    target = [d for d in found if d.code == code and d.range.start.line == line]
    assert len(target) == 1
    actions = await code_actions(client, uri, target)
    fix, suppress = actions
    assert suppress.title == f"Suppress {code} on this line"
    assert fix.kind == types.CodeActionKind.QuickFix and fix.is_preferred is preferred
    assert list(fix.diagnostics or ()) == target  # the client's own diagnostic, linked
    assert fix.edit is not None and fix.edit.changes is not None
    [text_edit] = fix.edit.changes[uri]
    start_column, end_column, new_text = change
    assert text_edit.range == types.Range(
        start=types.Position(line=line, character=start_column),
        end=types.Position(line=line, character=end_column),
    )
    assert text_edit.new_text == new_text
    apply(client, uri, fix, 2)
    await diagnostics(
        client, uri, lambda d: not any(x.code == code and x.range.start.line == line for x in d)
    )


async def test_suppression_comment_removes_the_diagnostic(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o2_arc_thread_roughing.nc")
    found = await diagnostics(client, uri, lambda d: "MB601" in codes(d))
    target = [d for d in found if d.code == "MB601" and d.range.start.line == 29]
    actions = await code_actions(client, uri, target)
    suppress = next(a for a in actions if a.title == "Suppress MB601 on this line")
    apply(client, uri, suppress, 2)
    left = await diagnostics(
        client, uri, lambda d: not any(x.code == "MB601" and x.range.start.line == 29 for x in d)
    )
    assert any(d.code == "MB601" and d.range.start.line == 63 for d in left)


# ---- commands --------------------------------------------------------------------------------


async def test_trace_command(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    result = await asyncio.wait_for(
        client.workspace_execute_command_async(
            types.ExecuteCommandParams(command="fanuc-macro.trace", arguments=[uri])
        ),
        WAIT,
    )
    assert isinstance(result, dict)
    g92 = [m for m in result["motions"] if m["code"] == "G92"]
    assert len(g92) == 186
    assert result["summary"]["by_code"]["G92"] == 186
    assert g92[0]["line"] == 32 and g92[0]["words"]["X"] == pytest.approx(49.816)


async def test_toolpath_command_gives_the_views_segments(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    result = await asyncio.wait_for(
        client.workspace_execute_command_async(
            types.ExecuteCommandParams(command="fanuc-macro.toolpath", arguments=[uri])
        ),
        WAIT,
    )
    assert isinstance(result, dict) and result["lathe"] is True and result["format"] == 3
    segments = unpacked(result)  # base64 of little-endian typed arrays
    thread = result["kinds"].index("thread")
    cuts = [i for i, k in enumerate(segments["kind"]) if k == thread]
    assert len(cuts) == 186  # one per G92 pass
    first = cuts[0]
    assert segments["line"][first] == 31  # 0-based: the G92 of trace line 32
    # X as a radius (the drawing's geometry), Y unknown (NaN) on the lathe.
    x, y, z = segments["start"][first]
    assert (x, z) == pytest.approx((24.908, 5.964)) and math.isnan(y)
    assert segments["end"][first][2] == pytest.approx(-54.036)
    # The pass's infeed ends where the thread starts: they share the point.
    assert segments["point"][first] == segments["point"][first - 1] + 1
    # The pass's block for its tooltip, and the thread's cut for the view's cross-section.
    assert segments["block_code"][segments["motion"][first]] == "G92"
    assert result["threads"][0]["name"].startswith("M50x3") and result["threads"][0]["profile"]
    none = await asyncio.wait_for(
        client.workspace_execute_command_async(
            types.ExecuteCommandParams(command="fanuc-macro.toolpath", arguments=[])
        ),
        WAIT,
    )
    assert "error" in none


async def test_toolpath_command_draws_the_bar_the_settings_give_and_a_mills_cutter(
    client: LanguageClient,
) -> None:
    await start(client, options={"view": {"stockDiameter": 56}})
    uri = open_seed(client, "o4009_external_m50x3.nc")
    lathe = await asyncio.wait_for(
        client.workspace_execute_command_async(
            types.ExecuteCommandParams(command="fanuc-macro.toolpath", arguments=[uri])
        ),
        WAIT,
    )
    assert isinstance(lathe, dict) and lathe["stock"]["diameter"] == 56.0
    assert "stockDiameter" in lathe["stock"]["source"]
    mill_uri = "untitled:mill.nc"
    open_text(
        client,
        mill_uri,
        "O1\n(T1 D=10. CR=0. - FLAT END MILL)\nG90 G17 G54\nG00 X0 Y0 Z5.\nG01 Z-1. F100\n"
        "X20. Y10.\nM30\n",
    )
    mill = await asyncio.wait_for(
        client.workspace_execute_command_async(
            types.ExecuteCommandParams(command="fanuc-macro.toolpath", arguments=[mill_uri])
        ),
        WAIT,
    )
    assert isinstance(mill, dict) and mill["lathe"] is False and mill["stock"] is None
    assert mill["tool"]["radius"] == 5.0 and mill["tool"]["line"] == 1


async def test_thread_module_command(client: LanguageClient) -> None:
    await start(client, None)

    async def run(spec: dict[str, Any]) -> dict[str, Any]:
        result = await asyncio.wait_for(
            client.workspace_execute_command_async(
                types.ExecuteCommandParams(command="fanuc-macro.threadModule", arguments=[spec])
            ),
            WAIT,
        )
        assert isinstance(result, dict)
        return result

    good = await run({"designation": "M50x3-5g6g", "length": 40.0, "internal": None})
    if importlib.util.find_spec("fanuc_macro.generators.thread_generator") is None:
        assert "no thread module generator" in good["error"]
    else:
        assert isinstance(good.get("text"), str) and good["text"]
    bad = await run({"designation": "M50x3-5g6g", "length": -1, "internal": False})
    assert "length" in bad["error"]
    if importlib.util.find_spec("fanuc_macro.generators.thread_generator") is not None:
        assert good["text"].startswith("%\nO4009")
        wrong = await run({"designation": "M50x3-9z", "length": 40.0, "internal": None})
        assert "tolerance position z is not" in wrong["error"]  # the generator's ValueError
        # All capitals with a class both kinds have: refused, never guessed; "internal" says.
        capitals = {"designation": "M50X3-5G6G", "length": 40.0}
        undecided = await run({**capitals, "internal": None})
        assert undecided == {
            "error": "M50X3-5G6G: the class 5G6G fits an external (5g6g) or an internal (5G6G) "
            'thread: say which with "internal": false (external) or true (internal), or write '
            "the class in the standard's case: M50x3-5g6g external, M50x3-5G6G internal"
        }
        external = await run({**capitals, "internal": False})
        assert external["text"].startswith("%\nO4009 (MAIN - EXTERNAL THREAD M50x3-5g6g L=40)")
        internal = await run({**capitals, "internal": True})
        assert internal["text"].startswith("%\nO4010 (MAIN - INTERNAL THREAD M50x3-5G6G L=40)")
        paper = await run({"designation": "M50X3-4H5H", "length": 40.0, "internal": None})
        assert paper["text"].startswith("%\nO4010 (MAIN - INTERNAL THREAD M50x3-4H5H L=40)")
        conflict = await run({"designation": "M50x3-5g6g", "length": 40.0, "internal": True})
        assert conflict == {
            "error": "M50x3-5g6g is an external thread (its class 5g6g is in lower case), but "
            '"internal": true was sent'
        }
        for refused in (wrong, undecided, conflict):
            assert not re.search(r"internal=|\bNone\b|\bTrue\b|'[^'\s]+'", refused["error"])
        # The module's options: flank infeed, taper; multi-start and hand from the designation.
        from fanuc_macro.generators.thread_generator import generate_module

        spec = {"designation": "M24xPh4P2-6g-LH", "length": 30.0, "internal": None}
        options = await run({**spec, "infeed": "left", "taper": 0.0625})
        assert options["text"] == generate_module(
            "M24xPh4P2-6g-LH", 30.0, None, infeed="left", taper=0.0625
        )
        assert "LEFT FLANK INFEED, LEFT HAND" in options["text"]
        unknown = await run({**spec, "infeed": "both"})
        assert "infeed both is not one of" in unknown["error"]
        steep = await run({**spec, "taper": "1:16"})
        assert "taper must be a number" in steep["error"]


# ---- robustness ------------------------------------------------------------------------------


async def test_survives_random_bytes_and_a_huge_document(client: LanguageClient) -> None:
    await start(client, None)
    rng = random.Random(20240601)
    noise = bytes(rng.getrandbits(8) for _ in range(100_000)).decode("latin-1")
    open_text(client, "untitled:noise.nc", noise)
    await hover(client, "untitled:noise.nc", 3, 2)  # answers, whatever it says
    # An edit right after a form feed or U+0085: lines as LSP counts them.
    edit(client, "untitled:noise.nc", 2, [replace(5, 0, 3, "#1=2\n")])
    lines = [
        f"N{i % 9000 + 1} G01 X{i % 97}.{i % 7} Z-{i % 53}. (pass {i % 1000})"
        for i in range(100_000)
    ]
    open_text(client, "untitled:huge.nc", "O1000\n" + "\n".join(lines) + "\nM30\n")
    text = await hover(client, "untitled:huge.nc", 5, 9)
    assert "X" in text
    uri = open_seed(client, "o4009_external_m50x3.nc")
    assert "**#4** = **1.907**" in await hover(client, uri, 21, 1)


EDIT_TEXTS = ("", "#1=", "[", "]", "\n", "\r\n", "GOTO10\n", "WHILE[#1LT3]DO1\n", "END1",
              "SIN[" * 30, "X11" * 40, "(", ")", ";", "%", "\u0085", "\u2028", "ア", "\t",
              "N10")  # fmt: skip
FEATURES = (
    types.TEXT_DOCUMENT_HOVER,
    types.TEXT_DOCUMENT_COMPLETION,
    types.TEXT_DOCUMENT_DEFINITION,
    types.TEXT_DOCUMENT_REFERENCES,
    types.TEXT_DOCUMENT_DOCUMENT_SYMBOL,
    types.TEXT_DOCUMENT_INLAY_HINT,
    types.TEXT_DOCUMENT_CODE_ACTION,
)


def feature_params(method: str, uri: str, line: int, character: int) -> dict[str, Any]:
    doc = {"uri": uri}
    position = {"line": line, "character": character}
    whole = {"start": {"line": 0, "character": 0}, "end": {"line": line, "character": character}}
    if method == types.TEXT_DOCUMENT_DOCUMENT_SYMBOL:
        return {"textDocument": doc}
    if method == types.TEXT_DOCUMENT_INLAY_HINT:
        return {"textDocument": doc, "range": whole}
    if method == types.TEXT_DOCUMENT_CODE_ACTION:
        return {"textDocument": doc, "range": whole, "context": {"diagnostics": []}}
    if method == types.TEXT_DOCUMENT_REFERENCES:
        return {"textDocument": doc, "position": position, "context": {"includeDeclaration": True}}
    return {"textDocument": doc, "position": position}


async def test_random_edits_and_requests_are_all_answered(client: LanguageClient) -> None:
    """Edits anywhere (past the end too) and every feature at any position: each request gets
    its answer, an invalid one the InvalidParams error, and nothing fails inside."""
    await start(client, None)
    rng = random.Random(20261201)
    uri = "untitled:random.nc"
    open_text(client, uri, (SEEDS / "o4009_external_m50x3.nc").read_text("utf-8"))
    version = 1
    answered = invalid = 0
    for _ in range(300):
        line, character = rng.randint(0, 80), rng.choice((0, 1, 5, 30, 200, 2**31 - 1))
        if rng.random() < 0.5:
            version += 1
            end = types.Position(line=line + rng.randint(0, 2), character=rng.randint(0, 40))
            begin = types.Position(line=line, character=min(character, 60))
            change = types.TextDocumentContentChangePartial(
                range=types.Range(start=begin, end=end), text=rng.choice(EDIT_TEXTS)
            )
            edit(client, uri, version, [change])
            continue
        method = rng.choice(FEATURES)
        if rng.random() < 0.2 and method != types.TEXT_DOCUMENT_DOCUMENT_SYMBOL:
            # A position that does not validate (document symbols have none).
            bad = rng.choice(((-1, 0), (0, -5), (2**31 + 2, 0), (0, 2**40)))
            with pytest.raises(JsonRpcException) as raised:
                await raw_request(client, method, feature_params(method, uri, *bad))
            assert raised.value.code == JsonRpcInvalidParams.CODE, method
            invalid += 1
        else:
            await raw_request(client, method, feature_params(method, uri, line, character))
            answered += 1
    assert answered > 80 and invalid > 15
    assert not [m for m in client.log_messages if m.type == types.MessageType.Error]
    found = await diagnostics(client, uri, lambda d: True)
    assert "MB000" not in codes(found)


async def test_a_10_mb_document_and_a_1_mb_line_get_their_verdicts(
    client: LanguageClient,
) -> None:
    await start(client, None)
    seed = open_seed(client, "o4009_external_m50x3.nc")
    assert "**#4** = **1.907**" in await hover(client, seed, 21, 1)
    started = time.monotonic()
    rows = [f"G01 X{i % 97}.5 Z-{i % 89}. F0.2" for i in range(500_000)]
    open_text(client, "untitled:ten.nc", "O1000\n" + "\n".join(rows) + "\nGOTO 9\nM30\n")
    open_text(client, "untitled:line.nc", "O1000\n" + "X1.5Y2.5" * 131_072 + "\nM30\n")
    # An analysed document answers while the big ones are read (no regex holds the GIL).
    assert "**#4** = **1.907**" in await hover(client, seed, 21, 1)
    # Read whole: the GOTO to no N9 in its last lines is reported, and nothing else.
    found = await diagnostics(client, "untitled:ten.nc", lambda d: "MB101" in codes(d), 120.0)
    assert codes(found) == {"MB101"} and found[0].range.start.line == 500_001
    found = await diagnostics(client, "untitled:line.nc", lambda d: "MB011" in codes(d))
    # 10-20 s beside the other tests on a 2-core VM; it was no answer in 200 s.
    assert time.monotonic() - started < 90.0


# A client that shows progress (window/workDoneProgress); the server shows it from the first
# checkpoint of an analysis (every 1,024 blocks read), since the delay is 0 here.
WITH_PROGRESS = types.ClientCapabilities(
    general=CAPABILITIES.general,
    text_document=CAPABILITIES.text_document,
    workspace=CAPABILITIES.workspace,
    window=types.WindowClientCapabilities(work_done_progress=True),
)
BIG = {
    "analysis": {
        "debounceMs": 20,
        "progressDelayMs": 0,
        "maxBlocks": 1_000_000,
        "maxFileSize": 100_000_000,
    }
}


def _bench_programs() -> ModuleType:
    """bench/bench_lsp.py, whose generated programs the tests use too."""
    path = Path(__file__).resolve().parents[1] / "bench" / "bench_lsp.py"
    spec = importlib.util.spec_from_file_location("bench_lsp_programs", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


# CAM output: a macro header, then plain motion blocks, no two alike.
cam_program: Callable[[int], str] = _bench_programs().cam_program


def progress_of(client: LanguageClient) -> dict[Any, list[Any]]:
    return {token: list(values) for token, values in client.progress_reports.items()}


async def progress_until(
    client: LanguageClient, what: Callable[[dict[Any, list[Any]]], bool]
) -> dict[Any, list[Any]]:
    deadline = time.monotonic() + WAIT
    while not what(progress_of(client)):
        assert time.monotonic() < deadline, f"no such progress: {progress_of(client)}"
        await asyncio.sleep(0.01)
    return progress_of(client)


def ended(values: list[Any]) -> bool:
    return bool(values) and isinstance(values[-1], types.WorkDoneProgressEnd)


async def test_an_edit_cancels_the_running_analysis_and_the_newest_text_is_analysed(
    client: LanguageClient,
) -> None:
    await start(client, None, BIG, WITH_PROGRESS)
    uri = "untitled:cam.nc"
    text = cam_program(100_000)
    open_text(client, uri, text)
    # Its progress has begun: the analysis of version 1 is under way (seconds of work).
    await progress_until(client, lambda p: any(p.values()))
    end = text.split("\n").index("M30")
    edit(client, uri, 2, [replace(end, 0, 0, "GOTO 9999\n")])
    found = await diagnostics(client, uri, lambda d: "MB101" in codes(d))
    assert "MB000" not in codes(found)
    cancelled = [m.message for m in client.log_messages if "cancelled" in m.message]
    assert len(cancelled) == 1, cancelled
    assert f"the analysis of {uri} (version 1) was cancelled while" in cancelled[0]
    # It stopped at a block boundary well before its end: "after 2,048 of 100,008 blocks".
    done, total = (int(n.replace(",", "")) for n in cancelled[0].split("after ")[1].split()[:3:2])
    assert 0 < done < total
    # Both analyses' progress ended: the first cancelled, the second done.
    shown = await progress_until(client, lambda p: len(p) == 2 and all(map(ended, p.values())))
    first, second = shown.values()
    assert isinstance(first[0], types.WorkDoneProgressBegin)
    assert first[0].title == "fanuc-macro: analysing cam.nc"
    assert first[-1].message.startswith("cancelled")
    assert second[-1].message == "done"
    assert not [m for m in client.log_messages if m.type == types.MessageType.Error]


async def test_a_long_analysis_shows_its_progress_and_a_short_one_none(
    client: LanguageClient,
) -> None:
    await start(client, None, BIG, WITH_PROGRESS)
    open_text(client, "untitled:short.nc", "O1000\n#1=1\nG01 X#1 Z1. F0.2\nM30\n")
    await diagnostics(client, "untitled:short.nc")
    assert not client.progress_reports  # fewer blocks than one checkpoint: never shown
    open_text(client, "untitled:cam.nc", cam_program(20_000))
    await diagnostics(client, "untitled:cam.nc")
    shown = await progress_until(client, lambda p: len(p) == 1 and ended(next(iter(p.values()))))
    (values,) = shown.values()
    begin, *reports, end = values
    assert isinstance(begin, types.WorkDoneProgressBegin)
    assert begin.title == "fanuc-macro: analysing cam.nc" and begin.cancellable is False
    assert begin.message.startswith("reading blocks: ")
    assert all(isinstance(r, types.WorkDoneProgressReport) for r in reports)
    percentages = [begin.percentage, *(r.percentage for r in reports)]
    assert percentages == sorted(percentages) and all(0 <= p <= 100 for p in percentages)
    assert isinstance(end, types.WorkDoneProgressEnd) and end.message == "done"
    open_text(client, "untitled:short2.nc", "O1001\nG00 X1.\nM30\n")
    await diagnostics(client, "untitled:short2.nc")
    assert len(client.progress_reports) == 1


async def test_a_crash_is_logged_and_the_server_goes_on(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:crash.nc"
    open_text(client, uri, f"O1000 ({FAULT})\nM30\n")
    found = await diagnostics(client, uri, lambda d: "MB000" in codes(d))
    assert "could not analyse" in found[0].message
    deadline = time.monotonic() + WAIT
    while not any("failed" in m.message for m in client.log_messages):
        assert time.monotonic() < deadline, "no window/logMessage about the failure"
        await asyncio.sleep(0.05)
    assert any(m.type == types.MessageType.Error for m in client.log_messages)
    edit(client, uri, 2, [replace(0, 6, 6 + len(FAULT), "FIXED")])
    await diagnostics(client, uri, lambda d: "MB000" not in codes(d))
    other = open_seed(client, "o4009_external_m50x3.nc")
    assert "**#4** = **1.907**" in await hover(client, other, 21, 1)


async def raw_request(client: LanguageClient, method: str, params: dict[str, Any]) -> Any:
    """A request as a client may send it, whatever the protocol's types allow (the typed
    helpers validate their parameters before sending)."""
    protocol = client.protocol
    msg_id = f"raw-{uuid.uuid4()}"
    future: concurrent.futures.Future[Any] = concurrent.futures.Future()
    protocol._request_futures[msg_id] = future
    protocol._send_data({"jsonrpc": "2.0", "id": msg_id, "method": method, "params": params})
    return await asyncio.wait_for(asyncio.wrap_future(future), WAIT)


async def test_invalid_parameters_get_an_invalid_params_error(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:p.nc"
    open_text(client, uri, "O1000\n#1=1.\nM30\n")
    for position in ({"line": 0, "character": 2**31 + 2}, {"line": -1, "character": 0}):
        with pytest.raises(JsonRpcException) as raised:
            await raw_request(
                client,
                types.TEXT_DOCUMENT_HOVER,
                {"textDocument": {"uri": uri}, "position": position},
            )
        assert raised.value.code == JsonRpcInvalidParams.CODE
        assert "invalid parameters of textDocument/hover" in str(raised.value)
    # Valid but far past the end of the document: an answer, not an error.
    far = {"textDocument": {"uri": uri}, "position": {"line": 10**6, "character": 2**31 - 1}}
    assert await raw_request(client, types.TEXT_DOCUMENT_HOVER, far) is None
    assert "#1" in await hover(client, uri, 1, 1)  # the server is still there


async def test_a_failing_feature_answers_an_error_and_the_server_goes_on(
    client: LanguageClient,
) -> None:
    await start(client, None)
    uri = "untitled:f.nc"
    open_text(client, uri, f"O1000 ({FEATURE_FAULT})\n#1=1.\nM30\n")
    await diagnostics(client, uri)
    with pytest.raises(JsonRpcException) as raised:
        await hover(client, uri, 1, 1)
    assert raised.value.code == JsonRpcInternalError.CODE
    assert "hover failed" in str(raised.value) and "please report it" in str(raised.value)
    edit(client, uri, 2, [replace(0, 7, 7 + len(FEATURE_FAULT), "FIXED")])
    await diagnostics(client, uri, lambda d: True)
    deadline = time.monotonic() + WAIT
    while True:  # the edit reaches the server before a hover after it
        try:
            assert "#1" in await hover(client, uri, 1, 1)
            break
        except JsonRpcException:
            assert time.monotonic() < deadline
            await asyncio.sleep(0.05)


# ---- the workspace ---------------------------------------------------------------------------


async def test_other_files_changing_reanalyses_open_documents(
    client: LanguageClient, tmp_path: Path
) -> None:
    main = tmp_path / "main.nc"
    main.write_text("O1000\nM98 P1234\nM30\n", "utf-8")
    await start(client, tmp_path)
    main_uri = main.as_uri()
    open_text(client, main_uri, main.read_text("utf-8"))
    await diagnostics(client, main_uri, lambda d: "MB403" in codes(d))
    # A new file on disk (the editor's file watcher tells the server) defines O1234.
    sub = tmp_path / "sub.nc"
    sub.write_text("O1234\n#100=1.\nM99\n", "utf-8")
    client.workspace_did_change_watched_files(
        types.DidChangeWatchedFilesParams(
            changes=[types.FileEvent(uri=sub.as_uri(), type=types.FileChangeType.Created)]
        )
    )
    await diagnostics(client, main_uri, lambda d: "MB403" not in codes(d))
    # Opened and edited in the editor: renaming the program breaks the call again.
    open_text(client, sub.as_uri(), sub.read_text("utf-8"))
    edit(client, sub.as_uri(), 2, [replace(0, 1, 5, "4321")])
    await diagnostics(client, main_uri, lambda d: "MB403" in codes(d))


def test_columns_in_utf16_utf8_and_utf32() -> None:
    from fanuc_macro.lsp.convert import Codec
    from fanuc_macro.lsp.documents import OpenDocument

    line = "(\U0001f600螺纹) #1=2"
    hash_at = line.index("#")  # 6 characters
    assert Codec("utf-16").to_client(line, hash_at) == 7  # the emoji is a surrogate pair
    assert Codec("utf-8").to_client(line, hash_at) == 1 + 4 + 3 + 3 + 1 + 1
    assert Codec("utf-32").to_client(line, hash_at) == 6
    for name in ("utf-8", "utf-16", "utf-32"):
        codec = Codec(name)
        assert codec.from_client(line, codec.to_client(line, hash_at)) == hash_at
    assert Codec("utf-16").from_client(line, 2) == 1  # inside the pair: before the emoji
    doc = OpenDocument("u", "u", "A\x0cB\r\nC\u2028D\rE\n", 1)
    assert [doc.line(i) for i in range(5)] == ["A\x0cB", "C\u2028D", "E", "", ""]
    doc.apply(replace(1, 2, 3, "x"), Codec("utf-16"))
    assert doc.text == "A\x0cB\r\nC\u2028x\rE\n"


def test_knowledge_covers_lathe_and_mill_codes() -> None:
    from fanuc_macro.program import knowledge

    required = [
        *(f"G{n:02d}" for n in (0, 1, 2, 3, 4, 20, 21, 28, 32, 40, 41, 42, 50, 65, 66, 67)),
        *(f"G{n}" for n in range(54, 60)),
        *(f"G{n}" for n in range(70, 77)),
        *(f"G{n}" for n in (80, 81, 82, 83, 84, 85, 86, 87, 88, 89, 90, 91, 92, 94)),
        *(f"G{n}" for n in (96, 97, 98, 99)),
        "G66.1",
    ]
    for code in required:
        info = knowledge.code_info("G", float(code[1:]))
        assert info is not None, code
        assert info.lathe is not None or info.mill is not None, code
    for n in (*range(0, 10), 30, 98, 99):
        assert knowledge.code_info("M", float(n)) is not None, n
    lathe = knowledge.code_markdown("G", 92.0, lathe=True) or ""
    mill = knowledge.code_markdown("G", 92.0, lathe=False) or ""
    assert lathe.startswith("**G92** — Threading cycle") and "On a mill" not in lathe
    assert mill.startswith("**G92** — Workpiece coordinate system") and "On a lathe" not in mill
    # A document read both ways (neither machine shows): both meanings.
    both = knowledge.code_markdown("G", 92.0, lathe=True, machine_known=False) or ""
    assert both.startswith("**G92** — Threading cycle") and "On a mill" in both
    assert "drilling" in (knowledge.code_markdown("G", 81.0, lathe=False) or "").lower()
    assert knowledge.code_name("G", 66.1) == "G66.1" and knowledge.code_name("M", 3.0) == "M03"
    names = [
        "SIN",
        "COS",
        "TAN",
        "ASIN",
        "ACOS",
        "ATAN",
        "SQRT",
        "ABS",
        "ROUND",
        "FIX",
        "FUP",
        "LN",
        "EXP",
        "POW",
        "ADP",
        "BIN",
        "BCD",
    ]
    assert set(names) <= set(knowledge.FUNCTIONS)
    assert "degrees" in (knowledge.function_markdown("SIN") or "")
    assert "-2" in (knowledge.function_markdown("FUP") or "")
    assert "PS0119" in (knowledge.function_markdown("SQRT") or "")
    assert "ATAN[a]/[b]" in (knowledge.function_markdown("ATAN") or "")
    for word in ("IF", "GOTO", "THEN", "WHILE", "DO", "END", "EQ", "AND", "MOD"):
        assert knowledge.keyword_markdown(word), word


async def test_added_workspace_folder_is_scanned(client: LanguageClient, tmp_path: Path) -> None:
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "o1234.nc").write_text("O1234 (LIB)\n#100=1.\nM99\n", "utf-8")
    await start(client, None)
    uri = "untitled:caller.nc"
    open_text(client, uri, "O1000\nG65 P1234 A1.\nM30\n")
    await diagnostics(client, uri, lambda d: "MB403" in codes(d))
    folder = types.WorkspaceFolder(uri=(tmp_path / "lib").as_uri(), name="lib")
    client.workspace_did_change_workspace_folders(
        types.DidChangeWorkspaceFoldersParams(
            event=types.WorkspaceFoldersChangeEvent(added=[folder], removed=[])
        )
    )
    await diagnostics(client, uri, lambda d: "MB403" not in codes(d))
    assert "A1." in await hover(client, uri, 1, 11) or "#1" in await hover(client, uri, 1, 11)


def test_incremental_edits_keep_line_starts_right() -> None:
    """Random edits (CR, LF and CRLF among them) give the same lines as a fresh split."""
    import random

    from fanuc_macro.lsp.convert import Codec
    from fanuc_macro.lsp.documents import OpenDocument

    rnd = random.Random(7)
    codec = Codec("utf-16")
    pieces = ["G01 X1.", "#1=2", "\n", "\r\n", "\r", "(注释)", "", "N10", "\n\n"]
    doc = OpenDocument("u", "u", "O1\nG00 X0\r\nM30\n", 1)
    for _ in range(400):
        lines = doc.text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
        a_line = rnd.randrange(len(lines))
        b_line = rnd.randrange(a_line, len(lines))
        a_char = rnd.randint(0, len(lines[a_line]))
        b_char = (
            rnd.randint(0, len(lines[b_line]))
            if b_line > a_line
            else rnd.randint(a_char, len(lines[b_line]))
        )
        change = types.TextDocumentContentChangePartial(
            range=types.Range(
                start=types.Position(line=a_line, character=codec.to_client(lines[a_line], a_char)),
                end=types.Position(line=b_line, character=codec.to_client(lines[b_line], b_char)),
            ),
            text=rnd.choice(pieces),
        )
        doc.apply(change, codec)
        fresh = OpenDocument("u", "u", doc.text, 1)
        assert doc._line_starts() == fresh._line_starts()
        assert [doc.line(i) for i in range(len(lines) + 3)] == [
            fresh.line(i) for i in range(len(lines) + 3)
        ]


def test_converted_diagnostics_are_kept_while_their_lines_are() -> None:
    from fanuc_macro.diagnostics import Related, make
    from fanuc_macro.lsp.convert import Codec, ConvertedDiagnostics, Lines, to_lsp_diagnostic
    from fanuc_macro.rules.addresses import MB603
    from fanuc_macro.rules.math_domain import MB501

    lines = Lines(["G01 X1.", "#1=SQRT[-1] (根)", "M30"], Codec())
    diags = [
        make(MB501, "SQRT of -1", 1, 3, 11),
        make(MB603, "no F", 0, 0, 7, related=[Related(2, 0, 3, "here")], data={"a": 1}),
    ]
    cache = ConvertedDiagnostics()
    first = cache.convert(diags, "k", "file:///k.nc", lines)
    assert first == [to_lsp_diagnostic(d, "k", "file:///k.nc", lines) for d in diags]
    again = cache.convert(diags, "k", "file:///k.nc", lines)
    assert all(a is b for a, b in zip(first, again, strict=True))
    # A line of a range or of a related place changed: that diagnostic is converted again.
    edited = Lines(["G01 X1.", "#1=SQRT[-1] (根)", "M30 (END)"], Codec())
    third = cache.convert(diags, "k", "file:///k.nc", edited)
    assert third[0] is first[0] and third[1] is not first[1]
    # Other data, another client's units: converted again, as the protocol needs them.
    other = [diags[0], make(MB603, "no F", 0, 0, 7, related=diags[1].related, data={"a": 2})]
    assert cache.convert(other, "k", "file:///k.nc", edited)[1].data == {"code": "MB603", "a": 2}
    utf8 = Lines(edited.lines, Codec("utf-8"))
    converted = cache.convert(diags, "k", "file:///k.nc", utf8)
    assert converted == [to_lsp_diagnostic(d, "k", "file:///k.nc", utf8) for d in diags]
