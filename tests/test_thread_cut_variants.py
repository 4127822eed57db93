"""Threading mistakes judged from the cut: realistic lathe programs, each with one mistake, and
their correct twins left quiet.

``tests/fixtures/thread_cut_variants/`` holds 15 correct programs (hand-typed G92 lists, G92
in a WHILE loop, two-block G76, G32 with manual retracts, internal threads, a subprogram run
twice by M98, NPT, ISO 7-1 R and Rc taper threads, an NPT on a bar turned elsewhere, a thread
with no designation at all, a two-start thread and a round thread) and 41 variants of one
mistake each, written without reading the rules and without a comment that
names the mistake; ``catalogue.toml`` says what each mistake is, the line a programmer would
fix and what the machine or the part would show. Every variant is listed here: caught at that
line, caught at another line (where its effect shows: said why), or missed (why the checker
cannot know). The errors and warnings of each are exactly the ones listed.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import tomllib

from variant_checks import errors_and_warnings

VARIANTS_DIR = Path(__file__).resolve().parent / "fixtures" / "thread_cut_variants"
CATALOGUE = tomllib.loads((VARIANTS_DIR / "catalogue.toml").read_text("utf-8"))["variant"]

# variant -> its errors and warnings: (1-based line, code)
CAUGHT: dict[str, set[tuple[int, str]]] = {
    "g92_m20_final_shallow.nc": {(14, "MB817")},
    "g92_m20_air_passes.nc": {(8, "MB818")},
    # The pass that plunges: too deep for the insert (MB804), most of the profile at once
    # (MB819), and the pass after it is shallower (MB803).
    "g92_m20_pass_jump.nc": {(10, "MB804"), (10, "MB819"), (11, "MB803")},
    "g76_p_as_diameter.nc": {(9, "MB818")},
    "g76_m12_q_too_deep.nc": {(9, "MB819")},
    "g76_m12_angle_80.nc": {(8, "MB817")},
    "g76_m30_finish_allowance.nc": {(35, "MB819")},
    "g76_m30_f_missing.nc": {(36, "MB810")},
    "g76_m30_p_q_swapped.nc": {(36, "MB819")},
    "g92_while_m24_start_in_material.nc": {(7, "MB813")},
    "g32_m16_pass_jump.nc": {(16, "MB819")},
    "g32_m16_no_retract.nc": {(22, "MB822")},
    "int_m36_final_shallow.nc": {(27, "MB817")},
    "int_m36_start_x_in_material.nc": {(21, "MB813")},
    "npt_half_r_sign.nc": {(30, "MB821")},
    "r_half_g76_r_sign.nc": {(31, "MB821")},
    "rc_3q_r_sign.nc": {(17, "MB821")},
    "rc_3q_r_as_diameter.nc": {(17, "MB821")},
    "twostart_m30_f_pitch.nc": {(8, "MB810")},
    "r_half_g76_p_as_diameter.nc": {(31, "MB818")},
    "npt_3q_bar_r_sign.nc": {(9, "MB823")},
    "npt_3q_bar_no_r.nc": {(9, "MB823")},
    "npt_3q_bar_r_diameter.nc": {(9, "MB823")},
    "rc_1_g76_q_deep.nc": {(24, "MB819")},
    "rc_1_g76_r_omitted.nc": {(24, "MB823")},
    "g92_plain_air.nc": {(20, "MB818")},
    # The pass that plunges: too deep for the insert (MB804), most of the profile at once
    # (MB819), and the pass after it is shallower (MB803).
    "g92_plain_jump.nc": {(22, "MB804"), (22, "MB819"), (23, "MB803")},
}

# variant -> (its errors and warnings, why they stand at another line than the catalogue's)
ELSEWHERE: dict[str, tuple[set[tuple[int, str]], str]] = {
    "g76_m30_g96_kept.nc": (
        {(35, "MB820")},
        "the G97 left out: said at the thread's first pass, where G96 is still in force",
    ),
    "npt_half_g96_kept.nc": (
        {(29, "MB820")},
        "the G97 left out: said at the thread's first pass, where G96 is still in force",
    ),
    "g92_while_m24_height_factor.nc": (
        {(21, "MB817")},
        "a hand-written height formula is no module the checker knows: the cut's pitch "
        "diameter is said at the pass that finishes the flanks",
    ),
    "g92_while_m24_clamp_gt.nc": (
        {(21, "MB819")},
        "the IF that sets the pass's X: said at the pass that takes the profile at once",
    ),
    "g32_m16_start_z_shift.nc": (
        {(20, "MB817")},
        "the Z that shifts the pass's start: said at the block that gives the shifted pass "
        "its depth, the line after it",
    ),
    "twostart_m30_shift_lead.nc": (
        {(8, "MB811")},
        "the second start's shift: said at the first pass, that only one start is cut",
    ),
    "int_m36_semi_past_root.nc": (
        {(30, "MB803"), (31, "MB814")},
        "within its class: a pass deeper than the last is seen as the passes after it going "
        "back and repeating",
    ),
    "round_thread_side_layer_deep.nc": (
        {(15, "MB824")},
        "the loop's bound that makes the shifted layers too deep: said at the layer's G92, "
        "the line after it, with how far it reaches past the profile",
    ),
    "round_thread_radians.nc": (
        {(31, "MB504"), (32, "MB504")},
        "the angles typed in radians: said where COS and SIN read them, with the step held "
        "in #3 (0.1396) that decides it",
    ),
    "g92_while_m24_clamp_wrong_var.nc": (
        {(25, "MB803")},
        "within its class by 0.004 mm: seen as the spring pass going back from the deeper one",
    ),
}

# variant -> why the checker does not see it
MISSED: dict[str, str] = {
    "g92_m20_no_runin.nc": "the run-in a Z axis needs to reach its feed depends on the "
    "machine's servo time constant, not in the program",
    "g76_m30_into_shoulder.nc": "the shoulder is the part's, turned by other blocks: the "
    "thread's end is not judged against the turned profile yet",
    "int_sub_m48_second_run_past_root.nc": "the deeper run stays inside 6H: only the intent "
    "says the final X was the root",
    "r_half_g76_dmin_large.nc": "the heaviest of its 5 passes removes 41% of the profile (0.434 "
    "of 1.047 mm²): a heavy schedule, but no pass takes most of it, and what the insert can "
    "take is not in the program",
}


def _path(name: str) -> Path:
    return VARIANTS_DIR / name


def test_every_variant_of_the_catalogue_is_listed_once() -> None:
    names = [v["file"] for v in CATALOGUE]
    assert len(names) == len(set(names)) >= 20
    listed = [*CAUGHT, *ELSEWHERE, *MISSED]
    assert sorted(listed) == sorted(names)
    on_disk = {p.name for p in VARIANTS_DIR.glob("*.nc")}
    assert on_disk == set(names) | {v["twin"] for v in CATALOGUE}


@pytest.mark.parametrize("name", sorted(CAUGHT))
def test_caught_at_the_line_to_fix(name: str) -> None:
    entry = next(v for v in CATALOGUE if v["file"] == name)
    found = errors_and_warnings(_path(name))
    assert found == CAUGHT[name], entry["mistake"]
    assert entry["line"] in {line for line, _code in found}


@pytest.mark.parametrize("name", sorted(ELSEWHERE))
def test_caught_where_the_effect_shows(name: str) -> None:
    found = errors_and_warnings(_path(name))
    assert found == ELSEWHERE[name][0]


@pytest.mark.parametrize("name", sorted(MISSED))
def test_missed_variants_stay_quiet(name: str) -> None:
    assert errors_and_warnings(_path(name)) == set()


@pytest.mark.parametrize("twin", sorted({v["twin"] for v in CATALOGUE}))
def test_the_twins_are_quiet(twin: str) -> None:
    assert errors_and_warnings(_path(twin)) == set()


def test_recall_and_false_alarms() -> None:
    total = len(CATALOGUE)
    at_line = len(CAUGHT)
    elsewhere = len(ELSEWHERE)
    twins = {v["twin"] for v in CATALOGUE}
    false_alarms = sum(len(errors_and_warnings(_path(t))) for t in twins)
    print(
        f"thread cut variants: {at_line} of {total} caught at the line to fix, {elsewhere} "
        f"more where the effect shows, {len(MISSED)} missed; {false_alarms} errors or "
        f"warnings on the {len(twins)} twins"
    )
    assert false_alarms == 0
    assert at_line + elsewhere >= 0.75 * total
