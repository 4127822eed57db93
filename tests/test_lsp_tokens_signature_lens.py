"""Semantic tokens, signature help and code lenses over stdio, from a real server process."""

from __future__ import annotations

import asyncio
from collections.abc import Sequence
from typing import Any

import pytest
from lsprotocol import types
from pytest_lsp import LanguageClient

from fanuc_macro.lsp.presentation import token_edits
from test_lsp import CAPABILITIES, SEEDS, WAIT, client, diagnostics, edit, open_seed, open_text

__all__ = ["client"]  # the fixture, shared with test_lsp

# An emoji (two UTF-16 code units) before the tokens of line 1.
TEXT = (
    "O1000 (MAIN)\n"
    "(😀) #1=SIN[30] (😀)\n"
    "G65 P9010 A1. X#1\n"
    "M30\n"
    "O9010 (BORE A HOLE)\n"
    "#100=#24+#1 (START X)\n"
    "#3000=1 (STOP)\n"
    "M99\n"
)


async def initialize(client: LanguageClient) -> types.InitializeResult:
    result = await asyncio.wait_for(
        client.initialize_session(
            types.InitializeParams(
                capabilities=CAPABILITIES,
                root_uri=SEEDS.as_uri(),
                workspace_folders=[types.WorkspaceFolder(uri=SEEDS.as_uri(), name=SEEDS.name)],
                initialization_options={"analysis": {"debounceMs": 20}},
            )
        ),
        WAIT,
    )
    return result


def decode(data: list[int], legend: types.SemanticTokensLegend) -> list[tuple[Any, ...]]:
    """(line, start, length, type, modifiers) of each token, in UTF-16 units."""
    out: list[tuple[Any, ...]] = []
    line = start = 0
    for i in range(0, len(data), 5):
        delta_line, delta_start, length, kind, bits = data[i : i + 5]
        line += delta_line
        start = start + delta_start if delta_line == 0 else delta_start
        modifiers = {m for b, m in enumerate(legend.token_modifiers) if bits & (1 << b)}
        out.append((line, start, length, legend.token_types[kind], modifiers))
    return out


async def test_semantic_tokens_full_and_range_in_utf16(client: LanguageClient) -> None:
    result = await initialize(client)
    provider = result.capabilities.semantic_tokens_provider
    assert isinstance(
        provider, types.SemanticTokensOptions | types.SemanticTokensRegistrationOptions
    )
    legend = provider.legend
    assert "parameter" in legend.token_types and "readonly" in legend.token_modifiers
    assert provider.range and provider.full
    uri = "untitled:tokens.nc"
    open_text(client, uri, TEXT)
    await diagnostics(client, uri)
    full = await asyncio.wait_for(
        client.text_document_semantic_tokens_full_async(
            types.SemanticTokensParams(text_document=types.TextDocumentIdentifier(uri=uri))
        ),
        WAIT,
    )
    assert full is not None
    tokens = decode(list(full.data), legend)
    by_line = {n: [t[1:] for t in tokens if t[0] == n] for n in range(8)}
    assert by_line[0] == [(0, 5, "namespace", {"declaration"})]
    # "(😀) " is 5 UTF-16 units: #1 starts at 5, SIN at 8.
    assert by_line[1] == [
        (5, 2, "variable", {"modification"}),
        (8, 3, "function", {"defaultLibrary"}),
    ]
    assert (4, 5, "namespace", set()) in by_line[2]  # P9010
    # O9010 is called by G65: #24 and #1 are its arguments.
    assert by_line[5] == [
        (0, 4, "variable", {"common", "modification"}),
        (5, 3, "parameter", set()),
        (9, 2, "parameter", set()),
    ]
    assert by_line[6] == [(0, 5, "variable", {"system", "defaultLibrary", "modification"})]
    ranged = await asyncio.wait_for(
        client.text_document_semantic_tokens_range_async(
            types.SemanticTokensRangeParams(
                text_document=types.TextDocumentIdentifier(uri=uri),
                range=types.Range(
                    start=types.Position(line=5, character=0),
                    end=types.Position(line=6, character=0),
                ),
            )
        ),
        WAIT,
    )
    assert ranged is not None
    assert decode(list(ranged.data), legend) == [t for t in tokens if 5 <= t[0] <= 6]


