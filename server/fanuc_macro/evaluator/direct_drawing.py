"""The end of a straight move written as one coordinate and the angle of the line (",A"):
FANUC 0i-TF "Direct drawing dimension programming" (the angle from the plane's first axis,
+Z on a lathe, counterclockwise); the mill's ",A" in the plane in force is taken the same way
(unverified for the 0i-MF: some controls have it as an option). The move's other coordinate
is where the line through the start at that angle meets the given one."""

from __future__ import annotations

import math

# An angle whose line runs along an axis reaches no other value on that axis.
_FLAT = 1e-12


def missing_coordinate(
    start: tuple[float, float],
    end_first: float | None,
    end_second: float | None,
    angle: float,
    second_scale: float = 1.0,
) -> float | None:
    """The end coordinate not given: the second (from ``end_first``) or the first (from
    ``end_second``), exactly one of them given. ``start`` is (first, second) in the program's
    values; ``second_scale`` 2 for a lathe's X in diameter. None when the line at ``angle``
    never reaches the given value (parallel to its axis)."""
    c = math.cos(math.radians(angle))
    s = math.sin(math.radians(angle))
    first, second = start
    if end_first is not None:
        if abs(c) < _FLAT:
            return None
        return second + (end_first - first) / c * s * second_scale
    if end_second is None or abs(s) < _FLAT:
        return None
    return first + (end_second - second) / second_scale / s * c
