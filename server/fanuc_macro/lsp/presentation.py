"""Semantic tokens, signature help and code lenses in the protocol's terms: the ide layer's
plain answers (``ide/semantic.py``, ``ide/signature.py``, ``ide/lenses.py``) converted to
lsprotocol types, in the client's position units. Pure; may run in a thread.
"""

from __future__ import annotations

from collections.abc import Sequence
from types import MappingProxyType

from lsprotocol import types

from .. import ide
from ..ide import TOKEN_MODIFIERS, TOKEN_TYPES
from ..translation import render
from .convert import Codec
from .features import View, locations, lsp_range

_TYPE_INDEX = MappingProxyType({name: i for i, name in enumerate(TOKEN_TYPES)})
_MODIFIER_BIT = MappingProxyType({name: 1 << i for i, name in enumerate(TOKEN_MODIFIERS)})


def encode(view: View, tokens: list[ide.SemanticToken]) -> list[int]:
    """The protocol's packed form: five integers a token, each position relative to the one
    before, in the client's units."""
    data: list[int] = []
    codec = view.lines.codec
    previous_line = previous_start = 0
    for token in tokens:
        text = view.lines.text(token.line)
        start = codec.to_client(text, token.start)
        length = codec.to_client(text, token.end) - start
        delta_line = token.line - previous_line
        delta_start = start - previous_start if delta_line == 0 else start
        bits = 0
        for modifier in token.modifiers:
            bits |= _MODIFIER_BIT[modifier.value]
        data += [delta_line, delta_start, length, _TYPE_INDEX[token.type.value], bits]
        previous_line, previous_start = token.line, start
    return data


def semantic_tokens(
    view: View, within: types.Range | None = None, result_id: str | None = None
) -> types.SemanticTokens:
    first, last = (within.start.line, within.end.line) if within is not None else (0, None)
    found = ide.semantic_tokens(view.ide, first, last)
    return types.SemanticTokens(data=encode(view, found), result_id=result_id)


def token_edits(old: Sequence[int], new: Sequence[int]) -> list[types.SemanticTokensEdit]:
    """``old`` made ``new`` by one edit: what the two share at their start and at their end is
    kept (an edit of a few lines changes the tokens of those lines, and the line deltas of the
    first token after them). None when they are equal."""
    if old == new:
        return []
    shorter = min(len(old), len(new))
    start = 0
    while start < shorter and old[start] == new[start]:
        start += 1
    end = 0  # how many at the end are the same, not reaching back into the start's
    while end < shorter - start and old[-1 - end] == new[-1 - end]:
        end += 1
    return [
        types.SemanticTokensEdit(
            start=start, delete_count=len(old) - start - end, data=list(new[start : len(new) - end])
        )
    ]


def _markdown(text: str) -> types.MarkupContent | None:
    return types.MarkupContent(kind=types.MarkupKind.Markdown, value=text) if text else None


def signature_help(
    line_text: str, column: int, codec: Codec, view: View | None, locale: str = "en"
) -> types.SignatureHelp | None:
    """Signature help at ``column`` (code points) of ``line_text``, the open document's newest
    text; ``view``, the newest analysis there is, may be of an older one."""
    found = ide.signature_help(line_text, column, view.ide if view else None)
    if found is None:
        return None
    label = found.label
    parameters = [
        types.ParameterInformation(
            label=(codec.to_client(label, p.start), codec.to_client(label, p.end)),
            documentation=_markdown(render(p.documentation, locale)),
        )
        for p in found.parameters
    ]
    # No parameter at the cursor: an index past the parameters, which highlights none.
    active = found.active if found.active is not None else len(parameters)
    return types.SignatureHelp(
        signatures=[
            types.SignatureInformation(
                label=label,
                documentation=_markdown(render(found.documentation, locale)),
                parameters=parameters,
                active_parameter=active,
            )
        ],
        active_signature=0,
        active_parameter=active,
    )


def code_lenses(view: View) -> list[types.CodeLens]:
    """Each lens with its title as a command of no id: a title to read, nothing to run (the
    places a title counts are the references the lens's data holds)."""
    out: list[types.CodeLens] = []
    for lens in ide.code_lenses(view.ide):
        places = locations(view, lens.references)
        out.append(
            types.CodeLens(
                range=lsp_range(view.lines, lens.range),
                command=types.Command(
                    title=render(lens.title, view.locale),
                    command="",
                    tooltip=render(lens.tooltip, view.locale) or None,
                ),
                data={"references": [[p.uri, p.range.start.line] for p in places]}
                if places
                else None,
            )
        )
    return out


__all__ = ("code_lenses", "encode", "semantic_tokens", "signature_help", "token_edits")
