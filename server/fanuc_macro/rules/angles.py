"""MB504: an angle stepped in radians given to SIN, COS and TAN, which take degrees on FANUC.

FANUC's trigonometric functions take and give degrees (Custom Macro B manual, "Arithmetic
and logic operation"). A sweep written in radians (0.3142 to 2.8275 for 18° to 162°) then
covers under 3° and the tool path that should follow an arc stays almost in one place.

The rule looks at a function whose argument is one variable, over every value it had in the
run, and decides by the sweep and the step, not by what the values are in degrees:

* the sweep: every value within ±2π and a sweep of 0.5 or more (under 0.5 a sweep is as
  likely a degree program's fine steps over a fraction of a degree);
* the step: the increment of the loop (``#16=#16+0.1396``, or ``#16=#16+#3`` with #3 of one
  value whenever the loop steps), or the sweep over the count of
  values, under 0.8: a radian step, which would be a sub-degree step of a sweep under 7° if
  the values were degrees;
* and one sign of radians that a degree program does not give, since a degree program can
  step 0.1° over 2.8° too: the step typed as a radian conversion (three decimals or more that
  are no fraction of a degree a programmer types: 0.1396, 0.0873, not 0.5, 0.25 or 0.125), the
  loop's bound at a quarter, half or whole turn in radians (``1.57``, ``3.1416``, ``6.2832``,
  or written with a π), or a π in the angle's assignments (``#16=#16+8.*3.14159/180.``).

An angle assigned from ATAN, ASIN or ACOS is degrees (they give degrees): quiet, unless a π in
its assignments converts it.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from typing import NamedTuple

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import DocumentFacts
from ..line_maps import LineMap
from ..per_line import PerLine
from ..syntax.tree import (
    Assign,
    Binary,
    Block,
    BlockIf,
    Bracket,
    Call,
    Compare,
    Cond,
    Expr,
    IfGoto,
    IfNc,
    IfThen,
    Logic,
    Num,
    ParsedLine,
    Span,
    Unary,
    Var,
    While,
)
from ..syntax.walk import subexpressions, top_expressions
from ..threads.linear import expr_text
from ..translation import tr
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
INVERSE = frozenset({"ATAN", "ASIN", "ACOS"})  # they give degrees
_PI_LIKE = (math.pi, 2 * math.pi, math.pi / 2, math.pi / 180, 180 / math.pi)

TURN = 2 * math.pi
RANGE = TURN + 0.01  # "within ±2π", with 6.29 for a 2π typed short
MIN_SWEEP = 0.5  # radians; under it, a degree program's fine steps are as likely
MAX_STEP = 0.8  # radians per step (46°); as degrees, a sub-degree step
# The turns a loop in radians ends at, and the fewest decimals they count with: 1.57, 3.14,
# 4.71 and 6.28 are no degree program's bounds; 0.785, 1.047 and 2.094 need a third decimal
# (0.79 and 1.05 could be degrees). Not 7π/4 (5.498): 5.5 is a degree bound.
_TURNS = (
    (math.pi / 6, "π/6", 3),
    (math.pi / 4, "π/4", 3),
    (math.pi / 3, "π/3", 3),
    (math.pi / 2, "π/2", 2),
    (2 * math.pi / 3, "2π/3", 3),
    (3 * math.pi / 4, "3π/4", 3),
    (math.pi, "π", 2),
    (3 * math.pi / 2, "3π/2", 2),
    (2 * math.pi, "2π", 2),
)


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


def _pi_like(expr: Expr) -> bool:
    """Whether ``expr`` holds a π-like constant (π, 2π, π/2, π/180, 180/π) written to 3
    decimals or more."""
    for node in subexpressions(expr):
        if isinstance(node, Num) and node.value > 0.01:
            for pi in _PI_LIKE:
                if abs(node.value - pi) / pi < 2e-3 and len(node.text) >= 4:
                    return True
    return False


def _line_pi(parsed: ParsedLine) -> bool:
    return any(
        _pi_like(top) for statement in line_statements(parsed) for top in top_expressions(statement)
    )


class _AngleLine(NamedTuple):
    """What one line says of the variables it assigns and compares."""

    # (variable, signed constant) of each '#n=#n+C' / '#n=#n-C' / '#n=C+#n'
    increments: tuple[tuple[int, float], ...] = ()
    inverse: frozenset[int] = frozenset()  # variables assigned from ATAN, ASIN or ACOS
    # (variable, the number it is compared with) in a condition: '#1LE1.57', '#1GE-3.1416'
    number_bounds: tuple[tuple[int, float], ...] = ()
    # (variable, the variable it is compared with): '#1LE#2'
    variable_bounds: tuple[tuple[int, int], ...] = ()
    pi_bounds: frozenset[int] = frozenset()  # compared with an expression holding a π
    # (variable, the variable it is stepped by, +1 or -1) of each '#n=#n+#k' / '#n=#n-#k'
    variable_increments: tuple[tuple[int, int, float], ...] = ()


def _strip(expr: Expr) -> Expr:
    while isinstance(expr, Bracket):
        expr = expr.inner
    return expr


def _direct(expr: Expr) -> int | None:
    expr = _strip(expr)
    if isinstance(expr, Var) and expr.number is not None and expr.index is None:
        return int(expr.number)
    return None


def _signed_number(expr: Expr) -> float | None:
    expr = _strip(expr)
    if isinstance(expr, Num):
        return expr.value
    if isinstance(expr, Unary) and isinstance(inner := _strip(expr.operand), Num):
        return -inner.value if expr.op == "-" else inner.value
    return None


def _increment(target: int, value: Expr) -> float | None:
    """C of '#n=#n+C', -C of '#n=#n-C', C of '#n=C+#n' (n being ``target``), else None."""
    value = _strip(value)
    if not isinstance(value, Binary) or value.op not in ("+", "-"):
        return None
    if _direct(value.left) == target:
        step = _signed_number(value.right)
        if step is not None:
            return step if value.op == "+" else -step
    elif value.op == "+" and _direct(value.right) == target:
        return _signed_number(value.left)
    return None


def _variable_increment(target: int, value: Expr) -> tuple[int, float] | None:
    """(k, +1) of '#n=#n+#k' or '#n=#k+#n', (k, -1) of '#n=#n-#k', else None."""
    value = _strip(value)
    if not isinstance(value, Binary) or value.op not in ("+", "-"):
        return None
    if _direct(value.left) == target and (k := _direct(value.right)) is not None:
        return k, (1.0 if value.op == "+" else -1.0)
    if value.op == "+" and _direct(value.right) == target and (k := _direct(value.left)):
        return k, 1.0
    return None


def _compares(cond: Cond) -> Iterator[Compare]:
    stack: list[Cond] = [cond]
    while stack:
        node = stack.pop()
        if isinstance(node, Compare):
            yield node
        elif isinstance(node, Logic):
            stack.append(node.first)
            stack.extend(c for _, c in node.rest)


def _line_angles(parsed: ParsedLine) -> _AngleLine | None:
    increments: list[tuple[int, float]] = []
    by_variable: list[tuple[int, int, float]] = []
    inverse: set[int] = set()
    number_bounds: list[tuple[int, float]] = []
    variable_bounds: list[tuple[int, int]] = []
    pi_bounds: set[int] = set()
    for statement in line_statements(parsed):
        assign = statement.then if isinstance(statement, IfThen) else statement
        if isinstance(assign, Assign) and (target := _direct(assign.target)) is not None:
            step = _increment(target, assign.value)
            if step is not None:
                increments.append((target, step))
            elif (stepped := _variable_increment(target, assign.value)) is not None:
                by_variable.append((target, *stepped))
            if any(
                isinstance(node, Call) and node.name in INVERSE
                for node in subexpressions(assign.value)
            ):
                inverse.add(target)
        if isinstance(statement, (IfGoto, IfThen, IfNc, BlockIf, While)) and statement.cond:
            for compare in _compares(statement.cond):
                for this, other in ((compare.left, compare.right), (compare.right, compare.left)):
                    n = _direct(this)
                    if n is None:
                        continue
                    bound = _signed_number(other)
                    m = _direct(other)
                    if bound is not None:
                        number_bounds.append((n, bound))
                    elif m is not None:
                        variable_bounds.append((n, m))
                    elif _pi_like(other):
                        pi_bounds.add(n)
    if not (increments or by_variable or inverse or number_bounds or variable_bounds or pi_bounds):
        return None
    return _AngleLine(
        tuple(increments),
        frozenset(inverse),
        tuple(number_bounds),
        tuple(variable_bounds),
        frozenset(pi_bounds),
        tuple(by_variable),
    )


# Per line: the trigonometric calls on one variable, whether a π-like constant is written,
# and what the line says of the variables it assigns and compares.
_trig_of: PerLine[tuple[tuple[str, int, Span], ...]] = PerLine(_line_trig)
_pi_of: PerLine[bool] = PerLine(_line_pi)
_angles_of: PerLine[_AngleLine | None] = PerLine(_line_angles)


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


def _decimals(value: float) -> int | None:
    """The decimals ``value`` is written with (1.57: 2, 0.1396: 4, 8.: 0), None past 8."""
    for places in range(9):
        scaled = abs(value) * 10**places
        if abs(scaled - round(scaled)) < 1e-6 * max(1.0, scaled):
            return places
    return None


def _turn(value: float) -> str | None:
    """The turn in radians (π/2, π, 2π, ...) ``value`` is as typed (1.57, 3.1416, 6.283: the
    turn rounded or cut to the decimals of ``value``), else None."""
    value = abs(value)
    places = _decimals(value)
    for turn, name, fewest in _TURNS:
        if places is None:  # worked out, not typed: 3.14159265...
            if abs(value - turn) < 1e-7 * turn:
                return name
        elif places >= fewest:
            scale = 10**places
            typed = round(value * scale)
            if typed in (round(turn * scale), math.floor(turn * scale)):
                return name
    return None


def _typed_conversion(step: float) -> bool:
    """Whether a typed step looks like radians worked out from degrees (0.1396, 0.0873,
    0.31416): three decimals or more, and no fraction of a degree a programmer types (0.5,
    0.25, 0.05, eighths 0.125, thirds 0.333)."""
    step = abs(step)
    places = _decimals(step)
    if places is not None and places <= 2:
        return False
    return not any(abs(step * k - round(step * k)) < 3e-3 for k in (8, 3))


class _Angle(NamedTuple):
    """What the program's text says of one variable, in the program that reads it."""

    increments: frozenset[float] = frozenset()  # the signed steps typed in '#n=#n+C'
    pi: bool = False  # a π in an assignment of it
    inverse: bool = False  # assigned from ATAN, ASIN or ACOS
    turn: str | None = None  # a loop bound at a turn: "the loop's bound 1.57 is π/2"


