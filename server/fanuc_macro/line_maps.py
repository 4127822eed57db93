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
:class:`Diff` serves other sequences too, such as a run's motions compared by identity.
"""

from __future__ import annotations

import threading
import weakref
from bisect import bisect_left
from collections.abc import Callable, Iterator, Sequence
from itertools import compress
from operator import attrgetter, is_, itemgetter, not_
from typing import Generic, TypeVar

from .cancel import CHECKING, SLICE, CancelToken
from .syntax.tree import Document, ParsedLine

T = TypeVar("T")
U = TypeVar("U")

# Documents (or runs) whose last version a map keeps: the open ones and a few more.
KEPT = 16


def common_prefix(a: Sequence[object], b: Sequence[object], identical: bool = False) -> int:
    """How many first items of ``a`` and ``b`` are equal (``identical``: the same objects).

    A bisection over slices: each comparison runs at C speed, and the slices compared add up to
    about the length of the common part."""
    lo, hi = 0, min(len(a), len(b))
    same = _identical if identical else _equal
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if same(a[lo:mid], b[lo:mid]):
            lo = mid
        else:
            hi = mid - 1
    return lo


def common_suffix(
    a: Sequence[object], b: Sequence[object], limit: int, identical: bool = False
) -> int:
    """How many last items of ``a`` and ``b`` are equal, at most ``limit``."""
    lo, hi = 0, min(len(a), len(b), limit)
    na, nb = len(a), len(b)
    same = _identical if identical else _equal
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if same(a[na - mid : na - lo], b[nb - mid : nb - lo]):
            lo = mid
        else:
            hi = mid - 1
    return lo


def _equal(a: Sequence[object], b: Sequence[object]) -> bool:
    return a == b


def _identical(a: Sequence[object], b: Sequence[object]) -> bool:
    return all(map(is_, a, b))


class Diff:
    """Where a new version of a sequence differs from the one before: its items before
    ``start`` and from ``end`` on are the old version's, the old ones from ``old_end`` on moved
    by ``shift`` (the items the change added, less those it removed)."""

    __slots__ = ("end", "old_end", "shift", "start")

    def __init__(self, old: Sequence[object], new: Sequence[object], identical: bool) -> None:
        start = common_prefix(old, new, identical)
        tail = common_suffix(old, new, min(len(old), len(new)) - start, identical)
        self.start = start
        self.end = len(new) - tail
        self.old_end = len(old) - tail
        self.shift = len(new) - len(old)

    def moved(self, old: int) -> int | None:
        """Where the old version's item ``old`` stands in the new one (None: the change
        replaced it)."""
        if old < self.start:
            return old
        if old >= self.old_end:
            return old + self.shift
        return None

    def before(self, new: int) -> int | None:
        """Where the new version's item ``new`` stood in the old one (None: the change put
        it in)."""
        if new < self.start:
            return new
        if new >= self.end:
            return new - self.shift
        return None


# The last few pairs of versions compared, by weak reference: a version the server no longer
# holds is freed with its blocks (a document of 100,000 lines edited where lines move makes a
# new block for every line after the edit, about 5 MB a version).
_diffs: list[tuple[weakref.ref[Document], weakref.ref[Document], Diff]] = []
_diffs_lock = threading.Lock()


def line_diff(old: Document, new: Document) -> Diff:
    """Which lines of ``new`` differ from ``old`` (worked out once per pair of versions: the
    maps of one analysis all compare with the same version before)."""
    with _diffs_lock:
        for a, b, diff in _diffs:
            if a() is old and b() is new:
                return diff
    if len(old.blocks) == len(new.blocks):
        # Blocks compare by line number and parsed line, the same object for unchanged text.
        diff = Diff(old.blocks, new.blocks, identical=False)
    else:
        # Lines moved: the blocks after the edit differ by their number, not their line.
        diff = Diff(_parsed(old), _parsed(new), identical=False)
    with _diffs_lock:
        _diffs.insert(0, (weakref.ref(old), weakref.ref(new), diff))
        del _diffs[4:]
    return diff


def _parsed(doc: Document) -> list[ParsedLine]:
    return list(map(itemgetter(1), doc.blocks))  # Block.parsed, read in C


class Kept(Generic[U]):
    """A few keys' last values, the least recently stored dropped first."""

    def __init__(self) -> None:
        self._items: dict[str, U] = {}
        self._lock = threading.Lock()

    def get(self, key: str) -> U | None:
        return self._items.get(key)

    def put(self, key: str, value: U) -> None:
        with self._lock:
            self._items.pop(key, None)
            self._items[key] = value
            while len(self._items) > KEPT:
                del self._items[next(iter(self._items))]


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

    def __init__(self, look: Callable[[ParsedLine], T | None]) -> None:
        self._look = look
        self._kept: Kept[Found[T]] = Kept()
        self.looked = 0  # lines looked at over the map's life, for the tests of the work done

    def __call__(self, doc: Document, cancel: CancelToken | None = None) -> Found[T]:
        """What the map found in ``doc``. A set ``cancel`` token is looked at every
        :data:`~fanuc_macro.cancel.SLICE` lines looked at; a cancelled look keeps the last
        version as it was."""
        last = self._kept.get(doc.uri)
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
        wanted = _unbare(doc, start, end)
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
        self.looked += end - start
        return lines, values


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


__all__ = ["KEPT", "Diff", "Found", "Kept", "LineMap", "common_prefix", "line_diff"]
