"""Rename, document highlight, folding and selection ranges, workspace symbols and the call
hierarchy (``lsp/navigation.py`` words them)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from lsprotocol import types
from pygls.exceptions import JsonRpcException

from . import Route

if TYPE_CHECKING:
    from ..server import FanucMacroLanguageServer


def _refused(answer: Any) -> Any:
    """A rename the ide layer refused is an error whose message the client shows."""
    from ..navigation import Refused

    if isinstance(answer, Refused):
        raise JsonRpcException(answer.message, code=types.LSPErrorCodes.RequestFailed)
    return answer


async def prepare_rename(
    ls: FanucMacroLanguageServer, params: types.PrepareRenameParams
) -> types.PrepareRenamePlaceholder | None:
    from ..navigation import prepare_rename

    found = await ls.answer(
        params.text_document.uri,
        "prepare rename",
        lambda view: prepare_rename(view, params.position),
    )
    return _refused(found)  # type: ignore[no-any-return]


async def rename(
    ls: FanucMacroLanguageServer, params: types.RenameParams
) -> types.WorkspaceEdit | None:
    from ..navigation import rename

    found = await ls.answer(
        params.text_document.uri,
        "rename",
        lambda view: rename(view, params.position, params.new_name),
    )
    return _refused(found)  # type: ignore[no-any-return]


async def document_highlight(
    ls: FanucMacroLanguageServer, params: types.DocumentHighlightParams
) -> list[types.DocumentHighlight] | None:
    from ..navigation import document_highlights

    return await ls.answer(
        params.text_document.uri,
        "document highlight",
        lambda view: document_highlights(view, params.position),
    )


async def folding_range(
    ls: FanucMacroLanguageServer, params: types.FoldingRangeParams
) -> list[types.FoldingRange] | None:
    from ..navigation import folding_ranges

    return await ls.answer(params.text_document.uri, "folding ranges", folding_ranges)


async def selection_range(
    ls: FanucMacroLanguageServer, params: types.SelectionRangeParams
) -> list[types.SelectionRange] | None:
    from ..navigation import selection_ranges

    return await ls.answer(
        params.text_document.uri,
        "selection ranges",
        lambda view: selection_ranges(view, params.positions),
    )


async def workspace_symbol(
    ls: FanucMacroLanguageServer, params: types.WorkspaceSymbolParams
) -> list[types.WorkspaceSymbol] | None:
    engine = ls.engine
    documents = engine.indexes  # replaced, never changed: safe to read from a thread
    from ..navigation import workspace_symbols

    return await ls.compute(
        "workspace symbols",
        lambda: workspace_symbols(documents, params.query, engine.codec, engine.client_uri),
    )


async def prepare_call_hierarchy(
    ls: FanucMacroLanguageServer, params: types.CallHierarchyPrepareParams
) -> list[types.CallHierarchyItem] | None:
    from ..navigation import prepare_call_hierarchy

    found = await ls.answer(
        params.text_document.uri,
        "call hierarchy",
        lambda view: prepare_call_hierarchy(view, params.position),
    )
    return found or None


async def incoming_calls(
    ls: FanucMacroLanguageServer, params: types.CallHierarchyIncomingCallsParams
) -> list[types.CallHierarchyIncomingCall] | None:
    engine = ls.engine
    documents = engine.indexes
    from ..navigation import incoming_calls

    return await ls.compute(
        "incoming calls",
        lambda: incoming_calls(documents, params.item, engine.codec, engine.client_uri),
    )


async def outgoing_calls(
    ls: FanucMacroLanguageServer, params: types.CallHierarchyOutgoingCallsParams
) -> list[types.CallHierarchyOutgoingCall] | None:
    engine = ls.engine
    documents = engine.indexes
    from ..navigation import outgoing_calls

    return await ls.compute(
        "outgoing calls",
        lambda: outgoing_calls(documents, params.item, engine.codec, engine.client_uri),
    )


ROUTES = (
    Route(types.TEXT_DOCUMENT_PREPARE_RENAME, prepare_rename),
    Route(types.TEXT_DOCUMENT_RENAME, rename, lambda: types.RenameOptions(prepare_provider=True)),
    Route(types.TEXT_DOCUMENT_DOCUMENT_HIGHLIGHT, document_highlight),
    Route(types.TEXT_DOCUMENT_FOLDING_RANGE, folding_range),
    Route(types.TEXT_DOCUMENT_SELECTION_RANGE, selection_range),
    Route(types.WORKSPACE_SYMBOL, workspace_symbol),
    Route(types.TEXT_DOCUMENT_PREPARE_CALL_HIERARCHY, prepare_call_hierarchy),
    Route(types.CALL_HIERARCHY_INCOMING_CALLS, incoming_calls),
    Route(types.CALL_HIERARCHY_OUTGOING_CALLS, outgoing_calls),
)
