"""Loops that count in a common variable, and whether any block sets that variable to a
start value: read from the text of the programs checked together.

A common variable (#100-#199, #500-#999, the extended range) keeps its value from one run or
call to the next; a WHILE loop that counts its turns in one must set it before it starts.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from ..syntax.parser import statements_of
from ..syntax.tree import Assign, Document, Mixed, ParsedLine, Var, While
from ..syntax.walk import cond_exprs, subexpressions
from .index import Loop
from .variables import classify

COMMON_KINDS = frozenset({"common", "retained", "extended-common"})


def _numbers(exprs: Iterable[object]) -> set[int]:
    """The variables named directly (``#100``) in expressions; -1 for an indirect one."""
    found: set[int] = set()
    for expr in exprs:
        for node in subexpressions(expr):  # type: ignore[arg-type]
            if isinstance(node, Var):
                found.add(-1 if node.number is None else int(node.number))
    return found


def commons_tested(parsed: ParsedLine) -> frozenset[int] | None:
    """The common variables a WHILE block's condition names directly; None for any other
    block, or a WHILE that names none."""
    kind = type(parsed.statement)
    if kind is not While and kind is not Mixed:
        return None  # most blocks, at once
    for statement in statements_of(parsed.statement):
        if isinstance(statement, While) and statement.cond is not None:
            tested = frozenset(
                n
                for n in _numbers(cond_exprs(statement.cond))
                if n > 0 and classify(n).kind in COMMON_KINDS
            )
            return tested or None
    return None


def loop_counters(doc: Document, loop: Loop, tested: frozenset[int]) -> dict[int, int]:
    """Of the common variables a WHILE loop tests (``tested``, :func:`commons_tested`), those
    its body adds to from themselves (``#100 = #100 + 1``): by number, the line of that
    update."""
    if loop.end_line is None:
        return {}
    counters: dict[int, int] = {}
    for line in range(loop.do_line + 1, loop.end_line):
        for statement in statements_of(doc.blocks[line].parsed.statement):
            if not isinstance(statement, Assign) or statement.target.number is None:
                continue
            n = int(statement.target.number)
            if n in tested and n in _numbers([statement.value]):
                counters.setdefault(n, line)
    return counters


def start_values(docs: Iterable[Document], number: int) -> Iterator[tuple[Document, int]]:
    """The blocks that may set ``number`` to a start value: an assignment to it that does
    not read it, or any assignment to an indirect variable (it may be that one)."""
    for doc in docs:
        for line, block in enumerate(doc.blocks):
            if "=" not in block.text:
                continue
            for statement in statements_of(block.parsed.statement):
                if not isinstance(statement, Assign):
                    continue
                target = statement.target
                if target.number is None or (
                    int(target.number) == number and number not in _numbers([statement.value])
                ):
                    yield doc, line
