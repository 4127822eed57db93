"""Macro B typed by the user at a stop (a watch, a breakpoint's condition, a console
assignment, a logpoint's ``{...}``), and what a DPRNT sends, read from a stopped activation
without recording anything in the run's facts."""

from __future__ import annotations

import re
from collections.abc import Callable

from ..evaluator.compiler import CondEvaluator, Evaluator, compile_cond, compile_expr
from ..evaluator.machine import Activation
from ..evaluator.values import MacroAlarm, Unknown, Value
from ..syntax.parser import default_parser
from ..syntax.tree import Assign, IfGoto, Var
from .answers import DebugError

_INTERPOLATION = re.compile(r"\{([^{}]*)\}")


def parse_expression(text: str) -> Evaluator:
    """A Macro B expression (``#4``, ``[#100-2*#9]``, ``SQRT[#4]``) as the evaluator runs it."""
    line = default_parser().parse_line(f"#1=[{text}]")
    statement = line.statement
    if line.problem is not None or not isinstance(statement, Assign):
        raise DebugError(f"{text!r} is not a Macro B expression")
    return compile_expr(statement.value)


def parse_condition(text: str) -> CondEvaluator:
    """A Macro B condition (``#9 GT 1.5``, ``[#1 EQ 2] AND [#2 LT 0]``)."""
    parser = default_parser()
    for code in (f"IF[{text}]GOTO1", f"IF{text}GOTO1"):
        line = parser.parse_line(code)
        if line.problem is None and isinstance(line.statement, IfGoto):
            return compile_cond(line.statement.cond)
    raise DebugError(
        f"{text!r} is not a Macro B condition (write it as in an IF: #9 GT 1.5, "
        "[#1 EQ 2] AND [#2 LT 0])"
    )


def parse_assignment(text: str) -> tuple[Var, Evaluator] | None:
    """``#100=5`` typed in the debug console: its target and value; None if it is not one."""
    if "=" not in text:
        return None
    line = default_parser().parse_line(text)
    statement = line.statement
    if line.problem is not None or not isinstance(statement, Assign):
        return None
    return statement.target, compile_expr(statement.value)


def hit_test(text: str) -> Callable[[int], bool]:
    """A hit condition: ``3`` (from the third hit on), ``>=3``, ``==3``, ``>3``, ``<3``,
    ``<=3``, ``%3`` (every third hit)."""
    found = re.fullmatch(r"\s*(>=|<=|==|=|>|<|%)?\s*(\d+)\s*", text)
    if found is None:
        raise DebugError(f"hit count {text!r}: write a number (3), or >=3, ==3, >3, <3, %3")
    op, count = found.group(1) or ">=", int(found.group(2))
    tests: dict[str, Callable[[int], bool]] = {
        ">=": lambda n: n >= count,
        "<=": lambda n: n <= count,
        "==": lambda n: n == count,
        "=": lambda n: n == count,
        ">": lambda n: n > count,
        "<": lambda n: n < count,
        "%": lambda n: count > 0 and n % count == 0,
    }
    return tests[op]


class Probe:
    """An activation as an expression typed at a stop reads it: without recording anything
    in the run's facts."""

    def __init__(self, act: Activation) -> None:
        self.act = act
        self.locals = act.locals
        self.store = act.store

    def read_global(self, number: int) -> Value:
        return self.act.read_global(number)

    def read_indirect(self, number: Value, node: Var) -> Value:
        return self.act.read_indirect(number, node)

    @property
    def signed_atan(self) -> bool:
        return self.act.signed_atan

    @property
    def length_increment(self) -> float:
        return self.act.length_increment

    def note_rounding(self, name: str, argument: float, result: float) -> None:
        pass


def read_variable(act: Activation, n: int) -> Value:
    if 1 <= n <= 33:
        return act.locals[n]
    if n == 0:
        return None
    v = act.store.get(n, act)
    return act.read_global(n) if v is act else v  # type: ignore[return-value]


def dprnt_line(text: str, act: Activation) -> str:
    """What ``DPRNT[...]`` sends: its characters as written (``*`` a space), each ``#n[ab]``
    as a number of ``a`` integer and ``b`` decimal digits (FANUC custom macro, "DPRNT"; the
    sign and the digits' padding, which parameter 6001 PRT sets, are unverified: a leading
    minus, no padding). A vacant variable prints as 0 (unverified)."""
    inner = text[text.find("[") + 1 : text.rfind("]")] if "[" in text else ""
    out: list[str] = []
    at = 0
    pattern = re.compile(r"#(\d+)(?:\[(\d)(\d)\])?")
    while at < len(inner):
        found = pattern.match(inner, at)
        if found is None:
            ch = inner[at]
            out.append(" " if ch == "*" else ch)
            at += 1
            continue
        n = int(found.group(1))
        decimals = int(found.group(3)) if found.group(3) is not None else 0
        value = read_variable(act, n)
        if value is None:
            value = 0.0
        if isinstance(value, Unknown):
            out.append(f"<#{n} {value.describe()}>")
        else:
            out.append(f"{value:.{decimals}f}" if decimals else f"{round(value):d}")
        at = found.end()
    return "".join(out)


def interpolate(text: str, act: Activation, show: Callable[[Value], str]) -> str:
    """A logpoint's message with each ``{expression}`` replaced by its value at ``act``."""

    def one(found: re.Match[str]) -> str:
        try:
            return show(parse_expression(found.group(1))(Probe(act)))
        except (DebugError, MacroAlarm) as err:
            return f"<{err}>"

    return _INTERPOLATION.sub(one, text)
