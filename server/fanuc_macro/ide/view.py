"""One analysed document as the features read it, with the workspace around it."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from ..analysis import Analysis
from ..config import Config
from ..evaluator.facts import DocumentFacts
from ..program.index import Call, Program, ProgramIndex
from ..syntax.tree import Block, Document
from .data import Location, Range
from .locate import Hit, find

# A workspace document as the front ends keep it: parsed, with its program index.
Indexed = tuple[Document, ProgramIndex]


@dataclass
class View:
    """One analysed document and what the features need around it."""

    key: str  # the document's name in the package
    analysis: Analysis
    config: Config
    # Every workspace document by key: (document, index), for calls across files.
    workspace: Mapping[str, Indexed] = field(default_factory=dict)
    # The document's lines as the front end has them (the analysed text's): past the blocks
    # the analysis read (MB013) too. None: the blocks' texts.
    lines: Sequence[str] | None = None

    def __post_init__(self) -> None:
        # The document's own settings: its machine as its codes show it (controller 0i-F).
        if self.analysis.config is not None:
            self.config = self.analysis.config

    @property
    def doc(self) -> Document:
        return self.analysis.doc

    @property
    def index(self) -> ProgramIndex:
        return self.analysis.index

    @property
    def facts(self) -> DocumentFacts | None:
        facts = self.analysis.facts
        return None if facts is None else facts.by_uri.get(self.key)

    def block(self, line: int) -> Block | None:
        blocks = self.doc.blocks
        return blocks[line] if 0 <= line < len(blocks) else None

    def hit_at(self, line: int, column: int) -> tuple[Block, Hit] | None:
        block = self.block(line)
        if block is None:
            return None
        hit = find(block, column)
        return None if hit is None else (block, hit)

    def document(self, key: str) -> Document | None:
        if key == self.key:
            return self.doc
        entry = self.workspace.get(key)
        return entry[0] if entry is not None else None

    def text(self, key: str, line: int) -> str:
        """The text of ``line`` of a document; "" past its end."""
        if key == self.key and self.lines is not None:
            return self.lines[line] if 0 <= line < len(self.lines) else ""
        doc = self.document(key)
        blocks = doc.blocks if doc is not None else ()
        return blocks[line].text if 0 <= line < len(blocks) else ""

    def location(self, key: str, line: int, start: int = 0, end: int | None = None) -> Location:
        """A place on one line of a document: to its end when ``end`` is None."""
        stop = len(self.text(key, line)) if end is None else end
        return Location(key, Range.of(line, start, line, stop))

    def program_entry(self, number: int) -> tuple[str, Document, Program] | None:
        """Where O``number`` is: this document first, then the workspace (as the evaluator)."""
        own = self.index.by_number(number)
        if own is not None:
            return self.key, self.doc, own
        for key, (doc, index) in self.workspace.items():
            if key == self.key:
                continue
            program = index.by_number(number)
            if program is not None:
                return key, doc, program
        return None


def comment_of(block: Block) -> str:
    return " ".join(c.text.strip() for c in block.parsed.comments if c.text.strip())


def first_comment(doc: Document, program: Program) -> str:
    for line in range(program.first_line, min(program.end_line, len(doc.blocks))):
        text = comment_of(doc.blocks[line])
        if text:
            return text
    return ""


def call_at(program: Program | None, line: int) -> Call | None:
    if program is None:
        return None
    return next((c for c in program.calls if c.line == line), None)


def lines_of(program: Program | None, doc: Document) -> tuple[int, int]:
    """The lines ``first``..``end``-1 of a program, or of the whole document."""
    return (program.first_line, program.end_line) if program else (0, len(doc.blocks))


__all__ = (
    "Indexed",
    "View",
    "call_at",
    "comment_of",
    "first_comment",
    "lines_of",
)
