"""The crown of a drum-shaped profile: the circle that best fits its points.

Seed paper 003 approximates a crowned guide roller (radius 3792 mm) by chained taper threads
through twelve profile points. Fitting a circle to the points gives the crown radius back, and
how far the points stray from it: a mistyped point shows at once.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class CrownFit:
    radius: float  # mm
    centre_radial: float  # mm from the axis (negative: the centre is across the axis)
    centre_z: float  # mm
    max_deviation: float  # mm, the point farthest from the circle


def fit_crown(points: Sequence[tuple[float, float]]) -> CrownFit:
    """Least-squares circle through (X diameter, Z) points, in the radial-Z plane.

    The algebraic fit solves r² + z² = 2·a·r + 2·b·z + c for the centre (a, b); it is exact for
    points on a circle and needs no starting guess. The points are taken about their mean
    (the fit does not change with the origin; the sums stay small beside a centre thousands
    of millimetres away), and the three unknowns are solved by a Householder QR
    factorisation, as a least-squares library does, in plain Python.
    """
    if len(points) < 3:
        raise ValueError(f"{len(points)} profile points: a crown needs at least 3")
    rs = [x / 2.0 for x, _ in points]
    zs = [z for _, z in points]
    r_mean = math.fsum(rs) / len(rs)
    z_mean = math.fsum(zs) / len(zs)
    rows = [[2.0 * (r - r_mean), 2.0 * (z - z_mean), 1.0] for r, z in zip(rs, zs, strict=True)]
    rhs = [(r - r_mean) ** 2 + (z - z_mean) ** 2 for r, z in zip(rs, zs, strict=True)]
    solution = least_squares(rows, rhs)
    if solution is None:
        raise ValueError("the profile points are on a straight line: no crown to fit")
    da, db, dc = solution
    a, b = r_mean + da, z_mean + db
    radius = math.sqrt(dc + da * da + db * db)
    deviation = max(abs(math.hypot(r - a, z - b) - radius) for r, z in zip(rs, zs, strict=True))
    return CrownFit(radius, a, b, deviation)


def least_squares(rows: Sequence[Sequence[float]], rhs: Sequence[float]) -> list[float] | None:
    """The x that makes ``rows`` · x nearest ``rhs`` (least squares), by Householder QR; None
    when the columns of ``rows`` are dependent to the precision of their values (the rank
    test of LAPACK's least squares: a diagonal of R below ε · max(m, n) times the largest).
    For a few unknowns and many rows."""
    m, n = len(rows), len(rows[0])
    a = [list(row) for row in rows]
    b = list(rhs)
    for k in range(n):
        norm = math.sqrt(math.fsum(a[i][k] ** 2 for i in range(k, m)))
        if norm == 0.0:
            return None
        alpha = -math.copysign(norm, a[k][k])
        v = [a[i][k] for i in range(k, m)]
        v[0] -= alpha
        vv = math.fsum(x * x for x in v)
        for column in range(k, n):
            f = 2.0 * math.fsum(v[i - k] * a[i][column] for i in range(k, m)) / vv
            for i in range(k, m):
                a[i][column] -= f * v[i - k]
        f = 2.0 * math.fsum(v[i - k] * b[i] for i in range(k, m)) / vv
        for i in range(k, m):
            b[i] -= f * v[i - k]
    diagonal = [abs(a[k][k]) for k in range(n)]
    if min(diagonal) <= sys.float_info.epsilon * max(m, n) * max(diagonal):
        return None
    x = [0.0] * n
    for k in reversed(range(n)):
        x[k] = (b[k] - math.fsum(a[k][j] * x[j] for j in range(k + 1, n))) / a[k][k]
    return x
