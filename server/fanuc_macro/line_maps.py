"""The few lines of a document that hold something, kept from one version to the next.

Several rules look at every line of a document for the few that matter: the lines with a line
rule's finding, the ends of programs, the marks of another control's dialect. On a document of
20,000 lines that look costs milliseconds on every keystroke, though an edit changes a line or
two. A :class:`LineMap` keeps, per document, the lines where its per-line function gave
something and what it gave; for the next version of the document it looks again only at the
stretch of lines the edit changed (:func:`edit_between`) and moves the lines after it.

What a map gives is always what a look at every line would give: the per-line function depends
on the line's text alone, and lines outside the edited stretch are the same lines
(``tests/test_line_maps.py`` compares the two after random edits).
"""

from __future__ import annotations

import threading
from bisect import bisect_left
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from operator import itemgetter
from typing import Generic, TypeVar

from .cancel import CHECKING, SLICE, CancelToken
from .syntax import Document, ParsedLine

T = TypeVar("T")

_PARSED = itemgetter(1)  # Block.parsed, read in C
_CHUNK = 256  # lines compared at once, as slices, before the first differing one is looked for


@dataclass(frozen=True, slots=True)
class Edit:
    """Two versions of a document differ only in one stretch: the lines before ``head`` are
    the same, and the old version's lines from ``old_end`` on are the new one's from
    ``new_end`` on."""

    head: int
    old_end: int
    new_end: int

    @property
    def shift(self) -> int:
        """How far the lines after the edit moved."""
        return self.new_end - self.old_end


def _same_head(x: Sequence[ParsedLine], y: Sequence[ParsedLine]) -> int:
    """How many lines from the first are the same (the same objects, or equal)."""
    n = min(len(x), len(y))
    i = 0
    # Slices compare in C, each pair by identity first: a few ns a line.
    while i + _CHUNK <= n and x[i : i + _CHUNK] == y[i : i + _CHUNK]:
        i += _CHUNK
    while i < n and x[i] == y[i]:
        i += 1
    return i


def edit_between(old: Sequence[ParsedLine], new: Sequence[ParsedLine]) -> Edit:
    """The stretch in which two versions' lines differ (any two documents have one)."""
    with _lock:
        for a, b, edit in _edits:
            if a is old and b is new:
                return edit
    edit = _edit_between(old, new)
    with _lock:
        _edits.insert(0, (old, new, edit))
        del _edits[_REMEMBERED:]
    return edit


def _edit_between(old: Sequence[ParsedLine], new: Sequence[ParsedLine]) -> Edit:
    head = _same_head(old, new)
    longest_tail = min(len(old), len(new)) - head
    tail = _same_head(old[::-1][:longest_tail], new[::-1][:longest_tail])
    return Edit(head, len(old) - tail, len(new) - tail)


# The maps of a document share its lines and the edit from its last version: each is worked
# out once per analysis, not once per map.
_REMEMBERED = 4
_lock = threading.Lock()
_lines: list[tuple[Document, list[ParsedLine]]] = []
_edits: list[tuple[Sequence[ParsedLine], Sequence[ParsedLine], Edit]] = []


def lines_of(doc: Document) -> list[ParsedLine]:
    """The parsed lines of a document's blocks, in order (the same list for the same document
    while it is among the last few asked about: do not change it)."""
    with _lock:
        for known, parsed in _lines:
            if known is doc:
                return parsed
    parsed = list(map(_PARSED, doc.blocks))
    with _lock:
        _lines.insert(0, (doc, parsed))
        del _lines[_REMEMBERED:]
    return parsed


@dataclass(frozen=True, slots=True)
class _Version(Generic[T]):
    doc: Document
    parsed: list[ParsedLine]
    lines: list[int]
    values: list[T]


class LineMap(Generic[T]):
    """The lines of a document where ``compute(parsed)`` is not None, with the values, for the
    last few documents asked about (by URI): the next version of a document is looked at only
    where it differs from the last.

    ``compute`` must depend on the line's text alone (such as a :class:`~fanuc_macro.per_line.
    PerLine` function); ``keep`` documents are remembered, the least recently asked dropped.
    """

    def __init__(self, compute: Callable[[ParsedLine], T | None], keep: int = 16) -> None:
        self._compute = compute
        self._keep = keep
        self._versions: dict[str, _Version[T]] = {}
        self._lock = threading.Lock()
        self.lines_computed = 0  # for the tests: the lines looked at, over the map's life

    def __call__(
        self, doc: Document, cancel: CancelToken | None = None
    ) -> tuple[Sequence[int], Sequence[T]]:
        """The lines (ascending) where the function gave something, and what it gave.

        A set ``cancel`` token is looked at every :data:`~fanuc_macro.cancel.SLICE` lines
        looked at; a cancelled look keeps the last version as it was."""
        parsed = lines_of(doc)
        with self._lock:
            last = self._versions.pop(doc.uri, None)
        if last is not None and last.doc is doc:
            version = last
        elif last is None:
            lines, values = self._look(parsed, 0, len(parsed), cancel)
            version = _Version(doc, parsed, lines, values)
        else:
            version = self._patched(last, doc, parsed, cancel)
        with self._lock:
            self._versions[doc.uri] = version
            while len(self._versions) > self._keep:
                del self._versions[next(iter(self._versions))]
        return version.lines, version.values

    def _patched(
        self, last: _Version[T], doc: Document, parsed: list[ParsedLine], cancel: CancelToken | None
    ) -> _Version[T]:
        edit = edit_between(last.parsed, parsed)
        before = bisect_left(last.lines, edit.head)
        after = bisect_left(last.lines, edit.old_end)
        lines, values = self._look(parsed, edit.head, edit.new_end, cancel)
        shift = edit.shift
        moved = last.lines[after:] if not shift else [line + shift for line in last.lines[after:]]
        return _Version(
            doc,
            parsed,
            [*last.lines[:before], *lines, *moved],
            [*last.values[:before], *values, *last.values[after:]],
        )

    def _look(
        self, parsed: Sequence[ParsedLine], start: int, end: int, cancel: CancelToken | None
    ) -> tuple[list[int], list[T]]:
        compute = self._compute
        lines: list[int] = []
        values: list[T] = []
        for line in range(start, end):
            if cancel is not None and line > start and line % SLICE == 0:
                cancel.reached(CHECKING, line, len(parsed))
            value = compute(parsed[line])
            if value is not None:
                lines.append(line)
                values.append(value)
        self.lines_computed += end - start
        return lines, values


__all__ = ["Edit", "LineMap", "edit_between", "lines_of"]