def _program_angles(
    facts: DocumentFacts, blocks: Sequence[Block], lines: range
) -> dict[int, _Angle]:
    """What the lines of one program that ran say of each variable they step, assign from
    ATAN or compare, by variable."""
    increments: dict[int, set[float]] = {}
    pi: set[int] = set()
    inverse: set[int] = set()
    turns: dict[int, str] = {}
    runs, writes, reads = facts.runs, facts.writes, facts.reads
    for at in lines:
        if not runs.get(at):
            continue
        parsed = blocks[at].parsed
        written = writes.get(at)
        if written is not None and _pi_of(parsed):
            pi.add(written[0])
        said = _angles_of(parsed)
        if said is None:
            continue
        for n, step in said.increments:
            increments.setdefault(n, set()).add(step)
        # A step held in a variable that has one value whenever the line runs (#3=0.1396
        # set before the loop) is the step as typed there.
        for n, k, sign in said.variable_increments:
            summary = reads.get((at, k))
            if summary is not None and summary.constant and isinstance(summary.first, float):
                increments.setdefault(n, set()).add(sign * summary.first)
        inverse.update(said.inverse)
        for n in said.pi_bounds:
            turns.setdefault(n, tr("the loop's bound is written with π"))
        bounds = list(said.number_bounds)
        for n, m in said.variable_bounds:
            summary = reads.get((at, m))
            if summary is not None and summary.constant and isinstance(summary.first, float):
                bounds.append((n, summary.first))
        for n, bound in bounds:
            name = None if n in turns else _turn(bound)
            if name is not None:
                turns[n] = tr("the loop's bound {bound:.6g} is {turn}", bound=bound, turn=name)
    return {
        n: _Angle(frozenset(increments.get(n, ())), n in pi, n in inverse, turns.get(n))
        for n in set(increments) | pi | inverse | set(turns)
    }


