"""``fanuc-macro arc-thread`` and ``fanuc-macro drum-groove`` run as a user runs them, in
subprocesses.  The commands the tests need are started at once, in two rounds (the generators,
then ``check`` and ``trace`` of what they printed); a few run as ``python -m fanuc_macro.cli``
each, the many others in one process that calls the command line's ``main`` for each, so that
the module takes a few seconds."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

import pytest

from cli_runner import run as run_cli
from fanuc_macro.analysis import analyse

ROOT = Path(__file__).resolve().parents[1]

CSV_POINTS = "X diameter;Z\n100;50\n102;25\n103;0\n102;-25\n100;-50\n"
CSV_TAB = "X\tZ\n100\t50\n102\t25\n103\t0\n"
CSV_BAD_ROW = "X,Z\n100,50\n102,25\n103;zero\n102,-25\n"

# The programs printed: name -> arguments.  Each is checked and its cuts counted.
PROGRAMS: dict[str, tuple[str, ...]] = {
    "arc": ("arc-thread",),
    "arc_3_layers": ("arc-thread", "--layers", "108,104,101", "--cuts-per-layer", "5"),
    "arc_lead": (
        "arc-thread",
        "--lead",
        "30",
        "--spindle",
        "M4",
        "--main",
        "O0100",
        "--rough",
        "101",
        "--finishing",
        "o102",
        "--finishing-tool-radius",
        "0.8",
    ),
    "arc_small": (
        "arc-thread",
        "--outer-diameter",
        "60",
        "--groove-radius",
        "5",
        "--tool-radius",
        "1",
        "--layers",
        "66,63",
        "--finishing-diameter",
        "62",
        "--retract-x",
        "80",
        "--start-x",
        "90",
        "--length",
        "80",
        "--run-in",
        "20",
        "--pitch",
        "12",
    ),
    "drum": ("drum-groove", "--pitch", "12"),
    "drum_csv": ("drum-groove", "--pitch", "8", "--points-file", "points.csv", "--main", "20"),
    "drum_tab": ("drum-groove", "--pitch", "8", "--points-file", "tab.csv"),
    "drum_right": (
        "drum-groove",
        "--pitch",
        "10",
        "--layers",
        "4",
        "--cuts-per-layer",
        "3",
        "--direction",
        "right",
        "--points",
        "298.91,205;302.104,173;304.83,140",
    ),
}

TRACED = ("arc", "drum")
# Run each in a process of its own, the rest in one: the papers' parts, a refusal of the
# generator and one of argparse.
ALONE: tuple[object, ...] = (
    "arc",
    "drum",
    ("refuse", "arc-thread", "--tool-radius", "10"),
    ("usage", "drum-groove"),
)

# Refusals: arguments -> what the one line on standard error must contain.
REFUSALS: dict[tuple[str, ...], tuple[str, ...]] = {
    ("arc-thread", "--tool-radius", "10"): ("tool nose radius r = 10", "groove radius R = 10"),
    ("arc-thread", "--finishing-tool-radius", "11"): ("finishing tool nose radius r = 11",),
    ("arc-thread", "--layers", "130"): ("roughing layer 1 J130", "ASIN", "1.809"),
    ("arc-thread", "--layers", "108,98"): ("roughing layer 2 J98", "finishing", "J100"),
    ("arc-thread", "--layers", "113.82"): ("roughing layer 1 J113.82", "cuts nothing"),
    ("arc-thread", "--layers", "103,108"): ("roughing layer 2 J108", "J103", "cuts nothing"),
    ("arc-thread", "--finishing-diameter", "90"): ("J90", "outer diameter 93.82"),
    (
        "arc-thread",
        "--outer-diameter",
        "10",
        "--finishing-diameter",
        "12",
        "--layers",
        "14",
        "--retract-x",
        "20",
        "--start-x",
        "30",
    ): ("J12", "R10", "J-2R = -8"),
    ("arc-thread", "--main", "3"): ("O0003", "three different numbers"),
    ("arc-thread", "--rough-tool", "100"): ("roughing tool T100",),
    ("drum-groove", "--pitch", "0"): ("pitch 0.0",),
    # A value the program's four decimals would change is not rounded behind the user's back.
    ("drum-groove", "--pitch", "0.00001"): ("pitch 1e-05", "4 decimals", "enter 0."),
    ("arc-thread", "--pitch", "25.00004"): ("pitch 25.00004", "4 decimals", "enter 25."),
    ("arc-thread", "--layers", "108,103.00001"): ("roughing layer 2 J 103.00001",),
    ("drum-groove", "--pitch", "12", "--points", "300,10;abc"): ("--points point 2", "'abc'"),
    ("drum-groove", "--pitch", "12", "--points-file", "bad.csv"): (
        "--points-file bad.csv row 4",
        "'103;zero'",
    ),
    ("drum-groove", "--pitch", "12", "--radial-step", "200"): ("200", "deep"),
}

# Usage problems argparse reports itself (several lines, exit 2).
USAGE: dict[tuple[str, ...], str] = {
    ("drum-groove",): "--pitch",
    ("arc-thread", "--pitch", "25", "--lead", "30"): "--lead",
    ("arc-thread", "--spindle", "M5"): "'M5'",
}


@dataclass(frozen=True)
class Done:
    returncode: int
    stdout: str
    stderr: str


def _start(cwd: Path, args: tuple[str, ...], module: bool = True) -> subprocess.Popen[str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "server")
    return subprocess.Popen(
        [sys.executable, *(("-m", "fanuc_macro.cli") if module else ()), *args],
        cwd=cwd,
        env=env,
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        encoding="utf-8",
    )


# One interpreter that runs the command line's main() on each argv it is given, standard
# output and error captured apart: the commands beyond those each run in a process of its own.
BATCH = """
import contextlib, io, json, sys
from fanuc_macro.cli import main
results = []
for argv in json.load(sys.stdin):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(argv)
    results.append([status, out.getvalue(), err.getvalue()])
