"""The words after a comma, ",C" (chamfer), ",R" (corner radius) and ",A" (the angle of the
line): read as their own addresses, not as a decimal comma nor as the C axis or an arc's R, and
",A" with one coordinate gives the other (direct drawing dimensions)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from cli_runner import check_text as check
from cli_runner import run
from fanuc_macro.config import Config
from fanuc_macro.evaluator.direct_drawing import missing_coordinate
from fanuc_macro.syntax.parser import BlockParser
from fanuc_macro.syntax.tree import NcStatement
from test_incremental import evaluate_text

# A lathe's finishing profile with a 45-degree chamfer by angle, a 30-degree cone ending at a
# Z, a corner radius and a chamfer to the next move.
LATHE_PROFILE = """\
O1000
G99 G21
G50 S2000
T0101
G96 S180 M03
G00 X52. Z2.
G01 X30. Z0 F0.2
X51.0,A-45.0
Z-30. ,R2.
X60. ,C1.
Z-50.
G01 Z-70.5, A150. F0.1
G00 X100. Z100.
M30
"""

MILL_PROFILE = """\
O2000
G90 G17 G21 G54
T1 M06
G43 H1 Z50.
S3000 M03
G00 X0 Y0
Z2.
G01 Z-2. F200.
X50. ,A30.
Y60. ,R5.
X0 ,C2.
G02 X-10. Y50. R10. ,C1.
G00 Z50.
M30
"""


def trace(tmp_path: Path, text: str, *options: str) -> list[dict[str, Any]]:
    (tmp_path / "part.nc").write_text(text)
    result = run(tmp_path, "trace", "--format", "json", *options, "part.nc")
    assert result.returncode == 0, result.stdout + result.stderr
    motions: list[dict[str, Any]] = json.loads(result.stdout)["motions"]
    return motions


@pytest.mark.parametrize(
    ("code", "addresses"),
    [
        ("X51.0,A-45.0", ["X", ",A"]),
        ("Z-30. ,R2.", ["Z", ",R"]),
        ("Y 50, R 15", ["Y", ",R"]),
        ("G01 X10. ,c#1", ["G", "X", ",C"]),
        ("X[ATAN[1,2]],C1.", ["X", ",C"]),
    ],
)
def test_a_comma_word_is_its_own_address(code: str, addresses: list[str]) -> None:
    statement = BlockParser().parse_line(code).statement
    assert isinstance(statement, NcStatement)
    assert [w.address for w in statement.words] == addresses


@pytest.mark.parametrize(
    ("code", "said"),
    [
        ("G01 X1,5", "FANUC's decimal point is '.'; write 1.5"),
        ("G01 X1. ,B2.", "unexpected ','"),
    ],
)
def test_a_comma_that_is_no_comma_word_is_still_an_error(
    tmp_path: Path, code: str, said: str
) -> None:
    found = check(tmp_path, f"O1000\n{code}\nM30\n")
    assert [d["code"] for d in found] == ["MB001"]
    assert said in found[0]["message"]


def test_a_lathe_profile_with_comma_words_is_quiet_and_its_angle_gives_the_end(
    tmp_path: Path,
) -> None:
    assert check(tmp_path, LATHE_PROFILE, "--controller", "0i-TF") == []
    moves = {m["line"]: m for m in trace(tmp_path, LATHE_PROFILE, "--controller", "0i-TF")}
    # X30. to X51. (radius +10.5) on a line at -45 degrees from +Z: Z-10.5.
    assert moves[8]["end"] == {"X": 51.0, "Z": -10.5}
    assert moves[9]["code"] == "G01" and moves[9]["end"] == {"X": 51.0, "Z": -30.0}
    # Z-50. to Z-70.5 at 150 degrees: the radius grows by 20.5 tan 30 = 11.836 (X 83.671).
    assert moves[12]["end"] == {"X": 83.671, "Z": -70.5}


def test_the_lathe_rules_see_the_end_the_angle_gives() -> None:
    facts = evaluate_text(LATHE_PROFILE, BlockParser(), Config(controller="0i-TF"))
    chamfer = next(m for m in facts.motions if m.line == 7)
    assert (chamfer.x, chamfer.z) == (51.0, -10.5)


def test_a_mill_s_angle_is_from_the_plane_s_first_axis_and_its_r_no_arc(tmp_path: Path) -> None:
    assert check(tmp_path, MILL_PROFILE, "--controller", "0i-MF") == []
    moves = {m["line"]: m for m in trace(tmp_path, MILL_PROFILE, "--controller", "0i-MF")}
    assert moves[9]["end"] == {"X": 50.0, "Y": 28.868, "Z": -2.0}  # 50 tan 30
    assert moves[10]["code"] == "G01"  # ",R5." rounds the corner; it is no arc's R
    assert moves[12]["code"] == "G02" and moves[12]["end"]["X"] == -10.0


def test_an_angle_along_the_given_axis_leaves_the_other_unknown(tmp_path: Path) -> None:
    text = "O1000\nG00 X20. Z0\nG01 Z-10. ,A90. F0.1\nG00 X50.\nM30\n"
    moves = {m["line"]: m for m in trace(tmp_path, text, "--controller", "0i-TF")}
    assert moves[3]["end"] == {"Z": -10.0}


def test_the_missing_coordinate_of_a_line_at_an_angle() -> None:
    assert missing_coordinate((0.0, 0.0), 10.0, None, 45.0) == pytest.approx(10.0)
    assert missing_coordinate((0.0, 0.0), None, 10.0, 45.0) == pytest.approx(10.0)
    assert missing_coordinate((0.0, 30.0), None, 51.0, -45.0, 2.0) == pytest.approx(-10.5)
    assert missing_coordinate((0.0, 0.0), 10.0, None, 90.0) is None
    assert missing_coordinate((0.0, 0.0), None, 10.0, 180.0) is None


def test_hover_says_what_a_comma_word_does(tmp_path: Path) -> None:
    (tmp_path / "part.nc").write_text(LATHE_PROFILE)
    result = run(tmp_path, "hover", "--controller", "0i-TF", "part.nc", "10", "6")
    assert result.returncode == 0, result.stderr
    assert "**,C** — Chamfer to the next move" in result.stdout
