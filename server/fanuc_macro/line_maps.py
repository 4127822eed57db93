"""The few lines of a document that hold something, kept from one version to the next.

Many rules look at every line of a document for the few that matter: the lines with a line
rule's finding, the ends of programs, the marks of another control's dialect, the #200-#499
named, the comments that name a thread or a variable's role. On a document of 20,000 lines
that look costs milliseconds on every keystroke, though an edit changes a line or two. A
:class:`LineMap` keeps, per document, the lines where its per-line function found something
and what it found; in the next version of the document it looks again only at the stretch of
lines the edit changed (:func:`line_diff`: the parser shares the parsed line of an unchanged
text, so the comparison is by pointer, at C speed) and moves the lines after it by the lines
added or removed.

What a map gives is always what a look at every line would give: the per-line function depends
on the line's text alone, and the comparison finds every line that differs from whatever
version the map saw last (``tests/test_line_maps.py`` compares the two after random edits).
:class:`Diff` (in :mod:`fanuc_macro.syntax.diff`) serves other sequences too, such as a run's
motions compared by identity. A map or a :class:`Kept` is a declaration: what it keeps is the
current database's (:mod:`fanuc_macro.database`), by document, freed when the document closes.
"""

from __future__ import annotations

from bisect import bisect_left
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from itertools import compress
from operator import attrgetter, itemgetter, not_
from typing import Any, Generic, TypeVar

from .cancel import CHECKING, SLICE, CancelToken
from .database import TableKey, current
from .syntax.diff import Diff, common_prefix, common_suffix, line_diff
from .syntax.tree import Document, ParsedLine

T = TypeVar("T")
U = TypeVar("U")

# Documents (or runs) whose last version a map keeps: the open ones and a few more.
KEPT = 16


@dataclass(frozen=True, eq=False)
class Kept(Generic[U]):
    """The last values of a few documents (by URI), the least recently stored dropped first,
    kept in the current database (a per-document table: closing a document frees its value).
    """

    name: str = "line_maps.kept"
    table: TableKey[str, U] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "table", TableKey(self.name, per_document=True))

    def get(self, key: str) -> U | None:
        return current().table(self.table).get(key)

    def put(self, key: str, value: U) -> None:
        items = current().table(self.table)
        items.pop(key, None)
        items[key] = value
        while len(items) > KEPT:  # the oldest first; another thread's put may drop it first
            try:
                del items[next(iter(items))]
            except (KeyError, RuntimeError, StopIteration):
                break


class Found(Generic[T]):
    """The lines of one version of a document where a map found something, ascending, with
    what it found."""

    __slots__ = ("doc", "lines", "values")

    def __init__(self, doc: Document, lines: list[int], values: list[T]) -> None:
        self.doc = doc
        self.lines = lines
        self.values = values

    def __iter__(self) -> Iterator[tuple[int, T]]:
        return zip(self.lines, self.values, strict=True)

    def __len__(self) -> int:
        return len(self.lines)

    def between(self, first: int, end: int) -> range:
        """The positions in ``lines`` and ``values`` of the lines ``first`` to ``end``
        (exclusive)."""
        return range(bisect_left(self.lines, first), bisect_left(self.lines, end))

    def within(self, first: int, end: int) -> list[tuple[int, T]]:
        """The lines ``first`` to ``end`` (exclusive) with what was found on them."""
        at = self.between(first, end)
        return list(
            zip(self.lines[at.start : at.stop], self.values[at.start : at.stop], strict=True)
        )


_PARSED = itemgetter(1)  # Block.parsed, read in C