json.dump(results, sys.stdout)
"""


def run_all(
    cwd: Path,
    commands: Mapping[object, tuple[str, ...]],
    alone: tuple[object, ...] = (),
) -> dict[object, Done]:
    """Run the commands side by side, those in ``alone`` each as ``python -m
    fanuc_macro.cli``, the others in one batch process; their results by key."""
    started = {key: _start(cwd, commands[key]) for key in alone}
    batched = [key for key in commands if key not in started]
    done: dict[object, Done] = {}
    if batched:
        batch = _start(cwd, ("-c", BATCH), module=False)
        batch_out, batch_err = batch.communicate(
            json.dumps([commands[key] for key in batched]), timeout=120
        )
        assert batch.returncode == 0, batch_err
        for key, (status, out, err) in zip(batched, json.loads(batch_out), strict=True):
            done[key] = Done(status, out, err)
    for key, process in started.items():
        out, err = process.communicate(timeout=120)
        done[key] = Done(process.returncode, out, err)
    return done


@dataclass(frozen=True)
class Runs:
    folder: Path
    generated: dict[object, Done]
    checked: Done
    traces: dict[object, Done]


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Runs]:
    folder = tmp_path_factory.mktemp("generators")
    (folder / "points.csv").write_text(CSV_POINTS, encoding="utf-8")
    (folder / "tab.csv").write_text(CSV_TAB, encoding="utf-8")
    (folder / "bad.csv").write_text(CSV_BAD_ROW, encoding="utf-8")
    commands: dict[object, tuple[str, ...]] = dict(PROGRAMS)
    commands.update({("refuse", *args): args for args in REFUSALS})
    commands.update({("usage", *args): args for args in USAGE})
    generated = run_all(folder, commands, ALONE)
    files = []
    for name in PROGRAMS:
        result = generated[name]
        assert result.returncode == 0, (name, result.stderr)
        path = folder / f"{name}.nc"
        path.write_text(result.stdout, encoding="utf-8")
        files.append(path.name)
    second: dict[object, tuple[str, ...]] = {"check": ("check", "--quiet", *files)}
    # The papers' parts through trace; the others' cuts are counted by the evaluator here.
    second.update({name: ("trace", f"{name}.nc", "--format", "json") for name in TRACED})
    finished = run_all(folder, second, tuple(second))
    checked = finished.pop("check")
    yield Runs(folder, generated, checked, finished)


def g32_cuts(runs: Runs, name: str) -> list[dict[str, object]]:
    """Each G32 executed: its program and words, from trace's JSON or from the evaluator."""
    if name in TRACED:
        traced = runs.traces[name]
        assert traced.returncode == 0, traced.stderr
        motions: list[dict[str, object]] = json.loads(traced.stdout)["motions"]
        return [m for m in motions if m["code"] == "G32"]
    facts = analyse(runs.generated[name].stdout, f"file:///{name}.nc").facts
    assert facts is not None and facts.stopped is None
    return [{"program": m.program, "words": m.words} for m in facts.motions if m.code == "G32"]


