"""Tests for fanuc_macro.threads: designations, ISO 965-1 tables, the symmetric thread module.

Test vectors: thread-math.md sections 1 and 4, and the seed paper's table 4 (M50x3).
"""

from __future__ import annotations

import itertools
import math

import pytest

from fanuc_macro.threads import (
    SideConflict,
    SideUndecided,
    ToleranceClass,
    ap_max,
    ap_min,
    basic_minor_diameter,
    basic_pitch_diameter,
    coarse_pitch,
    count_rough_passes,
    cumulative_depth,
    diameter_range,
    fundamental_deviation,
    fundamental_triangle_height,
    major_diameter_tolerance,
    minor_diameter_tolerance,
    nose_radius_ok,
    nose_radius_range,
    paper_internal_minor_diameter,
    parse_designation,
    pass_depth,
    pitch_diameter_tolerance,
    plan_from_tolerances,
    plan_symmetric_thread,
    rough_passes,
    run_in_out,
    side_offset,
    table_cells,
    theoretical_nose_radius,
    thread_height,
    tolerances,
)
from fanuc_macro.threads.iso965 import (
    DERIVED_RANGES,
    GRADE_FACTORS,
    PREFERRED_NUMBERS,
    formula_major_tolerance_6,
    formula_minor_tolerance_6,
    formula_pitch_tolerance_6,
    preferred_number,
)


def mm(value: float | None) -> float:
    assert value is not None
    return round(value, 3)


# ---------------------------------------------------------------------------------------------
# ISO 965-1 test vectors (thread-math.md section 4)
# ---------------------------------------------------------------------------------------------


def test_m50x3_5g6g_external() -> None:
    t = tolerances("M50x3-5g6g")
    assert not t.internal
    assert t.es == pytest.approx(-0.048)
    assert t.ei is None
    # First grade (5) is the pitch-diameter grade: Td2(5) for 45 < d <= 90, P = 3.
    assert t.pitch_diameter_tolerance == pytest.approx(0.170)
    # Second grade (6) is the crest (major) diameter grade.
    assert t.crest_diameter_tolerance == pytest.approx(0.375)
    assert t.derived == ()


def test_m50x3_4h5h_internal() -> None:
    t = tolerances("M50x3-4H5H")
    assert t.internal
    assert t.ei == pytest.approx(0.0)
    assert t.es is None
    assert t.pitch_diameter_tolerance == pytest.approx(0.180)  # TD2 grade 4
    assert t.crest_diameter_tolerance == pytest.approx(0.400)  # TD1 grade 5


def test_m50x3_limits_match_seed_paper_table_4() -> None:
    ext = tolerances("M50x3-5g6g")
    assert (mm(ext.major_min), mm(ext.major_max)) == (49.577, 49.952)
    assert (mm(ext.pitch_min), mm(ext.pitch_max)) == (47.833, 48.003)
    assert mm(ext.pitch_basic) == 48.051
    assert mm(ext.minor_basic) == 46.752
    internal = tolerances("M50×3-4H5H")
    assert mm(internal.major_min) == 50.0
    assert internal.major_max is None
    assert (mm(internal.pitch_min), mm(internal.pitch_max)) == (48.051, 48.231)
    assert (mm(internal.minor_min), mm(internal.minor_max)) == (46.752, 47.152)


def test_grade_reading_of_the_m50x3_row() -> None:
    """Which grade holds which number in the 45-90 mm, P = 3 row.

    The paper's 0.170 / 0.180 are the grade-5 Td2 and grade-4 TD2 of this row, i.e. the
    standard read with the first grade as the pitch-diameter grade.  The grade-6 Td2 (0.212)
    and grade-5 TD2 (0.224) are different numbers; 0.132 is the grade-4 Td2.
    """
    ext = {g: pitch_diameter_tolerance(g, 3.0, 50.0, internal=False).mm for g in range(3, 10)}
    assert ext == pytest.approx(
        {3: 0.106, 4: 0.132, 5: 0.170, 6: 0.212, 7: 0.265, 8: 0.335, 9: 0.425}
    )
    internal = {g: pitch_diameter_tolerance(g, 3.0, 50.0, internal=True).mm for g in range(4, 9)}
    assert internal == pytest.approx({4: 0.180, 5: 0.224, 6: 0.280, 7: 0.355, 8: 0.450})
    # 0.170 as a grade-6 Td2 belongs to another row (11.2-22.4 mm, P = 2.5).
    assert pitch_diameter_tolerance(6, 2.5, 20.0, internal=False).mm == pytest.approx(0.170)


