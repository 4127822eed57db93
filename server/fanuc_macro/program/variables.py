"""What a variable number means on a FANUC control (see shared reference macro-b.md §2).

Facts marked [K] in the reference are background knowledge not checked against a FANUC manual;
they are kept here as they are there, and the hover text says "unverified" for them.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..translation import tr


@dataclass(frozen=True, slots=True)
class VariableKind:
    kind: str  # "null", "local", "common", "retained", "extended-common", "system", "none"
    meaning: str
    read_only: bool = False
    verified: bool = True


# (first, last, meaning, read_only, verified)
_SYSTEM_RANGES: tuple[tuple[int, int, str, bool, bool], ...] = (
    (1000, 1015, tr("interface input signal UI000-UI015 (bit, from the PMC)"), True, False),
    (1032, 1032, tr("interface input signals UI000-UI031 (word)"), True, False),
    (1100, 1115, tr("interface output signal UO000-UO015 (bit, to the PMC)"), False, False),
    (1132, 1133, tr("interface output signals (word)"), False, False),
    (2001, 2200, tr("tool offset (wear; lathe: X wear; mill memory C: H wear)"), False, False),
    (
        2201,
        2400,
        tr("tool offset (mill memory C: H geometry; lathe: nose radius wear)"),
        False,
        False,
    ),
    (2401, 2499, tr("lathe Y offsets (wear/geometry)"), False, False),
    (2501, 2501, tr("lathe workpiece shift X"), False, False),
    (2601, 2601, tr("lathe workpiece shift Z"), False, False),
    (2701, 2999, tr("lathe tool geometry offsets (X, Z, nose radius)"), False, False),
    (3000, 3000, tr("macro alarm: #3000=n (MESSAGE) stops with alarm 3000+n"), False, True),
    (3001, 3001, tr("millisecond clock"), False, True),
    (3002, 3002, tr("hour clock"), False, False),
    (3003, 3003, tr("single-block suppression and FIN wait (bits 0 and 1)"), False, False),
    (3004, 3004, tr("feed hold / override / exact-stop suppression (bits 0-2)"), False, True),
    (3005, 3005, tr("settings"), False, False),
    (3006, 3006, tr("stop with message: #3006=1 (MESSAGE)"), False, True),
    (3007, 3007, tr("mirror image status"), True, False),
    (3011, 3011, tr("date YYYYMMDD"), True, True),
    (3012, 3012, tr("time HHMMSS"), True, True),
    (3901, 3901, tr("parts machined"), False, True),
    (3902, 3902, tr("parts required"), False, True),
    (4000, 4000, tr("main program number"), True, True),
    (4001, 4030, tr("modal G code of group (number - 4000), block being pre-read"), True, True),
    (
        4102,
        4130,
        tr("modal value of address B D E F H M N O S T P (#4102 B ... #4120 T)"),
        True,
        True,
    ),
    (4201, 4430, tr("modal information of the executing block (30i)"), True, False),
    (
        5001,
        5020,
        tr("block end position, workpiece coordinates (axis = number - 5000)"),
        True,
        True,
    ),
    (5021, 5040, tr("current machine position (stops buffering)"), True, True),
    (5041, 5060, tr("current workpiece position"), True, True),
    (5061, 5080, tr("skip (G31) position"), True, True),
    (5081, 5100, tr("tool length offset in effect"), True, True),
    (5101, 5120, tr("servo position deviation"), True, True),
    (5201, 5220, tr("external workpiece zero offset (EXT)"), False, True),
    (5221, 5240, tr("G54 work offset (axis = number - 5220)"), False, True),
    (5241, 5260, tr("G55 work offset"), False, True),
    (5261, 5280, tr("G56 work offset"), False, True),
    (5281, 5300, tr("G57 work offset"), False, True),
    (5301, 5320, tr("G58 work offset"), False, True),
    (5321, 5340, tr("G59 work offset"), False, True),
    (7001, 7948, tr("G54.1 P1-P48 additional work offsets"), False, True),
    (10001, 19999, tr("tool offsets (full range) and G54.1 P1-P300 (option)"), False, False),
)

LOCAL_LAST = 33


# The kinds of the ranges outside the system variables, made once.
_NULL = VariableKind("null", tr("always vacant (<vacant>); read-only"), read_only=True)
_LOCAL = VariableKind("local", tr("local variable of the current macro level"))
_COMMON = VariableKind("common", tr("common variable, cleared at power-off"))
_RETAINED = VariableKind("retained", tr("common variable, kept through power-off"))
_EXTENDED = VariableKind(
    "extended-common",
    tr("common variable of the extended range (an option on 0i-F / 30i)"),
    verified=False,
)
_SYSTEM = VariableKind("system", tr("system variable"), verified=False)
_NONE = VariableKind("none", tr("no such variable on a FANUC control (alarm PS0115)"))


def classify(number: int) -> VariableKind:
    if number == 0:
        return _NULL
    if 1 <= number <= LOCAL_LAST:
        return _LOCAL
    if 100 <= number <= 199:
        return _COMMON
    if 500 <= number <= 999:
        return _RETAINED
    if 200 <= number <= 499:
        return _EXTENDED
    for first, last, meaning, read_only, verified in _SYSTEM_RANGES:
        if first <= number <= last:
            return VariableKind("system", meaning, read_only, verified)
    if number >= 1000:
        return _SYSTEM
    return _NONE


def exists(number: int) -> bool:
    return classify(number).kind != "none"


# G65 argument letters, specification I: letter -> local variable.
ARGUMENT_VARIABLES: Mapping[str, int] = MappingProxyType({
    "A": 1, "B": 2, "C": 3, "I": 4, "J": 5, "K": 6, "D": 7, "E": 8, "F": 9, "H": 11,
    "M": 13, "Q": 17, "R": 18, "S": 19, "T": 20, "U": 21, "V": 22, "W": 23, "X": 24,
    "Y": 25, "Z": 26,
})  # fmt: skip

FORBIDDEN_ARGUMENTS = frozenset("GLNOP")
