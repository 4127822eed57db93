"""What is under the cursor in a block: a variable, a function, an NC word, a label, a keyword."""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from ..program.variables import LOCAL_LAST
from ..syntax.lines import cut_comments
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import (
    Assign,
    Block,
    Call,
    End,
    Expr,
    Goto,
    IfGoto,
    IfNc,
    IfThen,
    NcStatement,
    ProgramStart,
    Span,
    Statement,
    Var,
    While,
    Word,
)
from ..syntax.walk import cond_exprs, subexpressions, variables


@dataclass(frozen=True)
class Hit:
    kind: str  # "var", "function", "word", "label", "program", "goto", "loop", "keyword"
    span: Span
    var: Var | None = None
    assign: Assign | None = None  # for a var: the assignment it is the target of
    call: Call | None = None
    word: Word | None = None
    nc: NcStatement | None = None
    goto: Goto | None = None
    loop_id: float | None = None
    keyword: str = ""


def _inside(span: Span, column: int) -> bool:
    return span.start <= column < span.end or (span.start == span.end == column)


def _in_expr(expr: Expr, column: int) -> Hit | None:
    """The innermost variable or function name at ``column`` in ``expr``."""
    best: Hit | None = None
    for node in subexpressions(expr):
        if isinstance(node, Var) and _inside(node.span, column):
            if best is None or node.span.end - node.span.start < best.span.end - best.span.start:
                best = Hit("var", node.span, var=node)
        elif isinstance(node, Call) and _inside(node.name_span, column):
            return Hit("function", node.name_span, call=node)
    return best


def _in_assign(assign: Assign, column: int) -> Hit | None:
    target = assign.target
    if _inside(target.span, column):
        if target.index is not None:
            inner = _in_expr(target.index, column)
            if inner is not None and inner.span != target.span:
                return inner
        return Hit("var", target.span, var=target, assign=assign)
    return _in_expr(assign.value, column)


def _in_nc(nc: NcStatement, column: int) -> Hit | None:
    for word in nc.words:
        if _inside(word.span, column):
            inner = _in_expr(word.value, column)
            if inner is not None:
                return inner
            return Hit("word", word.span, word=word, nc=nc)
    return None


def _in_statement(statement: Statement, column: int) -> Hit | None:
    if isinstance(statement, ProgramStart):
        return Hit("program", statement.span) if _inside(statement.span, column) else None
    if isinstance(statement, Assign):
        return _in_assign(statement, column)
    if isinstance(statement, NcStatement):
        return _in_nc(statement, column)
    if isinstance(statement, IfThen | IfGoto | IfNc | While) and statement.cond is not None:
        for expr in cond_exprs(statement.cond):
            hit = _in_expr(expr, column)
            if hit is not None:
                return hit
    if isinstance(statement, IfThen):
        return _in_assign(statement.then, column)
    if isinstance(statement, IfNc):
        return _in_nc(statement.words, column)
    if isinstance(statement, Goto | IfGoto):
        goto = statement if isinstance(statement, Goto) else statement.goto
        hit = _in_expr(goto.target, column)
        if hit is not None:
            return hit
        if _inside(goto.span, column):
            return Hit("goto", goto.span, goto=goto)
        return None
    if isinstance(statement, While | End) and (
        _inside(statement.id_span, column) or _do_word(statement, column)
    ):
        return Hit("loop", statement.id_span, loop_id=statement.loop_id)
    return None


def _do_word(statement: While | End, column: int) -> bool:
    """The ``DO``/``END`` letters just before the loop number."""
    start = statement.id_span.start
    width = 2 if isinstance(statement, While) else 3
    return start - width - 1 <= column < start


_WORD = re.compile(r"[A-Za-z]+")


def find(block: Block, column: int) -> Hit | None:
    parsed = block.parsed
    if parsed.seq_span is not None and _inside(parsed.seq_span, column):
        return Hit("label", parsed.seq_span)
    for statement in statements_of(parsed.statement):
        hit = _in_statement(statement, column)
        if hit is not None:
            return hit
    return keyword_at(block.text, column)


def keyword_at(text: str, column: int) -> Hit | None:
    code = cut_comments(text).code  # comments are spaces there: no keywords in them
    for m in _WORD.finditer(code):
        if m.start() <= column < m.end() or (column == m.end() and column > m.start()):
            return Hit("keyword", Span(m.start(), m.end()), keyword=m.group().upper())
    return None


# ---- variables of a program ------------------------------------------------------------------


@dataclass(frozen=True)
class VarUse:
    line: int
    var: Var
    assign: Assign | None  # set when this use is the target of that assignment


def uses(blocks: tuple[Block, ...], first: int, end: int) -> Iterator[VarUse]:
    """Every direct variable read or written in the lines ``first``..``end``-1."""
    for line in range(max(0, first), min(end, len(blocks))):
        for statement in statements_of(blocks[line].statement):
            targets: dict[int, Assign] = {}
            for assign in assignments_in(statement):
                targets[id(assign.target)] = assign
            for var in variables(statement):
                if var.number is not None:
                    yield VarUse(line, var, targets.get(id(var)))


def assignments_in(statement: Statement) -> list[Assign]:
    if isinstance(statement, Assign):
        return [statement]
    if isinstance(statement, IfThen):
        return [statement.then]
    return []


def number_of(var: Var) -> int | None:
    if var.number is None or var.number != int(var.number):
        return None
    return int(var.number)


def goto_target(goto: Goto) -> int | None:
    value = constant_value(goto.target)
    if value is None or value != int(value):
        return None
    return int(value)


def locals_read_before_set(blocks: tuple[Block, ...], first: int, end: int) -> dict[int, int]:
    """The locals (#1-#33) the lines ``first``..``end``-1 read before they set them, in the
    order of the lines, each with the first line reading it: what a macro takes from its call.
    An assignment reads its value before it sets its target (``#1=#1+1`` reads #1)."""
    reads: dict[int, int] = {}
    written: set[int] = set()
    for line in range(max(0, first), min(end, len(blocks))):
        for statement in statements_of(blocks[line].statement):
            targets = {id(a.target) for a in assignments_in(statement)}
            sets: list[int] = []
            for var in variables(statement):
                number = number_of(var)
                if number is None or not 1 <= number <= LOCAL_LAST or number in written:
                    continue
                if id(var) in targets:
                    sets.append(number)
                else:
                    reads.setdefault(number, line)
            written.update(sets)
    return reads
