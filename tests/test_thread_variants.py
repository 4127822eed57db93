"""Threading mistakes as programmers make them, each caught at the line they would fix.

``tests/fixtures/thread_variants/`` holds faulty variants of the seed thread modules (the
symmetric module O4009/O3331 external and O4010/O3330 internal of seed paper 000, the
fitting-method arc thread of seed paper 002) and of hand-written G92/G76 programs, one
realistic mistake each, written the way shops write them: mostly without comments, or with
only a thread designation in the header. Every diagnostic of the evaluator's rule families
(MB5xx, MB8xx) must be the listed ones: the mistake, at its line, and what follows from it
that is true. The ``*_clean`` programs are the same programs without the mistake.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pytest

from fanuc_macro.analysis import Analysis, analyse

VARIANTS_DIR = Path(__file__).resolve().parent / "fixtures" / "thread_variants"

# file -> (the mistake, the (1-based line, code) that names it, the other true findings)
VARIANTS: dict[str, tuple[str, tuple[int, str], set[tuple[int, str]]]] = {
    "o3331_nose_radius_029p.nc": ("nose radius 0.29P", (21, "MB805"), set()),
    "o3331_nose_radius_05.nc": ("nose radius 0.5 for P3", (21, "MB805"), set()),
    "o3331_height_typo.nc": ("#103*2. for #103/2. in the height", (22, "MB808"), {(42, "MB801")}),
    "o3331_no_radius_term.nc": ("height without its - r term", (22, "MB808"), {(32, "MB801")}),
    "o3331_spring_past_root.nc": ("spring passes 0.05 mm past the root", (44, "MB801"), set()),
    "o3331_two_start_lead_as_pitch.nc": (
        "2-start M50X3 with the lead 6 typed as the pitch",
        (32, "MB811"),
        # The depth and the nose radius are computed for P6: all three are true.
        {(21, "MB805"), (22, "MB808"), (32, "MB801")},
    ),
    "o3331_start_inside.nc": ("G92 start point inside the part", (31, "MB813"), set()),
    "o3331_pair_other_feed.nc": ("one G92 of each pair with F1.5", (34, "MB812"), set()),
    "o4009_es_with_sign.nc": ("es entered with its ISO sign", (9, "MB809"), set()),
    "o4009_tolerance_typo.nc": ("Td2 typed 0.70 for 0.170", (10, "MB808"), {(32, "MB801")}),
    "o4009_comment_other_pitch.nc": ("designation M50X2 on a P3 program", (32, "MB810"), set()),
    "o3330_nose_radius_03.nc": ("internal nose radius 0.3 for P3", (25, "MB805"), set()),
    "o3330_external_height.nc": (
        "7H/8 copied into the internal module",
        (26, "MB808"),
        {(37, "MB801")},
    ),
    "o3330_start_outside_bore.nc": ("internal start point outside the bore", (36, "MB813"), set()),
    "g92_m20_past_root.nc": ("hand-written passes past the root", (15, "MB801"), set()),
    "g92_internal_past_root.nc": ("internal passes past the root", (13, "MB801"), set()),
    # The pass lost to FIX leaves the thread shallow: its last depth is never cut.
    "g92_fix_step.nc": ("FIX[#30*10.] on a 0.1 step", (9, "MB814"), {(11, "MB817")}),
    "g92_pass_duplicated.nc": ("a pass typed twice", (9, "MB814"), set()),
    "g92_depth_back.nc": ("passes typed out of order", (10, "MB803"), set()),
    "g92_lead_not_pitch.nc": ("F2 for an M16x1.5", (6, "MB810"), set()),
    "g92_two_start_no_shift.nc": ("two starts, no start shift", (6, "MB811"), set()),
    "g76_root_typo.nc": ("G76 root X typed too deep", (7, "MB801"), set()),
    "g76_start_inside.nc": ("G76 start point below the crest", (5, "MB813"), set()),
    "g76_internal_past_root.nc": ("internal G76 past the root", (7, "MB801"), set()),
    "o5_radians.nc": ("fitting-method angles in radians", (7, "MB504"), {(8, "MB504")}),
    "o3_tool_larger_than_groove.nc": (
        "tool radius above the groove radius",
        (14, "MB806"),
        {(18, "MB501")},  # ASIN[#18/[#4-#18]] leaves its domain: the control's alarm
    ),
}
CLEAN = ["o4009_clean.nc", "o4010_clean.nc", "g92_clean.nc", "g76_clean.nc"]


def _evaluator_codes(analysis: Analysis) -> set[tuple[int, str]]:
    return {(d.line + 1, d.code) for d in analysis.diagnostics if d.code[2] in "5678"}


@cache
def analysis_of(name: str) -> Analysis:
    path = VARIANTS_DIR / name
    return analyse(path.read_text("utf-8"), str(path))


def test_every_fixture_is_listed() -> None:
    on_disk = {p.name for p in VARIANTS_DIR.glob("*.nc")}
    assert on_disk == set(VARIANTS) | set(CLEAN)
    assert len(VARIANTS) >= 20


@pytest.mark.parametrize("name", sorted(VARIANTS))
def test_variant_is_caught_at_the_line_to_fix(name: str) -> None:
    mistake, primary, others = VARIANTS[name]
    found = _evaluator_codes(analysis_of(name))
    assert primary in found, f"{mistake}: not caught; found {sorted(found)}"
    assert found == {primary, *others}, f"{mistake}: found {sorted(found)}"


@pytest.mark.parametrize("name", CLEAN)
def test_the_program_without_the_mistake_is_quiet(name: str) -> None:
    assert _evaluator_codes(analysis_of(name)) == set()


def test_recall_on_the_variants() -> None:
    caught = [
        n
        for n, (_m, primary, _o) in VARIANTS.items()
        if primary in _evaluator_codes(analysis_of(n))
    ]
    recall = len(caught) / len(VARIANTS)
    print(f"threading variants caught: {len(caught)} of {len(VARIANTS)} ({recall:.0%})")
    assert recall == 1.0


def test_every_verdict_says_where_the_thread_is_known_from() -> None:
    for name in VARIANTS:
        for d in analysis_of(name).diagnostics:
            if d.code in ("MB801", "MB805", "MB808", "MB810", "MB811"):
                assert "known from the cuts" in d.message, (name, d.message)


def test_messages_carry_the_numbers() -> None:
    by_code = {d.code: d.message for d in analysis_of("o3331_height_typo.nc").diagnostics}
    assert "#4 = 1.9788" in by_code["MB808"] and "1.9068" in by_code["MB808"]
    assert "#103 is taken ×2 where the formula has es/2" in by_code["MB808"]
    assert "past the root X46.101" in by_code["MB801"]
    assert "class 5g from its es 0.048 (#103) and Td2 0.17 (#104)" in by_code["MB801"]
    fix = next(iter(analysis_of("g92_fix_step.nc").diagnostics)).message
    assert "FIX[#30*10.] at line 9 gave 7 for 7.999999999999999" in fix
    sign = next(iter(analysis_of("o4009_es_with_sign.nc").diagnostics)).message
    assert "#103 = -0.048" in sign and "enter 0.048" in sign


def test_radians_rule_takes_an_angle_that_starts_vacant() -> None:
    # Found by the fuzz campaign: the first value read is vacant, the later ones numbers.
    text = "O1\n#1=#0\nWHILE[#1LE2.8]DO1\n#2=SIN[#1]\n#1=#1+0.31416\nEND1\nM30\n"
    diagnostics = analyse(text, "vacant.nc").diagnostics
    assert not [d for d in diagnostics if d.code == "MB000"]
    assert [d.code for d in diagnostics if d.code == "MB504"] == ["MB504"]