def test_m10x1_5_6g() -> None:
    t = tolerances("M10x1.5-6g")
    assert t.es == pytest.approx(-0.032)
    assert t.pitch_diameter_tolerance == pytest.approx(0.132)
    assert t.crest_diameter_tolerance == pytest.approx(0.236)
    assert (mm(t.pitch_min), mm(t.pitch_max)) == (8.862, 8.994)
    assert (mm(t.major_min), mm(t.major_max)) == (9.732, 9.968)
    assert mm(t.minor_max) == 8.344
    assert t.minor_min is None


def test_m10x1_5_6h() -> None:
    t = tolerances("M10x1.5-6H")
    assert t.ei == pytest.approx(0.0)
    assert t.pitch_diameter_tolerance == pytest.approx(0.180)
    assert t.crest_diameter_tolerance == pytest.approx(0.300)
    assert (mm(t.pitch_min), mm(t.pitch_max)) == (9.026, 9.206)
    assert (mm(t.minor_min), mm(t.minor_max)) == (8.376, 8.676)


def test_coarse_designation_uses_coarse_pitch_tolerances() -> None:
    assert tolerances("M10-6g").pitch_max == pytest.approx(tolerances("M10x1.5-6g").pitch_max)


@pytest.mark.parametrize(
    ("text", "pitch_min", "pitch_max"),
    [
        ("M3-6g", 2.580, 2.655),
        ("M6-6g", 5.212, 5.324),
        ("M12-6g", 10.679, 10.829),
        ("M24-6g", 21.803, 22.003),
        # Coarse internal designations spelt with the pitch: "M36-6H" has no lower-case letter,
        # so it does not say internal (it may be M36-6h upper-cased).
        ("M36x4-6H", 33.402, 33.702),
        ("M64x6-6H", 60.103, 60.478),
    ],
)
def test_common_6g_6h_pitch_limits(text: str, pitch_min: float, pitch_max: float) -> None:
    t = tolerances(text)
    assert (mm(t.pitch_min), mm(t.pitch_max)) == (pitch_min, pitch_max)


def test_fundamental_deviations() -> None:
    assert fundamental_deviation("g", 3.0).micrometres == -48
    assert fundamental_deviation("G", 3.0).micrometres == 48
    assert fundamental_deviation("H", 3.0).micrometres == 0
    assert fundamental_deviation("h", 0.2).micrometres == 0
    assert fundamental_deviation("e", 1.5).micrometres == -67
    assert fundamental_deviation("f", 1.5).micrometres == -45
    assert fundamental_deviation("g", 1.5).micrometres == -32
    assert fundamental_deviation("g", 8.0).micrometres == -100
    assert tolerances("M3-6e").es == pytest.approx(-0.050)
    with pytest.raises(ValueError, match=r"no fundamental deviation e for P = 0\.4"):
        fundamental_deviation("e", 0.4)
    with pytest.raises(ValueError, match="not tabulated"):
        fundamental_deviation("d", 1.5)


def test_crest_tolerance_tables() -> None:
    assert major_diameter_tolerance(6, 3.0).micrometres == 375
    assert major_diameter_tolerance(4, 3.0).micrometres == 236
    assert major_diameter_tolerance(8, 3.0).micrometres == 600
    assert minor_diameter_tolerance(5, 3.0).micrometres == 400
    assert minor_diameter_tolerance(6, 1.5).micrometres == 300
    with pytest.raises(ValueError, match="no grade 5"):
        major_diameter_tolerance(5, 3.0)
    with pytest.raises(ValueError, match=r"no grade-8 value for P = 0\.5"):
        major_diameter_tolerance(8, 0.5)


