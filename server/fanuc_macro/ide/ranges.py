"""Folding ranges and selection ranges: the shapes of a document by its lines and its syntax.

Folding: each O program (its O line to its last M99/M30/M02, or to the line before the next
program), each ``WHILE``..``END`` loop (the ``END`` stays in sight), Haas block ``IF``..``ELSE``..
``ENDIF`` (the one dialect with block IFs; FANUC's ``IF [..] THEN`` is one block), and runs of
comment-only lines. Selection: from the innermost expression at the cursor out through the
brackets, the word and the statement, to the block, the loop bodies and the program.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from ..program.index import Program
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import Block, BlockIf, NcStatement, Span
from ..syntax.walk import subexpressions, top_expressions
from .data import Position, Range
from .number_uses import nc_parts
from .view import View

PROGRAM_ENDS = frozenset({2.0, 30.0, 99.0})  # M02, M30, M99


class FoldKind(str, Enum):
    REGION = "region"
    COMMENT = "comment"


@dataclass(frozen=True, order=True)
class Fold:
    start: int  # the line that stays in sight
    end: int  # the last line folded away
    kind: FoldKind


def folding_ranges(view: View) -> list[Fold]:
    """The folds of the document, in order of their first line (then the longest first)."""
    blocks = view.doc.blocks
    out: set[Fold] = set()
    for program in view.index.programs:
        last = _program_end(blocks, program)
        if last > program.first_line:
            out.add(Fold(program.first_line, last, FoldKind.REGION))
        for loop in program.loops:
            if loop.end_line is not None and loop.end_line - 1 > loop.do_line:
                out.add(Fold(loop.do_line, loop.end_line - 1, FoldKind.REGION))
    out.update(_block_ifs(blocks))
    out.update(_comment_runs(blocks))
    return sorted(out, key=lambda f: (f.start, -f.end, f.kind.value))


def _program_end(blocks: tuple[Block, ...], program: Program) -> int:
    """The program's last M99/M30/M02, else its last line that holds anything."""
    end = min(program.end_line, len(blocks))
    last_code = program.first_line
    for line in range(end - 1, program.first_line - 1, -1):
        parsed = blocks[line].parsed
        text = blocks[line].text
        if ("M" in text or "m" in text) and any(
            w.address == "M" and constant_value(w.value) in PROGRAM_ENDS
            for nc in nc_parts(blocks[line])
            for w in nc.words
        ):
            return line
        if last_code == program.first_line and (parsed.statement is not None or parsed.comments):
            last_code = line
    return last_code


def _block_ifs(blocks: tuple[Block, ...]) -> list[Fold]:
    out: list[Fold] = []
    open_at: list[int] = []  # the IF or ELSE line each open block IF folds from
    for block in blocks:
        for statement in statements_of(block.statement):
            if not isinstance(statement, BlockIf):
                continue
            if statement.keyword == "IF":
                open_at.append(block.line)
            elif open_at:
                start = open_at.pop()
                if block.line - 1 > start:
                    out.append(Fold(start, block.line - 1, FoldKind.REGION))
                if statement.keyword == "ELSE":
                    open_at.append(block.line)
    return out


def _comment_only(block: Block) -> bool:
    parsed = block.parsed
    return (
        bool(parsed.comments)
        and parsed.statement is None
        and parsed.seq is None
        and not parsed.tape_mark
        and parsed.problem is None
    )


def _comment_runs(blocks: tuple[Block, ...]) -> list[Fold]:
    out: list[Fold] = []
    start: int | None = None
    for block in (*blocks, None):
        if block is not None and _comment_only(block):
            if start is None:
                start = block.line
            continue
        if start is not None:
            last = (block.line if block is not None else len(blocks)) - 1
            if last > start:
                out.append(Fold(start, last, FoldKind.COMMENT))
            start = None
    return out


# ---- selection ranges ------------------------------------------------------------------------


def selection_ranges(view: View, positions: list[Position]) -> list[list[Range]]:
    """For each position, the ranges around it from the innermost out, each holding the one
    before: expressions, brackets, the NC word, the statement, the block, loops, the program."""
    return [_around(view, p.line, p.column) for p in positions]


def _around(view: View, line: int, column: int) -> list[Range]:
    block = view.block(line)
    if block is None:
        return [Range.of(line, column, line, column)]
    spans: list[Span] = []
    for statement in statements_of(block.statement):
        spans.append(statement.span)
        if isinstance(statement, NcStatement):
            spans.extend(w.span for w in statement.words)
        for expr in top_expressions(statement):
            spans.extend(node.span for node in subexpressions(expr))
    for nc in nc_parts(block):
        spans.append(nc.span)
        spans.extend(w.span for w in nc.words)
    if block.statement is not None:
        spans.append(block.statement.span)
    if block.parsed.seq_span is not None:
        spans.append(block.parsed.seq_span)
    holding = sorted(
        {s for s in spans if s.start <= column <= s.end and s.end > s.start},
        key=lambda s: (s.end - s.start, s.start),
    )
    out: list[Range] = []
    for span in holding:
        if out and not (out[-1].start.column >= span.start and out[-1].end.column <= span.end):
            continue  # not around the one before: a sibling
        out.append(Range.of(line, span.start, line, span.end))
    text = view.text(view.key, line)
    whole = Range.of(line, 0, line, len(text))
    if not out or out[-1] != whole:
        out.append(whole)
    program = view.index.program_at(line)
    if program is not None:
        for loop in reversed(program.enclosing_loops(line)):
            assert loop.end_line is not None  # only closed loops hold lines
            if loop.do_line < line < loop.end_line and loop.end_line - loop.do_line > 1:
                _push(out, _lines(view, loop.do_line + 1, loop.end_line - 1))  # the body
            _push(out, _lines(view, loop.do_line, loop.end_line))
        _push(out, _lines(view, program.first_line, _program_end(view.doc.blocks, program)))
    return out


def _lines(view: View, first: int, last: int) -> Range:
    return Range.of(first, 0, last, len(view.text(view.key, last)))


def _push(out: list[Range], r: Range) -> None:
    """Add ``r`` when it holds the last range and is larger."""
    last = out[-1]
    if r == last or not (r.start <= last.start and last.end <= r.end):
        return
    out.append(r)
