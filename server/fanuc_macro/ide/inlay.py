"""Inlay hints: the value of an assignment the analysis ran, where the text does not show it."""

from __future__ import annotations

from ..syntax.parser import statements_of
from ..syntax.tree import Bracket, Expr, Num, Unary
from .data import InlayHint, Position
from .locate import assignments_in
from .values import short_summary
from .view import View


def _written_number(expr: Expr) -> bool:
    """Whether ``expr`` is a number as written (``50.``, ``-2.5``, ``[10]``): its hint would
    repeat the text."""
    while isinstance(expr, Unary | Bracket):
        expr = expr.operand if isinstance(expr, Unary) else expr.inner
    return isinstance(expr, Num)


def inlay_hints(view: View, first: int, last: int) -> list[InlayHint]:
    """``= value`` after every assignment the analysis ran in the lines ``first``..``last``,
    but for one of a written number (``#100=50.``), whose value the line already shows. The
    protocol's front end puts a gap before the hint."""
    facts = view.facts
    if facts is None:
        return []
    hints: list[InlayHint] = []
    for line in sorted(ln for ln in facts.writes if first <= ln <= last):
        if not facts.runs.get(line):
            continue
        block = view.block(line)
        if block is None:
            continue
        number, summary = facts.writes[line]
        label = short_summary(summary)
        if label is None:
            continue
        assign = next(
            (
                a
                for s in statements_of(block.statement)
                for a in assignments_in(s)
                if not _written_number(a.value)
            ),
            None,
        )
        if assign is None:
            continue
        hints.append(
            InlayHint(
                Position(line, assign.span.end),
                label=f"= {label}",
                tooltip=f"#{number} = {summary.describe()}",
            )
        )
    return hints