def test_diameter_ranges() -> None:
    assert diameter_range(1.0) == (0.99, 1.4)
    assert diameter_range(45.0) == (22.4, 45.0)  # upper bound included
    assert diameter_range(48.0) == (45.0, 90.0)
    with pytest.raises(ValueError, match="outside"):
        diameter_range(0.8)
    with pytest.raises(ValueError, match="outside"):
        diameter_range(700.0)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("M10x3-6g", "P = 3 mm is not tabulated for 5.6 < d <= 11.2"),
        ("M10x1.5-6g5g", "no grade 5"),  # Td has grades 4, 6, 8 only
        ("M10x1.5-3H", "no grade 3"),  # TD2 starts at grade 4
        ("M1x0.25-6H", "no grade-6 value for P = 0.25"),  # blank cell
        ("M2x0.4-6e", "no fundamental deviation e "),
        ("M700x6-6g", "outside"),
    ],
)
def test_outside_the_tables(text: str, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        tolerances(text)


def test_derived_cells_are_flagged() -> None:
    assert frozenset({(355.0, 600.0)}) == DERIVED_RANGES
    cell = pitch_diameter_tolerance(6, 6.0, 400.0, internal=False)
    assert cell.derived
    assert tolerances("M400x6-6g").derived == ("Td2",)
    assert tolerances("M400x6-6H").derived == ("TD2",)
    assert not pitch_diameter_tolerance(6, 6.0, 300.0, internal=False).derived


def test_preferred_numbers() -> None:
    assert preferred_number(211.6) == 212
    assert preferred_number(26.3) == 26
    assert preferred_number(47.4) == 48
    assert 1180 in PREFERRED_NUMBERS
    with pytest.raises(ValueError):
        preferred_number(0.0)


def test_tables_are_consistent() -> None:
    """Typo guard: every cell within one preferred step of the annex formula, grades rising."""
    cells = table_cells()
    assert len(cells) > 500
    by_row: dict[tuple[str, tuple[float, float] | None, float], dict[int, int]] = {}
    for cell in cells:
        factor = GRADE_FACTORS[cell.grade]
        if cell.table == "Td":
            estimate = factor * formula_major_tolerance_6(cell.pitch)
        elif cell.table == "TD1":
            estimate = factor * formula_minor_tolerance_6(cell.pitch)
        else:
            assert cell.diameter_range is not None
            estimate = factor * formula_pitch_tolerance_6(cell.pitch, cell.diameter_range)
            if cell.table == "TD2":
                estimate *= 1.32
        value = cell.value.micrometres
        assert value in PREFERRED_NUMBERS, cell
        steps = abs(
            PREFERRED_NUMBERS.index(value) - PREFERRED_NUMBERS.index(preferred_number(estimate))
        )
        assert steps <= 1, (cell, estimate)
        by_row.setdefault((cell.table, cell.diameter_range, cell.pitch), {})[cell.grade] = value
    for key, row in by_row.items():
        grades = sorted(row)
        assert all(row[a] < row[b] for a, b in itertools.pairwise(grades)), key


def test_internal_pitch_tolerance_is_larger_than_external() -> None:
    for cell in table_cells():
        if cell.table != "TD2" or cell.diameter_range is None:
            continue
        hi = cell.diameter_range[1]
        ext = pitch_diameter_tolerance(cell.grade, cell.pitch, hi, internal=False)
        assert cell.value.micrometres > ext.micrometres, cell


# ---------------------------------------------------------------------------------------------
# Designations
# ---------------------------------------------------------------------------------------------


def test_parse_external_two_classes() -> None:
    d = parse_designation("M50x3-5g6g")
    assert d.nominal_diameter == 50.0
    assert d.pitch == 3.0
    assert not d.internal
    assert d.pitch_class == ToleranceClass(5, "g")
    assert d.crest_class == ToleranceClass(6, "g")
    assert not d.left_hand
    assert not d.coarse_pitch_used
    assert d.internal_basis == "case"
    assert not d.internal_ambiguous
    assert d.text == "M50x3-5g6g"
    assert d.canonical() == "M50x3-5g6g"


def test_parse_internal_with_multiplication_sign() -> None:
    d = parse_designation("M50×3-4H5H")
    assert d.internal
    assert d.pitch_class == ToleranceClass(4, "H")
    assert d.crest_class == ToleranceClass(5, "H")
    assert d.internal_basis == "case"  # the typographic × shows lower case was available


def test_parse_all_uppercase_class_of_both_kinds_is_undecided() -> None:
    # All capitals: the case may have been lost, and ISO 965-1 has 5g6g and 5G6G.
    with pytest.raises(SideUndecided) as undecided:
        parse_designation("M50X3-5G6G")
    err = undecided.value
    assert (err.external.canonical(), err.internal.canonical()) == ("M50x3-5g6g", "M50x3-5G6G")
    assert str(err) == (
        "M50X3-5G6G: the class 5G6G fits an external (5g6g) or an internal (5G6G) thread: "
        "say which, or write the class in the standard's case: M50x3-5g6g external, "
        "M50x3-5G6G internal"
    )
    assert "with --external or --internal" in err.question("with --external or --internal")
    for text in ("M20X1.5-6H", "M10-6H", "M50X3-7H6H", "M24XPH4P2-6G"):
        with pytest.raises(SideUndecided):
            parse_designation(text)

    ext = parse_designation("M50X3-5G6G", internal=False)
    assert not ext.internal
    assert ext.internal_basis == "caller"
    assert ext.pitch_class == ToleranceClass(5, "g")
    assert ext.crest_class == ToleranceClass(6, "g")
    assert tolerances(ext).pitch_diameter_tolerance == pytest.approx(0.170)

    nut = parse_designation("M50X3-5G6G", internal=True)
    assert nut.internal and nut.internal_basis == "caller"
    assert nut.canonical() == "M50x3-5G6G"


def test_parse_all_uppercase_class_of_one_kind_is_that_kind() -> None:
    # E and F exist only as external positions (ISO 965-1), so upper case E is e.
    e = parse_designation("M10X1.5-6E")
    assert not e.internal and e.internal_basis == "class"
    assert e.pitch_class == ToleranceClass(6, "e")
    # The seed paper's M50X3-4H5H: ISO 965-1 has no crest grade 5 for external threads (Td
    # grades 4, 6, 8), so only the internal 4H5H exists.
    nut = parse_designation("M50X3-4H5H")
    assert nut.internal and nut.internal_basis == "class"
    assert nut.canonical() == "M50x3-4H5H"
    # 7H: no Td grade 7; 3G4G: no TD2 grade 3.
    assert parse_designation("M20X1.5-7H").internal
    assert not parse_designation("M20X1.5-3G4G").internal
    assert parse_designation("M50X3-4H5H", internal=True).internal_basis == "class"
    with pytest.raises(SideConflict, match="no crest-diameter grade 5 for external threads"):
        parse_designation("M50X3-4H5H", internal=False)
    with pytest.raises(SideConflict, match="position E only for external threads"):
        parse_designation("M10X1.5-6E", internal=True)
    with pytest.raises(ValueError, match="neither kind of thread has the class 9H"):
        parse_designation("M50X3-9H", internal=True)


def test_case_contradicting_internal_argument() -> None:
    with pytest.raises(SideConflict) as conflict:
        parse_designation("M10x1.5-6g", internal=True)
    assert str(conflict.value) == (
        "M10x1.5-6g is an external thread (its class 6g is in lower case), but an internal "
        "thread was asked for"
    )
    with pytest.raises(SideConflict, match="is an internal thread"):
        parse_designation("M10x1.5-6H", internal=False)
    assert parse_designation("M10x1.5-6g", internal=False).internal_basis == "case"


def test_parse_coarse_single_class() -> None:
    d = parse_designation("M10-6g")
    assert d.pitch == 1.5
    assert d.coarse_pitch_used
    assert d.pitch_class == d.crest_class == ToleranceClass(6, "g")
    assert d.canonical() == "M10-6g"


@pytest.mark.parametrize("text", ["M20x1.5LH-6H", "M20x1.5-6H-LH", "M20 x 1.5 - 6H - LH"])
def test_parse_left_hand(text: str) -> None:
    d = parse_designation(text)
    assert d.left_hand
    assert d.internal
    assert d.pitch == 1.5
    assert d.canonical() == "M20x1.5-6H-LH"


def test_parse_engagement_and_default_class() -> None:
    d = parse_designation("M20x2-7g6g-L")
    assert d.engagement == "L"
    assert d.pitch_class == ToleranceClass(7, "g")
    with pytest.raises(SideUndecided, match="no tolerance class") as undecided:
        parse_designation("M10x1.5")
    bare = undecided.value.external
    assert bare.class_omitted
    assert bare.pitch_class == ToleranceClass(6, "g")
    assert parse_designation("M10x1.5", internal=False).internal_basis == "caller"
    nut = parse_designation("M10x1.5", internal=True)
    assert nut.pitch_class == ToleranceClass(6, "H")
    small = parse_designation("M1.2", internal=True)
    assert small.pitch == 0.25
    assert small.pitch_class == ToleranceClass(5, "H")


def test_parse_multiple_start() -> None:
    d = parse_designation("M16xPh3P1.5-6H")
    assert (d.pitch, d.lead, d.starts, d.thread_lead) == (1.5, 3.0, 2, 3.0)
    assert d.internal and d.canonical() == "M16xPh3P1.5-6H"
    upper = parse_designation("M50XPH6P3-5G6G", internal=False)
    assert (upper.pitch, upper.starts, upper.canonical()) == (3.0, 2, "M50xPh6P3-5g6g")
    single = parse_designation("M50x3-5g6g")
    assert (single.starts, single.thread_lead) == (1, 3.0)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("Tr40x7-7e", "trapezoidal"),
        ("TR40X7", "trapezoidal"),
        ("G1/2", "parallel pipe"),
        ("Rc1/2", "taper pipe"),
        ("1/4-20 UNC", "Unified"),
        ("MJ10x1.25-4h6h", "MJ"),
        ("M16xPh4P1.5-6H", "whole multiple of the pitch"),
        ("M10x1.5-6H/6g", "fit"),
        ("M10-1.5", "after an x"),
        ("M10x1.5-6k", "position k is not defined for external threads"),
        ("M10x1.5-6E", "position E is not defined for internal threads"),
        ("M10X1.5-6K", "no tolerance position K"),
        ("M10x1.5-6G6g", "mixes letter cases"),
        ("M10x1.5-5g6h", "share one tolerance position"),
        ("M10x1.5-6g-XY", "unexpected part"),
        ("M10x12", "not smaller than the diameter"),
        ("Mx1.5", "cannot read"),
        ("", "empty"),
        ("hello", "not an ISO metric thread"),
        ("M50-6g", "no coarse pitch"),
    ],
)
def test_parse_errors(text: str, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        parse_designation(text)


# ---------------------------------------------------------------------------------------------
# Coarse pitches (ISO 261)
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("diameter", "pitch"),
    [
        (1, 0.25),
        (1.6, 0.35),
        (3, 0.5),
        (4.5, 0.75),
        (10, 1.5),
        (12, 1.75),
        (24, 3),
        (30, 3.5),
        (42, 4.5),
        (48, 5),
        (52, 5),
        (56, 5.5),
        (64, 6),
        (68, 6),
    ],
)
def test_coarse_pitch(diameter: float, pitch: float) -> None:
    assert coarse_pitch(diameter) == pitch


