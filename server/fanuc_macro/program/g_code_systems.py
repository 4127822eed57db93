"""FANUC's lathe G code systems A, B and C: the same functions under other numbers.

A lathe control reads its programs in one of three G code systems (parameters GSB and GSC,
No. 3401#6 and #7). The analysis thinks in system A, the 0i-TF default: a block of a system B or
C program has its G codes translated to system A's before the evaluator runs it, and its
messages name the codes as the program writes them (:func:`written`).

Source: FANUC Series 0i-TF Plus Operator's Manual (B-64694EN), "List of G codes" (lathe
system: G code systems A, B, C side by side). The rows taken:

===================================  ======  ======  ======
function                             A       B       C
===================================  ======  ======  ======
inch / metric input                  G20/21  G20/21  G70/71
threading                            G32     G33     G33
coordinate system setting, S clamp   G50     G92     G92
workpiece coordinate system preset   G50.3   G92.1   G92.1
finishing cycle                      G70     G70     G72
stock removal in turning             G71     G71     G73
stock removal in facing              G72     G72     G74
pattern repeating                    G73     G73     G75
end face peck drilling               G74     G74     G76
outer / inner diameter drilling      G75     G75     G77
multiple threading cycle             G76     G76     G78
turning cycle                        G90     G77     G20
threading cycle                      G92     G78     G21
facing cycle                         G94     G79     G24
feed per minute / per revolution     G98/99  G94/95  G94/95
absolute / incremental programming   (U W)   G90/91  G90/91
canned drilling: initial / R level   none    G98/99  G98/99
===================================  ======  ======  ======

Every other G code is the same in the three systems. Unverified against the manual's text:
that a system B or C program's U and W still read as incremental X and Z (they are kept so).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from types import MappingProxyType

ABSOLUTE = 90.0  # systems B and C: G90, absolute programming (group 03)
INCREMENTAL = 91.0  # systems B and C: G91, incremental programming

# The written code of a system B program -> system A's code of the same function; None: a
# code with no function in system B that system A gives one (G32, G50, G50.3 are A's only),
# or one that no run here needs (the return level of a drilling cycle).
_B: Mapping[float, float | None] = MappingProxyType(
    {
        32.0: None,
        33.0: 32.0,
        50.0: None,
        50.3: None,
        92.0: 50.0,
        92.1: 50.3,
        77.0: 90.0,
        78.0: 92.0,
        79.0: 94.0,
        90.0: None,
        91.0: None,
        94.0: 98.0,
        95.0: 99.0,
        98.0: None,
        99.0: None,
    }
)

_C: Mapping[float, float | None] = MappingProxyType(
    {
        **_B,
        20.0: 90.0,
        21.0: 92.0,
        24.0: 94.0,
        70.0: 20.0,
        71.0: 21.0,
        72.0: 70.0,
        73.0: 71.0,
        74.0: 72.0,
        75.0: 73.0,
        76.0: 74.0,
        77.0: 75.0,
        78.0: 76.0,
        79.0: None,
    }
)

_TO_A: Mapping[str, Mapping[float, float | None]] = MappingProxyType({"B": _B, "C": _C})

# System A's code -> the code a system B or C program writes for the same function.
_FROM_A: Mapping[str, Mapping[float, float]] = MappingProxyType(
    {
        system: MappingProxyType({a: written for written, a in table.items() if a is not None})
        for system, table in _TO_A.items()
    }
)


def translated(g_codes: Sequence[float], system: str) -> tuple[Sequence[float], float | None]:
    """A block's G codes as system A's, and the group 03 code it gives (ABSOLUTE,
    INCREMENTAL, or None) in system B or C; system A's are returned as they are."""
    table = _TO_A.get(system)
    if table is None:
        return g_codes, None
    codes: list[float] = []
    mode: float | None = None
    for g in g_codes:
        if g in (ABSOLUTE, INCREMENTAL):
            mode = g
        elif g in table:
            a = table[g]
            if a is not None:
                codes.append(a)
        else:
            codes.append(g)
    return codes, mode


def system_a_code(value: float, system: str) -> float | None:
    """The system A code of the function a ``system`` program's G``value`` has (None: none)."""
    table = _TO_A.get(system)
    if table is None or value not in table:
        return value
    return table[value]


def written(code: str, system: str) -> str:
    """System A's code name (``"G92"``) as a ``system`` program writes it (``"G78"``)."""
    table = _FROM_A.get(system)
    if table is None or not code.startswith("G"):
        return code
    try:
        value = float(code[1:])
    except ValueError:
        return code
    other = table.get(value)
    if other is None:
        return code
    return f"G{int(other):02d}" if other == int(other) else f"G{other:g}"


def group_03_name(value: float) -> str:
    """What G90 and G91 do in systems B and C (hover)."""
    return "absolute programming" if value == ABSOLUTE else "incremental programming"
