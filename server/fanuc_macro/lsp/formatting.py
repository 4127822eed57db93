"""Formatting and "Renumber N labels" in the protocol's terms: the ide layer's edits
(``ide/formatting.py``, ``ide/renumber.py``) in the client's units. The ide modules are imported
when first asked for: the server answers ``initialize`` before it loads the parser."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from lsprotocol import types

from ..config import FormatSettings
from .convert import Codec, Lines

if TYPE_CHECKING:
    from ..ide import FormatOptions, TextEdit
    from .features import View

RENUMBER_KIND = "source.renumber.fanuc-macro"  # ide.data.ActionKind.SOURCE_RENUMBER


def wants(only: Sequence[str] | None, kind: str) -> bool:
    """Whether a code action request's ``only`` asks for actions of ``kind`` (a kind asks for
    its sub-kinds too: ``source`` for ``source.renumber.fanuc-macro``). A source action is
    offered only when asked for (VS Code's *Source Action...* asks for ``source``), not with
    the quick fixes of every request."""
    return only is not None and any(kind == k or kind.startswith(f"{k}.") for k in only)


def _options(settings: FormatSettings, options: types.FormattingOptions) -> FormatOptions:
    from ..ide import FormatOptions

    trim = options.trim_trailing_whitespace
    return FormatOptions(
        settings=settings,
        trim_trailing_whitespace=True if trim is None else trim,
        insert_final_newline=bool(options.insert_final_newline),
        trim_final_newlines=bool(options.trim_final_newlines),
    )


def _converted(edits: Sequence[TextEdit], lines: Lines) -> list[types.TextEdit]:
    return [
        types.TextEdit(
            range=lines.range(
                e.range.start.line, e.range.start.column, e.range.end.line, e.range.end.column
            ),
            new_text=e.new_text,
        )
        for e in edits
    ]


def document_edits(
    text: str,
    lines: Sequence[str],
    codec: Codec,
    settings: FormatSettings,
    options: types.FormattingOptions,
) -> list[types.TextEdit]:
    from ..ide import format_document

    chosen = _options(settings, options)
    return _converted(format_document(text, chosen), Lines(lines, codec))


def range_edits(
    text: str,
    lines: Sequence[str],
    codec: Codec,
    settings: FormatSettings,
    options: types.FormattingOptions,
    asked: types.Range,
) -> list[types.TextEdit]:
    """The lines the range touches (a range that ends at a line's start leaves that line)."""
    from ..ide import format_lines

    chosen = _options(settings, options)
    first, last = asked.start.line, asked.end.line
    if asked.end.character == 0 and last > first:
        last -= 1
    return _converted(format_lines(text, chosen, first, last), Lines(lines, codec))


def renumber_action(view: View, line: int, step: int) -> types.CodeAction | None:
    """ "Renumber N labels" of the program at ``line``: a source action; disabled, with the
    reason, when it cannot be done."""
    from ..ide import renumber_labels

    action = renumber_labels(view.ide, line, step)
    if action is None:
        return None
    from ..translation import render

    title = render(action.title, view.locale)
    if action.disabled:
        return types.CodeAction(
            title=title,
            kind=RENUMBER_KIND,
            disabled=types.CodeActionDisabled(reason=render(action.disabled, view.locale)),
        )
    changes = {
        view.uri_of(edit.key): _converted(edit.edits, view.lines_of(edit.key))
        for edit in action.edits
    }
    return types.CodeAction(
        title=title, kind=RENUMBER_KIND, edit=types.WorkspaceEdit(changes=changes)
    )


__all__ = ("RENUMBER_KIND", "document_edits", "range_edits", "renumber_action", "wants")