def test_no_coarse_pitch_for_third_choice_or_large_sizes() -> None:
    # M50 is a third-choice size of ISO 261 with fine pitches only (3, 2, 1.5).
    with pytest.raises(ValueError, match="M50 has no coarse pitch"):
        coarse_pitch(50)
    with pytest.raises(ValueError, match="only up to M68"):
        coarse_pitch(72)


# ---------------------------------------------------------------------------------------------
# Geometry and the symmetric thread module (thread-math.md section 1)
# ---------------------------------------------------------------------------------------------


def test_basic_profile() -> None:
    assert fundamental_triangle_height(3.0) == pytest.approx(math.sqrt(3) / 2 * 3)
    assert basic_pitch_diameter(50.0, 3.0) == pytest.approx(50 - 0.649519 * 3, abs=1e-6)
    assert basic_minor_diameter(50.0, 3.0) == pytest.approx(50 - 1.082532 * 3, abs=1e-6)
    assert round(basic_pitch_diameter(50.0, 3.0), 3) == 48.051
    assert round(basic_minor_diameter(50.0, 3.0), 3) == 46.752
    assert paper_internal_minor_diameter(50.0, 3.0) == pytest.approx(basic_minor_diameter(50, 3))


def test_nose_radius() -> None:
    assert theoretical_nose_radius(3.0, internal=False) == pytest.approx(0.4330, abs=5e-5)
    assert theoretical_nose_radius(3.0, internal=True) == pytest.approx(0.2165, abs=5e-5)
    assert nose_radius_range(3.0, internal=False) == pytest.approx((0.375, 0.432))
    assert nose_radius_range(3.0, internal=True) == pytest.approx((0.0, 0.216))
    assert nose_radius_ok(0.4, 3.0, internal=False)
    assert not nose_radius_ok(0.3, 3.0, internal=False)
    assert not nose_radius_ok(0.0, 3.0, internal=True)