def by_program(cuts: list[dict[str, object]]) -> dict[str, int]:
    counts: dict[str, int] = {}
    for m in cuts:
        name = str(m["program"]).split()[0]
        counts[name] = counts.get(name, 0) + 1
    return counts


def test_every_generated_program_checks_clean(runs: Runs) -> None:
    assert runs.checked.stdout == "" and runs.checked.stderr == ""
    assert runs.checked.returncode == 0


def test_the_arc_thread_papers_part_has_33_cuts(runs: Runs) -> None:
    text = runs.generated["arc"].stdout
    assert text.startswith("%\nO0002 ")
    assert runs.generated["arc"].stderr == ""
    cuts = g32_cuts(runs, "arc")
    assert len(cuts) == 33
    assert by_program(cuts) == {"O0003": 14, "O0005": 19}
    assert {m["words"]["F"] for m in cuts} == {25.0}  # type: ignore[index]
    assert text.count("G65 P0003 ") == 2 and text.count("G65 P0005 ") == 1
    assert "J108: 7 CUTS, ANGLE 51.25 TO 134.85 DEG" in text


def test_arc_thread_options_change_the_program(runs: Runs) -> None:
    three = runs.generated["arc_3_layers"].stdout
    assert three.count("G65 P0003 ") == 3
    assert [int(c) for c in re.findall(r"G65 P0003 .* J(\d+)\.", three)] == [108, 104, 101]
    assert by_program(g32_cuts(runs, "arc_3_layers")) == {"O0003": 15, "O0005": 19}

    lead = runs.generated["arc_lead"].stdout
    assert lead.startswith("%\nO0100 ") and "\nO0101 " in lead and "\nO0102 " in lead
    assert " C30. " in lead and " M4. " in lead
    assert "G65 P0102 " in lead and " R0.8 " in lead.split("G65 P0102 ")[1].split("\n")[0]
    cuts = g32_cuts(runs, "arc_lead")
    assert {m["words"]["F"] for m in cuts} == {30.0}  # type: ignore[index]
    assert len(cuts) == 33

    small = g32_cuts(runs, "arc_small")
    assert {m["words"]["Z"] for m in small} == {-80.0}  # type: ignore[index]
    assert {m["words"]["F"] for m in small} == {12.0}  # type: ignore[index]


