"""Hover, inlay hints, definitions, references, symbols, completion, code actions and
formatting: each from the document's analysis (``lsp/features.py``) or, for completion and
formatting, from its newest text without waiting for one."""

from __future__ import annotations

import asyncio
from typing import TYPE_CHECKING

from lsprotocol import types

from ..formatting import RENUMBER_KIND, wants
from . import Route

if TYPE_CHECKING:
    from ..server import FanucMacroLanguageServer

SCAN_WAIT = 15.0  # seconds a definition waits for the workspace scan to find its target


def _end_of_line(text: str) -> str:
    return "\r\n" if "\r\n" in text[:65536] else "\n"


async def hover(ls: FanucMacroLanguageServer, params: types.HoverParams) -> types.Hover | None:
    from ..features import hover

    return await ls.answer(
        params.text_document.uri, "hover", lambda view: hover(view, params.position)
    )


async def inlay_hint(
    ls: FanucMacroLanguageServer, params: types.InlayHintParams
) -> list[types.InlayHint] | None:
    view = await ls.view(params.text_document.uri)
    if view is None:
        return None
    from ..features import inlay_hints

    r = params.range
    return await ls.compute("inlay hints", lambda: inlay_hints(view, r.start.line, r.end.line))


async def definition(
    ls: FanucMacroLanguageServer, params: types.DefinitionParams
) -> list[types.Location] | None:
    # Read before the view is made: a scan that ends after it may hold the target.
    scanned = ls.engine.scan_done.is_set()
    view = await ls.view(params.text_document.uri)
    if view is None:
        return None
    from ..features import definition

    found = await ls.compute("definition", lambda: definition(view, params.position))
    if found is None and not scanned:
        # A program in a file the workspace scan has not reached yet.
        try:
            await asyncio.wait_for(ls.engine.scan_done.wait(), SCAN_WAIT)
        except asyncio.TimeoutError:
            return None
        later = await ls.view(params.text_document.uri)
        if later is not None:
            found = await ls.compute("definition", lambda: definition(later, params.position))
    return found


async def references(
    ls: FanucMacroLanguageServer, params: types.ReferenceParams
) -> list[types.Location] | None:
    view = await ls.view(params.text_document.uri)
    if view is None:
        return None
    others = [
        ls.make_view(r)
        for r in ls.engine.results.values()
        if r.analysis is not None and r.key != view.key
    ]
    from ..features import references

    include = params.context.include_declaration
    return await ls.compute(
        "references", lambda: references(view, params.position, include, others)
    )


async def document_symbol(
    ls: FanucMacroLanguageServer, params: types.DocumentSymbolParams
) -> list[types.DocumentSymbol] | None:
    from ..features import document_symbols

    return await ls.answer(params.text_document.uri, "document symbols", document_symbols)


async def completion(
    ls: FanucMacroLanguageServer, params: types.CompletionParams
) -> types.CompletionList | None:
    at = ls.typed_at(params.text_document.uri, params.position)
    if at is None:
        return None
    from ..features import completion

    doc, line_text, column, view = at.doc, at.line_text, at.column, at.view
    support, codec = ls.completion_support, ls.engine.codec
    config = ls.engine.config_for(doc.key)
    line, line_count, eol = params.position.line, len(doc.lines()), _end_of_line(doc.text)
    locale = ls.engine.catalogue.locale
    return await ls.compute(
        "completion",
        lambda: completion(
            line_text, line, column, codec, config, support, view, line_count, eol, locale
        ),
    )


async def code_action(
    ls: FanucMacroLanguageServer, params: types.CodeActionParams
) -> list[types.CodeAction] | None:
    doc = ls.engine.document(params.text_document.uri)
    view = await ls.view(params.text_document.uri)
    if view is None or doc is None:
        return None
    eol = _end_of_line(doc.text)
    from ..features import code_actions

    diagnostics = params.context.diagnostics
    actions = await ls.compute("code actions", lambda: code_actions(view, diagnostics, eol))
    if actions is not None and wants(params.context.only, RENUMBER_KIND):
        from ..formatting import renumber_action

        line, step = params.range.start.line, ls.engine.format_settings.renumber_step
        found = await ls.compute("renumbering", lambda: renumber_action(view, line, step))
        if found is not None:
            actions.append(found)
    return actions


# ---- formatting: the open document's text, no analysis waited for -------------------------
async def formatting(
    ls: FanucMacroLanguageServer, params: types.DocumentFormattingParams
) -> list[types.TextEdit] | None:
    engine = ls.engine
    doc = engine.document(params.text_document.uri)
    if doc is None:
        return None
    from ..formatting import document_edits

    text, lines, codec = doc.text, doc.lines(), engine.codec
    settings, options = engine.format_settings, params.options
    return await ls.compute(
        "formatting", lambda: document_edits(text, lines, codec, settings, options)
    )


async def range_formatting(
    ls: FanucMacroLanguageServer, params: types.DocumentRangeFormattingParams
) -> list[types.TextEdit] | None:
    engine = ls.engine
    doc = engine.document(params.text_document.uri)
    if doc is None:
        return None
    from ..formatting import range_edits

    text, lines, codec = doc.text, doc.lines(), engine.codec
    settings, options, asked = engine.format_settings, params.options, params.range
    return await ls.compute(
        "range formatting",
        lambda: range_edits(text, lines, codec, settings, options, asked),
    )


ROUTES = (
    Route(types.TEXT_DOCUMENT_HOVER, hover),
    Route(
        types.TEXT_DOCUMENT_INLAY_HINT,
        inlay_hint,
        lambda: types.InlayHintOptions(resolve_provider=False),
    ),
    Route(types.TEXT_DOCUMENT_DEFINITION, definition),
    Route(types.TEXT_DOCUMENT_REFERENCES, references),
    Route(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL, document_symbol),
    Route(
        types.TEXT_DOCUMENT_COMPLETION,
        completion,
        lambda: types.CompletionOptions(trigger_characters=["#"], resolve_provider=False),
    ),
    Route(
        types.TEXT_DOCUMENT_CODE_ACTION,
        code_action,
        lambda: types.CodeActionOptions(
            code_action_kinds=[types.CodeActionKind.QuickFix, RENUMBER_KIND]
        ),
    ),
    Route(types.TEXT_DOCUMENT_FORMATTING, formatting),
    Route(types.TEXT_DOCUMENT_RANGE_FORMATTING, range_formatting),
)
