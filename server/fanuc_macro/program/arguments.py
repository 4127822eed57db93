"""A macro's arguments: the local each argument letter of a call fills, and the locals a called
program names at all.

FANUC Custom Macro B (shared reference macro-b.md §5.2): argument specification I gives A #1,
B #2, C #3, I #4, J #5, K #6, D #7 ... Z #26; specification II gives A, B, C and up to ten sets
of I, J, K, filling #4-#33 in sets of three. A G65 or G66 call opens a new level of locals
holding the arguments; M98 opens none, so a subprogram reads and writes its caller's locals.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from types import MappingProxyType
from typing import NamedTuple

from ..syntax.parser import statements_of
from ..syntax.tree import Document, End, Goto, IfGoto, ParsedLine, While
from .index import Program
from .variables import ARGUMENT_VARIABLES

# A variable named by number, with the spaces FANUC allows (``# 4``, ``#04``); ``#[`` is an
# indirect one, whose number the text does not say.
_DIRECT = re.compile(r"#\s*0*(\d+)")
_INDIRECT = re.compile(r"#\s*\[")
# The variable a block assigns, after its optional block delete and N number.
_ASSIGNED = re.compile(r"\s*(?:/\d?\s*)?(?:N\s*\d+\s*)?(#\s*0*(\d+))\s*=")
# The letter that passes each local #1-#26 (specification I); #27-#33 only specification II's.
ARGUMENT_LETTER: Mapping[int, str] = MappingProxyType(
    {n: letter for letter, n in ARGUMENT_VARIABLES.items()}
)


def local_name(n: int) -> str:
    """``#18 (R)``: a local with the letter that passes it (specification I); ``#28``."""
    letter = ARGUMENT_LETTER.get(n)
    return f"#{n} ({letter})" if letter is not None else f"#{n}"


# Calls that open no level of locals: the called program shares this one's (M98, Haas M97).
_SHARING_CALLS = frozenset({"M98", "M97"})


def argument_numbers(letters: list[str]) -> list[int | None]:
    """The local each argument letter of a call fills, in order: specification I, and for an
    I, J or K that repeats or comes out of order, specification II (sets of three from #4; the
    later of two letters filling one local wins: ``I-3. I4. D5.`` gives #4 -3. and #7 5.)."""
    out: list[int | None] = []
    ijk_set = -1
    seen: set[str] = set()
    for letter in letters:
        if letter in "IJK":
            order = "IJK".index(letter)
            if ijk_set < 0 or letter in seen or any(order < "IJK".index(s) for s in seen):
                ijk_set += 1
                seen = set()
            seen.add(letter)
            number = 4 + 3 * ijk_set + order
            out.append(number if number <= 33 else None)
        else:
            out.append(ARGUMENT_VARIABLES.get(letter))
    return out


class LocalsNamed(NamedTuple):
    """What a program does with its locals #1-#33: those it names at all (``named``), those
    it reads before any block of it sets them, in the order of the lines (``read_first``),
    and those a value from its call can reach a read of (``used``; every named one when the
    program jumps, since a GOTO may skip a set)."""

    named: frozenset[int]
    read_first: tuple[int, ...]
    used: frozenset[int]


def locals_named(
    doc: Document, program: Program, with_subprograms: bool = True
) -> LocalsNamed | None:
    """What ``program``'s blocks do with the locals, anywhere outside comments (on any path,
    in any block, parsed or not); None when the text cannot say: an indirect variable
    ``#[...]`` may be any of them, and (``with_subprograms``) a subprogram it calls with M98
    shares them.

    Without jumps the blocks run in the order of the lines, loops aside: a read is covered by
    a set on an earlier line at its own loop level or an outer one (an inner loop may run no
    time; a set in ``IF [...] THEN`` counts as a read, as if it might not happen)."""
    if with_subprograms and any(call.kind in _SHARING_CALLS for call in program.calls):
        return None
    named: set[int] = set()
    assigned: set[int] = set()
    read_first: dict[int, None] = {}  # in the order of the lines
    jumps = False
    loops: list[float] = []  # the DO numbers open at a line, outermost first
    sets: dict[int, list[tuple[float, ...]]] = {}  # local -> the loop paths of its sets
    used: set[int] = set()
    for block in doc.blocks[program.first_line : program.end_line]:
        parsed = block.parsed
        for statement in statements_of(parsed.statement):
            if isinstance(statement, Goto | IfGoto):
                jumps = True
            elif isinstance(statement, End) and statement.loop_id in loops:
                del loops[loops.index(statement.loop_id) :]
        path = tuple(loops)
        for statement in statements_of(parsed.statement):
            if isinstance(statement, While):
                loops.append(statement.loop_id)
        if "#" not in parsed.text:
            continue
        use = _line_use(parsed, 0)
        if use is None:
            return None
        reads = use.reads
        for n in reads:  # '#1=#1+1' reads #1 before it sets it
            if n not in assigned:
                read_first[n] = None
            if not any(path[: len(outer)] == outer for outer in sets.get(n, ())):
                used.add(n)
        named.update(reads)
        target = use.sets
        if target is not None:
            named.add(target)
            assigned.add(target)
            sets.setdefault(target, []).append(path)
    return LocalsNamed(
        frozenset(named), tuple(read_first), frozenset(named) if jumps else frozenset(used)
    )


class LocalUse(NamedTuple):
    """A line's use of the locals #1-#33: the one it sets (None: none) and those it reads."""

    line: int
    sets: int | None
    reads: tuple[int, ...]  # in the order of the text ('#1=#1+1' reads #1 before it sets it)


def _line_use(parsed: ParsedLine, line: int) -> LocalUse | None:
    """The locals a line sets and reads, outside comments; None when it names one
    indirectly (``#[...]``: it may be any)."""
    text = parsed.text
    for comment in parsed.comments:  # blanked: a '#' in a comment names nothing
        start, end = comment.span.start, comment.span.end
        text = text[:start] + " " * (end - start) + text[end:]
    if _INDIRECT.search(text):
        return None
    target = _ASSIGNED.match(text)
    at = -1 if target is None else target.start(1)
    reads = tuple(
        n for m in _DIRECT.finditer(text) if m.start() != at and 1 <= (n := int(m.group(1))) <= 33
    )
    sets = None if target is None else int(target.group(2))
    return LocalUse(line, sets if sets is not None and 1 <= sets <= 33 else None, reads)


def local_uses(doc: Document, program: Program) -> list[LocalUse] | None:
    """The lines of ``program`` that name a local, in order; None when an indirect variable
    ``#[...]`` may be any of them."""
    uses: list[LocalUse] = []
    for line in range(program.first_line, program.end_line):
        parsed = doc.blocks[line].parsed
        if "#" not in parsed.text:
            continue
        use = _line_use(parsed, line)
        if use is None:
            return None
        if use.reads or use.sets is not None:
            uses.append(use)
    return uses
