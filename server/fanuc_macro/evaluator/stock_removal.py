"""The lathe's multiple repetitive cycles that cut to a profile: the moves of G71 (stock
removal in turning), G72 (stock removal in facing) and G73 (pattern repeating), worked out
from the start point and the finishing profile N(ns)..N(nf) (G70, finishing, runs the profile
itself: the evaluator executes its blocks).

Source: FANUC Series 0i-TF Operator's Manual (B-64604EN) and 0i-TD (B-64304EN), "Multiple
repetitive cycle (G70-G76)": "Stock removal in turning (G71)", "Stock removal in facing
(G72)", "Pattern repeating (G73)", "Finishing cycle (G70)". What is taken from them:

- G71 ``U(Δd) R(e)`` / ``G71 P(ns) Q(nf) U(Δu) W(Δw) F``: the area between the start point A
  and the profile A'-B, moved by the finishing allowance (Δu/2 in X, a radius, and Δw in Z),
  is cut in layers Δd deep (a radius), each parallel to Z, in the direction of the profile;
  the tool goes in to each layer as the ns block moves (G00 or G01), leaves it by e at 45°,
  goes back to A's Z, and after the last layer cuts along the moved profile ("rough cutting
  as finishing", parameter 5105#1 RF1 = 0, the default) and returns to A.
  Type I (the ns block moves X only) is drawn; type II (the ns block names Z too, W0 when Z
  does not move) is not.
- G72 ``W(Δd) R(e)`` / ``G72 P Q U W F``: the same with the layers parallel to X, Δd deep in
  Z; type I: the ns block moves Z only.
- G73 ``U(Δi) W(Δk) R(d)`` / ``G73 P Q U(Δu) W(Δw) F``: the profile cut d times, each time
  moved less, from Δi (a radius) + Δu/2 and Δk + Δw for the first to Δu/2 and Δw for the
  last, each from A and back to it.

Unverified (not spelt out in the manuals' text, or set by parameters): the 45° escape and the
return to the start point are drawn at rapid; a layer that would be less than Δd from the
profile's nearest level is not cut, the semi-finishing pass takes what is left; a layer whose
level the profile never reaches is cut to the profile's end; G73 returns to A after each pass
at rapid.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence

Point = dict[str, float]
# A stretch of the profile: kind ("rapid", "feed", "arc"), start, end, the arc's centre and
# direction (G02: clockwise), in work coordinates (X a diameter).
Segment = tuple[str, Point, Point, Point | None, bool | None]
# A move the cycle makes: kind, end, centre, clockwise.
Leg = tuple[str, Point, Point | None, bool | None]

MAX_LAYERS = 2000  # a cycle with more layers or passes than this is cut short (a typo)
EPS = 1e-9

# The plane of the profile as the geometry works it: (z, r), r the radius (X / 2); G03 turns
# counter-clockwise in it (0i-TF "Plane selection": G18, Z to X).
Plane2 = tuple[float, float]


def _zr(p: Point) -> Plane2:
    return (p["Z"], p["X"] / 2.0)


def _work(base: Point, zr: Plane2, q: Callable[[float], float]) -> Point:
    return {**base, "X": q(zr[1] * 2.0), "Z": q(zr[0])}


def _moved(p: Point, dz: float, dr: float) -> Point:
    return {**p, "X": p["X"] + 2.0 * dr, "Z": p["Z"] + dz}


def _sweep(centre: Plane2, start: Plane2, point: Plane2, clockwise: bool) -> float:
    """How far along the arc from ``start`` ``point`` is, as an angle in [0, 2π)."""
    a0 = math.atan2(start[1] - centre[1], start[0] - centre[0])
    a1 = math.atan2(point[1] - centre[1], point[0] - centre[0])
    turn = (a0 - a1) if clockwise else (a1 - a0)
    return turn % (2.0 * math.pi)


def crossing(contour: Sequence[Segment], depth: int, level: float) -> float | None:
    """Where, along the other coordinate, the contour first reaches ``level`` of coordinate
    ``depth`` (0: Z, 1: the radius), going from its start; None if it never does."""
    cut = 1 - depth
    for kind, s, e, centre, clockwise in contour:
        a, b = _zr(s), _zr(e)
        if kind != "arc" or centre is None:
            da, db = a[depth] - level, b[depth] - level
            if abs(da) <= EPS:
                return a[cut]
            if da * db <= 0.0 and a[depth] != b[depth]:
                t = (level - a[depth]) / (b[depth] - a[depth])
                return a[cut] + t * (b[cut] - a[cut])
            continue
        c = _zr(centre)
        radius = math.hypot(a[0] - c[0], a[1] - c[1])
        offset = level - c[depth]
        if abs(offset) > radius + EPS:
            continue
        half = math.sqrt(max(0.0, radius * radius - offset * offset))
        total = _sweep(c, a, b, bool(clockwise)) or 2.0 * math.pi
        best: tuple[float, float] | None = None
        for sign in (-1.0, 1.0):
            p = [0.0, 0.0]
            p[depth] = level
            p[cut] = c[cut] + sign * half
            point = (p[0], p[1])
            t = _sweep(c, a, point, bool(clockwise))
            if t <= total + EPS and (best is None or t < best[0]):
                best = (t, point[cut])
        if best is not None:
            return best[1]
    return None


def monotonic(contour: Sequence[Segment]) -> bool:
    """Whether X and Z each only rise or only fall along the contour's ends of stretches."""
    for axis in ("X", "Z"):
        values = [contour[0][1][axis], *(seg[2][axis] for seg in contour)]
        steps = [b - a for a, b in itertools.pairwise(values)]
        if any(s > EPS for s in steps) and any(s < -EPS for s in steps):
            return False
    return True