def apply(data: list[int], edits: Sequence[types.SemanticTokensEdit]) -> list[int]:
    for e in sorted(edits, key=lambda e: e.start, reverse=True):
        data = data[: e.start] + list(e.data or []) + data[e.start + e.delete_count :]
    return data


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ([], [1, 2, 3, 4, 5]),
        ([1, 2, 3, 4, 5], []),
        ([0, 1, 2, 3, 0, 1, 0, 2, 2, 0], [0, 1, 2, 3, 0, 2, 0, 2, 2, 0]),
        ([1, 1, 1, 1, 1], [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]),  # repeats: prefix and suffix overlap
        ([5, 6, 7], [5, 6, 7]),
    ],
)
def test_token_edits_turn_the_old_data_into_the_new(old: list[int], new: list[int]) -> None:
    edits = token_edits(old, new)
    assert apply(old, edits) == new
    assert len(edits) == (0 if old == new else 1)


async def test_semantic_tokens_delta_after_an_edit(client: LanguageClient) -> None:
    result = await initialize(client)
    provider = result.capabilities.semantic_tokens_provider
    assert provider is not None
    assert provider.full == types.SemanticTokensFullDelta(delta=True)
    uri = "untitled:delta.nc"
    open_text(client, uri, TEXT)
    await diagnostics(client, uri)
    ident = types.TextDocumentIdentifier(uri=uri)
    full = await asyncio.wait_for(
        client.text_document_semantic_tokens_full_async(
            types.SemanticTokensParams(text_document=ident)
        ),
        WAIT,
    )
    assert full is not None and full.result_id
    # #1 of line 1 becomes #500: one token's length and modifiers change.
    edit(client, uri, 2, [types.TextDocumentContentChangePartial(
        range=types.Range(
            start=types.Position(line=1, character=5), end=types.Position(line=1, character=7)
        ),
        text="#500",
    )])  # fmt: skip
    delta = await asyncio.wait_for(
        client.text_document_semantic_tokens_full_delta_async(
            types.SemanticTokensDeltaParams(text_document=ident, previous_result_id=full.result_id)
        ),
        WAIT,
    )
    assert isinstance(delta, types.SemanticTokensDelta) and delta.result_id
    assert len(delta.edits) == 1 and len(delta.edits[0].data or []) < len(full.data)
    again = await asyncio.wait_for(
        client.text_document_semantic_tokens_full_async(
            types.SemanticTokensParams(text_document=ident)
        ),
        WAIT,
    )
    assert again is not None and again.data != full.data
    assert apply(list(full.data), delta.edits) == list(again.data)
    # An id the server no longer has: the full tokens.
    stale = await asyncio.wait_for(
        client.text_document_semantic_tokens_full_delta_async(
            types.SemanticTokensDeltaParams(text_document=ident, previous_result_id="no such id")
        ),
        WAIT,
    )
    assert isinstance(stale, types.SemanticTokens) and list(stale.data) == list(again.data)


async def signature(
    client: LanguageClient, uri: str, line: int, character: int
) -> types.SignatureHelp | None:
    return await asyncio.wait_for(
        client.text_document_signature_help_async(
            types.SignatureHelpParams(
                text_document=types.TextDocumentIdentifier(uri=uri),
                position=types.Position(line=line, character=character),
            )
        ),
        WAIT,
    )


