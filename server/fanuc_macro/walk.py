"""Walking the AST: the expressions of a statement, sub-expressions, variables, nesting."""

from __future__ import annotations

from collections.abc import Iterator

from .syntax import (
    Assign,
    BareCond,
    Binary,
    BlockIf,
    Bracket,
    Call,
    Compare,
    Cond,
    Expr,
    Goto,
    IfGoto,
    IfNc,
    IfThen,
    Logic,
    Mixed,
    NcStatement,
    Statement,
    Unary,
    Var,
    While,
)


def cond_exprs(cond: Cond) -> Iterator[Expr]:
    if isinstance(cond, Compare):
        yield cond.left
        yield cond.right
    elif isinstance(cond, Logic):
        yield from cond_exprs(cond.first)
        for _, rest in cond.rest:
            yield from cond_exprs(rest)
    elif isinstance(cond, BareCond):
        yield cond.value


def top_expressions(statement: Statement) -> Iterator[Expr]:
    """The expressions a statement holds directly, in source order (targets included)."""
    if isinstance(statement, Assign):
        yield statement.target
        yield statement.value
    elif isinstance(statement, NcStatement):
        for word in statement.words:
            yield word.value
    elif isinstance(statement, Goto):
        yield statement.target
    elif isinstance(statement, IfGoto):
        yield from cond_exprs(statement.cond)
        yield statement.goto.target
    elif isinstance(statement, IfThen):
        yield from cond_exprs(statement.cond)
        yield from top_expressions(statement.then)
    elif isinstance(statement, IfNc):
        yield from cond_exprs(statement.cond)
        yield from top_expressions(statement.words)
    elif isinstance(statement, (While, BlockIf)):
        if statement.cond is not None:
            yield from cond_exprs(statement.cond)
    elif isinstance(statement, Mixed):
        yield from top_expressions(statement.nc)
        yield from top_expressions(statement.macro)


def subexpressions(expr: Expr) -> Iterator[Expr]:
    """``expr`` and everything inside it, parents before children."""
    stack: list[Expr] = [expr]
    while stack:
        node = stack.pop()
        yield node
        if isinstance(node, Binary):
            stack.append(node.right)
            stack.append(node.left)
        elif isinstance(node, (Unary,)):
            stack.append(node.operand)
        elif isinstance(node, Bracket):
            stack.append(node.inner)
        elif isinstance(node, Call):
            stack.extend(reversed(node.args))
        elif isinstance(node, Var) and node.index is not None:
            stack.append(node.index)


def variables(statement: Statement) -> Iterator[Var]:
    for top in top_expressions(statement):
        for node in subexpressions(top):
            if isinstance(node, Var):
                yield node


def bracket_depth(expr: Expr) -> int:
    """Nesting of ``[ ]``, counting function brackets and ``#[ ]`` as FANUC does."""
    if isinstance(expr, Bracket):
        return 1 + bracket_depth(expr.inner)
    if isinstance(expr, Call):
        return 1 + max(bracket_depth(a) for a in expr.args)
    if isinstance(expr, Var):
        return 0 if expr.index is None else 1 + bracket_depth(expr.index)
    if isinstance(expr, Binary):
        return max(bracket_depth(expr.left), bracket_depth(expr.right))
    if isinstance(expr, Unary):
        return bracket_depth(expr.operand)
    return 0
