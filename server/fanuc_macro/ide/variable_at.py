"""The Macro B variable under the mouse, for the debugger's hover: the editor's own word would
be ``123`` of ``#123`` and drop the ``#``, so the server gives it the whole variable."""

from __future__ import annotations

__all__ = ("variable_at",)

_DIGITS = frozenset("0123456789")
_NAME_CHARACTERS = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_")


def _closing_bracket(line: str, opening: int) -> int:
    """The end of the ``[...]`` that opens at ``opening``, nested brackets included; -1 when it
    is not closed (a ``(`` starts a comment: Macro B brackets are only ``[ ]``)."""
    depth = 0
    for i in range(opening, len(line)):
        ch = line[i]
        if ch == "[":
            depth += 1
        elif ch == "]":
            depth -= 1
            if depth == 0:
                return i + 1
        elif ch == "(":
            return -1
    return -1


def _variable_from(line: str, hash_at: int) -> tuple[int, int] | None:
    """The variable the ``#`` at ``hash_at`` starts: ``#123``, ``#[expression]``, or a system
    variable's name such as ``#_UI[2]`` or ``#<NAME>``; None when nothing follows the ``#``."""
    end = hash_at + 1
    following = line[end : end + 1]
    if following == "[":
        close = _closing_bracket(line, end)
        return None if close < 0 else (hash_at, close)
    if following == "<":
        close = line.find(">", end)
        return None if close < 0 else (hash_at, close + 1)
    if following and following in _DIGITS:
        while end < len(line) and line[end] in _DIGITS:
            end += 1
        return hash_at, end
    if following == "_":
        while end < len(line) and line[end] in _NAME_CHARACTERS:
            end += 1
        if line[end : end + 1] == "[":
            close = _closing_bracket(line, end)
            end = close if close > 0 else end
        return (hash_at, end) if end > hash_at + 2 else None
    return None


def _in_comments(line: str) -> list[bool]:
    inside = [False] * len(line)
    depth = 0
    for i, ch in enumerate(line):
        depth += ch == "("
        inside[i] = depth > 0
        if ch == ")" and depth > 0:
            depth -= 1
    return inside


def variable_at(line: str, column: int) -> tuple[int, int] | None:
    """The columns (start, end excluded) of the variable under ``column`` of ``line``: of the
    variables that hold the column the shortest, so that ``#1`` of ``#[#1+1]`` is ``#1`` and
    the ``+`` the whole ``#[#1+1]``. None off a variable and in comments."""
    comments = _in_comments(line)
    if 0 <= column < len(line) and comments[column]:
        return None
    best: tuple[int, int] | None = None
    for hash_at in [i for i, ch in enumerate(line) if ch == "#" and not comments[i]]:
        found = _variable_from(line, hash_at)
        if found is None or not found[0] <= column < found[1]:
            continue
        if best is None or found[1] - found[0] < best[1] - best[0]:
            best = found
    return best
