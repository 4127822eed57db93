"""Scans of a whole document or a whole run that the next analysis does again only where the
document or the run changed.

The language server analyses a document on every keystroke; the threading rules ask for the
few lines whose comments name a thread or a variable's role, and for the few motions that cut
a thread, out of tens of thousands. A scan keeps, per document, what it found in the last
version it saw: in the next version the lines before the first changed one and after the last
(the parser shares the parsed lines of unchanged text) keep their findings, moved by the lines
added or removed, and only the lines between are looked at again. The motions of a resumed
run are the earlier run's own records before the resumption and after the point where it met
the earlier run again (:mod:`fanuc_macro.evaluator.checkpoints`), so the same holds of them,
by identity.
"""

from __future__ import annotations

import threading
from bisect import bisect_left
from collections.abc import Callable, Sequence
from operator import is_, itemgetter
from typing import Generic, TypeVar

from ..syntax import Document, ParsedLine

T = TypeVar("T")
U = TypeVar("U")

# Documents (or runs) a scan keeps its last findings for: the open ones and a few more.
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


def update_found(
    found: list[tuple[int, T]], diff: Diff, middle: list[tuple[int, T]]
) -> list[tuple[int, T]]:
    """``found`` (by position, in order) of the old version, for the new one: those before the
    change, ``middle`` (what the changed stretch holds), those after it moved."""
    positions = [at for at, _ in found]
    head = found[: bisect_left(positions, diff.start)]
    tail = found[bisect_left(positions, diff.old_end) :]
    if diff.shift:
        shift = diff.shift
        tail = [(at + shift, value) for at, value in tail]
    return [*head, *middle, *tail]


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


_diffs: list[tuple[Document, Document, Diff]] = []  # the last few pairs of versions compared


def line_diff(old: Document, new: Document) -> Diff:
    """Which lines of ``new`` differ from ``old`` (worked out once per pair of versions: the
    scans of one analysis all compare with the same version before)."""
    for a, b, diff in _diffs:
        if a is old and b is new:
            return diff
    if len(old.blocks) == len(new.blocks):
        # Blocks compare by line number and parsed line; the parser shares the parsed line
        # of an unchanged text, so the comparison is by pointer, at C speed.
        diff = Diff(old.blocks, new.blocks, identical=False)
    else:
        # Lines moved: the blocks after the edit differ by their number, not their line.
        diff = Diff(_parsed(old), _parsed(new), identical=False)
    _diffs.insert(0, (old, new, diff))
    del _diffs[4:]
    return diff


def _parsed(doc: Document) -> list[ParsedLine]:
    return list(map(itemgetter(1), doc.blocks))  # Block.parsed


class LineScan(Generic[T]):
    """The lines of a document for which ``look(parsed)`` finds something (not None), with
    what it found, in line order; ``look`` depends on the parsed line alone."""

    def __init__(self, look: Callable[[ParsedLine], T | None]) -> None:
        self._look = look
        self._kept: Kept[tuple[Document, list[tuple[int, T]]]] = Kept()
        self.looked = 0  # lines looked at, for the tests of the work done

    def __call__(self, doc: Document) -> list[tuple[int, T]]:
        kept = self._kept.get(doc.uri)
        if kept is None:
            found = self._scan(doc, 0, len(doc.blocks))
        else:
            old, old_found = kept
            if old is doc:
                return old_found
            diff = line_diff(old, doc)
            found = update_found(old_found, diff, self._scan(doc, diff.start, diff.end))
        self._kept.put(doc.uri, (doc, found))
        return found

    def _scan(self, doc: Document, start: int, end: int) -> list[tuple[int, T]]:
        look = self._look
        blocks = doc.blocks
        found: list[tuple[int, T]] = []
        for at in range(start, end):
            value = look(blocks[at].parsed)
            if value is not None:
                found.append((at, value))
        self.looked += end - start
        return found


def within(found: list[tuple[int, T]], start: int, end: int) -> list[tuple[int, T]]:
    """The findings of the lines ``start`` to ``end`` (exclusive)."""
    positions = [at for at, _ in found]
    return found[bisect_left(positions, start) : bisect_left(positions, end)]