def _along(contour: Sequence[Segment], dz: float, dr: float) -> list[Leg]:
    """The contour's moves, moved by (dz, dr)."""
    return [
        (kind, _moved(e, dz, dr), None if centre is None else _moved(centre, dz, dr), clockwise)
        for kind, _s, e, centre, clockwise in contour
    ]


def layers(
    start: Point,
    approach: str,
    contour: Sequence[Segment],
    facing: bool,
    depth_of_cut: float,
    escape: float,
    allowance_x: float,
    allowance_z: float,
    q: Callable[[float], float],
) -> tuple[list[Leg], bool]:
    """The moves of G71 (``facing`` False) or G72 type I from the start point A, and whether
    the layers were cut short. ``approach``: how the ns block moves ("rapid" or "feed");
    ``contour``: the profile from A' (the ns block's end) to B; the allowances as written
    (Δu a diameter)."""
    depth = 0 if facing else 1  # the coordinate the layers step along
    cut = 1 - depth
    dz, dr = allowance_z, allowance_x / 2.0
    a = _zr(start)
    first = _zr(_moved(contour[0][1], dz, dr))
    last = _zr(_moved(contour[-1][2], dz, dr))
    moved = [
        (kind, _moved(s, dz, dr), _moved(e, dz, dr), None if c is None else _moved(c, dz, dr), cw)
        for kind, s, e, c, cw in contour
    ]
    inward = math.copysign(1.0, first[depth] - a[depth]) if first[depth] != a[depth] else 0.0
    forward = math.copysign(1.0, last[cut] - first[cut]) if last[cut] != first[cut] else 0.0
    legs: list[Leg] = []
    short = False
    step = abs(depth_of_cut)
    at_start = a[cut]
    k = 1
    while inward and forward and step > 0.0:
        level = a[depth] + inward * k * step
        if inward * (first[depth] - level) <= EPS:
            break
        if k > MAX_LAYERS:
            short = True
            break
        k += 1
        end = crossing(moved, depth, level)
        if end is None:
            end = last[cut]
        if (end - at_start) * forward <= EPS:
            continue  # no stock at this level
        p_in = [0.0, 0.0]
        p_in[depth], p_in[cut] = level, at_start
        p_end = list(p_in)
        p_end[cut] = end
        p_out = [0.0, 0.0]
        p_out[depth], p_out[cut] = level - inward * escape, end - forward * escape
        p_back = list(p_out)
        p_back[cut] = at_start
        legs.append((approach, _work(start, (p_in[0], p_in[1]), q), None, None))
        legs.append(("feed", _work(start, (p_end[0], p_end[1]), q), None, None))
        legs.append(("rapid", _work(start, (p_out[0], p_out[1]), q), None, None))
        legs.append(("rapid", _work(start, (p_back[0], p_back[1]), q), None, None))
    # Rough cutting as finishing: along the profile moved by the allowance, then back to A.
    legs.append((approach, _work(start, first, q), None, None))
    for kind, end_point, centre, clockwise in _along(contour, dz, dr):
        legs.append((kind, _rounded(end_point, q), _centre(centre), clockwise))
    legs.append(("rapid", dict(start), None, None))
    return legs, short


def pattern(
    start: Point,
    approach: str,
    contour: Sequence[Segment],
    escape_x: float,
    escape_z: float,
    divisions: int,
    allowance_x: float,
    allowance_z: float,
    q: Callable[[float], float],
) -> list[Leg]:
    """The passes of G73 from the start point A: ``divisions`` times the profile (A' to B),
    moved from (Δi + Δu/2, Δk + Δw) for the first to (Δu/2, Δw) for the last, each from A
    as the ns block moves and back to A at rapid."""
    legs: list[Leg] = []
    for n in range(1, divisions + 1):
        share = (divisions - n) / (divisions - 1) if divisions > 1 else 0.0
        dr = escape_x * share + allowance_x / 2.0
        dz = escape_z * share + allowance_z
        legs.append((approach, _rounded(_moved(contour[0][1], dz, dr), q), None, None))
        for kind, end_point, centre, clockwise in _along(contour, dz, dr):
            legs.append((kind, _rounded(end_point, q), _centre(centre), clockwise))
        legs.append(("rapid", dict(start), None, None))
    return legs


def _rounded(p: Point, q: Callable[[float], float]) -> Point:
    return {a: q(v) for a, v in p.items()}


def _centre(c: Point | None) -> Point | None:
    return None if c is None else {a: round(v, 6) for a, v in c.items()}
