"""Values and variables in words: the short forms of inlay hints, the formula of an
assignment with the values it read, the kind of a variable."""

from __future__ import annotations

from ..evaluator.compiler import compile_expr
from ..evaluator.facts import DocumentFacts, ValueSummary
from ..evaluator.values import MacroAlarm, Unknown, Value, fmt
from ..program.variables import classify
from ..syntax.tree import Assign, Binary, Block, Bracket, Expr, Num, Span, Unary, Var
from ..syntax.walk import subexpressions
from .locate import number_of


def short(value: Value) -> str:
    """A value for an inlay hint: three decimals, as a machinist reads a drawing."""
    if value is None:
        return "<vacant>"
    if isinstance(value, Unknown):
        return "?"
    if value != value or value in (float("inf"), float("-inf")):
        return fmt(value)
    if value == int(value) and abs(value) < 1e9:
        return f"{int(value)}."
    if abs(value) < 0.001:
        return f"{value:.3g}"
    text = f"{value:.3f}".rstrip("0")
    return text + "0" if text.endswith(".") else text


def short_summary(summary: ValueSummary) -> str | None:
    if summary.count == 0:
        return None
    if summary.count == 1 or summary.constant:
        if isinstance(summary.first, Unknown):
            return None
        return short(summary.first)
    if not summary.numeric:
        return None
    return f"{short(summary.first)} → {short(summary.last)} ×{summary.count}"


def _value_text(value: Value) -> str:
    text = fmt(value)
    return f"[{text}]" if text.startswith("-") else text


def _literal(expr: Expr) -> bool:
    """Numbers and arithmetic only, with at least one operation (``7./8.``, not ``7.``)."""
    operation = False
    for node in subexpressions(expr):
        if isinstance(node, Binary):
            if node.op not in ("+", "-", "*", "/"):
                return False
            operation = True
        elif isinstance(node, Unary):
            operation = True
        elif not isinstance(node, Num | Bracket):
            return False
    return operation


class _NoFrame:
    """A frame for constant expressions: they read no variable."""

    signed_atan = False
    length_increment = 0.001

    def __init__(self) -> None:
        self.locals: list[Value] = []
        self.store: dict[int, Value] = {}

    def note_rounding(self, name: str, argument: float, result: float) -> None:
        pass

    def read_global(self, number: int) -> Value:
        raise LookupError(number)

    def read_indirect(self, number: Value, node: Var) -> Value:
        raise LookupError(number)


def _fold(expr: Expr) -> Value:
    try:
        return compile_expr(expr)(_NoFrame())
    except (MacroAlarm, LookupError, ArithmeticError):
        return None


def substituted(block: Block, assign: Assign, facts: DocumentFacts) -> str | None:
    """The right-hand side with the constant values read at this block put in for variables
    (and written constants such as ``[7./8.]`` folded); None when nothing changes."""
    line = block.line
    base = assign.value.span.start
    replacements: list[tuple[Span, str]] = []

    def visit(node: Expr) -> None:
        if isinstance(node, Var):
            n = number_of(node)
            if n is not None:
                summary = facts.reads.get((line, n))
                if summary is not None and summary.constant:
                    replacements.append((node.span, _value_text(summary.first)))
            return
        if isinstance(node, Bracket) and _literal(node.inner):
            value = _fold(node.inner)
            if isinstance(value, float):
                replacements.append((node.inner.span, fmt(value)))
                return
        if isinstance(node, Binary):
            visit(node.left)
            visit(node.right)
        elif isinstance(node, Unary):
            visit(node.operand)
        elif isinstance(node, Bracket):
            visit(node.inner)
        elif not isinstance(node, Num):
            for arg in node.args:
                visit(arg)

    visit(assign.value)
    if not replacements:
        return None
    text = block.source(assign.value.span)
    for span, new in sorted(replacements, key=lambda r: -r[0].start):
        text = text[: span.start - base] + new + text[span.end - base :]
    return text.strip()


def code(text: str) -> str:
    text = text.strip()
    ticks = "``" if "`" in text else "`"
    return f"{ticks}{text}{ticks}"


def times(n: int) -> str:
    return "once" if n == 1 else f"{n} times"


def variable_kind(number: int) -> str:
    kind = classify(number)
    label = {
        "null": "null variable",
        "local": "local variable",
        "common": "common variable",
        "retained": "common variable (retained)",
        "extended-common": "common variable (extended range)",
        "system": "system variable",
        "none": "not a FANUC variable",
    }.get(kind.kind, kind.kind)
    return label
