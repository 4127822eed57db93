"""Mistakes in the calls of macros and subprograms, as programmers make them, each caught at
the line they would fix.

``tests/fixtures/call_variants/`` holds mill and lathe programs that call a macro (a bolt
circle, an ellipse profile of the textbooks, a pocket with argument checks, a groove), written
the way shops write them, without comments naming the mistake. Each ``*_clean`` program is
right and gets no error or warning; each variant holds one mistake: its errors and warnings
must be the listed ones, the mistake at its line and what truly follows from it.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from variant_checks import errors_and_warnings

VARIANTS_DIR = Path(__file__).resolve().parent / "fixtures" / "call_variants"

# file -> (the mistake, the (1-based line, code) that names it, the other true findings)
VARIANTS: dict[str, tuple[str, tuple[int, str], set[tuple[int, str]]]] = {
    "bolt_circle_i_for_r.nc": ("the radius passed as I, read as #18 (R)", (9, "MB411"), set()),
    "bolt_circle_m98.nc": (
        "the macro called with M98 and argument words",
        (9, "MB412"),
        # The second call, and the hole count #11 vacant: 360/#11 divides by zero.
        {(10, "MB412"), (16, "MB502")},
    ),
    "ellipse_c_for_b.nc": (
        "the semi-minor axis passed as C, read as #2 (B)",
        (11, "MB411"),
        {(19, "MB901")},  # #2 read vacant in the loop
    ),
    "pocket_eq_zero.nc": ("a missing D tested with EQ 0", (14, "MB905"), set()),
    "pocket_ne_zero.nc": ("a missing Z tested with NE 0", (15, "MB905"), set()),
    "groove_m98.nc": ("the groove macro called with M98", (8, "MB412"), set()),
}
CLEAN = ["bolt_circle_clean.nc", "ellipse_clean.nc", "pocket_clean.nc", "groove_clean.nc"]


def serious(name: str) -> set[tuple[int, str]]:
    return errors_and_warnings(VARIANTS_DIR / name)


@pytest.mark.parametrize("name", sorted(VARIANTS))
def test_each_mistake_is_named_at_its_line(name: str) -> None:
    _mistake, named, follows = VARIANTS[name]
    assert serious(name) == {named} | follows


@pytest.mark.parametrize("name", CLEAN)
def test_the_clean_twins_get_no_error_or_warning(name: str) -> None:
    assert serious(name) == set()


def test_every_variant_has_its_twin() -> None:
    files = {p.name for p in VARIANTS_DIR.glob("*.nc")}
    assert files == set(VARIANTS) | set(CLEAN)
    stems = {name.split("_")[0] for name in VARIANTS}
    assert stems == {name.split("_")[0] for name in CLEAN}
