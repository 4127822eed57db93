"""The plain results of the editor features: positions in the package's units (0-based lines,
columns in code points), markdown texts, edits, locations, symbols, completions and fixes.

A front end converts them: the language server to the protocol's types and the client's
units, the command line to text or JSON.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum


@dataclass(frozen=True, order=True)
class Position:
    line: int  # 0-based
    column: int  # 0-based, in code points


@dataclass(frozen=True)
class Range:
    start: Position
    end: Position

    @staticmethod
    def of(line: int, column: int, end_line: int, end_column: int) -> Range:
        return Range(Position(line, column), Position(end_line, end_column))

    @staticmethod
    def at(position: Position) -> Range:
        return Range(position, position)


@dataclass(frozen=True)
class TextEdit:
    range: Range
    new_text: str


@dataclass(frozen=True)
class Location:
    key: str  # the document's name in the package
    range: Range


@dataclass(frozen=True)
class Hover:
    markdown: str
    range: Range  # what the text is about


@dataclass(frozen=True)
class InlayHint:
    position: Position
    label: str
    tooltip: str


class SymbolKind(str, Enum):
    MAIN_PROGRAM = "main program"
    SUBPROGRAM = "subprogram"
    LABEL = "label"
    LOOP = "loop"


@dataclass(frozen=True)
class Symbol:
    name: str
    detail: str  # "" when there is none
    kind: SymbolKind
    range: Range  # the whole of it
    selection: Range  # its name
    children: tuple[Symbol, ...] = ()


class CompletionKind(str, Enum):
    VARIABLE = "variable"
    CODE = "code"  # a G or M code
    FUNCTION = "function"
    KEYWORD = "keyword"
    SNIPPET = "snippet"


@dataclass(frozen=True)
class CompletionItem:
    label: str
    kind: CompletionKind
    detail: str = ""
    documentation: str = ""  # markdown
    insert_text: str = ""
    snippet: bool = False  # insert_text has snippet placeholders ($1)
    sort_text: str = ""
    filter_text: str = ""
    replace: Range | None = None  # the typed text insert_text replaces; None: at the cursor
    # Edits elsewhere in the document, made with the item (a sub-program after the program).
    additional_edits: tuple[TextEdit, ...] = ()


@dataclass(frozen=True)
class CompletionList:
    items: tuple[CompletionItem, ...]
    incomplete: bool = False


@dataclass(frozen=True)
class Problem:
    """A diagnostic a fix is asked for: its code and where it starts."""

    code: str
    line: int
    column: int


@dataclass(frozen=True)
class DocumentEdit:
    key: str  # the document's name in the package
    edits: tuple[TextEdit, ...]


class ActionKind(str, Enum):
    QUICK_FIX = "quickfix"
    SOURCE_RENUMBER = "source.renumber.fanuc-macro"  # a source action of the whole program


@dataclass(frozen=True)
class CodeAction:
    title: str
    kind: ActionKind
    edits: tuple[DocumentEdit, ...]
    fixes: tuple[Problem, ...] = ()  # the problems it answers, as they were asked
    preferred: bool = False
    disabled: str = ""  # why it cannot be done ("" when it can)


__all__ = (
    "ActionKind",
    "CodeAction",
    "CompletionItem",
    "CompletionKind",
    "CompletionList",
    "DocumentEdit",
    "Hover",
    "InlayHint",
    "Location",
    "Position",
    "Problem",
    "Range",
    "Symbol",
    "SymbolKind",
    "TextEdit",
)
