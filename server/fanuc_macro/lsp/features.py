"""The editor features in the protocol's terms: the ide layer's plain results (positions in
code points, markdown, edits by document key) converted to lsprotocol types, in the client's
units and names. Nothing here analyses or words anything; every function is pure and may run
in a thread.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from types import MappingProxyType

from lsprotocol import types

from .. import ide
from ..analysis import Analysis
from ..config import Config
from ..ide import Indexed
from ..ide import View as IdeView
from ..translation import render
from .client import CompletionSupport
from .convert import Codec, Lines


@dataclass
class View:
    """One analysed document as the client names and counts it, around the ide layer's view."""

    key: str
    uri: str  # as the client names it
    analysis: Analysis
    lines: Lines
    config: Config
    # Every workspace document by key: (document, index), for calls across files.
    workspace: Mapping[str, Indexed] = field(default_factory=dict)
    client_uri: Callable[[str], str] = lambda key: key
    markdown: bool = True
    locale: str = "en"  # the language of the words the features answer with

    @cached_property
    def ide(self) -> IdeView:
        return IdeView(self.key, self.analysis, self.config, self.workspace, self.lines.lines)

    def lines_of(self, key: str) -> Lines:
        if key == self.key:
            return self.lines
        entry = self.workspace.get(key)
        texts = [b.text for b in entry[0].blocks] if entry is not None else []
        return Lines(texts, self.lines.codec)

    def uri_of(self, key: str) -> str:
        return self.uri if key == self.key else self.client_uri(key)


# ---- conversions -----------------------------------------------------------------------------


def position(lines: Lines, p: ide.Position) -> types.Position:
    return lines.position(p.line, p.column)


def lsp_range(lines: Lines, r: ide.Range) -> types.Range:
    return lines.range(r.start.line, r.start.column, r.end.line, r.end.column)


def locations(view: View, found: Iterable[ide.Location]) -> list[types.Location]:
    lines: dict[str, Lines] = {}  # a document's lines, made once for all its places
    out: list[types.Location] = []
    for loc in found:
        of = lines.get(loc.key)
        if of is None:
            of = lines[loc.key] = view.lines_of(loc.key)
        out.append(types.Location(uri=view.client_uri(loc.key), range=lsp_range(of, loc.range)))
    return out


SYMBOL_KIND = MappingProxyType(
    {
        ide.SymbolKind.MAIN_PROGRAM: types.SymbolKind.Module,
        ide.SymbolKind.SUBPROGRAM: types.SymbolKind.Function,
        ide.SymbolKind.LABEL: types.SymbolKind.Key,
        ide.SymbolKind.LOOP: types.SymbolKind.Array,
    }
)
PROGRAMS = (ide.SymbolKind.MAIN_PROGRAM, ide.SymbolKind.SUBPROGRAM)

COMPLETION_KIND = MappingProxyType(
    {
        ide.CompletionKind.VARIABLE: types.CompletionItemKind.Variable,
        ide.CompletionKind.CODE: types.CompletionItemKind.Value,
        ide.CompletionKind.FUNCTION: types.CompletionItemKind.Function,
        ide.CompletionKind.KEYWORD: types.CompletionItemKind.Keyword,
        ide.CompletionKind.SNIPPET: types.CompletionItemKind.Snippet,
    }
)

ACTION_KIND = MappingProxyType({ide.ActionKind.QUICK_FIX: types.CodeActionKind.QuickFix})


def _symbol(lines: Lines, symbol: ide.Symbol) -> types.DocumentSymbol:
    children = [_symbol(lines, child) for child in symbol.children]
    return types.DocumentSymbol(
        name=symbol.name,
        detail=symbol.detail or None,
        kind=SYMBOL_KIND[symbol.kind],
        range=lsp_range(lines, symbol.range),
        selection_range=lsp_range(lines, symbol.selection),
        # A program lists its children, if none an empty list; a label or loop only if any.
        children=children if children or symbol.kind in PROGRAMS else None,
    )


def _documentation(text: str, support: CompletionSupport) -> types.MarkupContent | str | None:
    if not text:
        return None
    if support.markdown:
        return types.MarkupContent(kind=types.MarkupKind.Markdown, value=text)
    return text


def _completion_item(
    item: ide.CompletionItem,
    line_text: str,
    codec: Codec,
    support: CompletionSupport,
    lines: Lines | None,
    locale: str = "en",
) -> types.CompletionItem:
    edit: types.TextEdit | None = None
    if item.replace is not None:
        start, end = item.replace.start, item.replace.end
        edit = types.TextEdit(
            range=types.Range(
                start=types.Position(
                    line=start.line, character=codec.to_client(line_text, start.column)
                ),
                end=types.Position(line=end.line, character=codec.to_client(line_text, end.column)),
            ),
            new_text=item.insert_text,
        )
    return types.CompletionItem(
        label=render(item.label, locale),
        kind=COMPLETION_KIND[item.kind],
        detail=render(item.detail, locale) or None,
        documentation=_documentation(render(item.documentation, locale), support),
        sort_text=item.sort_text or None,
        filter_text=item.filter_text or None,
        text_edit=edit,
        insert_text=item.insert_text if edit is None else None,
        insert_text_format=(
            types.InsertTextFormat.Snippet if item.snippet else types.InsertTextFormat.PlainText
        ),
        additional_text_edits=[
            types.TextEdit(range=lsp_range(lines, e.range), new_text=e.new_text)
            for e in item.additional_edits
        ]
        if item.additional_edits and lines is not None
        else None,
    )