async def test_signature_help_of_a_macro_call_and_of_a_function(client: LanguageClient) -> None:
    result = await initialize(client)
    options = result.capabilities.signature_help_provider
    assert options is not None and options.trigger_characters is not None
    assert {"[", ",", " ", "X"} <= set(options.trigger_characters)
    uri = "untitled:signature.nc"
    open_text(client, uri, TEXT)
    await diagnostics(client, uri)
    help = await signature(client, uri, 2, len("G65 P9010 A1. X#1"))
    assert help is not None
    (sig,) = help.signatures
    assert sig.label == "G65 P9010 A=#1 X=#24"
    assert help.active_parameter == 1
    labels = [p.label for p in sig.parameters or []]
    assert labels == [(10, 14), (15, 20)]
    x = sig.parameters[1].documentation  # type: ignore[index]
    assert isinstance(x, types.MarkupContent) and "(START X)" in x.value
    # Typed on a new line and not analysed yet: the text is read as it is now.
    edit(client, uri, 2, [types.TextDocumentContentChangePartial(
        range=types.Range(
            start=types.Position(line=3, character=0), end=types.Position(line=3, character=0)
        ),
        text="(😀) #2=ATAN[1]/[\n",
    )])  # fmt: skip
    atan = await signature(client, uri, 3, len("(😀) #2=ATAN[1]/[") + 1)
    assert atan is not None and atan.signatures[0].label == "ATAN[a]/[b]"
    assert atan.active_parameter == 1
    assert await signature(client, uri, 0, 3) is None


async def test_code_lenses_over_the_o_lines_of_a_seed(client: LanguageClient) -> None:
    await initialize(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")
    await diagnostics(client, uri)
    lenses = await asyncio.wait_for(
        client.text_document_code_lens_async(
            types.CodeLensParams(text_document=types.TextDocumentIdentifier(uri=uri))
        ),
        WAIT,
    )
    assert lenses is not None
    shown = [
        (lens.range.start.line, lens.command.title if lens.command else None) for lens in lenses
    ]
    assert shown[0] == (1, "entered once")
    # The cycle time of the main program's run (worked out by hand in test_cycle_time.py),
    # its parts in the tooltip.
    assert shown[1] == (1, "cycle time 10 min 1.3 s")
    assert lenses[1].command is not None and lenses[1].command.tooltip is not None
    assert lenses[1].command.tooltip.startswith(
        "cutting: 11.4 s\nthreading: 9 min 18.0 s\nrapid: 29.9 s\ntool change: 2.0 s\n"
        "1 tool change\n\n"
    )
    assert shown[2] == (17, "called from O4009 · 1×")
    line, title = shown[3]
    assert line == 17 and title is not None
    assert title.startswith("entered once · M50x3-5g6g: 186 cuts at ") and title.endswith(
        "(G92 F3)"
    )
    assert shown[4] == (17, "9 min 59.0 s in its own blocks")
    assert lenses[2].data == {"references": [[uri, 10]]}  # the M98 P0013331 line
    assert lenses[2].command is not None and lenses[2].command.tooltip == "O4009, line 11"
    assert lenses[2].command.command == ""  # a title to read: VS Code shows it as text
    assert lenses[0].range.end.character == len("O4009")
    hover = await asyncio.wait_for(
        client.text_document_hover_async(
            types.HoverParams(
                text_document=types.TextDocumentIdentifier(uri=uri),
                position=types.Position(line=1, character=2),
            )
        ),
        WAIT,
    )
    assert hover is not None and isinstance(hover.contents, types.MarkupContent)
    assert "Cycle time 10 min 1.3 s (cutting: 11.4 s, threading: 9 min 18.0 s" in (
        hover.contents.value
    )


async def test_the_lenses_are_fetched_again_after_each_analysis(client: LanguageClient) -> None:
    asked: list[object] = []

    @client.feature(types.WORKSPACE_CODE_LENS_REFRESH)
    def refresh(params: None) -> None:
        asked.append(params)

    capabilities = types.ClientCapabilities(
        text_document=CAPABILITIES.text_document,
        window=CAPABILITIES.window,
        workspace=types.WorkspaceClientCapabilities(
            code_lens=types.CodeLensWorkspaceClientCapabilities(refresh_support=True)
        ),
    )
    await asyncio.wait_for(
        client.initialize_session(
            types.InitializeParams(
                capabilities=capabilities,
                initialization_options={"analysis": {"debounceMs": 20}},
            )
        ),
        WAIT,
    )
    uri = "untitled:lens.nc"
    open_text(client, uri, "O1\nM98 P2\nM30\n")
    await diagnostics(client, uri)
    for _ in range(200):
        if asked:
            break
        await asyncio.sleep(0.02)
    assert asked, "no workspace/codeLens/refresh after the analysis"
