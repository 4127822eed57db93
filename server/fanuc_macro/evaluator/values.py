"""Macro values as a FANUC control holds them, plus "unknown" for a static analysis.

A value is a ``float``, ``None`` (vacant, ``<空>``) or :class:`Unknown` (the analysis cannot know
it: a common or system variable nobody set, or something computed from one). FANUC's vacancy
rules: a vacant variable is 0 in arithmetic and in GT/LT/GE/LE, differs from 0 in EQ/NE, and a
plain copy ``#2=#1`` keeps it vacant; trigonometry is in degrees.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from enum import Enum
from types import MappingProxyType

from ..translation import tr


@dataclass(frozen=True, slots=True)
class Unknown:
    """A value the analysis cannot compute; ``deps`` are the variables it comes from."""

    deps: frozenset[int]

    def describe(self) -> str:
        if not self.deps:
            return tr("unknown")
        names = ", ".join(f"#{n}" for n in sorted(self.deps)[:6])
        more = "..." if len(self.deps) > 6 else ""
        return tr("depends on {variables}{more}", variables=names, more=more)


Value = float | Unknown | None

NO_DEPS: frozenset[int] = frozenset()
UNKNOWN = Unknown(NO_DEPS)


def merge_unknown(*values: Value) -> Unknown:
    deps: set[int] = set()
    for v in values:
        if isinstance(v, Unknown):
            deps |= v.deps
    return Unknown(frozenset(deps))


class AlarmKind(Enum):
    """What an alarm is about; its value is the name the trace and the debugger print."""

    ZERO_DIVIDE = "zero-divide"
    OVERFLOW = "overflow"
    SQRT_NEGATIVE = "sqrt-negative"
    ASIN_RANGE = "asin-range"
    ACOS_RANGE = "acos-range"
    LN_DOMAIN = "ln-domain"
    BIN_RANGE = "bin-range"
    BCD_RANGE = "bcd-range"
    POW_RANGE = "pow-range"
    ATAN_ZERO = "atan-zero"
    MACRO_ALARM = "macro-alarm"  # #3000
    GOTO_TARGET = "goto-target"
    GOTO_MISSING = "goto-missing"
    RETURN_MISSING = "return-missing"
    NESTING = "nesting"
    WRITE_READ_ONLY = "write-read-only"
    NO_SUCH_VARIABLE = "no-such-variable"
    FEED_ZERO = "feed-zero"
    LEAD_ZERO = "lead-zero"


class MacroAlarm(Exception):
    """An alarm the control would raise (``PS0112 ZERO DIVIDE`` ...)."""

    def __init__(
        self, alarm: str, kind: AlarmKind, message: str, operand: float | None = None
    ) -> None:
        super().__init__(message)
        self.alarm = alarm
        self.kind = kind
        self.message = message
        self.operand = operand
        self.node: object | None = None  # the AST node, set by the compiled closure


def fmt(value: Value) -> str:
    """A value as the control's display shows it (8 significant digits at most)."""
    if value is None:
        return "<vacant>"
    if isinstance(value, Unknown):
        return value.describe()
    if value != value:
        return "NaN"
    if math.isinf(value):
        return "overflow"
    if value == int(value) and abs(value) < 1e15:
        return f"{int(value)}."
    text = f"{value:.8g}"
    if "e" in text:
        return text
    if "." not in text:
        text += "."
    return text


def fmt_address(value: float, inch: bool = False) -> str:
    """An address value rounded to the usual least input increment (IS-B): 0.001 mm, or
    0.0001 inch in G20."""
    places = 4 if inch else 3
    rounded = round(value, places)
    if rounded == int(rounded):
        return f"{int(rounded)}."
    return f"{rounded:.{places}f}".rstrip("0")


# ---- functions (degrees) ---------------------------------------------------------------------


def _num(v: float | None) -> float:
    return 0.0 if v is None else v


def f_sin(x: float) -> float:
    return math.sin(math.radians(x))


def f_cos(x: float) -> float:
    return math.cos(math.radians(x))


def f_tan(x: float) -> float:
    c = math.cos(math.radians(x))
    if abs(c) < 1e-12:
        raise MacroAlarm(
            "PS0112",
            AlarmKind.ZERO_DIVIDE,
            tr(
                "TAN[{argument}]: the tangent of {argument} degrees is infinite (ZERO DIVIDE)",
                argument=fmt(x),
            ),
            x,
        )
    return math.sin(math.radians(x)) / c


def f_asin(x: float) -> float:
    if not -1.0 <= x <= 1.0:
        raise MacroAlarm(
            "PS0119",
            AlarmKind.ASIN_RANGE,
            tr("ASIN argument {argument} is outside [-1, 1]", argument=fmt(x)),
            x,
        )
    return math.degrees(math.asin(x))


def f_acos(x: float) -> float:
    if not -1.0 <= x <= 1.0:
        raise MacroAlarm(
            "PS0119",
            AlarmKind.ACOS_RANGE,
            tr("ACOS argument {argument} is outside [-1, 1]", argument=fmt(x)),
            x,
        )
    return math.degrees(math.acos(x))


def f_atan(x: float) -> float:
    # One-argument form (30i): the result of FANUC's ATAN is 0 to 360 degrees by default
    # (unverified; parameter 6004#0 NAT gives -180 to 180).
    return math.degrees(math.atan(x)) % 360.0


def f_atan2(a: float, b: float) -> float:
    if a == 0.0 and b == 0.0:
        raise MacroAlarm("PS0119", AlarmKind.ATAN_ZERO, tr("ATAN[0]/[0] has no angle"), 0.0)
    return math.degrees(math.atan2(a, b)) % 360.0


