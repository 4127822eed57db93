"""Where a new version of a sequence differs from the one before.

:class:`Diff` finds the common head and tail of two versions, by bisection over slices
compared at C speed. :func:`line_diff` compares two versions of a document: the parser shares
the parsed line of an unchanged text, so the comparison is by pointer. The parser compares a
document's versions with it, the line maps find the lines an edit changed, and the evaluator
compares a run's motions by identity.
"""

from __future__ import annotations

import weakref
from collections.abc import Sequence
from operator import is_, itemgetter

from ..database import TableKey, current
from .tree import Document, ParsedLine


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


# The last few pairs of versions compared, by the ids of the two versions, each named by weak
# reference: a version the server no longer holds is freed with its blocks (a document of
# 100,000 lines edited where lines move makes a new block for every line after the edit, about
# 5 MB a version), and an id used again by a later version is told apart by its reference.
_DIFFS: TableKey[tuple[int, int], tuple[weakref.ref[Document], weakref.ref[Document], Diff]] = (
    TableKey("syntax.line_diffs", cache=True)
)
_DIFFS_KEPT = 4


def line_diff(old: Document, new: Document) -> Diff:
    """Which lines of ``new`` differ from ``old`` (worked out once per pair of versions: the
    maps of one analysis all compare with the same version before)."""
    diffs = current().table(_DIFFS)
    key = (id(old), id(new))
    found = diffs.get(key)
    if found is not None and found[0]() is old and found[1]() is new:
        return found[2]
    if len(old.blocks) == len(new.blocks):
        # Blocks compare by line number and parsed line, the same object for unchanged text.
        diff = Diff(old.blocks, new.blocks, identical=False)
    else:
        # Lines moved: the blocks after the edit differ by their number, not their line.
        diff = Diff(_parsed(old), _parsed(new), identical=False)
    diffs.pop(key, None)
    diffs[key] = (weakref.ref(old), weakref.ref(new), diff)
    while len(diffs) > _DIFFS_KEPT:  # the oldest first; another thread may drop it first
        try:
            del diffs[next(iter(diffs))]
        except (KeyError, RuntimeError, StopIteration):
            break
    return diff


def _parsed(doc: Document) -> list[ParsedLine]:
    return list(map(itemgetter(1), doc.blocks))  # Block.parsed, read in C


__all__ = ("Diff", "common_prefix", "common_suffix", "line_diff")
