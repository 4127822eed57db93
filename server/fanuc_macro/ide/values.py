"""Values and variables in words: the short forms of inlay hints, the formula of an
assignment with the values it read, the kind of a variable."""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from ..evaluator.compiler import compile_expr
from ..evaluator.facts import DocumentFacts, ValueSummary
from ..evaluator.values import MacroAlarm, Unknown, Value, fmt
from ..program.variables import classify
from ..syntax.lines import cut_comments
from ..syntax.tree import Assign, Binary, Block, Bracket, Expr, Num, Span, Unary, Var
from ..syntax.walk import subexpressions
from ..translation import tr
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


# G20 / G21 as a word of its own (not G200, not #120, not X20.).
_UNIT_CODE = re.compile(r"(?<![A-Z#\d.])G0*(20|21)(?![\d.])", re.IGNORECASE)


def inch_at(blocks: Sequence[Block], line: int) -> bool:
    """Whether the last G20 / G21 before ``line`` in the document is G20 (inch input). The
    control starts in the unit of parameter 0000#2 (INI); millimetres are assumed when the
    text sets none (FANUC 0i-F operator's manual, "Inch/metric conversion (G20, G21)")."""
    for index in range(min(line, len(blocks) - 1), -1, -1):
        text = blocks[index].text
        if "20" not in text and "21" not in text:
            continue
        found: list[str] = _UNIT_CODE.findall(cut_comments(text).code)
        if found:
            return found[-1] == "20"
    return False


@dataclass(frozen=True)
class Precision:
    """How a hover shows a value: at the control's least input increment in the program's
    unit (IS-B: 0.001 mm, 0.0001 inch), or in full (8 significant digits, the control's
    display of a macro variable) when the user asks for it (setting ``hover.fullPrecision``)."""

    inch: bool = False
    full: bool = False

    @property
    def unit(self) -> str:
        return "inch" if self.inch else "mm"

    def show(self, value: Value) -> str:
        if self.full or not isinstance(value, float) or value != value:
            return fmt(value)
        if value in (float("inf"), float("-inf")):
            return fmt(value)
        digits = 4 if self.inch else 3
        rounded = round(value, digits)
        if rounded == 0.0 and value != 0.0:
            return f"{value:.2g}"  # below the increment: its size, not a 0
        if rounded == int(rounded) and abs(rounded) < 1e15:
            return f"{int(rounded)}."
        return f"{rounded:.{digits}f}".rstrip("0")

    def summary(self, summary: ValueSummary) -> str:
        return summary.describe(self.show)


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


def _value_text(value: Value, show: Callable[[Value], str] = fmt) -> str:
    text = show(value)
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


def substituted(
    block: Block, assign: Assign, facts: DocumentFacts, show: Callable[[Value], str] = fmt
) -> str | None:
    """The right-hand side with the constant values read at this block put in for variables
    (and written constants such as ``[7./8.]`` folded), each as ``show`` writes it; None when
    nothing changes."""
    line = block.line
    base = assign.value.span.start
    replacements: list[tuple[Span, str]] = []

    def visit(node: Expr) -> None:
        if isinstance(node, Var):
            n = number_of(node)
            if n is not None:
                summary = facts.reads.get((line, n))
                if summary is not None and summary.constant:
                    replacements.append((node.span, _value_text(summary.first, show)))
            return
        if isinstance(node, Bracket) and _literal(node.inner):
            value = _fold(node.inner)
            if isinstance(value, float):
                replacements.append((node.inner.span, show(value)))
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
    return tr("once") if n == 1 else tr("{count} times", count=n)


def variable_kind(number: int) -> str:
    kind = classify(number)
    label = {
        "null": tr("null variable"),
        "local": tr("local variable"),
        "common": tr("common variable"),
        "retained": tr("common variable (retained)"),
        "extended-common": tr("common variable (extended range)"),
        "system": tr("system variable"),
        "none": tr("not a FANUC variable"),
    }.get(kind.kind, kind.kind)
    return label
