"""The open documents' texts, kept in step with the client by incremental changes, and the
newest text of each for the worker (:class:`DocumentStore`).

Kept here rather than in pygls' workspace because pygls splits lines with ``str.splitlines``,
which also breaks at form feeds, U+0085 and U+2028: an edit after such a character (random
bytes read as Latin-1 have them) would land on the wrong line.
"""

from __future__ import annotations

import threading
from array import array
from collections.abc import Sequence
from dataclasses import dataclass, field

from lsprotocol import types
from pygls.uris import from_fs_path, to_fs_path

from .convert import LINE_BREAK, Codec, TextLines, line_starts


def key_of(uri: str) -> str:
    """The package's name of a document: file URIs in one normal form, so that a URI the client
    sends and one made from a path found on disk name the same file."""
    if uri.startswith("file:"):
        path = to_fs_path(uri)
        if path:
            normal = from_fs_path(path)
            if normal:
                return str(normal)
    return uri


@dataclass
class OpenDocument:
    uri: str  # as the client names it
    key: str  # as the package names it (key_of)
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


@dataclass(frozen=True)
class NewestText:
    """A text of an open document as the worker reads it."""

    seq: int  # increases with every text the loop side receives
    version: int | None
    text: str
    uri: str
    lines: TextLines  # of ``text``: its line starts are the open document's


class DocumentStore:
    """The open documents by key: changed on the event loop, which keeps their texts; the
    newest text of each is what the worker reads (any thread, under a lock)."""

    def __init__(self) -> None:
        self.docs: dict[str, OpenDocument] = {}  # event loop only
        self._lock = threading.Lock()  # guards _texts and _seq, shared with the worker
        self._texts: dict[str, NewestText] = {}
        self._seq = 0

    # ---- the event loop --------------------------------------------------------------------
    def open(self, uri: str, text: str, version: int | None, language_id: str = "") -> str:
        key = key_of(uri)
        doc = OpenDocument(uri, key, text, version, language_id)
        self.docs[key] = doc
        self._set_text(key, doc)
        return key

    def change(
        self,
        uri: str,
        version: int | None,
        changes: Sequence[types.TextDocumentContentChangeEvent],
        codec: Codec,
    ) -> str | None:
        """Apply the client's changes; the document's key, None when it is not open."""
        key = key_of(uri)
        doc = self.docs.get(key)
        if doc is None:
            return None
        for change in changes:
            doc.apply(change, codec)
        doc.version = version
        self._set_text(key, doc)
        return key

    def close(self, uri: str) -> str:
        key = key_of(uri)
        self.docs.pop(key, None)
        with self._lock:
            self._texts.pop(key, None)
        return key

    def _set_text(self, key: str, doc: OpenDocument) -> None:
        with self._lock:
            self._seq += 1
            self._texts[key] = NewestText(self._seq, doc.version, doc.text, doc.uri, doc.lines())

    def document(self, uri: str) -> OpenDocument | None:
        return self.docs.get(key_of(uri))

    def client_uri(self, key: str) -> str:
        doc = self.docs.get(key)
        return doc.uri if doc is not None else key

    # ---- any thread ------------------------------------------------------------------------
    def newest(self, key: str) -> tuple[NewestText | None, int]:
        """The newest text of ``key`` (None once closed), and the seq of the newest text of
        all, read together."""
        with self._lock:
            return self._texts.get(key), self._seq

    def newest_all(self) -> dict[str, NewestText]:
        with self._lock:
            return dict(self._texts)

    def is_open(self, key: str) -> bool:
        with self._lock:
            return key in self._texts

    def open_keys(self) -> list[str]:
        with self._lock:
            return list(self._texts)

    def changed_since(self, seq: int, keys: frozenset[str]) -> bool:
        """A text of one of ``keys`` came after ``seq``."""
        with self._lock:
            return any(t.seq > seq for k, t in self._texts.items() if k in keys)
