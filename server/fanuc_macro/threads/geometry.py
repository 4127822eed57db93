"""Basic ISO metric profile and the symmetric thread-cutting module of the seed paper.

The seed paper (a molybdenum-electrode study, sub-programs O3331 external / O3330 internal)
cuts each rough pass twice with G92, once offset to the left by ``u`` and once to the right,
with depths following the constant-chip-area rule of G76, then finishes by straight infeed
and ``n'`` spring passes.  All depths here are radius values in mm; P is the pitch.

The paper enters the fundamental deviation as a MAGNITUDE (``#103 = 0.048`` for es = -0.048
of 5g6g), so :func:`thread_height` takes ``abs(es)`` / EI, not the signed deviation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .iso965 import ThreadTolerances

__all__ = (
    "DEFAULT_DEPTH_COEFFICIENT",
    "SIN60",
    "TAN30",
    "RoughPass",
    "SymmetricThreadPlan",
    "ap_max",
    "ap_min",
    "basic_minor_diameter",
    "basic_pitch_diameter",
    "count_rough_passes",
    "cumulative_depth",
    "fundamental_triangle_height",
    "nose_radius_ok",
    "nose_radius_range",
    "paper_internal_minor_diameter",
    "pass_depth",
    "plan_from_tolerances",
    "plan_symmetric_thread",
    "rough_passes",
    "run_in_out",
    "side_offset",
    "theoretical_nose_radius",
    "thread_height",
)

SIN60 = math.sqrt(3.0) / 2.0
TAN30 = 1.0 / math.sqrt(3.0)
# 0.2 is the paper's coefficient for ordinary steel; molybdenum takes a third of it.
DEFAULT_DEPTH_COEFFICIENT = 0.2 / 3.0


# ---- basic profile (ISO 68-1 / ISO 724) -----------------------------------------------------


def fundamental_triangle_height(pitch: float) -> float:
    """H = sqrt(3)/2 * P."""
    return SIN60 * pitch


def basic_pitch_diameter(diameter: float, pitch: float) -> float:
    """d2 = D2 = d - 0.649519 P (= d - 3H/4)."""
    return diameter - 0.75 * fundamental_triangle_height(pitch)


def basic_minor_diameter(diameter: float, pitch: float) -> float:
    """d1 = D1 = d - 1.082532 P (= d - 5H/4)."""
    return diameter - 1.25 * fundamental_triangle_height(pitch)


def paper_internal_minor_diameter(diameter: float, pitch: float) -> float:
    """O3330's ``#11 = D - 2*(5/8)*SIN[60]*P``; the same number as the basic D1."""
    return diameter - 2.0 * (5.0 / 8.0) * SIN60 * pitch


# ---- tool and thread height ------------------------------------------------------------------


def theoretical_nose_radius(pitch: float, *, internal: bool) -> float:
    """Theoretical (minimum) tool nose radius: P/(8 sin60) external, P/(16 sin60) internal."""
    return pitch / ((16.0 if internal else 8.0) * SIN60)


def nose_radius_range(pitch: float, *, internal: bool) -> tuple[float, float]:
    """Open interval of acceptable real nose radii: 0.125P..0.144P external, 0..0.072P internal."""
    if internal:
        return 0.0, 0.072 * pitch
    return 0.125 * pitch, 0.144 * pitch


def nose_radius_ok(radius: float, pitch: float, *, internal: bool) -> bool:
    lo, hi = nose_radius_range(pitch, internal=internal)
    return lo < radius < hi


def thread_height(
    pitch: float,
    *,
    internal: bool,
    deviation: float,
    pitch_tolerance: float,
    nose_radius: float | None = None,
) -> float:
    """Thread height h (radius) as the paper computes it.

    External: 7H/8 - r + es/2 + Td2/4; internal: 6H/8 - r + EI/2 + TD2/4.  ``deviation`` is the
    magnitude |es| or EI (the paper writes 0.048 for es = -0.048).  ``nose_radius`` defaults to
    the theoretical radius.
    """
    if deviation < 0:
        raise ValueError("enter the fundamental deviation as a magnitude, as the paper does")
    r = theoretical_nose_radius(pitch, internal=internal) if nose_radius is None else nose_radius
    big_h = fundamental_triangle_height(pitch)
    base = (6.0 if internal else 7.0) / 8.0 * big_h
    return base - r + deviation / 2.0 + pitch_tolerance / 4.0


# ---- depths of cut ---------------------------------------------------------------------------


def ap_max(height: float, coefficient: float = DEFAULT_DEPTH_COEFFICIENT) -> float:
    """First (largest) depth of cut: coef * sqrt(h)."""
    return coefficient * math.sqrt(height)


def ap_min(first_depth: float, coefficient: float = DEFAULT_DEPTH_COEFFICIENT) -> float:
    """Minimum depth of cut, also the finishing allowance: coef * sqrt(ap_max)."""
    return coefficient * math.sqrt(first_depth)


def pass_depth(n: int, first_depth: float) -> float:
    """ap(n) = (sqrt(n) - sqrt(n-1)) * ap_max: equal chip area per pass."""
    if n < 1:
        raise ValueError("passes are numbered from 1")
    return (math.sqrt(n) - math.sqrt(n - 1)) * first_depth