def f_sqrt(x: float) -> float:
    if x < 0.0:
        raise MacroAlarm(
            "PS0119",
            AlarmKind.SQRT_NEGATIVE,
            tr("SQRT argument {argument} is negative", argument=fmt(x)),
            x,
        )
    return math.sqrt(x)


def f_ln(x: float) -> float:
    if x <= 0.0:
        raise MacroAlarm(
            "PS0119",
            AlarmKind.LN_DOMAIN,
            tr("LN argument {argument} is not positive", argument=fmt(x)),
            x,
        )
    return math.log(x)


def f_exp(x: float) -> float:
    try:
        return math.exp(x)
    except OverflowError:
        raise MacroAlarm(
            "PS0111", AlarmKind.OVERFLOW, tr("EXP[{argument}] overflows", argument=fmt(x)), x
        ) from None


def f_round(x: float) -> float:
    # FANUC rounds halves away from zero.
    return float(math.floor(abs(x) + 0.5)) * (1.0 if x >= 0 else -1.0)


def f_fix(x: float) -> float:
    return float(math.trunc(x))


def f_fup(x: float) -> float:
    t = math.trunc(x)
    return float(t if t == x else t + (1 if x > 0 else -1))


def f_abs(x: float) -> float:
    return abs(x)


def f_bin(x: float) -> float:
    """BCD to binary."""
    if x < 0:
        raise MacroAlarm(
            "PS0119",
            AlarmKind.BIN_RANGE,
            tr("BIN argument {argument} is negative", argument=fmt(x)),
            x,
        )
    n = int(x)
    result = 0
    scale = 1
    while n:
        digit = n & 0xF
        if digit > 9:
            raise MacroAlarm(
                "PS0119",
                AlarmKind.BIN_RANGE,
                tr("BIN argument {argument} is not BCD", argument=fmt(x)),
                x,
            )
        result += digit * scale
        scale *= 10
        n >>= 4
    return float(result)


def f_bcd(x: float) -> float:
    """Binary to BCD."""
    if x < 0:
        raise MacroAlarm(
            "PS0119",
            AlarmKind.BCD_RANGE,
            tr("BCD argument {argument} is negative", argument=fmt(x)),
            x,
        )
    n = int(x)
    result = 0
    shift = 0
    while n:
        result |= (n % 10) << shift
        shift += 4
        n //= 10
    try:
        return float(result)
    except OverflowError:  # 4 bits a digit: past 77 digits the BCD form is no double
        raise MacroAlarm(
            "PS0111",
            AlarmKind.OVERFLOW,
            tr("BCD[{argument}] overflows (CALCULATED DATA OVERFLOW)", argument=fmt(x)),
            x,
        ) from None


def f_adp(x: float) -> float:
    # ADP adds the decimal point an argument was passed without; this analysis takes values
    # as written in mm, so it leaves them as they are (ADP's exact semantics are unverified).
    return x


def f_pow(a: float, b: float) -> float:
    try:
        result = math.pow(a, b)
    except OverflowError:
        raise MacroAlarm(
            "PS0111",
            AlarmKind.OVERFLOW,
            tr(
                "POW[{base},{exponent}] overflows (CALCULATED DATA OVERFLOW)",
                base=fmt(a),
                exponent=fmt(b),
            ),
            a,
        ) from None
    except ValueError:
        raise MacroAlarm(
            "PS0119",
            AlarmKind.POW_RANGE,
            tr("POW[{base},{exponent}] has no real value", base=fmt(a), exponent=fmt(b)),
            a,
        ) from None
    return result


ONE_ARG: Mapping[str, Callable[[float], float]] = MappingProxyType({
    "SIN": f_sin, "COS": f_cos, "TAN": f_tan, "ASIN": f_asin, "ACOS": f_acos, "ATAN": f_atan,
    "SQRT": f_sqrt, "ABS": f_abs, "ROUND": f_round, "FIX": f_fix, "FUP": f_fup, "LN": f_ln,
    "EXP": f_exp, "BIN": f_bin, "BCD": f_bcd, "ADP": f_adp,
})  # fmt: skip
TWO_ARG: Mapping[str, Callable[[float, float], float]] = MappingProxyType(
    {"ATAN": f_atan2, "POW": f_pow}
)


def divide(a: float, b: float) -> float:
    if b == 0.0:
        raise MacroAlarm(
            "PS0112",
            AlarmKind.ZERO_DIVIDE,
            tr("division of {dividend} by zero (ZERO DIVIDE)", dividend=fmt(a)),
            b,
        )
    return a / b


def modulo(a: float, b: float) -> float:
    ia, ib = int(a), int(b)
    if ib == 0:
        raise MacroAlarm(
            "PS0112",
            AlarmKind.ZERO_DIVIDE,
            tr("{dividend} MOD 0 (ZERO DIVIDE)", dividend=fmt(a)),
            b,
        )
    return float(math.fmod(ia, ib))


def bit_and(a: float, b: float) -> float:
    return float(int(a) & int(b))


def bit_or(a: float, b: float) -> float:
    return float(int(a) | int(b))


def bit_xor(a: float, b: float) -> float:
    return float(int(a) ^ int(b))


def compare(op: str, a: Value, b: Value) -> bool | None:
    """A FANUC comparison; None when an operand is unknown."""
    if isinstance(a, Unknown) or isinstance(b, Unknown):
        return None
    # Vacant equals vacant and nothing else: None == 0.0 is False, as FANUC has it.
    if op == "EQ":
        return a == b
    if op == "NE":
        return a != b
    x, y = _num(a), _num(b)
    if op == "GT":
        return x > y
    if op == "LT":
        return x < y
    if op == "GE":
        return x >= y
    return x <= y  # LE