_NOTHING_SAID = _Angle()


def _show(value: float, digits: int = 4) -> str:
    """``value`` to ``digits`` significant digits, a rounding error near zero shown as 0."""
    return f"{round(value, 9) + 0.0:.{digits}g}"


MB504_DOC = RuleDoc(
    "MB504",
    reports="""
`SIN`, `COS` or `TAN` of one variable whose values over the run are an angle stepped in
radians, decided by the sweep and the step: all values within ±2π, a sweep of 0.5 or more,
steps under 0.8 (the loop's increment, a number or a variable of one value, else the sweep
over the count of values: as degrees,
sub-degree steps over a sweep under 7° that moves the tool almost nowhere), and one sign of
radians a degree program does not give: the step typed as a radian conversion (three decimals
or more and no fraction of a degree: `0.1396`, `0.0873`, not `0.5`, `0.25` or `0.125`), the
loop's bound at a quarter, half or whole turn in radians (`1.57`, `3.1416`, `6.2832`, or
written with a π), or a π in the angle's assignments (`#16=#16+8.*3.14159/180.`). The
message gives the first value, the step and the sweep in radians and what they are in
degrees, the sign that decided, and how little the function's value moves.
""",
    why="""
FANUC's trigonometric functions take degrees: an arc written
in radians (18° to 162° as 0.3142 to 2.8275) is swept over under 3°, so every cut of a
fitting-method program lands within a fraction of a millimetre instead of following the
profile, and the part is cut wrong without any alarm.
""",
    example="""
```nc
O5001 (ARC FINISHING)
#16=0.3142
G00 X150. Z100.
N5 G00 Z[50.+8.8*COS[#16]]
X[100.-17.6*SIN[#16]]
G32 Z-113. F25.
G00 X140.
#16=#16+0.1396
IF[#16LE2.8275]GOTO5
M30
```
""",
    fix="""
Write the angles in degrees (`#16=18.`, `#16=#16+8.`), or convert once
(`#16=#16*57.29578`).
""",
    not_reported="""
Degree programs: angles beyond ±2π (0° to 360° in steps of 10°, a bolt circle's 360/N
pitch, an ellipse from 0° to 90°), a sweep under 0.5, steps of 0.8 and more, and small angles
in round degree steps with a bound that is no turn in radians (a taper of 0.5° to 3° in steps
of 0.5°; even 0° to 2.8° in steps of 0.1°, which could be radians, is left alone). Angles
assigned from `ATAN`, `ASIN` or `ACOS` (degrees) unless a π converts them, a value that
does not change or is read fewer than three times, and arguments that are expressions rather
than one variable.
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    facts = ctx.doc_facts()
    if facts is None:
        return
    blocks = ctx.doc.blocks
    programs: dict[int | None, dict[int, _Angle]] = {}
    for line, calls in _trig_lines(ctx.doc):
        for text, number, span in calls:
            summary = facts.reads.get((line, number))
            if summary is None or summary.count < 3 or not summary.numeric or summary.constant:
                continue
            low, high = summary.minimum, summary.maximum
            sweep = high - low
            if low < -RANGE or high > RANGE or sweep < MIN_SWEEP:
                continue
            program = ctx.index.program_at(line)
            key = None if program is None else program.first_line
            said = programs.get(key)
            if said is None:
                lines = (
                    range(len(blocks))
                    if program is None
                    else range(program.first_line, min(program.end_line, len(blocks)))
                )
                said = programs[key] = _program_angles(facts, blocks, lines)
            angle = said.get(number, _NOTHING_SAID)
            if angle.inverse and not angle.pi:
                continue  # ATAN, ASIN and ACOS give degrees
            # The first value may be vacant or unknown (a loop whose counter starts unset).
            first = summary.first if isinstance(summary.first, float) else low
            rising = first - low <= high - first
            # The loop's increment, when it is one and steps through the values read here.
            typed = next(iter(angle.increments)) if len(angle.increments) == 1 else None
            if typed is not None and (
                typed == 0 or summary.count - 1 < sweep / abs(typed) - 0.5 or (typed > 0) != rising
            ):
                typed = None
            step = abs(typed) if typed is not None else sweep / (summary.count - 1)
            if step >= MAX_STEP:
                continue  # steps of a degree and more
            sign: str
            if angle.pi:
                sign = tr("a π in its assignments")
            elif angle.turn is not None:
                sign = angle.turn
            elif typed is not None and _typed_conversion(typed):
                sign = tr(
                    "the step {step:.6g} is typed as a radian conversion, not degrees",
                    step=abs(typed),
                )
            else:
                continue  # as likely small angles in degrees: quiet
            name = text.split("[", 1)[0]
            last = high if rising else low
            signed = step if rising else -step
            in_degrees = tr(
                "{first}° in steps of {step}° to {last}°",
                first=_show(math.degrees(first)),
                step=_show(math.degrees(signed), 3),
                last=_show(math.degrees(last)),
            )
            results = [_degrees_function(name, v) for v in (low, high)]
            yield make(
                MB504,
                tr(
                    "{call_text} gets #{variable} from {first} in steps of {step} to "
                    "{last} ({count} times), a sweep of {sweep}: radians "
                    "({in_degrees}; {sign}), but {function} takes degrees, so the sweep is "
                    "{sweep_degrees:.3g}° and {function} stays between {low:.3g} and "
                    "{high:.3g}; write the angles in degrees (or multiply by 57.29578)",
                    call_text=text,
                    variable=number,
                    first=_show(first),
                    step=_show(signed),
                    last=_show(last),
                    count=summary.count,
                    sweep=_show(sweep),
                    in_degrees=in_degrees,
                    sign=sign,
                    function=name,
                    sweep_degrees=sweep,
                    low=min(results),
                    high=max(results),
                ),
                line,
                span.start,
                span.end,
            )


def _degrees_function(name: str, value: float) -> float:
    angle = math.radians(value)
    return {"SIN": math.sin, "COS": math.cos}.get(name, math.tan)(angle)
