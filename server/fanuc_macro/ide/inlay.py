"""Inlay hints: the value of every assignment the analysis ran."""

from __future__ import annotations

from ..syntax.parser import statements_of
from .data import InlayHint, Position
from .locate import assignments_in
from .values import short_summary
from .view import View


def inlay_hints(view: View, first: int, last: int) -> list[InlayHint]:
    """``= value`` after every assignment the analysis ran, in the lines ``first``..``last``."""
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
        assign = next((a for s in statements_of(block.statement) for a in assignments_in(s)), None)
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