# ---- the requests ----------------------------------------------------------------------------


def hover(view: View, at: types.Position) -> types.Hover | None:
    found = ide.hover(view.ide, at.line, view.lines.column(at))
    if found is None:
        return None
    kind = types.MarkupKind.Markdown if view.markdown else types.MarkupKind.PlainText
    return types.Hover(
        contents=types.MarkupContent(kind=kind, value=render(found.markdown, view.locale)),
        range=lsp_range(view.lines, found.range),
    )


def inlay_hints(view: View, first: int, last: int) -> list[types.InlayHint]:
    return [
        types.InlayHint(
            position=position(view.lines, hint.position),
            label=render(hint.label, view.locale),
            padding_left=True,
            tooltip=render(hint.tooltip, view.locale),
        )
        for hint in ide.inlay_hints(view.ide, first, last)
    ]


def definition(view: View, at: types.Position) -> list[types.Location] | None:
    found = ide.definition(view.ide, at.line, view.lines.column(at))
    return locations(view, found) or None


def references(
    view: View,
    at: types.Position,
    include_declaration: bool,
    open_views: Sequence[View] = (),
) -> list[types.Location] | None:
    found = ide.references(
        view.ide,
        at.line,
        view.lines.column(at),
        include_declaration,
        [other.ide for other in open_views],
    )
    return None if found is None else locations(view, found)


def document_symbols(view: View) -> list[types.DocumentSymbol]:
    return [_symbol(view.lines, symbol) for symbol in ide.document_symbols(view.ide)]


def completion(
    line_text: str,
    line: int,
    column: int,
    codec: Codec,
    config: Config,
    support: CompletionSupport,
    view: View | None = None,
    line_count: int | None = None,
    eol: str = "\n",
    locale: str = "en",
) -> types.CompletionList:
    """Completion at ``column`` (code points) of ``line_text``, the open document's newest text
    of ``line_count`` lines: ``view``, the newest analysis there is, may be of an older one;
    an edit away from the cursor (the thread module's sub-program) is made only from a view
    of as many lines, whose other lines are those of the text."""
    same_lines = view is not None and len(view.lines.lines) == line_count
    found = ide.completion(
        line_text,
        line,
        column,
        view.ide.config if view is not None else config,  # its machine, as its codes show
        view.ide if view is not None else None,
        snippets_supported=support.snippets,
        has_snippets=support.builtin_snippets,
        eol=eol,
    )
    lines = view.lines if view is not None and same_lines else None
    return types.CompletionList(
        is_incomplete=found.incomplete,
        items=[
            _completion_item(item, line_text, codec, support, lines, locale)
            for item in found.items
            if lines is not None or not item.additional_edits
        ],
    )


def code_actions(
    view: View, diagnostics: Iterable[types.Diagnostic], eol: str
) -> list[types.CodeAction]:
    asked: dict[int, tuple[ide.Problem, types.Diagnostic]] = {}
    for diag in diagnostics:
        if diag.source not in (None, "fanuc-macro") or not isinstance(diag.code, str):
            continue
        start = diag.range.start
        problem = ide.Problem(diag.code, start.line, view.lines.column(start))
        asked[id(problem)] = (problem, diag)
    out: list[types.CodeAction] = []
    for action in ide.code_actions(view.ide, [p for p, _ in asked.values()], eol):
        changes: dict[str, list[types.TextEdit]] = {}
        for edit in action.edits:
            lines = view.lines_of(edit.key)
            changes[view.uri_of(edit.key)] = [
                types.TextEdit(range=lsp_range(lines, e.range), new_text=e.new_text)
                for e in edit.edits
            ]
        out.append(
            types.CodeAction(
                title=render(action.title, view.locale),
                kind=ACTION_KIND[action.kind],
                # Each fix names the problem it was asked for: the client's diagnostic.
                diagnostics=[asked[id(p)][1] for p in action.fixes] or None,
                edit=types.WorkspaceEdit(changes=changes),
                is_preferred=True if action.preferred else None,
            )
        )
    return out


__all__ = (
    "CompletionSupport",
    "View",
    "code_actions",
    "completion",
    "definition",
    "document_symbols",
    "hover",
    "inlay_hints",
    "references",
)
