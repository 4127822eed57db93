"""Rename, document highlight, folding and selection ranges, workspace symbols and the call
hierarchy in the protocol's terms: the ide layer's plain answers converted to lsprotocol types
in the client's units. Pure functions; they may run in a thread.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from lsprotocol import types

from .. import ide
from ..ide import Indexed
from .convert import Codec, Lines
from .features import SYMBOL_KIND, View, lsp_range


@dataclass(frozen=True)
class Refused:
    """A rename the ide layer refused: the server answers it as an error whose message the
    client shows."""

    message: str


HIGHLIGHT_KIND = MappingProxyType(
    {
        ide.HighlightKind.TEXT: types.DocumentHighlightKind.Text,
        ide.HighlightKind.READ: types.DocumentHighlightKind.Read,
        ide.HighlightKind.WRITE: types.DocumentHighlightKind.Write,
    }
)
FOLD_KIND = MappingProxyType(
    {
        ide.FoldKind.REGION: types.FoldingRangeKind.Region,
        ide.FoldKind.COMMENT: types.FoldingRangeKind.Comment,
    }
)


class DocumentLines:
    """The lines of workspace documents as the client counts them, made once per document."""

    def __init__(self, documents: Mapping[str, Indexed], codec: Codec) -> None:
        self.documents = documents
        self.codec = codec
        self._made: dict[str, Lines] = {}

    def of(self, key: str) -> Lines:
        made = self._made.get(key)
        if made is None:
            entry = self.documents.get(key)
            texts = [b.text for b in entry[0].blocks] if entry is not None else []
            made = self._made[key] = Lines(texts, self.codec)
        return made

    def keep(self, key: str, lines: Lines) -> None:
        """Count ``key`` by ``lines`` (an open document's, as the client has it)."""
        self._made[key] = lines


def prepare_rename(
    view: View, at: types.Position
) -> types.PrepareRenamePlaceholder | Refused | None:
    found = ide.prepare_rename(view.ide, at.line, view.lines.column(at))
    if isinstance(found, ide.Refusal):
        return Refused(found.message)
    if found is None:
        return None
    return types.PrepareRenamePlaceholder(
        range=lsp_range(view.lines, found.range), placeholder=found.placeholder
    )


def rename(view: View, at: types.Position, new_name: str) -> types.WorkspaceEdit | Refused:
    found = ide.rename(view.ide, at.line, view.lines.column(at), new_name)
    if isinstance(found, ide.Refusal):
        return Refused(found.message)
    changes: dict[str, list[types.TextEdit]] = {}
    for edit in found:
        lines = view.lines_of(edit.key)
        changes[view.uri_of(edit.key)] = [
            types.TextEdit(range=lsp_range(lines, e.range), new_text=e.new_text) for e in edit.edits
        ]
    return types.WorkspaceEdit(changes=changes)


def document_highlights(view: View, at: types.Position) -> list[types.DocumentHighlight]:
    return [
        types.DocumentHighlight(range=lsp_range(view.lines, h.range), kind=HIGHLIGHT_KIND[h.kind])
        for h in ide.highlights(view.ide, at.line, view.lines.column(at))
    ]


def folding_ranges(view: View) -> list[types.FoldingRange]:
    return [
        types.FoldingRange(start_line=f.start, end_line=f.end, kind=FOLD_KIND[f.kind])
        for f in ide.folding_ranges(view.ide)
    ]


def selection_ranges(view: View, positions: Sequence[types.Position]) -> list[types.SelectionRange]:
    asked = [ide.Position(p.line, view.lines.column(p)) for p in positions]
    out: list[types.SelectionRange] = []
    for chain in ide.selection_ranges(view.ide, asked):
        parent: types.SelectionRange | None = None
        for r in reversed(chain):  # the outermost first: each is the parent of the next
            parent = types.SelectionRange(range=lsp_range(view.lines, r), parent=parent)
        assert parent is not None  # a chain holds at least the position's line
        out.append(parent)
    return out


def workspace_symbols(
    documents: Mapping[str, Indexed],
    query: str,
    codec: Codec,
    client_uri: Callable[[str], str],
) -> list[types.WorkspaceSymbol]:
    lines = DocumentLines(documents, codec)
    return [
        types.WorkspaceSymbol(
            name=s.name,
            kind=SYMBOL_KIND[s.kind],
            location=types.Location(
                uri=client_uri(s.location.key),
                range=lsp_range(lines.of(s.location.key), s.location.range),
            ),
            container_name=s.container or (s.detail or None),
        )
        for s in ide.workspace_symbols(documents, query)
    ]


def _item(
    item: ide.CallItem, lines: DocumentLines, client_uri: Callable[[str], str]
) -> types.CallHierarchyItem:
    of = lines.of(item.key)
    return types.CallHierarchyItem(
        name=item.name,
        kind=SYMBOL_KIND[item.kind],
        uri=client_uri(item.key),
        range=lsp_range(of, item.range),
        selection_range=lsp_range(of, item.selection),
        detail=item.detail or None,
        data={"key": item.key, "line": item.first_line},
    )


def prepare_call_hierarchy(view: View, at: types.Position) -> list[types.CallHierarchyItem]:
    found = ide.prepare_call_hierarchy(view.ide, at.line, view.lines.column(at))
    documents = dict(view.workspace)
    documents[view.key] = (view.analysis.doc, view.analysis.index)
    lines = DocumentLines(documents, view.lines.codec)
    lines.keep(view.key, view.lines)
    return [_item(item, lines, view.client_uri) for item in found]


def item_key(item: types.CallHierarchyItem) -> tuple[str, int] | None:
    """The document key and first line a client's item names (from its ``data``)."""
    named: Any = item.data
    if not isinstance(named, dict):
        return None
    key, line = named.get("key"), named.get("line")
    if not isinstance(key, str) or not isinstance(line, int) or isinstance(line, bool):
        return None
    return key, line


def incoming_calls(
    documents: Mapping[str, Indexed],
    item: types.CallHierarchyItem,
    codec: Codec,
    client_uri: Callable[[str], str],
) -> list[types.CallHierarchyIncomingCall]:
    named = item_key(item)
    if named is None:
        return []
    lines = DocumentLines(documents, codec)
    return [
        types.CallHierarchyIncomingCall(
            from_=_item(edge.item, lines, client_uri),
            from_ranges=[lsp_range(lines.of(edge.item.key), r) for r in edge.ranges],
        )
        for edge in ide.incoming_calls(documents, *named)
    ]


def outgoing_calls(
    documents: Mapping[str, Indexed],
    item: types.CallHierarchyItem,
    codec: Codec,
    client_uri: Callable[[str], str],
) -> list[types.CallHierarchyOutgoingCall]:
    named = item_key(item)
    if named is None:
        return []
    lines = DocumentLines(documents, codec)
    source = lines.of(named[0])  # the calls are in the item's document
    return [
        types.CallHierarchyOutgoingCall(
            to=_item(edge.item, lines, client_uri),
            from_ranges=[lsp_range(source, r) for r in edge.ranges],
        )
        for edge in ide.outgoing_calls(documents, *named)
    ]
