"""Document highlight: what the cursor is on and the other places in the document that name it.

A variable's reads and writes (in its program for a local ``#1``-``#33``, in the whole document
for the others, which every program shares); a label with what jumps or returns to it; a
program number with its O line and the calls of it in this document.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from .data import Range
from .locate import number_of, uses
from .number_uses import (
    Named,
    NumberUse,
    call_digits,
    calls_in,
    documents_of,
    label_uses,
    named_at,
    program_uses,
    resolve,
)
from .view import View, lines_of


class HighlightKind(str, Enum):
    TEXT = "text"  # a label or program number
    READ = "read"
    WRITE = "write"


@dataclass(frozen=True)
class Highlight:
    range: Range
    kind: HighlightKind


def highlights(view: View, line: int, column: int) -> list[Highlight]:
    """The places of the document that name what is at ``line``, ``column``, in order."""
    found = view.hit_at(line, column)
    if found is None:
        return []
    block, hit = found
    if hit.kind == "var" and hit.var is not None:
        n = number_of(hit.var)
        if n is None:
            return []
        local = 1 <= n <= 33
        first, end = (
            lines_of(view.index.program_at(block.line), view.doc)
            if local
            else (0, len(view.doc.blocks))
        )
        return [
            Highlight(
                Range.of(use.line, use.var.span.start, use.line, use.var.span.end),
                HighlightKind.WRITE if use.assign is not None else HighlightKind.READ,
            )
            for use in uses(view.doc.blocks, first, end)
            if number_of(use.var) == n
        ]
    named = named_at(view, line, hit)
    if not isinstance(named, Named):
        return []
    if named.kind == "label":
        assert named.program is not None
        places = label_uses(view, named.program, named.number)
    else:
        documents = documents_of(view)
        program = resolve(documents, view.key, named.number)
        if program is None:  # a program found nowhere: the calls of its number here
            places = [
                NumberUse(
                    view.key, call.line, call_digits(view.doc.blocks[call.line].text, call), "call"
                )
                for _, call in calls_in(view.index)
                if call.program == named.number and call.program_span is not None
            ]
        else:
            places = program_uses(documents, program[0], program[1], only=view.key)
    return [
        Highlight(Range.of(use.line, use.span.start, use.line, use.span.end), HighlightKind.TEXT)
        for use in sorted(places, key=lambda use: (use.line, use.span.start))
    ]
