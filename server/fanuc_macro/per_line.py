"""Values computed from one parsed line alone, cached while the line is in use.

Parsed lines are shared by every block with the same text (the parser caches them), so what
depends on a line's text only (its compiled statement, its line rules' findings, the meaning
its comment gives a variable) is worked out once per distinct line, not on every analysis.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Generic, TypeVar

from .syntax import ParsedLine

T = TypeVar("T")


class PerLine(Generic[T]):
    def __init__(self, compute: Callable[[ParsedLine], T], limit: int = 400_000) -> None:
        self._compute = compute
        self._limit = limit
        # id(line) -> (line, value): the entry keeps the line alive, so its id stays its own.
        self._cache: dict[int, tuple[ParsedLine, T]] = {}

    def __call__(self, parsed: ParsedLine) -> T:
        entry = self._cache.get(id(parsed))
        if entry is not None and entry[0] is parsed:
            return entry[1]
        if len(self._cache) >= self._limit:
            self._cache.clear()
        value = self._compute(parsed)
        self._cache[id(parsed)] = (parsed, value)
        return value
