"""The open documents' texts, kept in step with the client by incremental changes.

Kept here rather than in pygls' workspace because pygls splits lines with ``str.splitlines``,
which also breaks at form feeds, U+0085 and U+2028: an edit after such a character (random
bytes read as Latin-1 have them) would land on the wrong line.
"""

from __future__ import annotations

from array import array
from dataclasses import dataclass, field

from lsprotocol import types

from .convert import LINE_BREAK, Codec, TextLines, line_starts


@dataclass
class OpenDocument:
    uri: str  # as the client names it
    key: str  # as the package names it (see Engine.key)
    text: str
    version: int | None
    language_id: str = ""
    _starts: array[int] | None = field(default=None, repr=False)

    def _line_starts(self) -> array[int]:
        """Where the text's lines begin: a new array after every edit, never changed in place,
        so that the analysis of a version shares its list (:class:`~.convert.TextLines`)."""
        if self._starts is None:
            self._starts = line_starts(self.text)
        return self._starts

    def lines(self) -> TextLines:
        """The lines of the current text, as the protocol numbers them."""
        return TextLines(self.text, self._line_starts())

    def line(self, number: int) -> str:
        starts = self._line_starts()
        if not 0 <= number < len(starts):
            return ""
        start = starts[number]
        end = starts[number + 1] if number + 1 < len(starts) else len(self.text)
        return self.text[start:end].rstrip("\r\n")

    def offset(self, position: types.Position, codec: Codec) -> int:
        starts = self._line_starts()
        if position.line < 0:
            return 0
        if position.line >= len(starts):
            return len(self.text)
        line = self.line(position.line)
        return starts[position.line] + codec.from_client(line, position.character)

    def apply(self, change: types.TextDocumentContentChangeEvent, codec: Codec) -> None:
        if not isinstance(change, types.TextDocumentContentChangePartial):
            self.text = change.text
            self._starts = None
            return
        starts = self._line_starts()
        start = self.offset(change.range.start, codec)
        end = max(start, self.offset(change.range.end, codec))
        old = self.text
        self.text = old[:start] + change.text + old[end:]
        first, last = change.range.start.line, change.range.end.line
        if not 0 <= first <= last < len(starts) or _touches_break(old, start, end):
            self._starts = None  # an edit next to a CR or LF may join or split a CRLF
            return
        # Keystrokes: move the line starts after the edit instead of rescanning the text.
        delta = len(change.text) - (end - start)
        inner = [start + m.end() for m in LINE_BREAK.finditer(change.text)]
        moved = array("q", [s + delta for s in starts[last + 1 :]]) if delta else starts[last + 1 :]
        self._starts = starts[: first + 1] + array("q", inner) + moved


def _touches_break(text: str, start: int, end: int) -> bool:
    before = text[start - 1 : start]
    after = text[end : end + 1]
    return before == "\r" or after == "\n" or (before == "\n" and after == "\r")