def test_thread_height_from_paper_inputs() -> None:
    ext = thread_height(3.0, internal=False, deviation=0.048, pitch_tolerance=0.170)
    internal = thread_height(3.0, internal=True, deviation=0.0, pitch_tolerance=0.180)
    assert ext == pytest.approx(1.9068, abs=5e-5)
    assert internal == pytest.approx(1.7771, abs=5e-5)
    assert round(ext, 3) == 1.907
    assert round(internal, 3) == 1.777
    with pytest.raises(ValueError, match="magnitude"):
        thread_height(3.0, internal=False, deviation=-0.048, pitch_tolerance=0.170)


@pytest.mark.parametrize(
    ("internal", "deviation", "tolerance", "first", "smallest", "u1", "passes", "cuts"),
    [
        (False, 0.048, 0.170, 0.0921, 0.0202, 1.0361, 88, 186),
        (True, 0.0, 0.180, 0.0889, 0.0199, 0.9632, 83, 176),
    ],
)
def test_symmetric_module_m50x3(
    internal: bool,
    deviation: float,
    tolerance: float,
    first: float,
    smallest: float,
    u1: float,
    passes: int,
    cuts: int,
) -> None:
    plan = plan_symmetric_thread(
        3.0, internal=internal, deviation=deviation, pitch_tolerance=tolerance, length=50.0
    )
    assert plan.ap_max == pytest.approx(first, abs=5e-5)
    assert plan.ap_min == pytest.approx(smallest, abs=5e-5)
    assert plan.passes[0].n == 1
    assert plan.passes[0].depth == pytest.approx(plan.ap_max)
    assert plan.passes[0].offset == pytest.approx(u1, abs=5e-5)
    assert plan.rough_pass_count == passes
    assert plan.g92_cut_count == cuts
    assert (plan.run_in, plan.run_out) == pytest.approx((7.0, 3.0))
    # Loop invariant: every rough pass is cut short of h - ap_min, and the next one would not be.
    assert all(p.cumulative < plan.height - plan.ap_min for p in plan.passes)
    assert plan.passes[-1].cumulative + plan.ap_min >= plan.height - plan.ap_min
    assert count_rough_passes(plan.height, plan.ap_max, plan.ap_min) == passes


