"""The few lines of a document that matter to a rule, kept from one analysis to the next.

Several rules look at every block of a document for something that only a handful of lines
hold (a #200-#499, a rejected block that may jump, a local variable read). The language server
analyses the same document again on every keystroke, and the parser keeps the blocks of the
lines an edit did not touch (:func:`fanuc_macro.parser.parse_text` with ``previous``): a
:class:`LineScan` compares the new blocks with those of the document's last scan, a comparison
of whole stretches at a time, and works out only the lines in between.
"""

from __future__ import annotations

import threading
from bisect import bisect_left
from collections.abc import Callable, Sequence
from operator import itemgetter
from typing import Generic, TypeVar

from ..syntax import Block, Document, ParsedLine

T = TypeVar("T")

_parsed_of = itemgetter(1)  # Block.parsed, without the attribute lookup


class Scanned(Generic[T]):
    """The lines of one version of a document whose piece is not empty, in order, with
    their pieces."""

    __slots__ = ("blocks", "lines", "pieces")

    def __init__(self, blocks: tuple[Block, ...], lines: list[int], pieces: list[T]) -> None:
        self.blocks = blocks
        self.lines = lines
        self.pieces = pieces

    def between(self, first: int, end: int) -> range:
        """Positions in ``lines`` (and ``pieces``) of the lines from ``first`` to before
        ``end``."""
        return range(bisect_left(self.lines, first), bisect_left(self.lines, end))


class LineScan(Generic[T]):
    """``piece(parsed)`` of each line of a document, keeping the lines whose piece is truthy.

    A piece depends on the line's text alone (not on where it stands), so a line the edit did
    not change keeps its piece, and the lines after an edit that added or removed some keep
    theirs under their new numbers. The last scan of the ``keep`` most recently scanned
    documents (by URI) is kept; whatever it was of, the comparison finds every line that
    differs, so a scan is never stale.
    """

    def __init__(self, piece: Callable[[ParsedLine], T], keep: int = 4) -> None:
        self._piece = piece
        self._keep = keep
        self._last: dict[str, Scanned[T]] = {}
        self._lock = threading.Lock()  # only around the dict: the analyses may be threads

    def __call__(self, doc: Document) -> Scanned[T]:
        blocks = doc.blocks
        with self._lock:
            before = self._last.get(doc.uri)
        if before is not None and before.blocks is blocks:
            return before
        scanned = self._scan(blocks) if before is None else self._rescan(before, blocks)
        with self._lock:
            self._last.pop(doc.uri, None)
            self._last[doc.uri] = scanned  # the most recent last
            while len(self._last) > self._keep:
                del self._last[next(iter(self._last))]
        return scanned

    def _pieces(self, blocks: Sequence[Block], shift: int = 0) -> tuple[list[int], list[T]]:
        piece = self._piece
        lines: list[int] = []
        pieces: list[T] = []
        for line, parsed in enumerate(map(_parsed_of, blocks), shift):
            found = piece(parsed)
            if found:
                lines.append(line)
                pieces.append(found)
        return lines, pieces

    def _scan(self, blocks: tuple[Block, ...]) -> Scanned[T]:
        lines, pieces = self._pieces(blocks)
        return Scanned(blocks, lines, pieces)

    def _rescan(self, before: Scanned[T], blocks: tuple[Block, ...]) -> Scanned[T]:
        head, old_end, new_end = edited(before.blocks, blocks)
        lines, pieces = before.lines, before.pieces
        lo, hi = bisect_left(lines, head), bisect_left(lines, old_end)
        mid_lines, mid_pieces = self._pieces(blocks[head:new_end], head)
        shift = new_end - old_end
        after = lines[hi:] if not shift else [line + shift for line in lines[hi:]]
        return Scanned(
            blocks,
            [*lines[:lo], *mid_lines, *after],
            [*pieces[:lo], *mid_pieces, *pieces[hi:]],
        )


# The last comparison: the scans of several rules compare the same two versions in a row.
_last_edit: tuple[tuple[Block, ...], tuple[Block, ...], tuple[int, int, int]] | None = None


def edited(old: tuple[Block, ...], new: tuple[Block, ...]) -> tuple[int, int, int]:
    """Where ``new`` differs from ``old``: (first line, end in ``old``, end in ``new``); the
    lines before and after are alike in both."""
    global _last_edit
    last = _last_edit
    if last is not None and last[0] is old and last[1] is new:
        return last[2]
    head = _common_head(old, new)
    # What follows the edit is compared by the lines' parse, which is the same object for a
    # line kept, wherever it stands now.
    room = min(len(old), len(new)) - head
    if len(old) == len(new):
        tail = _common_tail(old, new, room)
    else:
        tail = _common_tail(
            list(map(_parsed_of, old[len(old) - room :])),
            list(map(_parsed_of, new[len(new) - room :])),
            room,
        )
    found = (head, len(old) - tail, len(new) - tail)
    _last_edit = (old, new, found)
    return found


def _common_head(a: Sequence[object], b: Sequence[object]) -> int:
    """How many items ``a`` and ``b`` begin with alike: stretches compared whole (an item
    kept is the same object, which a comparison passes at once), halved near the end."""
    size = min(len(a), len(b))
    head = 0
    step = 1024
    while step:
        while head + step <= size and a[head : head + step] == b[head : head + step]:
            head += step
        step //= 2
    return head


def _common_tail(a: Sequence[object], b: Sequence[object], room: int) -> int:
    """How many items, at most ``room``, ``a`` and ``b`` end with alike."""
    tail = 0
    step = 1024
    na, nb = len(a), len(b)
    while step:
        while tail + step <= room and (
            a[na - tail - step : na - tail] == b[nb - tail - step : nb - tail]
        ):
            tail += step
        step //= 2
    return tail