def test_the_drum_groove_papers_profile_has_108_cuts(runs: Runs) -> None:
    done = runs.generated["drum"]
    assert len(g32_cuts(runs, "drum")) == 108
    assert "9 PASSES OF 11 TAPER SEGMENTS, 108 G32 BLOCKS" in done.stdout
    # The fit of the paper's 12 points: R3792.2, the paper's R3792.
    assert "(CROWN R3792.2 " in done.stdout
    assert "crown: R3792.2 mm" in done.stderr
    # 9 passes of 15 blocks (3 rapids and 12 G32, the paper's count) and the two rapids of the
    # main program, against the generated text's 53 blocks.
    assert (
        "this program 53; the same cut written out without a macro 142 "
        "(137 motions + 5 set-up): 89 saved" in done.stderr
    )
    assert "THIS PROGRAM: 53 BLOCKS; WRITTEN OUT WITHOUT A MACRO: 137 MOTION" in done.stdout


def test_drum_groove_points_from_a_file_and_options(runs: Runs) -> None:
    csv = runs.generated["drum_csv"]
    assert csv.stdout.startswith("%\nO0020 ")
    assert "#111=100. " in csv.stdout and "#135=-50. " in csv.stdout
    cuts = g32_cuts(runs, "drum_csv")
    assert len(cuts) == 9 * 5  # 9 passes of a run-in and 4 segments
    assert {m["words"]["F"] for m in cuts if "F" in m["words"]} == {8.0}  # type: ignore[operator]
    assert "of the 5 points" in csv.stderr

    tab = runs.generated["drum_tab"]
    assert "#113=103. " in tab.stdout and len(g32_cuts(runs, "drum_tab")) == 9 * 3

    right = runs.generated["drum_right"]
    assert " E0.5 " in right.stdout  # each cut of a layer one axial step toward +Z
    assert len(g32_cuts(runs, "drum_right")) == 4 * 3 * 3
    assert "crown:" in right.stderr


@pytest.mark.parametrize("args", list(REFUSALS), ids=lambda a: " ".join(a))
def test_refusals_exit_2_with_one_line_naming_the_value(runs: Runs, args: tuple[str, ...]) -> None:
    done = runs.generated[("refuse", *args)]
    assert done.returncode == 2
    assert done.stdout == ""
    lines = done.stderr.splitlines()
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith(f"fanuc-macro {args[0]}: ")
    for fragment in REFUSALS[args]:
        assert fragment in lines[0]


@pytest.mark.parametrize("args", list(USAGE), ids=lambda a: " ".join(a))
def test_usage_problems_exit_2(runs: Runs, args: tuple[str, ...]) -> None:
    done = runs.generated[("usage", *args)]
    assert done.returncode == 2 and done.stdout == ""
    assert USAGE[args] in done.stderr


def test_into_a_file_the_programs_take_the_numbers_it_does_not_have(tmp_path: Path) -> None:
    part = tmp_path / "part.nc"
    part.write_text("O0002\nM30\n%\nO0003\nM99\n%\nO0010\nM30\n", encoding="utf-8")
    arc = run_cli(tmp_path, "arc-thread", "--into", str(part))
    assert arc.returncode == 0, arc.stderr
    assert arc.stdout.startswith("%\nO0004 (") and "G65 P0006 " in arc.stdout
    assert "\nO0006 (" in arc.stdout and "\nO0005 (" in arc.stdout
    assert arc.stderr == (
        "fanuc-macro arc-thread: O0002 and O0003 are in the file already: the main program is "
        "O0004 and the roughing macro is O0006.\n"
    )
    drum = run_cli(tmp_path, "drum-groove", "--pitch", "40", "--into", str(part))
    assert drum.returncode == 0, drum.stderr
    assert "\nO0011 (" in drum.stdout and "G65 P0001 " in drum.stdout
    assert drum.stderr.startswith(
        "fanuc-macro drum-groove: O0010 is in the file already: the main program is O0011.\n"
    )
    refused = run_cli(tmp_path, "arc-thread", "--into", str(part), "--rough", "3")
    assert refused.returncode == 2
    assert refused.stderr == "fanuc-macro arc-thread: the file has O0003 already\n"
    # Without --into, the paper's numbers, whatever a file has.
    assert run_cli(tmp_path, "arc-thread").stdout.startswith("%\nO0002 (")
