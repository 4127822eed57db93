"""MB504 (trig-radians) decides radians by the sweep and the step, not by round degrees.

``tests/fixtures/radians/`` holds programs that step an angle in radians (typed with four
decimals that are no round degrees, a WHILE loop in steps of 0.05 up to 1.57, a bolt circle to
6.2832, a bound written with π, a bound in a variable) and degree programs that must stay
quiet: fine steps of 0.5° over 10°, a bolt circle of 360/N, an ellipse from 0° to 90°, angles
from ATAN, one small angle, a taper of 0.5° to 3°, 0° to 2.8° in steps of 0.1° (which could be
radians: the rule prefers silence), a sweep under 0.5 and the degree twin of O5.
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

import pytest

from fanuc_macro.analysis import Analysis, analyse
from fanuc_macro.rules.angles import MB504_DOC, _turn, _typed_conversion

RADIANS_DIR = Path(__file__).resolve().parent / "fixtures" / "radians"

# file -> the (1-based) lines MB504 stands on, one entry per diagnostic
RADIANS: dict[str, list[int]] = {
    "o5_four_decimals.nc": [7, 8],  # 0.3142 in steps of 0.1396 to 2.8275, no π
    "while_step_005.nc": [9, 10],  # 0 to 1.57 in steps of 0.05
    "bolt_circle_radians.nc": [9, 9],  # 0 to 6.2832 in steps of 0.5236: COS and SIN
    "down_bound_with_pi.nc": [10, 10],  # from 3.14159 down by 3.14159/36.
    "pi_in_bound.nc": [7, 7],  # WHILE[#1LE[3.14159/2.]] in steps of 0.1
    "bound_in_variable.nc": [9, 9],  # WHILE[#1LE#5] with #5=1.5708, the step in #6
    "step_in_variable.nc": [8, 8],  # 0.2618 to 2.88 in steps of #6=0.0873 (5° in radians)
}
DEGREES = [
    "deg_fine_half_degree.nc",  # 0° to 10° in steps of 0.5°
    "deg_bolt_circle.nc",  # 24 holes, 360/#2 pitch
    "deg_bolt_circle_short.nc",  # 6 holes from 0.5°
    "deg_ellipse.nc",  # 0° to 90° in steps of 2°
    "deg_atan.nc",  # ATAN[#1]/[100.]: 0.57° to 4.57°
    "deg_single_small.nc",  # TAN[0.75] once
    "deg_taper_steps.nc",  # 0.5° to 3° in steps of 0.5°
    "deg_tenth_degree.nc",  # 0° to 2.8° in steps of 0.1°: could be radians, left alone
    "deg_sweep_under_half.nc",  # 0° to 0.45° in steps of 0.05°
    "deg_arc_18_to_162.nc",  # O5 in degrees
    "deg_step_in_variable.nc",  # 0.5° to 6° in steps of #6=0.5°
]


@cache
def analysis_of(name: str) -> Analysis:
    path = RADIANS_DIR / name
    return analyse(path.read_text("utf-8"), str(path))


def _mb504(analysis: Analysis) -> list[int]:
    return sorted(d.line + 1 for d in analysis.diagnostics if d.code == "MB504")


def _messages(name: str) -> list[str]:
    return [d.message for d in analysis_of(name).diagnostics if d.code == "MB504"]


def test_every_fixture_is_listed() -> None:
    on_disk = {p.name for p in RADIANS_DIR.glob("*.nc")}
    assert on_disk == set(RADIANS) | set(DEGREES)
    assert len(DEGREES) >= 6


@pytest.mark.parametrize("name", sorted(RADIANS))
def test_angles_in_radians_are_reported(name: str) -> None:
    assert _mb504(analysis_of(name)) == RADIANS[name]


@pytest.mark.parametrize("name", DEGREES)
def test_angles_in_degrees_are_quiet(name: str) -> None:
    assert _mb504(analysis_of(name)) == []


@pytest.mark.parametrize("name", sorted(RADIANS) + DEGREES)
def test_no_internal_error(name: str) -> None:
    assert not [d for d in analysis_of(name).diagnostics if d.code == "MB000"]


def test_four_decimals_that_are_no_round_degrees() -> None:
    # The issue: 0.3142 in steps of 0.1396 (18.002° and 7.998°) to 2.8275, no π anywhere.
    cos, sin = _messages("o5_four_decimals.nc")
    for message in (cos, sin):
        assert "from 0.3142 in steps of 0.1396 to 2.827 (19 times)" in message
        assert "a sweep of 2.513: radians (18° in steps of 8° to 162°" in message
        assert "the step 0.1396 is typed as a radian conversion" in message
        assert "so the sweep is 2.51°" in message
    assert cos.startswith("COS[#16]") and "COS stays between 0.999 and 1" in cos
    assert sin.startswith("SIN[#16]") and "SIN stays between 0.00548 and 0.0493" in sin


def test_while_loop_in_steps_of_005_to_half_a_turn() -> None:
    for message in _messages("while_step_005.nc"):
        assert "from 0 in steps of 0.05 to 1.55 (32 times), a sweep of 1.55" in message
        assert "(0° in steps of 2.86° to 88.81°; the loop's bound 1.57 is π/2)" in message


def test_the_message_says_what_decided() -> None:
    assert "the loop's bound 6.2832 is 2π" in _messages("bolt_circle_radians.nc")[0]
    assert "the loop's bound is written with π" in _messages("pi_in_bound.nc")[0]
    assert "the loop's bound 1.5708 is π/2" in _messages("bound_in_variable.nc")[0]
    down = _messages("down_bound_with_pi.nc")[0]
    assert "from 3.142 in steps of -0.08727 to 0 (37 times)" in down
    assert "(180° in steps of -5° to 0°; a π in its assignments)" in down


def _loop(start: str, bound: str, step: str, op: str = "LE") -> str:
    return (
        f"O1\n#1={start}\nWHILE[#1{op}{bound}]DO1\nG01 X[50.*COS[#1]] Z[50.*SIN[#1]] F0.1\n"
        f"#1=#1+{step}\nEND1\nM30\n"
    )


@pytest.mark.parametrize(
    ("start", "bound", "step"),
    [
        ("0", "2.8", "0.0873"),  # 5° as radians, a bound no turn
        ("0.1745", "3.1416", "0.1745"),  # 10° steps to π
        ("0", "0.7854", "0.1"),  # to π/4 with a third decimal
        ("-1.5708", "1.5708", "0.2618"),  # -π/2 to π/2 in 15° steps
        ("0", "6.28", "0.2"),  # to 2π typed 6.28
    ],
)
def test_other_loops_in_radians(start: str, bound: str, step: str) -> None:
    assert _mb504(analyse(_loop(start, bound, step), "loop.nc")) == [4, 4]


@pytest.mark.parametrize(
    ("start", "bound", "step"),
    [
        ("0", "3.", "0.125"),  # eighths of a degree
        ("0", "2.", "0.25"),  # quarters of a degree
        ("0.5", "5.5", "0.5"),  # 5.5 is no turn (7π/4 is 5.498)
        ("0", "1.05", "0.05"),  # 1.05 could be π/3 but needs a third decimal
        ("0", "6.", "0.333"),  # thirds of a degree
        ("0", "3.", "0.1"),  # a tenth of a degree over 3°: could be radians, quiet
        ("0", "3.", "1."),  # whole degrees
        ("0", "0.4", "0.05"),  # a sweep under 0.5
    ],
)
def test_small_angles_in_degrees_are_quiet(start: str, bound: str, step: str) -> None:
    assert _mb504(analyse(_loop(start, bound, step), "loop.nc")) == []


def test_angles_from_atan_converted_with_pi_are_radians() -> None:
    text = (
        "O1\n#2=1.\nWHILE[#2LE20.]DO1\n#1=ATAN[#2]/[10.]*3.14159/180.\n"
        "#3=SIN[#1]+COS[#1]\n#2=#2+1.\nEND1\nM30\n"
    )
    assert _mb504(analyse(text, "atan.nc")) == [5, 5]
    degrees = text.replace("*3.14159/180.", "")  # 5.7° to 63.4°: beyond 2π anyway
    assert _mb504(analyse(degrees, "atan.nc")) == []


def test_a_counter_that_starts_vacant() -> None:
    text = "O1\n#1=#0\nWHILE[#1LE2.8]DO1\n#2=SIN[#1]\n#1=#1+0.1396\nEND1\nM30\n"
    (message,) = _messages_of(text)
    assert "from 0.1396 in steps of 0.1396 to 2.792 (21 times)" in message


def _messages_of(text: str) -> list[str]:
    return [d.message for d in analyse(text, "t.nc").diagnostics if d.code == "MB504"]


def test_the_documented_example_is_reported() -> None:
    m = re.search(r"```nc\n(.*?)```", MB504_DOC.example, re.S)
    assert m is not None
    assert _mb504(analyse(m.group(1), "example.nc")) == [4, 5]
    for part in (MB504_DOC.reports, MB504_DOC.not_reported):
        assert "round numbers of degrees" not in part
    assert "the step" in MB504_DOC.reports and "sweep" in MB504_DOC.reports


def test_turns_as_typed() -> None:
    assert [_turn(v) for v in (1.57, 1.5708, 3.14, 3.1415, 3.1416, 6.28, 6.2832, -1.571)] == [
        "π/2",
        "π/2",
        "π",
        "π",
        "π",
        "2π",
        "2π",
        "π/2",
    ]
    assert _turn(0.7854) == "π/4" and _turn(1.047) == "π/3"
    assert [_turn(v) for v in (1.5, 1.58, 3.15, 3.2, 5.5, 1.05, 0.79, 2.8275, 10.0, 0.0)] == [
        None
    ] * 10


def test_steps_typed_as_radian_conversions() -> None:
    assert all(_typed_conversion(v) for v in (0.1396, 0.13963, 0.0873, 0.31416, 0.5236, 0.017))
    assert not any(_typed_conversion(v) for v in (0.5, 0.25, 0.1, 0.05, 0.125, 0.375, 0.333, 0.2))
