"""What a parsed line says at once to the layers above: the value of a word written as a
constant, whether a block calls a program, whether the program index needs the line.

The parser decides the last two once per distinct line (``ParsedLine.has_call``,
``ParsedLine.indexed``), so that the index looks only at the lines it needs.
"""

from __future__ import annotations

from .tree import (
    Bracket,
    End,
    Expr,
    Goto,
    IfGoto,
    IfNc,
    Mixed,
    NcStatement,
    Num,
    ProgramStart,
    Unary,
    While,
)


def constant_value(expr: Expr) -> float | None:
    """The value of an expression written as a constant (``10``, ``-5.``, ``[10]``)."""
    if isinstance(expr, Num):
        return expr.value
    if isinstance(expr, Bracket):
        return constant_value(expr.inner)
    if isinstance(expr, Unary):
        inner = constant_value(expr.operand)
        if inner is None:
            return None
        return -inner if expr.op == "-" else inner
    return None


# The words that make a block a call (or a return): the index looks at such blocks closer.
CALL_CODES = frozenset(
    {("G", 65.0), ("G", 66.0), ("G", 66.1), ("M", 98.0), ("M", 97.0), ("M", 99.0)}
)


def mentions_call(statement: object) -> bool:
    """Whether a statement has a word that calls or returns (decided once per parsed line)."""
    if isinstance(statement, Mixed):
        statement = statement.nc
    elif isinstance(statement, IfNc):
        statement = statement.words
    if not isinstance(statement, NcStatement):
        return False
    for word in statement.words:
        if word.address in ("G", "M") and (word.address, constant_value(word.value)) in CALL_CODES:
            return True
    return False


# Statements the index records; assignments and plain NC blocks (most lines) it skips.
INDEXED_STATEMENTS: frozenset[type] = frozenset(
    {Goto, IfGoto, IfNc, While, End, Mixed, ProgramStart}
)
