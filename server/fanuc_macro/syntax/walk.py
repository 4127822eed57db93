"""Walking the AST: the expressions of a statement, sub-expressions, variables, nesting."""

from __future__ import annotations

from collections.abc import Callable, Iterator

from .tree import (
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
    Num,
    ParsedLine,
    PlainNc,
    Statement,
    Unary,
    Var,
    While,
)


def cond_exprs(cond: Cond) -> Iterator[Expr]:
    """The expressions of a condition, in source order (nested AND/OR/XOR included)."""
    stack: list[Cond] = [cond]
    while stack:
        node = stack.pop()
        if isinstance(node, Compare):
            yield node.left
            yield node.right
        elif isinstance(node, Logic):
            stack.extend(c for _, c in reversed(node.rest))
            stack.append(node.first)
        elif isinstance(node, BareCond):
            yield node.value


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
    if type(expr) is Num:  # most words' values
        yield expr
        return
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


def plain_variables(statement: NcStatement) -> list[Var] | None:
    """The variables of an NC statement whose words' values are numbers, ``#n`` or ``-#n``
    (what most blocks of a program hold), in source order; None when a value holds more
    (brackets, operators, functions, ``#[...]``). The line rules take these without walking."""
    found: list[Var] = []
    for word in statement.words:
        value = word.value
        if type(value) is Num:
            continue
        if type(value) is Unary:
            value = value.operand
        if type(value) is Var and value.index is None:
            found.append(value)
            continue
        return None
    return found


def variables(statement: Statement) -> Iterator[Var]:
    """The variables of a statement's expressions, in source order (parents before the
    variables of their indexes)."""
    if type(statement) is PlainNc:
        return iter(())  # numbers only
    if type(statement) is NcStatement:
        plain = plain_variables(statement)
        if plain is not None:
            return iter(plain)
    return _variables(statement)


_KEEP_VARIABLES: Callable[[ParsedLine, tuple[Var, ...]], None] = vars(ParsedLine)[
    "statement_variables"
].__set__


def all_line_variables(parsed: ParsedLine) -> tuple[Var, ...]:
    """:func:`variables` of a line's statements in turn (one, or a mixed block's NC words then
    its macro statement), walked once and kept on the line: every block of its text shares
    them."""
    found = parsed.statement_variables
    if found is None:
        statement = parsed.statement
        if statement is None:
            found = ()
        elif type(statement) is Mixed:
            found = (*variables(statement.nc), *variables(statement.macro))
        else:
            found = tuple(variables(statement))
        _KEEP_VARIABLES(parsed, found)
    return found


def line_variables(parsed: ParsedLine) -> tuple[tuple[Var, ...], ...]:
    """:func:`all_line_variables` by statement (``parser.statements_of``'s order)."""
    found = all_line_variables(parsed)
    statement = parsed.statement
    if statement is None:
        return ()
    if type(statement) is Mixed:  # few blocks: its NC words' variables counted again
        split = sum(1 for _ in variables(statement.nc))
        return (found[:split], found[split:])
    return (found,)


def _variables(statement: Statement) -> Iterator[Var]:
    # subexpressions' walk, keeping only the variables (run for most lines by several rules).
    found: list[Var] = []
    for top in top_expressions(statement):
        kind = type(top)
        if kind is Num:
            continue
        if kind is Var and top.index is None:  # type: ignore[union-attr]
            found.append(top)  # type: ignore[arg-type]
            continue
        stack: list[Expr] = [top]
        while stack:
            node = stack.pop()
            kind = type(node)
            if kind is Binary:
                stack.append(node.right)  # type: ignore[union-attr]
                stack.append(node.left)  # type: ignore[union-attr]
            elif kind is Var:
                found.append(node)  # type: ignore[arg-type]
                if node.index is not None:  # type: ignore[union-attr]
                    stack.append(node.index)  # type: ignore[union-attr]
            elif kind is Unary:
                stack.append(node.operand)  # type: ignore[union-attr]
            elif kind is Bracket:
                stack.append(node.inner)  # type: ignore[union-attr]
            elif kind is Call:
                stack.extend(reversed(node.args))  # type: ignore[union-attr]
    return iter(found)


def bracket_depth(expr: Expr) -> int:
    """Nesting of ``[ ]``, counting function brackets and ``#[ ]`` as FANUC does."""
    if type(expr) is Num or (type(expr) is Var and expr.index is None):
        return 0
    deepest = 0
    stack: list[tuple[Expr, int]] = [(expr, 0)]  # a node and the brackets around it
    while stack:
        node, depth = stack.pop()
        if isinstance(node, Bracket):
            stack.append((node.inner, depth + 1))
        elif isinstance(node, Call):
            stack.extend((a, depth + 1) for a in node.args)
        elif isinstance(node, Var):
            if node.index is not None:
                stack.append((node.index, depth + 1))
        elif isinstance(node, Binary):
            stack.append((node.left, depth))
            stack.append((node.right, depth))
        elif isinstance(node, Unary):
            stack.append((node.operand, depth))
        # A bracket closed around a leaf counts: [1] is one level.
        deepest = max(deepest, depth)
    return deepest


def expression_depth(statement: Statement) -> int:
    """The deepest nesting of nodes in a statement's expressions and conditions: each operator,
    sign, bracket, function and AND/OR/XOR is a level. The parser refuses blocks nested deeper
    than the analysis can follow (see ``fanuc_macro.syntax.parser.MAX_EXPRESSION_DEPTH``)."""
    deepest = 0
    stack: list[tuple[Expr | Cond, int]] = [(c, 1) for c in _conditions(statement)]
    stack.extend((e, 1) for e in top_expressions(statement))
    while stack:
        node, depth = stack.pop()
        deepest = max(deepest, depth)
        if isinstance(node, Logic):
            stack.append((node.first, depth + 1))
            stack.extend((c, depth + 1) for _, c in node.rest)
        elif isinstance(node, Compare):
            stack.append((node.left, depth + 1))
            stack.append((node.right, depth + 1))
        elif isinstance(node, BareCond):
            stack.append((node.value, depth + 1))
        elif isinstance(node, Binary):
            stack.append((node.left, depth + 1))
            stack.append((node.right, depth + 1))
        elif isinstance(node, Unary):
            stack.append((node.operand, depth + 1))
        elif isinstance(node, Bracket):
            stack.append((node.inner, depth + 1))
        elif isinstance(node, Call):
            stack.extend((a, depth + 1) for a in node.args)
        elif isinstance(node, Var) and node.index is not None:
            stack.append((node.index, depth + 1))
    return deepest


def _conditions(statement: Statement) -> Iterator[Cond]:
    if isinstance(statement, IfGoto | IfThen | IfNc) or (
        isinstance(statement, While | BlockIf) and statement.cond is not None
    ):
        assert statement.cond is not None
        yield statement.cond
    elif isinstance(statement, Mixed):
        yield from _conditions(statement.macro)
