"""MB504: angles of radian size given to SIN, COS and TAN, which take degrees on FANUC.

FANUC's trigonometric functions take and give degrees (Custom Macro B manual, "Arithmetic
and logic operation"). A sweep written in radians (0.314 to 2.827 for 18° to 162°) then
covers under 3° and the tool path that should follow an arc stays almost in one place. The
rule looks at a function whose argument is one variable, over every value it had in the run:
all within ±2π, a sweep of at least 0.5 and radian-size steps, and radians that are round
numbers of degrees (18°, 8°: 0.31416, 0.13963) or a π in the program.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..line_maps import LineMap
from ..per_line import PerLine
from ..syntax.tree import Call, Num, ParsedLine, Span, Var
from ..syntax.walk import subexpressions, top_expressions
from ..threads.linear import expr_text
from .context import RuleContext, line_statements

FAMILY = "math-domain"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB504 = RuleInfo("MB504", "trig-radians", Severity.WARNING,
                 "SIN, COS or TAN gets angles that look like radians; FANUC takes degrees.", FAMILY)
# fmt: on


TRIG = frozenset({"SIN", "COS", "TAN"})
_PI_LIKE = (math.pi, 2 * math.pi, math.pi / 2, math.pi / 180, 180 / math.pi)


def _line_trig(parsed: ParsedLine) -> tuple[tuple[str, int, Span], ...]:
    found: list[tuple[str, int, Span]] = []
    for statement in line_statements(parsed):
        for top in top_expressions(statement):
            for node in subexpressions(top):
                if isinstance(node, Call) and node.name in TRIG and len(node.args) == 1:
                    arg = node.args[0]
                    if isinstance(arg, Var) and arg.number is not None:
                        found.append((expr_text(node), int(arg.number), node.span))
    return tuple(found)


def _line_pi(parsed: ParsedLine) -> bool:
    for statement in line_statements(parsed):
        for top in top_expressions(statement):
            for node in subexpressions(top):
                if isinstance(node, Num) and node.value > 0.01:
                    for pi in _PI_LIKE:
                        if abs(node.value - pi) / pi < 2e-3 and len(node.text) >= 4:
                            return True
    return False


# The trigonometric calls on one variable, and whether a π-like constant is written, per line.
_trig_of: PerLine[tuple[tuple[str, int, Span], ...]] = PerLine(_line_trig)
_pi_of: PerLine[bool] = PerLine(_line_pi)


def _trig_line(parsed: ParsedLine) -> tuple[tuple[str, int, Span], ...] | None:
    source = parsed.text
    if (
        "SIN" not in source
        and "COS" not in source
        and "TAN" not in source
        and not parsed.has_lowercase
    ):
        return None  # spare most lines the per-line lookup
    return _trig_of(parsed) or None


# The lines with such calls, looked at again only where the document changed.
_trig_lines: LineMap[tuple[tuple[str, int, Span], ...]] = LineMap(_trig_line)


def _round_degrees(value: float) -> bool:
    degrees = math.degrees(value)
    return abs(degrees * 2 - round(degrees * 2)) < 0.04  # a multiple of 0.5° within 0.02°


MB504_DOC = RuleDoc(
    "MB504",
    reports="""
`SIN`, `COS` or `TAN` of one variable whose values over the run look like
radians: all within ±2π, a sweep of 0.5 or more in steps under 0.8, and either round numbers of
degrees when read as radians (0.31416 is 18°) or a π in the assignments of the angle
(`#16=#16+8.*3.14159/180.`). The message gives the range of the argument, the angles
it would stand for, and how little the function's value moves in degrees.
""",
    why="""
FANUC's trigonometric functions take degrees: an arc written
in radians (18° to 162° as 0.314 to 2.827) is swept over under 3°, so every cut of a
fitting-method program lands within a fraction of a millimetre instead of following the
profile, and the part is cut wrong without any alarm.
""",
    example="""
```nc
O5001 (ARC FINISHING)
#16=0.31416
G00 X150. Z100.
N5 G00 Z[50.+8.8*COS[#16]]
X[100.-17.6*SIN[#16]]
G32 Z-113. F25.
G00 X140.
#16=#16+0.13963
IF[#16LE2.8275]GOTO5
M30
```
""",
    fix="""
Write the angles in degrees (`#16=18.`, `#16=#16+8.`), or convert once
(`#16=#16*57.29578`).
""",
    not_reported="""
Small angles in degrees (a taper of 0.5° to 3° in steps of 0.5°:
not round numbers of degrees as radians, no π in their assignments), arguments that are
expressions rather than one variable, and functions run fewer than three times.
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    facts = ctx.doc_facts()
    if facts is None:
        return
    for line, calls in _trig_lines(ctx.doc):
        for text, number, span in calls:
            summary = facts.reads.get((line, number))
            if summary is None or summary.count < 3 or not summary.numeric or summary.constant:
                continue
            low, high = summary.minimum, summary.maximum
            if low < -2 * math.pi - 1e-6 or high > 2 * math.pi + 1e-6 or high - low < 0.5:
                continue
            if (high - low) / (summary.count - 1) >= 0.8:
                continue  # steps of a degree and more
            # The first value may be vacant or unknown (a loop whose counter starts unset).
            first = summary.first if isinstance(summary.first, float) else low
            # A π in the assignments of the angle itself: it is computed in radians.
            with_pi = any(
                _pi_of(ctx.doc.blocks[w].parsed)
                for w, (n, _s) in facts.writes.items()
                if n == number
            )
            radians = with_pi or all(_round_degrees(v) for v in (low, high, first))
            if not radians:
                continue
            name = text.split("[", 1)[0]
            results = [_degrees_function(name, v) for v in (low, high)]
            yield make(
                MB504,
                f"{text} gets #{number} from {low:.4g} to {high:.4g} ({summary.count} times): "
                f"angles of radian size ({math.degrees(low):.4g}° to {math.degrees(high):.4g}° "
                f"as radians), but {name} takes degrees, so the sweep is {high - low:.3g}° "
                f"and {name} stays between {min(results):.3g} and {max(results):.3g}; write "
                "the angles in degrees (or multiply by 57.29578)",
                line,
                span.start,
                span.end,
            )


def _degrees_function(name: str, value: float) -> float:
    angle = math.radians(value)
    return {"SIN": math.sin, "COS": math.cos}.get(name, math.tan)(angle)
