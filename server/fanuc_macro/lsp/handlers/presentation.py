"""Semantic tokens (full, delta, range), signature help and code lenses
(``lsp/presentation.py`` words them)."""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

from lsprotocol import types

from ...ide import TOKEN_MODIFIERS, TOKEN_TYPES
from . import Route

if TYPE_CHECKING:
    from ..server import FanucMacroLanguageServer

KEPT_TOKEN_RESULTS = 8  # documents whose last semantic tokens are kept for a delta
# Signature help opens on a macro call's argument letters (spec I; either case as typed).
SIGNATURE_LETTERS = (*"ABCDEFHIJKMQRSTUVWXYZ", *"abcdefhijkmqrstuvwxyz")


class SentTokens:
    """The last full tokens sent of each document, for a delta: (result id, data). A few
    documents, the most recent; an unknown id gets the full tokens again. Event loop only."""

    def __init__(self) -> None:
        self._sent: dict[str, tuple[str, list[int]]] = {}
        self._ids = itertools.count(1)

    def next_id(self) -> str:
        return str(next(self._ids))

    def get(self, uri: str) -> tuple[str, list[int]] | None:
        return self._sent.get(uri)

    def keep(self, uri: str, tokens: types.SemanticTokens) -> types.SemanticTokens:
        self._sent.pop(uri, None)
        self._sent[uri] = (tokens.result_id or "", list(tokens.data))
        while len(self._sent) > KEPT_TOKEN_RESULTS:
            del self._sent[next(iter(self._sent))]
        return tokens


async def semantic_tokens(
    ls: FanucMacroLanguageServer, params: types.SemanticTokensParams
) -> types.SemanticTokens | None:
    uri = params.text_document.uri
    view = await ls.view(uri)
    if view is None:
        return None
    from ..presentation import semantic_tokens

    result_id = ls.sent_tokens.next_id()
    found = await ls.compute("semantic tokens", lambda: semantic_tokens(view, None, result_id))
    return None if found is None else ls.sent_tokens.keep(uri, found)


async def semantic_tokens_delta(
    ls: FanucMacroLanguageServer, params: types.SemanticTokensDeltaParams
) -> types.SemanticTokens | types.SemanticTokensDelta | None:
    uri = params.text_document.uri
    view = await ls.view(uri)
    if view is None:
        return None
    from ..presentation import semantic_tokens, token_edits

    result_id = ls.sent_tokens.next_id()
    found = await ls.compute("semantic tokens", lambda: semantic_tokens(view, None, result_id))
    if found is None:
        return None
    before = ls.sent_tokens.get(uri)
    ls.sent_tokens.keep(uri, found)
    if before is None or before[0] != params.previous_result_id:
        return found
    edits = token_edits(before[1], found.data)
    return types.SemanticTokensDelta(edits=edits, result_id=result_id)


async def semantic_tokens_range(
    ls: FanucMacroLanguageServer, params: types.SemanticTokensRangeParams
) -> types.SemanticTokens | None:
    view = await ls.view(params.text_document.uri)
    if view is None:
        return None
    from ..presentation import semantic_tokens

    within = params.range
    return await ls.compute("semantic tokens", lambda: semantic_tokens(view, within))


async def signature_help(
    ls: FanucMacroLanguageServer, params: types.SignatureHelpParams
) -> types.SignatureHelp | None:
    at = ls.typed_at(params.text_document.uri, params.position)
    if at is None:
        return None
    from ..presentation import signature_help

    codec, locale = ls.engine.codec, ls.engine.catalogue.locale
    return await ls.compute(
        "signature help", lambda: signature_help(at.line_text, at.column, codec, at.view, locale)
    )


async def code_lens(
    ls: FanucMacroLanguageServer, params: types.CodeLensParams
) -> list[types.CodeLens] | None:
    from ..presentation import code_lenses

    return await ls.answer(params.text_document.uri, "code lenses", code_lenses)


ROUTES = (
    Route(
        types.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL,
        semantic_tokens,
        lambda: types.SemanticTokensRegistrationOptions(
            legend=types.SemanticTokensLegend(
                token_types=list(TOKEN_TYPES), token_modifiers=list(TOKEN_MODIFIERS)
            ),
            full=types.SemanticTokensFullDelta(delta=True),
            range=True,
        ),
    ),
    Route(types.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL_DELTA, semantic_tokens_delta),
    Route(types.TEXT_DOCUMENT_SEMANTIC_TOKENS_RANGE, semantic_tokens_range),
    Route(
        types.TEXT_DOCUMENT_SIGNATURE_HELP,
        signature_help,
        lambda: types.SignatureHelpOptions(
            # A bracket or comma of a function; a space or a letter of a G65/G66 line.
            trigger_characters=["[", ",", " ", *SIGNATURE_LETTERS],
            retrigger_characters=["/", "]"],
        ),
    ),
    Route(
        types.TEXT_DOCUMENT_CODE_LENS,
        code_lens,
        lambda: types.CodeLensOptions(resolve_provider=False),
    ),
)
