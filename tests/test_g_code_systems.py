"""A lathe's G code systems B and C (setting machine.gCodeSystem, ``--g-code-system``): the
codes translated to system A's for the run, the messages naming the codes as written, the
machine read from the codes, hover and completion in the system's numbers."""

from __future__ import annotations

import json
import random
from pathlib import Path
from typing import Any

import pytest

from cli_runner import check_text as check
from cli_runner import run
from fanuc_macro.config import Config
from fanuc_macro.program import knowledge
from fanuc_macro.program.g_code_systems import translated, written
from fanuc_macro.syntax.parser import BlockParser
from test_incremental import assert_same, evaluate_text, mutate

# The same part in the three systems: a turning cycle of three passes, a threading cycle of
# two, and a return to the reference point. System A's U/W are B's and C's G91 X/Z.
TURN_AND_THREAD = {
    "A": """\
O1000
G99 G21
G50 S2000
T0101
G96 S180 M03
G00 X52. Z2.
G90 X46. Z-30. F0.25
X42.
X38.
G00 X100. Z100.
T0303
G97 S800 M03
G00 X32. Z5.
G92 X29.3 Z-20. F1.5
X28.8
G00 U-2. W-3.
G28 U0 W0
M30
""",
    "B": """\
O1000
G90 G95 G21
G92 S2000
T0101
G96 S180 M03
G00 X52. Z2.
G77 X46. Z-30. F0.25
X42.
X38.
G00 X100. Z100.
T0303
G97 S800 M03
G00 X32. Z5.
G78 X29.3 Z-20. F1.5
X28.8
G91 G00 X-2. Z-3.
G28 X0 Z0
M30
""",
    "C": """\
O1000
G90 G95 G71
G92 S2000
T0101
G96 S180 M03
G00 X52. Z2.
G20 X46. Z-30. F0.25
X42.
X38.
G00 X100. Z100.
T0303
G97 S800 M03
G00 X32. Z5.
G21 X29.3 Z-20. F1.5
X28.8
G91 G00 X-2. Z-3.
G28 X0 Z0
M30
""",
}


def trace(tmp_path: Path, text: str, *options: str) -> dict[str, Any]:
    (tmp_path / "part.nc").write_text(text)
    result = run(
        tmp_path, "trace", "--format", "json", "--controller", "0i-TF", *options, "part.nc"
    )
    assert result.returncode == 0, result.stdout + result.stderr
    answer: dict[str, Any] = json.loads(result.stdout)
    return answer


def path_of(answer: dict[str, Any]) -> list[tuple[int, tuple[Any, ...], tuple[Any, ...]]]:
    """Each motion's line, start and end: what the machine does, whatever the codes' names."""
    return [
        (m["line"], tuple(sorted(m["start"].items())), tuple(sorted(m["end"].items())))
        for m in answer["motions"]
    ]


@pytest.mark.parametrize("system", ["B", "C"])
def test_a_program_of_system_b_or_c_runs_as_its_system_a_twin(tmp_path: Path, system: str) -> None:
    twin = trace(tmp_path, TURN_AND_THREAD["A"])
    own = trace(tmp_path, TURN_AND_THREAD[system], "--g-code-system", system.lower())
    assert path_of(own) == path_of(twin)
    codes = [m["code"] for m in own["motions"]]
    cycle, thread = {"B": ("G77", "G78"), "C": ("G20", "G21")}[system]
    assert codes.count(cycle) == 3 and codes.count(thread) == 2  # named as written
    # G91 X-2. Z-3. from X32. Z5.: X and Z are distances, as A's U and W.
    step = next(m for m in own["motions"] if m["line"] == 16)
    assert (step["start"], step["end"]) == ({"X": 32.0, "Z": 5.0}, {"X": 30.0, "Z": 2.0})


def test_read_in_system_a_the_cycles_of_system_b_do_not_run(tmp_path: Path) -> None:
    answer = trace(tmp_path, TURN_AND_THREAD["B"])
    assert not any(m["code"] in ("G77", "G78", "G90", "G92") for m in answer["motions"])


# A threading cycle started inside the thread's diameter: the return in Z crosses the thread.
THREAD_START_INSIDE = """\
O1001
G90 G95 G21
T0303
G97 S800 M03
G00 X{start} Z5.
G78 X29.3 Z-20. F1.5
X28.8
G00 X100. Z100.
M30
"""


def test_a_verdict_of_a_system_b_program_names_its_code(tmp_path: Path) -> None:
    wrong = check(tmp_path, THREAD_START_INSIDE.format(start="26."), "--g-code-system", "B")
    errors = [d for d in wrong if d["severity"] == "error"]
    assert [d["code"] for d in errors] == ["MB813"]
    assert errors[0]["message"].startswith("G78 starts at X26., but the thread is cut from")
    twin = check(tmp_path, THREAD_START_INSIDE.format(start="32."), "--g-code-system", "B")
    assert [d for d in twin if d["severity"] in ("error", "warning")] == []


