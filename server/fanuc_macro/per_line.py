"""Values computed from one parsed line alone, cached while the line is in use.

Parsed lines are shared by every block with the same text (the parser caches them), so what
depends on a line's text only (its compiled statement, its line rules' findings, the meaning
its comment gives a variable) is worked out once per distinct line, not on every analysis.
A :class:`PerLine` is a declaration; its cache is the current database's
(:mod:`fanuc_macro.database`), so each workspace keeps its own and frees it with itself.
"""

from __future__ import annotations

from collections.abc import Callable
from itertools import islice
from typing import Any, Generic, TypeVar

from .database import TableKey, current
from .syntax.tree import ParsedLine

T = TypeVar("T")


class _Entry:
    """A cached value: the line it is of (another parse of the same text, with other limits,
    may differ), the value and when it was last used. Slots: a cache holds one per distinct
    line of the documents analysed (a list of three costs half as much again)."""

    __slots__ = ("line", "used", "value")

    def __init__(self, line: ParsedLine, value: Any, used: int) -> None:
        self.line = line
        self.value = value
        self.used = used


class PerLine(Generic[T]):
    """A cache of ``compute(line)`` holding at most ``limit`` lines, the least recently used
    evicted first.

    Age is counted in misses: an entry is in use while it was asked for within the last
    ``limit`` misses. When the cache is full, the oldest entries of its insertion order are
    looked at in batches: those in use go to the end (the order follows use lazily, so a hit
    only stamps its entry), the others are dropped. When every entry is in use, a new value is
    returned without being kept: analysing a document of more distinct lines than ``limit``
    keeps the same ``limit`` lines from one analysis to the next and computes only the others,
    where strict LRU order would evict each line just before it is asked for again.

    Entries are found by the line's text, whose hash the string keeps (an id would be a new
    int per entry), and stamped with the miss count at the last multiple of the batch, one
    int shared by the entries of a batch (the sweep allows for the batch it may be behind).
    """

    __slots__ = ("_compute", "_limit")

    def __init__(self, compute: Callable[[ParsedLine], T], limit: int = 400_000) -> None:
        self._compute = compute
        self._limit = limit

    def cache(self) -> _LineCache[T]:
        """This declaration's cache in the current database, made on first use."""
        caches = current().table(_CACHES)
        found: _LineCache[T] | None = caches.get(self)
        if found is None:
            found = caches.setdefault(self, _LineCache(self._compute, self._limit))
        return found

    def __len__(self) -> int:
        return len(self.cache().entries)

    def __contains__(self, parsed: ParsedLine) -> bool:
        entry = self.cache().entries.get(parsed.text)
        return entry is not None and entry.line is parsed

    def __call__(self, parsed: ParsedLine) -> T:
        # The hit path inline: one database look-up, then the entry (no call of the cache's).
        cache: _LineCache[T] | None = current().table(_CACHES).get(self)
        if cache is None:
            cache = self.cache()
        entry = cache.entries.get(parsed.text)
        if entry is not None and entry.line is parsed:
            entry.used = cache.stamp
            value: T = entry.value
            return value
        return cache.miss(parsed)


class _LineCache(Generic[T]):
    """The storage of one :class:`PerLine` in one database: the entries by the line's text and
    the counts of the eviction (see :class:`PerLine`)."""

    __slots__ = ("batch", "compute", "entries", "limit", "misses", "next_sweep", "stamp")

    def __init__(self, compute: Callable[[ParsedLine], T], limit: int) -> None:
        self.compute = compute
        self.limit = limit
        self.batch = max(1, limit // 8)
        self.entries: dict[str, _Entry] = {}  # by the line's text
        self.misses = 0
        self.stamp = 0  # the miss count at the last multiple of the batch
        self.next_sweep = 0  # no sweep before this miss count: the last one found all in use

    def __len__(self) -> int:
        return len(self.entries)

    def __call__(self, parsed: ParsedLine) -> T:
        entry = self.entries.get(parsed.text)
        if entry is not None and entry.line is parsed:
            entry.used = self.stamp
            value: T = entry.value
            return value
        return self.miss(parsed)

    def miss(self, parsed: ParsedLine) -> T:
        value = self.compute(parsed)
        self.misses += 1
        if self.misses - self.stamp >= self.batch:
            self.stamp = self.misses
        if len(self.entries) >= self.limit:
            self._evict()
        if len(self.entries) < self.limit:
            self.entries[parsed.text] = _Entry(parsed, value, self.stamp)
        return value

    def _evict(self) -> None:
        if self.misses < self.next_sweep:
            return
        cache = self.entries
        # Used at or before this miss (a stamp is up to a batch behind): not in use.
        oldest = self.misses - self.limit - self.batch
        dropped = 0
        for key in list(islice(cache, self.batch)):
            entry = cache.pop(key, None)  # None: another thread's sweep took it
            if entry is None:
                continue
            if entry.used > oldest:
                cache[key] = entry  # in use: to the end of the order
            else:
                dropped += 1
        if not dropped:
            self.next_sweep = self.misses + self.batch


# Each database's caches, by their declaration.
_CACHES: TableKey[PerLine[Any], _LineCache[Any]] = TableKey("per_line.caches", cache=True)
