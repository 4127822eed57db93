"""The crown of a drum-shaped profile: the circle that best fits its points.

Seed paper 003 approximates a crowned guide roller (radius 3792 mm) by chained taper threads
through twelve profile points. Fitting a circle to the points gives the crown radius back, and
how far the points stray from it: a mistyped point shows at once.
"""

from __future__ import annotations

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
    points on a circle and needs no starting guess.
    """
    # numpy only here: the language server must start without it (the VS Code extension can
    # ship the pure-Python server for a bare interpreter).
    import numpy as np

    if len(points) < 3:
        raise ValueError(f"{len(points)} profile points: a crown needs at least 3")
    r = np.array([x / 2.0 for x, _ in points], dtype=float)
    z = np.array([z for _, z in points], dtype=float)
    a_matrix = np.column_stack([2.0 * r, 2.0 * z, np.ones_like(r)])
    solution, _, rank, _ = np.linalg.lstsq(a_matrix, r * r + z * z, rcond=None)
    if rank < 3:
        raise ValueError("the profile points are on a straight line: no crown to fit")
    a, b, c = (float(v) for v in solution)
    radius = float(np.sqrt(c + a * a + b * b))
    deviation = float(np.max(np.abs(np.hypot(r - a, z - b) - radius)))
    return CrownFit(radius, a, b, deviation)