def test_plan_from_iso_tolerances_equals_paper() -> None:
    ext = plan_from_tolerances(tolerances("M50x3-5g6g"), length=50.0)
    internal = plan_from_tolerances(tolerances("M50x3-4H5H"), length=50.0)
    assert round(ext.height, 3) == 1.907
    assert round(internal.height, 3) == 1.777
    assert (ext.rough_pass_count, internal.rough_pass_count) == (88, 83)


def test_depth_rules() -> None:
    h = 1.906804
    first = ap_max(h)
    smallest = ap_min(first)
    assert ap_max(h, 0.2) == pytest.approx(3 * first)
    assert pass_depth(1, first) == pytest.approx(first)
    assert pass_depth(4, first) == pytest.approx((2 - math.sqrt(3)) * first)
    # sqrt(n) rule while ap(n) >= ap_min (n <= 5 here), then + ap_min per pass.
    assert cumulative_depth(4, first, smallest) == pytest.approx(2 * first)
    assert cumulative_depth(5, first, smallest) == pytest.approx(math.sqrt(5) * first)
    assert cumulative_depth(7, first, smallest) == pytest.approx(
        math.sqrt(5) * first + 2 * smallest
    )
    passes = rough_passes(h, first, smallest, 0.4330127)
    assert [p.cumulative for p in passes[:7]] == pytest.approx(
        [cumulative_depth(n, first, smallest) for n in range(1, 8)]
    )
    assert side_offset(h, 0.433, smallest, first) == pytest.approx(
        (h - smallest - first) * math.tan(math.radians(30))
    )
    with pytest.raises(ValueError):
        pass_depth(0, first)


def test_run_in_out() -> None:
    assert run_in_out(50.0, 3.0) == pytest.approx((7.0, 3.0))
    assert run_in_out(48.0, 3.0) == pytest.approx((9.0, 3.0))  # L a multiple of P
