"""``fanuc-macro trace`` run as a user runs it, in a subprocess: what it lists as motions, and
what it says of a file it reads only in part."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from cli_runner import run

ROOT = Path(__file__).resolve().parents[1]


def trace_json(cwd: Path, *args: str) -> dict[str, Any]:
    result = run(cwd, "trace", "--format", "json", *args)
    assert result.returncode == 0, result.stdout + result.stderr
    answer: dict[str, Any] = json.loads(result.stdout)
    return answer


# A lathe program whose blocks with axis words are not all moves: a dwell (X, U in seconds, P
# in milliseconds), a work offset set by G10, a move to the reference point through U0.
NOT_MOVES = """\
O1000 (DWELL AT THE GROOVE)
G00 X40. Z5.
G01 Z-10. F0.2
G04 X0.5
G04 U1.
G04 P500
G10 L2 P1 X5. Z3.
G01 X30.
G28 U0.
M30
"""


def test_a_dwell_and_a_data_setting_are_not_motions(tmp_path: Path) -> None:
    (tmp_path / "dwell.nc").write_text(NOT_MOVES)
    answer = trace_json(tmp_path, "dwell.nc")
    rows = [(m["line"], m["code"], m["words"]) for m in answer["motions"]]
    assert rows == [
        (2, "G00", {"X": 40.0, "Z": 5.0}),
        (3, "G01", {"Z": -10.0, "F": 0.2}),
        (8, "G01", {"X": 30.0, "F": 0.2}),  # from X40., where the dwells left the tool
        (9, "G28", {"U": 0.0}),  # a one-shot move at rapid, under its own code
    ]
    assert answer["motions"][2]["start"] == {"X": 40.0, "Z": -10.0}
    assert answer["summary"]["by_code"] == {"G00": 1, "G01": 2, "G28": 1}
    text = run(tmp_path, "trace", "dwell.nc").stdout
    assert "G04" not in text and "X0.5" not in text and "G10" not in text


def test_a_dwell_before_a_threading_cycle_leaves_its_start_point(tmp_path: Path) -> None:
    """The cycle starts where G00 put the tool, X26.: a G04 X0.5 before it is no move to
    X0.5, which would put the start point inside the thread (MB813)."""
    program = (
        "%\nO1118 (M24X3)\nG97 S450 M03\nT0101\nG00 X26. Z5.\nG04 X0.5\n"
        "G92 X23.5 Z-35. F3.\nX23.1\nX22.7\nX22.3\nX21.9\nX21.5\nX21.1\nX20.8\nX20.5\n"
        "X20.3\nX20.15\nX20.15\nG00 X100. Z100.\nM30\n%\n"
    )
    (tmp_path / "thread.nc").write_text(program)
    result = run(tmp_path, "check", "--format", "json", "thread.nc")
    assert (result.returncode, json.loads(result.stdout)) == (0, []), result.stdout
    cycle = trace_json(tmp_path, "thread.nc")["motions"][1]
    assert (cycle["code"], cycle["start"]) == ("G92", {"X": 26.0, "Z": 5.0})


def test_the_centre_of_a_rotation_or_scaling_is_no_move(tmp_path: Path) -> None:
    """On a mill, G68's X Y are the centre of the rotation, G51's the centre of the scaling,
    G51.1's the axis of the mirror image, G22's the stroke limits: the tool stays."""
    program = (
        "O2000\nG90 G00 X5. Y5. Z20.\nG68 X10. Y10. R45.\nG51 X0 Y0 P2.\nG51.1 X0\n"
        "G22 X100. Y100. Z50. I-100. J-100. K-50.\nG01 X6. F100.\nM30\n"
    )
    (tmp_path / "mill.nc").write_text(program)
    answer = trace_json(tmp_path, "mill.nc", "--controller", "0i-MF")
    rows = [(m["line"], m["code"], m["start"], m["end"]) for m in answer["motions"]]
    assert rows == [
        (2, "G00", {}, {"X": 5.0, "Y": 5.0, "Z": 20.0}),
        (7, "G01", {"X": 5.0, "Y": 5.0, "Z": 20.0}, {"X": 6.0, "Y": 5.0, "Z": 20.0}),
    ]
    assert answer["toolpath"]["moves"] == 2


# A program of 32 lines: 29 cuts of 1 mm each.
LONG = "\n".join(["O1000", "G00 X40. Z5.", *(f"G01 Z-{i}. F0.2" for i in range(1, 30)), "M30"])


def test_a_file_read_in_part_is_said_so_with_the_setting(tmp_path: Path) -> None:
    (tmp_path / "long.nc").write_text(LONG + "\n")
    text = run(tmp_path, "trace", "--max-blocks", "10", "long.nc").stdout
    assert text.splitlines()[-3:] == [
        "9 motions (G00 1, G01 8); 10 blocks executed",
        # F0.2 per revolution (a lathe's G99 at power on) with no S: counted, not timed; the
        # G00 starts where the run began, not known.
        "cycle time 0.0 s; 8 moves not timed (F or speed not known)",
        "read only up to line 10: analysed the first 10 blocks of 32: the document has 32 "
        "blocks, more than the 10 the analysis reads (setting "
        "fanuc-macro.analysis.maxBlocks, --max-blocks); the blocks from line 11 on are not "
        "checked",
    ]
    summary = trace_json(tmp_path, "--max-file-size", "100", "long.nc")["summary"]
    [part] = summary["read_in_part"]
    assert part["last_line_read"] == 7 and "--max-file-size" in part["message"]
    whole = trace_json(tmp_path, "long.nc")["summary"]
    assert (whole["read_in_part"], whole["motions"]) == ([], 30)


def test_a_called_file_read_in_part_is_named(tmp_path: Path) -> None:
    (tmp_path / "main.nc").write_text("O2000\nM98 P1000\nM30\n")
    (tmp_path / "long.nc").write_text(LONG.replace("M30", "M99") + "\n")
    result = run(tmp_path, "trace", "--max-blocks", "10", "main.nc", "--with", "long.nc")
    assert result.stdout.splitlines()[-1].startswith("long.nc: read only up to line 10: ")
    [part] = trace_json(tmp_path, "--max-blocks", "10", "main.nc", "--with", "long.nc")["summary"][
        "read_in_part"
    ]
    assert (part["path"], part["last_line_read"]) == ("long.nc", 10)


def test_a_g50_clamp_leaves_the_surface_speed_the_trace_shows(tmp_path: Path) -> None:
    """A lathe's G50 S under G96 clamps the spindle speed: the cuts after it keep the surface
    speed G96 gave."""
    (tmp_path / "css.nc").write_text(
        "O1\nG00 X60. Z2.\nG96 S180 M03\nG50 S2000\nG01 X50. F0.2\nZ-20.\nM30\n"
    )
    motions = trace_json(tmp_path, "css.nc")["motions"]
    cuts = [m for m in motions if m["code"] == "G01"]
    assert len(cuts) == 2
    assert all(m.get("surface_speed") == 180.0 and "speed" not in m for m in cuts)


def test_the_cycle_time_of_the_seed_module(tmp_path: Path) -> None:
    """O4009's 186 G92 cuts at F3 S400 (tests/test_cycle_time.py works the figures out by
    hand): 558 s of threading among 601.274 s, in the summary and at each motion."""
    seed = ROOT / "tests" / "fixtures" / "seeds" / "o4009_external_m50x3.nc"
    answer = trace_json(tmp_path, str(seed))
    timed = answer["summary"]["cycle_time"]
    parts = {"cutting": 11.409, "threading": 558.0, "rapid": 29.865, "dwell": 0.0}
    parts |= {"tool change": 2.0, "M codes": 0.0}
    assert (timed["seconds"], timed["text"], timed["parts"]) == (601.274, "10 min 1.3 s", parts)
    [run_time] = timed["runs"]
    assert (run_time["program"], run_time["line"], run_time["tool_changes"]) == ("O4009", 2, 1)
    clocks = [m["clock"] for m in answer["motions"]]
    # The first motion after the tool change (2 s); the clock never goes back.
    assert clocks[0] == 2.0 and clocks == sorted(clocks) and clocks[-1] < 601.274
    text = run(tmp_path, "trace", str(seed)).stdout.splitlines()
    assert text[-1] == (
        "cycle time 10 min 1.3 s (cutting 11.4 s, threading 9 min 18.0 s, rapid 29.9 s, "
        "tool change 2.0 s)"
    )


def test_a_dwell_takes_its_time_in_the_trace(tmp_path: Path) -> None:
    # NOT_MOVES dwells 0.5 + 1 + 0.5 s; its G01s at F0.2 per revolution with no S are not
    # timed; the G28 U0. goes to the reference point, whose place is not known.
    (tmp_path / "dwell.nc").write_text(NOT_MOVES)
    timed = trace_json(tmp_path, "dwell.nc")["summary"]["cycle_time"]
    assert (timed["parts"]["dwell"], timed["untimed_moves"]) == (2.0, 2)
