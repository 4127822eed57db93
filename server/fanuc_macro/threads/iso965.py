"""ISO 965-1 (= GB/T 197-2003) tolerances for ISO general-purpose metric threads.

The normative tables are written out below as literal data in micrometres; the formulas of
the standard's annex (and of thread-math.md section 4) only approximate them, because the
standard rounds to preferred numbers in a way that is not uniform.

Provenance of the cells
-----------------------
*Tabulated* (literal data, ``derived=False``):

- fundamental deviations e, f, g, h (external) and G, H (internal), P = 0.2 ... 8;
- Td (major diameter, external) grades 4, 6, 8 and TD1 (minor diameter, internal) grades 4-8,
  P = 0.2 ... 8;
- Td2 (pitch diameter, external) grades 3-9 and TD2 (internal) grades 4-8 for the diameter
  ranges 0.99-1.4 ... 180-355 mm, with the pitch rows the standard lists for each range.

A blank cell of the standard (for example grade 8 for pitches below 0.8 mm, or the internal
grade 6 for P = 0.25 mm) raises ValueError: the standard deliberately gives no value there.
Positions d (external) and E, F (internal) are not part of the ISO 965-1:1998 / GB/T 197-2003
tables and are rejected.  The grade-6 cells, g/G deviations included, were cross-checked against
published 6g/6H limits of size for M1 ... M355; the other grades against the annex formulas
(every cell lies within one preferred-number step of them, see the tests).

*Derived* (``derived=True``): the whole 355 < d <= 600 mm range of Td2 / TD2 (pitch rows 4, 6
and 8 mm).  Those cells are computed from the annex formulas, Td2(6) = 90 P^0.4 d^0.1 with d the
geometric mean of the range, TD2 = 1.32 Td2(6), times the grade factor, then rounded to the
nearest number of the rounded R40 series.  Results built from a derived cell say so in
:attr:`ThreadTolerances.derived`.

Grades of a two-grade class
---------------------------
In ``5g6g`` the FIRST class is the pitch-diameter class and the second the crest-diameter class
(ISO 965-1).  For ``M50x3-5g6g`` this gives Td2 = 0.170 mm (grade 5, range 45-90 mm, P = 3) and
Td = 0.375 mm (grade 6); for ``M50x3-4H5H`` TD2 = 0.180 mm (grade 4) and TD1 = 0.400 mm
(grade 5).  These are exactly the values of the seed paper's table 4, so the paper reads the
standard correctly.  Reading its 0.170 / 0.180 as grade-6 / grade-5 values would be wrong: in
the 45-90 mm row the grade-6 Td2 is 0.212 and the grade-5 TD2 is 0.224 (0.170 is the grade-6
Td2 of the 11.2-22.4 mm range at P = 2.5, a different row).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from .designation import (
    EXTERNAL_CREST_GRADES,
    EXTERNAL_PITCH_GRADES,
    INTERNAL_CREST_GRADES,
    INTERNAL_PITCH_GRADES,
    ThreadDesignation,
    parse_designation,
)

__all__ = (
    "DERIVED_RANGES",
    "DIAMETER_RANGES",
    "GRADE_FACTORS",
    "PREFERRED_NUMBERS",
    "PitchClass",
    "TableCell",
    "TableValue",
    "ThreadTolerances",
    "diameter_range",
    "formula_fundamental_deviation",
    "formula_major_tolerance_6",
    "formula_minor_tolerance_6",
    "formula_pitch_tolerance_6",
    "fundamental_deviation",
    "loosest_pitch_class",
    "major_diameter_tolerance",
    "minor_diameter_tolerance",
    "pitch_classes",
    "pitch_diameter_tolerance",
    "preferred_number",
    "table_cells",
    "tolerances",
)

GRADE_FACTORS: Mapping[int, float] = MappingProxyType(
    {3: 0.5, 4: 0.63, 5: 0.8, 6: 1.0, 7: 1.25, 8: 1.6, 9: 2.0}
)

DIAMETER_RANGES: tuple[tuple[float, float], ...] = (
    (0.99, 1.4),
    (1.4, 2.8),
    (2.8, 5.6),
    (5.6, 11.2),
    (11.2, 22.4),
    (22.4, 45.0),
    (45.0, 90.0),
    (90.0, 180.0),
    (180.0, 355.0),
    (355.0, 600.0),
)

# Ranges whose Td2 / TD2 cells are computed, not tabulated (see module docstring).
DERIVED_RANGES: frozenset[tuple[float, float]] = frozenset({(355.0, 600.0)})
_DERIVED_PITCHES: tuple[float, ...] = (4.0, 6.0, 8.0)

# Rounded R40 series as the standard uses it (per decade; 26.5 -> 26, 42.5 -> 42 ...).
_R40 = (
    1.00, 1.06, 1.12, 1.18, 1.25, 1.32, 1.40, 1.50, 1.60, 1.70,
    1.80, 1.90, 2.00, 2.12, 2.24, 2.36, 2.50, 2.65, 2.80, 3.00,
    3.15, 3.35, 3.55, 3.75, 4.00, 4.25, 4.50, 4.75, 5.00, 5.30,
    5.60, 6.00, 6.30, 6.70, 7.10, 7.50, 8.00, 8.50, 9.00, 9.50,
)  # fmt: skip
PREFERRED_NUMBERS: tuple[int, ...] = tuple(
    sorted({round(m * 10**e) for e in (1, 2, 3) for m in _R40} | {10000})
)


def _read_only_rows(
    table: dict[tuple[float, float], dict[float, tuple[int | None, ...]]],
) -> Mapping[tuple[float, float], Mapping[float, tuple[int | None, ...]]]:
    """A table of rows by diameter range, read-only at both levels."""
    return MappingProxyType({rng: MappingProxyType(rows) for rng, rows in table.items()})


# --------------------------------------------------------------------------------------------
# Literal tables, micrometres.  None = blank cell in the standard.
# --------------------------------------------------------------------------------------------

# Fundamental deviations.  pitch: (EI of G, es of e, es of f, es of g); H and h are 0.
_FUNDAMENTAL: Mapping[float, tuple[int, int | None, int | None, int]] = MappingProxyType(
    {
        0.2: (17, None, None, -17),
        0.25: (18, None, None, -18),
        0.3: (18, None, None, -18),
        0.35: (19, None, -34, -19),
        0.4: (19, None, -34, -19),
        0.45: (20, None, -35, -20),
        0.5: (20, -50, -36, -20),
        0.6: (21, -53, -36, -21),
        0.7: (22, -56, -38, -22),
        0.75: (22, -56, -38, -22),
        0.8: (24, -60, -38, -24),
        1.0: (26, -60, -40, -26),
        1.25: (28, -63, -42, -28),
        1.5: (32, -67, -45, -32),
        1.75: (34, -71, -48, -34),
        2.0: (38, -71, -52, -38),
        2.5: (42, -80, -58, -42),
        3.0: (48, -85, -63, -48),
        3.5: (53, -90, -70, -53),
        4.0: (60, -95, -75, -60),
        4.5: (63, -100, -80, -63),
        5.0: (71, -106, -85, -71),
        5.5: (75, -112, -90, -75),
        6.0: (80, -118, -95, -80),
        8.0: (100, -140, -118, -100),
    }
)

# Td, major-diameter tolerance of external threads.  pitch: (grade 4, grade 6, grade 8)
_TD_MAJOR_GRADES: tuple[int, ...] = EXTERNAL_CREST_GRADES  # 4, 6, 8
_TD_MAJOR: Mapping[float, tuple[int | None, ...]] = MappingProxyType(
    {
        0.2: (36, 56, None),
        0.25: (42, 67, None),
        0.3: (48, 75, None),
        0.35: (53, 85, None),
        0.4: (60, 95, None),
        0.45: (63, 100, None),
        0.5: (67, 106, None),
        0.6: (80, 125, None),
        0.7: (90, 140, None),
        0.75: (90, 140, None),
        0.8: (95, 150, 236),
        1.0: (112, 180, 280),
        1.25: (132, 212, 335),
        1.5: (150, 236, 375),
        1.75: (170, 265, 425),
        2.0: (180, 280, 450),
        2.5: (212, 335, 530),
        3.0: (236, 375, 600),
        3.5: (265, 425, 670),
        4.0: (300, 475, 750),
        4.5: (315, 500, 800),
        5.0: (335, 530, 850),
        5.5: (355, 560, 900),
        6.0: (375, 600, 950),
        8.0: (450, 710, 1180),
    }
)

# TD1, minor-diameter tolerance of internal threads.  pitch: (grades 4, 5, 6, 7, 8)
_TD1_MINOR_GRADES: tuple[int, ...] = INTERNAL_CREST_GRADES  # 4-8
_TD1_MINOR: Mapping[float, tuple[int | None, ...]] = MappingProxyType(
    {
        0.2: (38, None, None, None, None),
        0.25: (45, 56, None, None, None),
        0.3: (53, 67, 85, None, None),
        0.35: (63, 80, 100, None, None),
        0.4: (71, 90, 112, None, None),
        0.45: (80, 100, 125, None, None),
        0.5: (90, 112, 140, 180, None),
        0.6: (100, 125, 160, 200, None),
        0.7: (112, 140, 180, 224, None),
        0.75: (118, 150, 190, 236, None),
        0.8: (125, 160, 200, 250, 315),
        1.0: (150, 190, 236, 300, 375),
        1.25: (170, 212, 265, 335, 425),
        1.5: (190, 236, 300, 375, 475),
        1.75: (212, 265, 335, 425, 530),
        2.0: (236, 300, 375, 475, 600),
        2.5: (280, 355, 450, 560, 710),
        3.0: (315, 400, 500, 630, 800),
        3.5: (355, 450, 560, 710, 900),
        4.0: (375, 475, 600, 750, 950),
        4.5: (425, 530, 670, 850, 1060),
        5.0: (450, 560, 710, 900, 1120),
        5.5: (475, 600, 750, 950, 1180),
        6.0: (500, 630, 800, 1000, 1250),
        8.0: (630, 800, 1000, 1250, 1600),
    }
)

# Td2, pitch-diameter tolerance of external threads.  pitch: (grades 3, 4, 5, 6, 7, 8, 9)
_TD2_EXT_GRADES: tuple[int, ...] = EXTERNAL_PITCH_GRADES  # 3-9
_N = None
_TD2_EXT: Mapping[tuple[float, float], Mapping[float, tuple[int | None, ...]]] = _read_only_rows(
    {
        (0.99, 1.4): {
            0.2: (24, 30, 38, 48, _N, _N, _N),
            0.25: (26, 34, 42, 53, _N, _N, _N),
            0.3: (28, 36, 45, 56, _N, _N, _N),
        },
        (1.4, 2.8): {
            0.2: (25, 32, 40, 50, _N, _N, _N),
            0.25: (28, 36, 45, 56, _N, _N, _N),
            0.35: (32, 40, 50, 63, 80, _N, _N),
            0.4: (34, 42, 53, 67, 85, _N, _N),
            0.45: (36, 45, 56, 71, 90, _N, _N),
        },
        (2.8, 5.6): {
            0.35: (34, 42, 53, 67, 85, _N, _N),
            0.5: (38, 48, 60, 75, 95, _N, _N),
            0.6: (42, 53, 67, 85, 106, _N, _N),
            0.7: (45, 56, 71, 90, 112, _N, _N),
            0.75: (45, 56, 71, 90, 112, _N, _N),
            0.8: (48, 60, 75, 95, 118, 150, 190),
        },
        (5.6, 11.2): {
            0.75: (50, 63, 80, 100, 125, _N, _N),
            1.0: (56, 71, 90, 112, 140, 180, 224),
            1.25: (60, 75, 95, 118, 150, 190, 236),
            1.5: (67, 85, 106, 132, 170, 212, 265),
        },
        (11.2, 22.4): {
            1.0: (60, 75, 95, 118, 150, 190, 236),
            1.25: (67, 85, 106, 132, 170, 212, 265),
            1.5: (71, 90, 112, 140, 180, 224, 280),
            1.75: (75, 95, 118, 150, 190, 236, 300),
            2.0: (80, 100, 125, 160, 200, 250, 315),
            2.5: (85, 106, 132, 170, 212, 265, 335),
        },
        (22.4, 45.0): {
            1.0: (63, 80, 100, 125, 160, 200, 250),
            1.5: (75, 95, 118, 150, 190, 236, 300),
            2.0: (85, 106, 132, 170, 212, 265, 335),
            3.0: (100, 125, 160, 200, 250, 315, 400),
            3.5: (106, 132, 170, 212, 265, 335, 425),
            4.0: (112, 140, 180, 224, 280, 355, 450),
            4.5: (118, 150, 190, 236, 300, 375, 475),
        },
        (45.0, 90.0): {
            1.5: (80, 100, 125, 160, 200, 250, 315),
            2.0: (90, 112, 140, 180, 224, 280, 355),
            3.0: (106, 132, 170, 212, 265, 335, 425),
            4.0: (118, 150, 190, 236, 300, 375, 475),
            5.0: (125, 160, 200, 250, 315, 400, 500),
            5.5: (132, 170, 212, 265, 335, 425, 530),
            6.0: (140, 180, 224, 280, 355, 450, 560),
        },
        (90.0, 180.0): {
            2.0: (95, 118, 150, 190, 236, 300, 375),
            3.0: (112, 140, 180, 224, 280, 355, 450),
            4.0: (125, 160, 200, 250, 315, 400, 500),
            6.0: (150, 190, 236, 300, 375, 475, 600),
            8.0: (170, 212, 265, 335, 425, 530, 670),
        },
        (180.0, 355.0): {
            3.0: (125, 160, 200, 250, 315, 400, 500),
            4.0: (140, 180, 224, 280, 355, 450, 560),
            6.0: (160, 200, 250, 315, 400, 500, 630),
            8.0: (180, 224, 280, 355, 450, 560, 710),
        },
    }
)

# TD2, pitch-diameter tolerance of internal threads.  pitch: (grades 4, 5, 6, 7, 8)
_TD2_INT_GRADES: tuple[int, ...] = INTERNAL_PITCH_GRADES  # 4-8
_TD2_INT: Mapping[tuple[float, float], Mapping[float, tuple[int | None, ...]]] = _read_only_rows(
    {
        (0.99, 1.4): {
            0.2: (40, _N, _N, _N, _N),
            0.25: (45, 56, _N, _N, _N),
            0.3: (48, 60, 75, _N, _N),
        },
        (1.4, 2.8): {
            0.2: (42, _N, _N, _N, _N),
            0.25: (48, 60, _N, _N, _N),
            0.35: (53, 67, 85, _N, _N),
            0.4: (56, 71, 90, _N, _N),
            0.45: (60, 75, 95, _N, _N),
        },
        (2.8, 5.6): {
            0.35: (56, 71, 90, _N, _N),
            0.5: (63, 80, 100, 125, _N),
            0.6: (71, 90, 112, 140, _N),
            0.7: (75, 95, 118, 150, _N),
            0.75: (75, 95, 118, 150, _N),
            0.8: (80, 100, 125, 160, 200),
        },
        (5.6, 11.2): {
            0.75: (85, 106, 132, 170, _N),
            1.0: (95, 118, 150, 190, 236),
            1.25: (100, 125, 160, 200, 250),
            1.5: (112, 140, 180, 224, 280),
        },
        (11.2, 22.4): {
            1.0: (100, 125, 160, 200, 250),
            1.25: (112, 140, 180, 224, 280),
            1.5: (118, 150, 190, 236, 300),
            1.75: (125, 160, 200, 250, 315),
            2.0: (132, 170, 212, 265, 335),
            2.5: (140, 180, 224, 280, 355),
        },
        (22.4, 45.0): {
            1.0: (106, 132, 170, 212, 265),
            1.5: (125, 160, 200, 250, 315),
            2.0: (140, 180, 224, 280, 355),
            3.0: (170, 212, 265, 335, 425),
            3.5: (180, 224, 280, 355, 450),
            4.0: (190, 236, 300, 375, 475),
            4.5: (200, 250, 315, 400, 500),
        },
        (45.0, 90.0): {
            1.5: (132, 170, 212, 265, 335),
            2.0: (150, 190, 236, 300, 375),
            3.0: (180, 224, 280, 355, 450),
            4.0: (200, 250, 315, 400, 500),
            5.0: (212, 265, 335, 425, 530),
            5.5: (224, 280, 355, 450, 560),
            6.0: (236, 300, 375, 475, 600),
        },
        (90.0, 180.0): {
            2.0: (160, 200, 250, 315, 400),
            3.0: (190, 236, 300, 375, 475),
            4.0: (212, 265, 335, 425, 530),
            6.0: (250, 315, 400, 500, 630),
            8.0: (280, 355, 450, 560, 710),
        },
        (180.0, 355.0): {
            3.0: (212, 265, 335, 425, 530),
            4.0: (236, 300, 375, 475, 600),
            6.0: (265, 335, 425, 530, 670),
            8.0: (300, 375, 475, 600, 750),
        },
    }
)


# --------------------------------------------------------------------------------------------
# Formulas (annex of ISO 965-1), used for the derived cells and as a plausibility check.
# --------------------------------------------------------------------------------------------


def preferred_number(value: float) -> int:
    """Round ``value`` (µm) to the nearest rounded-R40 number, nearest on a log scale."""
    if value <= 0:
        raise ValueError("preferred numbers are positive")
    return min(PREFERRED_NUMBERS, key=lambda n: abs(math.log(n / value)))


def formula_pitch_tolerance_6(pitch: float, diameter_range: tuple[float, float]) -> float:
    """Unrounded Td2 of grade 6 (µm): 90 P^0.4 d^0.1, d = geometric mean of the range."""
    lo, hi = diameter_range
    return 90.0 * math.pow(pitch, 0.4) * math.pow(math.sqrt(lo * hi), 0.1)


def formula_major_tolerance_6(pitch: float) -> float:
    """Unrounded Td of grade 6 (µm): 180 P^(2/3) - 3.15 / sqrt(P)."""
    return 180.0 * math.pow(pitch, 2.0 / 3.0) - 3.15 / math.sqrt(pitch)


def formula_minor_tolerance_6(pitch: float) -> float:
    """Unrounded TD1 of grade 6 (µm): 433P - 190P^1.22 below 1 mm, 230 P^0.7 from 1 mm."""
    if pitch < 1.0:
        return 433.0 * pitch - 190.0 * math.pow(pitch, 1.22)
    return 230.0 * math.pow(pitch, 0.7)


def formula_fundamental_deviation(position: str, pitch: float) -> float:
    """Unrounded fundamental deviation (µm, signed) of e, f, g, h, G, H."""
    offsets = {"e": 50.0, "f": 30.0, "g": 15.0, "G": 15.0}
    if position in ("h", "H"):
        return 0.0
    if position not in offsets:
        raise ValueError(f"no fundamental-deviation formula for the position {position}")
    magnitude = offsets[position] + 11.0 * pitch
    return magnitude if position.isupper() else -magnitude


# --------------------------------------------------------------------------------------------
# Lookups
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class TableValue:
    """One cell: value in micrometres and whether it was derived rather than tabulated."""

    micrometres: int
    derived: bool = False

    @property
    def mm(self) -> float:
        return self.micrometres / 1000.0


def _pitch_key(table: Mapping[float, object], pitch: float) -> float | None:
    for key in table:
        if abs(key - pitch) < 1e-9:
            return key
    return None


def _pitches(table: Mapping[float, object]) -> str:
    return ", ".join(f"{p:g}" for p in table)


def _cell(
    what: str,
    row: tuple[int | None, ...],
    grades: tuple[int, ...],
    grade: int,
    pitch: float,
) -> int:
    if grade not in grades:
        raise ValueError(
            f"{what}: ISO 965-1 has no grade {grade} (grades {', '.join(map(str, grades))})"
        )
    value = row[grades.index(grade)]
    if value is None:
        available = [str(g) for g, v in zip(grades, row, strict=True) if v is not None]
        raise ValueError(
            f"{what}: ISO 965-1 gives no grade-{grade} value for P = {pitch:g} mm "
            f"(grades for this pitch: {', '.join(available)})"
        )
    return value


def diameter_range(diameter: float) -> tuple[float, float]:
    """The ISO 965-1 basic-major-diameter range ``lo < d <= hi`` containing ``diameter``."""
    for lo, hi in DIAMETER_RANGES:
        if lo < diameter <= hi:
            return lo, hi
    raise ValueError(
        f"d = {diameter:g} mm is outside the ISO 965-1 diameter ranges "
        f"({DIAMETER_RANGES[0][0]:g} < d <= {DIAMETER_RANGES[-1][1]:g} mm)"
    )


def fundamental_deviation(position: str, pitch: float) -> TableValue:
    """es (e f g h, <= 0) or EI (G H, >= 0) in µm for ``pitch``."""
    if position not in ("e", "f", "g", "h", "G", "H"):
        raise ValueError(
            f"the tolerance position {position} is not tabulated in ISO 965-1 "
            "(external e f g h, internal G H)"
        )
    key = _pitch_key(_FUNDAMENTAL, pitch)
    if key is None:
        raise ValueError(
            f"P = {pitch:g} mm is not a pitch of the ISO 965-1 tables ({_pitches(_FUNDAMENTAL)})"
        )
    if position in ("h", "H"):
        return TableValue(0)
    big_g, e, f, g = _FUNDAMENTAL[key]
    value = {"G": big_g, "e": e, "f": f, "g": g}[position]
    if value is None:
        raise ValueError(
            f"ISO 965-1 defines no fundamental deviation {position} for P = {pitch:g} mm"
        )
    return TableValue(value)


def major_diameter_tolerance(grade: int, pitch: float) -> TableValue:
    """Td, major-diameter tolerance of an external thread (µm)."""
    key = _pitch_key(_TD_MAJOR, pitch)
    if key is None:
        raise ValueError(f"Td: P = {pitch:g} mm is not tabulated ({_pitches(_TD_MAJOR)})")
    return TableValue(_cell("Td", _TD_MAJOR[key], _TD_MAJOR_GRADES, grade, pitch))


def minor_diameter_tolerance(grade: int, pitch: float) -> TableValue:
    """TD1, minor-diameter tolerance of an internal thread (µm)."""
    key = _pitch_key(_TD1_MINOR, pitch)
    if key is None:
        raise ValueError(f"TD1: P = {pitch:g} mm is not tabulated ({_pitches(_TD1_MINOR)})")
    return TableValue(_cell("TD1", _TD1_MINOR[key], _TD1_MINOR_GRADES, grade, pitch))


def _derived_row(rng: tuple[float, float], internal: bool) -> dict[float, tuple[int | None, ...]]:
    rows: dict[float, tuple[int | None, ...]] = {}
    for pitch in _DERIVED_PITCHES:
        base = formula_pitch_tolerance_6(pitch, rng)
        if internal:
            rows[pitch] = tuple(
                preferred_number(GRADE_FACTORS[g] * 1.32 * base) for g in _TD2_INT_GRADES
            )
        else:
            rows[pitch] = tuple(preferred_number(GRADE_FACTORS[g] * base) for g in _TD2_EXT_GRADES)
    return rows


def _td2_derived(internal: bool) -> dict[tuple[float, float], dict[float, tuple[int | None, ...]]]:
    """The derived Td2 or TD2 rows, computed when asked for: 21 cells of a few arithmetic
    operations each, neither at every start nor kept."""
    return {rng: _derived_row(rng, internal=internal) for rng in DERIVED_RANGES}


def pitch_diameter_tolerance(
    grade: int, pitch: float, diameter: float, *, internal: bool
) -> TableValue:
    """Td2 (external) or TD2 (internal), pitch-diameter tolerance (µm)."""
    rng = diameter_range(diameter)
    name = "TD2" if internal else "Td2"
    derived = rng in DERIVED_RANGES
    rows = _td2_derived(internal)[rng] if derived else (_TD2_INT if internal else _TD2_EXT)[rng]
    grades = _TD2_INT_GRADES if internal else _TD2_EXT_GRADES
    key = _pitch_key(rows, pitch)
    if key is None:
        raise ValueError(
            f"{name}: P = {pitch:g} mm is not tabulated for {rng[0]:g} < d <= {rng[1]:g} mm "
            f"(pitches: {_pitches(rows)})"
        )
    return TableValue(_cell(name, rows[key], grades, grade, pitch), derived=derived)


@dataclass(frozen=True)
class TableCell:
    """One non-blank cell of the tables, for listing and checking them."""

    table: str  # "Td", "TD1", "Td2" or "TD2"
    diameter_range: tuple[float, float] | None  # None for Td / TD1 (pitch only)
    pitch: float
    grade: int
    value: TableValue


def table_cells() -> list[TableCell]:
    """Every tolerance cell (tabulated and derived), in table order."""
    cells: list[TableCell] = []
    simple = (("Td", _TD_MAJOR, _TD_MAJOR_GRADES), ("TD1", _TD1_MINOR, _TD1_MINOR_GRADES))
    for name, table, grades in simple:
        for pitch, row in table.items():
            for grade, um in zip(grades, row, strict=True):
                if um is not None:
                    cells.append(TableCell(name, None, pitch, grade, TableValue(um)))
    ranged = (
        ("Td2", _TD2_EXT, _td2_derived(False), _TD2_EXT_GRADES),
        ("TD2", _TD2_INT, _td2_derived(True), _TD2_INT_GRADES),
    )
    for name, tabulated, derived, grades in ranged:
        for rng in DIAMETER_RANGES:
            is_derived = rng in derived
            rows = derived[rng] if is_derived else tabulated[rng]
            for pitch, row in rows.items():
                for grade, um in zip(grades, row, strict=True):
                    if um is not None:
                        cell = TableValue(um, derived=is_derived)
                        cells.append(TableCell(name, rng, pitch, grade, cell))
    return cells


# --------------------------------------------------------------------------------------------
# Limits of size
# --------------------------------------------------------------------------------------------

_D2_FACTOR = 3.0 * math.sqrt(3.0) / 8.0  # 0.649519: d2 = d - 3H/4
_D1_FACTOR = 5.0 * math.sqrt(3.0) / 8.0  # 1.082532: d1 = d - 5H/4


@dataclass(frozen=True)
class ThreadTolerances:
    """Deviations, tolerances and limits of size of one thread, all in mm.

    For an external thread ``fundamental_deviation`` is es (negative for e f g), the pitch
    tolerance is Td2 and the crest tolerance Td; ``minor_max`` is d1 + es (the flat-root basic
    minor diameter moved by es) and ``minor_min`` is None because ISO 965-1 bounds the root only
    through its contour.  For an internal thread it is EI, TD2 and TD1, and ``major_max`` is
    None (the standard sets no upper limit for D).  ``derived`` names the values that come
    from derived table cells.
    """

    designation: ThreadDesignation
    internal: bool
    fundamental_deviation: float
    pitch_diameter_tolerance: float
    crest_diameter_tolerance: float
    major_basic: float
    pitch_basic: float
    minor_basic: float
    major_max: float | None
    major_min: float
    pitch_max: float
    pitch_min: float
    minor_max: float
    minor_min: float | None
    derived: tuple[str, ...] = field(default_factory=tuple)

    @property
    def es(self) -> float | None:
        """Upper deviation of an external thread (None for internal)."""
        return None if self.internal else self.fundamental_deviation

    @property
    def ei(self) -> float | None:
        """EI, lower deviation of an internal thread (None for external)."""
        return self.fundamental_deviation if self.internal else None


def tolerances(designation: ThreadDesignation | str) -> ThreadTolerances:
    """ISO 965-1 deviations, tolerances and limits for a designation (or its text)."""
    des = parse_designation(designation) if isinstance(designation, str) else designation
    d = des.nominal_diameter
    p = des.pitch
    position = des.pitch_class.position
    internal = des.internal
    deviation = fundamental_deviation(position, p)
    pitch_tol = pitch_diameter_tolerance(des.pitch_class.grade, p, d, internal=internal)
    if internal:
        crest_tol = minor_diameter_tolerance(des.crest_class.grade, p)
    else:
        crest_tol = major_diameter_tolerance(des.crest_class.grade, p)
    derived = tuple(
        name
        for name, cell in (
            ("TD2" if internal else "Td2", pitch_tol),
            ("TD1" if internal else "Td", crest_tol),
        )
        if cell.derived
    )

    dev = deviation.mm
    d2 = d - _D2_FACTOR * p
    d1 = d - _D1_FACTOR * p
    if internal:
        return ThreadTolerances(
            designation=des,
            internal=True,
            fundamental_deviation=dev,
            pitch_diameter_tolerance=pitch_tol.mm,
            crest_diameter_tolerance=crest_tol.mm,
            major_basic=d,
            pitch_basic=d2,
            minor_basic=d1,
            major_max=None,
            major_min=d + dev,
            pitch_max=d2 + dev + pitch_tol.mm,
            pitch_min=d2 + dev,
            minor_max=d1 + dev + crest_tol.mm,
            minor_min=d1 + dev,
            derived=derived,
        )
    return ThreadTolerances(
        designation=des,
        internal=False,
        fundamental_deviation=dev,
        pitch_diameter_tolerance=pitch_tol.mm,
        crest_diameter_tolerance=crest_tol.mm,
        major_basic=d,
        pitch_basic=d2,
        minor_basic=d1,
        major_max=d + dev,
        major_min=d + dev - crest_tol.mm,
        pitch_max=d2 + dev,
        pitch_min=d2 + dev - pitch_tol.mm,
        minor_max=d1 + dev,
        minor_min=None,
        derived=derived,
    )


@dataclass(frozen=True)
class PitchClass:
    """One tolerance class of a size: the pitch-diameter band it allows (mm)."""

    position: str  # e f g h (external), G H (internal)
    grade: int
    deviation: float  # es (<= 0) or EI (>= 0)
    tolerance: float  # Td2 or TD2

    @property
    def name(self) -> str:
        return f"{self.grade}{self.position}"


def pitch_classes(diameter: float, pitch: float, *, internal: bool) -> list[PitchClass]:
    """Every pitch-diameter class ISO 965-1 tabulates for ``diameter`` and ``pitch``."""
    positions = ("G", "H") if internal else ("e", "f", "g", "h")
    grades = _TD2_INT_GRADES if internal else _TD2_EXT_GRADES
    found: list[PitchClass] = []
    for position in positions:
        try:
            deviation = fundamental_deviation(position, pitch).mm
        except ValueError:
            continue
        for grade in grades:
            try:
                tolerance = pitch_diameter_tolerance(grade, pitch, diameter, internal=internal).mm
            except ValueError:
                continue
            found.append(PitchClass(position, grade, deviation, tolerance))
    return found


def loosest_pitch_class(diameter: float, pitch: float, *, internal: bool) -> PitchClass | None:
    """The class that lets the pitch diameter go furthest from the basic profile: the one that
    allows the deepest root, so a pass past it is past the root of every class."""
    classes = pitch_classes(diameter, pitch, internal=internal)
    if not classes:
        return None
    return max(classes, key=lambda c: abs(c.deviation) + c.tolerance)
