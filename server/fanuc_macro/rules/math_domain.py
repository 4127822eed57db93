"""MB5xx: alarms the arithmetic raises on the values that reach it (evaluator)."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleInfo, Severity, make, register
from .context import RuleContext

FAMILY = "math-domain"
register(
    RuleInfo("MB501", "math-domain", Severity.ERROR,
             "A function gets an argument outside its domain: SQRT of a negative, ASIN/ACOS "
             "outside [-1, 1], LN of a non-positive number (PS0119).", FAMILY),
    RuleInfo("MB502", "zero-divide", Severity.ERROR,
             "A division by zero, TAN of 90 degrees or MOD 0 (PS0112).", FAMILY),
    RuleInfo("MB503", "macro-alarm-reached", Severity.WARNING,
             "The program reaches its own #3000 alarm with the values the analysis has.", FAMILY),
)  # fmt: skip

_CODES = {"zero-divide": "MB502", "macro-alarm": "MB503", "overflow": "MB501"}
_DOMAIN = (
    "sqrt-negative",
    "asin-range",
    "acos-range",
    "ln-domain",
    "bin-range",
    "bcd-range",
    "pow-range",
    "atan-zero",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings("alarm:"):
        kind = f.kind.split(":", 1)[1]
        code = _CODES.get(kind) or ("MB501" if kind in _DOMAIN else None)
        if code is not None:
            yield make(code, f.message, f.line, f.column, f.end_column)
