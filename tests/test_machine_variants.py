"""Mistakes in realistic mill and lathe programs, caught at the line a programmer would fix,
and their correct twins left quiet.

``tests/fixtures/machine_variants/`` holds 15 correct programs (Chinese textbook ellipse and
parabola loops, bolt circles, pockets, contours with compensation, tool changes, peck
drilling, probing, counters, turning, facing, threading, grooving, parting off) and 40
variants with one mistake each, written without reading the rules and without a comment that
names the mistake; ``catalogue.toml`` says what each mistake is, its line and what the control
or the machine would do. Every variant is listed here: caught, with the errors and warnings it
must get (the mistake and what truly follows from it), or missed, with why the checker cannot
know. A missed variant must stay quiet, as its twin does.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import tomllib

from variant_checks import analysed, errors_and_warnings

VARIANTS_DIR = Path(__file__).resolve().parent / "fixtures" / "machine_variants"
CATALOGUE = tomllib.loads((VARIANTS_DIR / "catalogue.toml").read_text("utf-8"))["variant"]

# variant -> its errors and warnings: (1-based line, code)
CAUGHT: dict[str, set[tuple[int, str]]] = {
    "ellipse_mill_do_no_end.nc": {(20, "MB201")},
    # The call's radius as I: lost, and the macro's own check of R stops it.
    "boltcircle_mill_unread_letter.nc": {(13, "MB411"), (33, "MB503")},
    "boltcircle_mill_m98_args.nc": {(12, "MB412"), (32, "MB503")},
    "boltcircle_mill_var_out_of_range.nc": {(22, "MB302")},
    "pocket_mill_vacancy_eq_zero.nc": {(18, "MB905")},
    "pocket_mill_alarm_reached.nc": {(45, "MB503")},
    # F not passed: the macro's feed is F0 where it cuts.
    "pocket_mill_no_f_arg.nc": {(33, "MB604"), (33, "MB901")},
    "pocket_mill_label_after_percent.nc": {(50, "MB014")},
    "contour_mill_arc_r_small.nc": {(16, "MB621")},
    "contour_mill_ij_sign.nc": {(18, "MB622")},
    "contour_mill_g40_on_arc.nc": {(23, "MB631")},
    # The G40 left out of the lead-out: compensation still on at the G28 after it.
    "contour_mill_comp_left_on.nc": {(27, "MB633")},
    "contour_mill_h_mismatch.nc": {(8, "MB613")},
    # The M03 left out after S1100: the first hole of the next cycle.
    "toolchange_mill_no_m03.nc": {(37, "MB611")},
    "toolchange_mill_no_g43.nc": {(37, "MB614")},
    "peck_mill_no_q.nc": {(22, "MB641")},
    "peck_mill_no_f.nc": {(22, "MB603")},
    "peck_mill_sub_after_percent.nc": {(22, "MB014")},
    "probe_mill_skip_read_before_g31.nc": {(20, "MB615")},
    "probe_mill_vacancy.nc": {(15, "MB905")},
    "counter_mill_counter_not_reset.nc": {(26, "MB711")},
    # The subprogram's #1 is the caller's row counter: the rows never end.
    "counter_mill_local_clobbered.nc": {(17, "MB413"), (27, "MB703")},
    "parabola_mill_goto_missing.nc": {(21, "MB101")},
    "od_turn_lathe_not_monotone.nc": {(11, "MB652")},
    "od_turn_lathe_g70_wrong_q.nc": {(32, "MB651")},
    "od_turn_lathe_g98_feed.nc": {(11, "MB605")},
    "facing_lathe_no_clamp.nc": {(10, "MB612")},
    "thread_lathe_wrong_lead.nc": {(12, "MB810")},
    "thread_lathe_too_deep.nc": {(12, "MB801")},
    "thread_lathe_blocks_after_percent.nc": {(14, "MB014")},
    "groove_lathe_unread_letter.nc": {(10, "MB411"), (31, "MB503")},
    "groove_lathe_vacancy.nc": {(16, "MB905")},
    "ellipse_lathe_sqrt_negative.nc": {(18, "MB501")},
    "ellipse_lathe_no_decrement.nc": {(16, "MB703")},
}

# variant -> why the checker does not see it
MISSED: dict[str, str] = {
    "boltcircle_mill_radians.nc": "a pitch of 2π/n degrees is a valid angle: only the intent "
    "says it was meant in radians",
    "probe_mill_sign.nc": "the sign of a work offset correction is the programmer's choice",
    "counter_mill_loop_le.nc": "LE or LT: one pass more is a valid loop; the depth meant is "
    "not in the program",
    "parabola_mill_divide_zero.nc": "a main program that reads #4 before setting it is taken "
    "as a macro given #4 by its caller (MB904's assumption): #4 is not known",
    "ellipse_lathe_radius_as_diameter.nc": "a radius sent as X is a valid diameter: the "
    "profile meant is not in the program",
    "partoff_lathe_decimal_p.nc": "whether G75 takes P with a decimal point is unverified for "
    "the 0i-F",
}


def serious(name: str) -> set[tuple[int, str]]:
    return errors_and_warnings(VARIANTS_DIR / name)


def test_every_variant_of_the_catalogue_is_judged() -> None:
    files = [v["file"] for v in CATALOGUE]
    assert len(files) == len(set(files)) == 40
    assert set(files) == set(CAUGHT) | set(MISSED)
    assert not set(CAUGHT) & set(MISSED)


@pytest.mark.parametrize("name", sorted({v["twin"] for v in CATALOGUE}))
def test_the_correct_twins_are_quiet(name: str) -> None:
    assert serious(name) == set()


@pytest.mark.parametrize("name", sorted(CAUGHT))
def test_each_mistake_is_caught_with_what_follows_from_it(name: str) -> None:
    assert serious(name) == CAUGHT[name]


@pytest.mark.parametrize("name", sorted(MISSED))
def test_a_missed_mistake_gets_no_false_verdict(name: str) -> None:
    assert serious(name) == set()


def test_the_verdicts_stand_at_the_mistake_or_name_it() -> None:
    """Each caught variant has a verdict within a few lines of the catalogued mistake, or one
    whose message names the mistake's line (a mode set there, a call into a macro)."""
    for variant in CATALOGUE:
        name = variant["file"]
        if name not in CAUGHT:
            continue
        line = variant["line"]
        found = [
            d
            for d in analysed(VARIANTS_DIR / name).diagnostics
            if (d.line + 1, d.code) in CAUGHT[name]
        ]
        assert any(
            abs(d.line + 1 - line) <= 3 or f"line {line}" in d.message for d in found
        ) or variant["class"] in ("calls", "end-of-record"), name