def test_the_lathe_of_system_b_is_known_by_its_codes(tmp_path: Path) -> None:
    (tmp_path / "part.nc").write_text(TURN_AND_THREAD["B"])
    as_a = run(tmp_path, "check", "--verbose", "part.nc")
    assert "Machine: not known" in as_a.stdout + as_a.stderr  # G90, G91: a mill's in system A
    as_b = run(tmp_path, "check", "--verbose", "--g-code-system", "B", "part.nc")
    said = as_b.stdout + as_b.stderr
    assert "Machine: a lathe (0i-F read as 0i-TF)" in said
    assert "A lathe's G codes are read in G code system B." in said


def test_a_mill_is_not_read_in_the_lathe_s_system(tmp_path: Path) -> None:
    mill = "O2000\nT1 M06\nG90 G54 G00 X0 Y0\nG43 H1 Z50.\nG91 G01 Z-5. F100.\nM30\n"
    as_a = trace(tmp_path, mill.replace("T1", "T01"), "--controller", "0i-MF")
    as_b = trace(
        tmp_path, mill.replace("T1", "T01"), "--controller", "0i-MF", "--g-code-system", "B"
    )
    assert as_a["motions"] == as_b["motions"]


def test_an_unknown_system_is_a_usage_error_on_the_command_line(tmp_path: Path) -> None:
    (tmp_path / "part.nc").write_text("O1\nM30\n")
    result = run(tmp_path, "check", "--g-code-system", "D", "part.nc")
    assert result.returncode == 2
    assert "--g-code-system" in result.stderr


def test_the_editor_setting_is_read_in_any_case_and_a_wrong_one_is_said() -> None:
    assert Config.from_settings({"machine": {"gCodeSystem": "c"}}).g_code_system == "C"
    assert Config.from_settings({"machine": {}}).g_code_system == "A"
    wrong = Config.from_settings({"machine": {"gCodeSystem": "Z"}})
    assert wrong.g_code_system == "A"
    assert wrong.setting_problems == (
        "machine.gCodeSystem: 'Z' is not a G code system (A, B or C); system A is used",
    )


def test_each_function_has_its_number_in_each_system() -> None:
    # (function, A, B, C): FANUC 0i-TF Plus Operator's Manual (B-64694EN), "List of G codes".
    rows = [
        ("threading", 32.0, 33.0, 33.0),
        ("coordinate system setting", 50.0, 92.0, 92.0),
        ("finishing cycle", 70.0, 70.0, 72.0),
        ("stock removal in turning", 71.0, 71.0, 73.0),
        ("multiple threading cycle", 76.0, 76.0, 78.0),
        ("turning cycle", 90.0, 77.0, 20.0),
        ("threading cycle", 92.0, 78.0, 21.0),
        ("facing cycle", 94.0, 79.0, 24.0),
        ("feed per minute", 98.0, 94.0, 94.0),
        ("feed per revolution", 99.0, 95.0, 95.0),
        ("inch input", 20.0, 20.0, 70.0),
    ]
    for function, a, b, c in rows:
        assert list(translated([b], "B")[0]) == [a], function
        assert list(translated([c], "C")[0]) == [a], function
        name = f"G{int(a):02d}"
        assert written(name, "B") == f"G{int(b):02d}", function
        assert written(name, "C") == f"G{int(c):02d}", function
        assert written(name, "A") == name
    # G90/G91 set absolute or incremental programming, which system A does by address.
    assert translated([91.0, 0.0], "B") == ([0.0], 91.0)
    assert translated([90.0], "A") == ([90.0], None)
    # A code of system A alone means nothing in B: G32 is not B's threading.
    assert list(translated([32.0, 50.0], "B")[0]) == []


def test_hover_and_completion_use_the_system_s_numbers() -> None:
    hover = knowledge.code_markdown("G", 78.0, True, "B")
    assert hover is not None and hover.startswith(
        "**G78** — Threading cycle *(G code system B; system A's G92)*"
    )
    assert knowledge.code_markdown("G", 91.0, True, "C") is not None
    assert "Incremental programming" in (knowledge.code_markdown("G", 91.0, True, "C") or "")
    assert knowledge.code_markdown("G", 50.0, True, "B") == (
        "**G50** — no meaning on a lathe of G code system B"
    )
    on_a_mill = knowledge.code_markdown("G", 92.0, False, "B") or ""
    assert "Coordinate system setting" in on_a_mill or "coordinate" in on_a_mill.lower()
    names = dict(knowledge.completion_codes(True, "C"))
    assert names["G20"] == "Outer/inner diameter cutting cycle"
    assert names["G70"] == "Inch input"
    assert names["G91"] == "Incremental programming"


def test_an_edit_resumes_in_the_incremental_mode_it_left() -> None:
    """The run's checkpoints keep G91: edits after it give what a fresh evaluation gives."""
    config = Config(controller="0i-TF", g_code_system="B")
    lines = TURN_AND_THREAD["B"].splitlines()
    lines[-2:-2] = [f"G01 X{n}. Z-{n}. F0.1" for n in range(1, 60)]  # in G91 after line 16
    parser = BlockParser()
    rng = random.Random(7)
    previous = evaluate_text("\n".join(lines), parser, config)
    last = previous.motions[-2]
    assert last.x is not None and last.x > 1000.0  # X30. + 1 + 2 + ... + 59: distances
    for _ in range(30):
        lines = mutate(lines, rng, shift=True)
        text = "\n".join(lines)
        resumed = evaluate_text(text, parser, config, previous)
        assert_same(resumed, evaluate_text(text, BlockParser(), config))
        previous = resumed