class LineMap(Generic[T]):
    """The lines of a document where ``look(parsed)`` finds something (a true value), for the
    last :data:`KEPT` documents asked about (by URI): the next version of a document is looked
    at only where it differs from the last.

    ``look`` must depend on the parsed line alone (such as a :class:`~fanuc_macro.per_line.
    PerLine` function)."""

    __slots__ = ("_kept", "_look", "every_line")

    def __init__(self, look: Callable[[ParsedLine], T | None], every_line: bool = False) -> None:
        self._look = look
        # Whether ``look`` may find something in a bare line too (a Y word, a G91): then every
        # changed line is looked at, not only those that are not bare.
        self.every_line = every_line
        name = getattr(look, "__qualname__", "look")
        self._kept: Kept[Found[T]] = Kept(f"line_maps.{name}")

    @property
    def looked(self) -> int:
        """Lines looked at in the current database, for the tests of the work done."""
        return current().table(_LOOKED).get(self, 0)

    def __call__(self, doc: Document, cancel: CancelToken | None = None) -> Found[T]:
        """What the map found in ``doc``. A set ``cancel`` token is looked at every
        :data:`~fanuc_macro.cancel.SLICE` lines looked at; a cancelled look keeps the last
        version as it was."""
        kept = current().table(self._kept.table)
        last = kept.get(doc.uri)
        if last is not None and last.doc is doc:
            return last
        if last is None:
            lines, values = self._look_at(doc, 0, len(doc.blocks), cancel)
            found = Found(doc, lines, values)
        else:
            diff = line_diff(last.doc, doc)
            lines, values = self._look_at(doc, diff.start, diff.end, cancel)
            at = last.between(diff.start, diff.old_end)
            moved = last.lines[at.stop :]
            if diff.shift:
                moved = [line + diff.shift for line in moved]
            found = Found(
                doc,
                [*last.lines[: at.start], *lines, *moved],
                [*last.values[: at.start], *values, *last.values[at.stop :]],
            )
        self._kept.put(doc.uri, found)
        return found

    def _look_at(
        self, doc: Document, start: int, end: int, cancel: CancelToken | None
    ) -> tuple[list[int], list[T]]:
        look = self._look
        blocks = doc.blocks
        lines: list[int] = []
        values: list[T] = []
        # The lines that are not bare (in which no map finds anything), a slice at a time,
        # looked at in C but for ``look`` itself; the token is looked at every SLICE lines.
        wanted = range(start, end) if self.every_line else _unbare(doc, start, end)
        at = 0
        while at < len(wanted):
            low = wanted[at]
            if cancel is not None and low > start:
                cancel.reached(CHECKING, low, len(blocks))
            high = bisect_left(wanted, min((low // SLICE + 1) * SLICE, end), at)
            these = wanted[at:high]
            found = list(map(look, map(_PARSED, map(blocks.__getitem__, these))))
            lines += compress(these, found)
            values += filter(None, found)
            at = high
        looked = current().table(_LOOKED)
        looked[self] = looked.get(self, 0) + end - start
        return lines, values


# Lines each map looked at, by map, in each database.
_LOOKED: TableKey[LineMap[Any], int] = TableKey("line_maps.looked")


_BARE = attrgetter("bare")  # ParsedLine.bare, read in C


def _unbare(doc: Document, start: int, end: int) -> Sequence[int]:
    """The lines from ``start`` to ``end`` (exclusive) that are not ``ParsedLine.bare``, or a
    range of them all when most are not: those of the whole document are kept on it, for the
    maps that look at it after the first (each ``look`` is a Python call, the mask is made in
    C)."""
    whole = start == 0 and end == len(doc.blocks)
    if whole and doc.unbare is not None:
        return doc.unbare
    found = tuple(
        compress(range(start, end), map(not_, map(_BARE, map(_PARSED, doc.blocks[start:end]))))
    )
    wanted: Sequence[int] = found if 2 * len(found) < end - start else range(start, end)
    if whole:
        object.__setattr__(doc, "unbare", wanted)  # the same for every map: no lock needed
    return wanted


__all__ = (
    "KEPT",
    "Diff",
    "Found",
    "Kept",
    "LineMap",
    "common_prefix",
    "common_suffix",
    "line_diff",
)