def cumulative_depth(n: int, first_depth: float, min_depth: float) -> float:
    """Total depth after pass n: sqrt(n)*ap_max while ap(n) >= ap_min, then + ap_min per pass."""
    if n < 1:
        raise ValueError("passes are numbered from 1")
    total = first_depth
    for k in range(2, n + 1):
        if pass_depth(k, first_depth) >= min_depth:
            total = first_depth * math.sqrt(k)
        else:
            total += min_depth
    return total


def side_offset(height: float, nose_radius: float, min_depth: float, depth: float) -> float:
    """u = (h + r - ap_min - depth) tan30 - r tan30: the left / right step at this depth."""
    return (height + nose_radius - min_depth - depth) * TAN30 - nose_radius * TAN30


def run_in_out(length: float, pitch: float) -> tuple[float, float]:
    """(delta1, delta2): run-in 2P + P + FIX[L/P]*P - L and run-out P."""
    delta1 = 2.0 * pitch + pitch + math.trunc(length / pitch) * pitch - length
    return delta1, pitch


# ---- the rough loop of O3331 / O3330 ----------------------------------------------------------


@dataclass(frozen=True)
class RoughPass:
    """One rough pass (two G92 cuts): number n, its depth ap(n), total depth and offset u."""

    n: int
    depth: float
    cumulative: float
    offset: float


def rough_passes(
    height: float, first_depth: float, min_depth: float, nose_radius: float
) -> list[RoughPass]:
    """The rough passes exactly as the paper's loop produces them.

    ``#7=1; #8=ap_max; #9=ap_max``; N10 cuts at depth #9; then ``#7+=1``,
    ``#8=ap_max*(sqrt(n)-sqrt(n-1))``; ``#9 = ap_max*sqrt(n)`` if ``#8 >= ap_min`` else
    ``#9 += ap_min``; loop while ``#9 < h - ap_min``.  The first pass is always cut.
    """
    if first_depth <= 0 or min_depth <= 0:
        raise ValueError("depths of cut must be positive")
    n = 1
    depth = first_depth
    total = first_depth
    passes: list[RoughPass] = []
    while True:
        passes.append(
            RoughPass(n, depth, total, side_offset(height, nose_radius, min_depth, total))
        )
        n += 1
        depth = first_depth * (math.sqrt(n) - math.sqrt(n - 1))
        if depth >= min_depth:
            total = first_depth * math.sqrt(n)
        else:
            total += min_depth
        if not total < height - min_depth:
            return passes


def count_rough_passes(height: float, first_depth: float, min_depth: float) -> int:
    """Number of rough passes (each = 2 G92 cuts) of the paper's loop."""
    return len(rough_passes(height, first_depth, min_depth, 0.0))


@dataclass(frozen=True)
class SymmetricThreadPlan:
    """Everything the symmetric module computes for one thread (radius values, mm)."""

    pitch: float
    internal: bool
    nose_radius: float
    height: float
    ap_max: float
    ap_min: float
    run_in: float
    run_out: float
    passes: tuple[RoughPass, ...]
    spring_passes: int

    @property
    def rough_pass_count(self) -> int:
        return len(self.passes)

    @property
    def g92_cut_count(self) -> int:
        """Two cuts per rough pass, straight-infeed rough + finish, then the spring passes."""
        return 2 * len(self.passes) + 2 + self.spring_passes


def plan_symmetric_thread(
    pitch: float,
    *,
    internal: bool,
    deviation: float,
    pitch_tolerance: float,
    length: float,
    coefficient: float = DEFAULT_DEPTH_COEFFICIENT,
    nose_radius: float | None = None,
    spring_passes: int = 8,
) -> SymmetricThreadPlan:
    """Run the whole O3331 (external) / O3330 (internal) computation.

    ``deviation`` is |es| or EI as a magnitude, ``pitch_tolerance`` Td2 or TD2 (mm).
    """
    r = theoretical_nose_radius(pitch, internal=internal) if nose_radius is None else nose_radius
    h = thread_height(
        pitch,
        internal=internal,
        deviation=deviation,
        pitch_tolerance=pitch_tolerance,
        nose_radius=r,
    )
    first = ap_max(h, coefficient)
    smallest = ap_min(first, coefficient)
    delta1, delta2 = run_in_out(length, pitch)
    return SymmetricThreadPlan(
        pitch=pitch,
        internal=internal,
        nose_radius=r,
        height=h,
        ap_max=first,
        ap_min=smallest,
        run_in=delta1,
        run_out=delta2,
        passes=tuple(rough_passes(h, first, smallest, r)),
        spring_passes=spring_passes,
    )


def plan_from_tolerances(
    tol: ThreadTolerances,
    *,
    length: float,
    coefficient: float = DEFAULT_DEPTH_COEFFICIENT,
    nose_radius: float | None = None,
    spring_passes: int = 8,
) -> SymmetricThreadPlan:
    """:func:`plan_symmetric_thread` with es/EI and Td2/TD2 taken from ISO 965-1."""
    return plan_symmetric_thread(
        tol.designation.pitch,
        internal=tol.internal,
        deviation=abs(tol.fundamental_deviation),
        pitch_tolerance=tol.pitch_diameter_tolerance,
        length=length,
        coefficient=coefficient,
        nose_radius=nose_radius,
        spring_passes=spring_passes,
    )
