"""A set of program files analysed together, so that calls between them resolve."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from .analysis import Analysis, analyse
from .blocks import decode_bytes
from .config import Config
from .index import ProgramIndex, build_index
from .parser import BlockParser, default_parser, parse_text
from .syntax import Document

PROGRAM_SUFFIXES = frozenset({".nc", ".mac", ".tap", ".cnc", ".eia", ".txt"})
_PROGRAM_HEAD = re.compile(rb"\A(?:\xef\xbb\xbf)?\s*(%|[oO]\d)")


def is_program_file(path: Path) -> bool:
    """Program files by extension, or with none and a first line that is '%' or 'O<number>'."""
    if path.suffix.lower() in PROGRAM_SUFFIXES:
        return True
    if path.suffix:
        return False
    try:
        with path.open("rb") as f:
            head = f.read(64)
    except OSError:
        return False
    return _PROGRAM_HEAD.match(head) is not None


@dataclass
class _Entry:
    text: str
    doc: Document
    index: ProgramIndex
    encoding: str
    decode_note: str | None


class Workspace:
    def __init__(self, config: Config | None = None, parser: BlockParser | None = None) -> None:
        self.config = config or Config()
        self.parser = parser or default_parser()
        self._entries: dict[str, _Entry] = {}

    def add_text(self, uri: str, text: str) -> Document:
        doc = parse_text(text, uri, self.parser)
        self._entries[uri] = _Entry(text, doc, build_index(doc), "utf-8", None)
        return doc

    def add_bytes(self, uri: str, data: bytes) -> Document:
        decoded = decode_bytes(data)
        doc = parse_text(decoded.text, uri, self.parser)
        doc = Document(uri, doc.blocks, decoded.encoding, decoded.note, doc.line_count)
        self._entries[uri] = _Entry(
            decoded.text, doc, build_index(doc), decoded.encoding, decoded.note
        )
        return doc

    def remove(self, uri: str) -> None:
        self._entries.pop(uri, None)

    def uris(self) -> list[str]:
        return list(self._entries)

    def document(self, uri: str) -> Document | None:
        entry = self._entries.get(uri)
        return entry.doc if entry else None

    def index(self, uri: str) -> ProgramIndex:
        return self._entries[uri].index

    def others(self, uri: str) -> list[tuple[str, Document, ProgramIndex]]:
        """The other documents, for the calls a document makes into them."""
        return [(u, e.doc, e.index) for u, e in self._entries.items() if u != uri]

    def program_numbers(self) -> frozenset[int]:
        return frozenset(
            p.number
            for entry in self._entries.values()
            for p in entry.index.programs
            if p.number is not None
        )

    def find_program(self, number: int) -> tuple[str, int] | None:
        """The document and header line of O<number>."""
        for uri, entry in self._entries.items():
            program = entry.index.by_number(number)
            if program is not None:
                return uri, program.header_line if program.header_line is not None else 0
        return None

    def analyse(self, uri: str, workspace_programs: frozenset[int] | None = None) -> Analysis:
        entry = self._entries[uri]
        programs = self.program_numbers() if workspace_programs is None else workspace_programs
        return analyse(
            entry.text,
            uri,
            self.config,
            programs,
            self.parser,
            doc=entry.doc,
            index=entry.index,
            other_documents=self.others(uri),
        )
