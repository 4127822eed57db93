"""Tests for the thread program generators, the module snippet and ``fanuc-macro thread``.

Test vectors: thread-math.md sections 1-3.  Every count here is taken by executing the
generated text with the evaluator; the formulas of threads.geometry only cross-check.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest

from fanuc_macro import cli
from fanuc_macro.analysis import Analysis, analyse
from fanuc_macro.cli.thread import add_thread_command
from fanuc_macro.evaluator import Motion
from fanuc_macro.generators.arc_thread_generator import build_arc_thread, generate_arc_thread
from fanuc_macro.generators.drum_groove_generator import (
    DRUM_PROFILE,
    build_drum_groove,
    generate_drum_groove,
)
from fanuc_macro.generators.generated_program import free_numbers, programs_in
from fanuc_macro.generators.thread_generator import build_module, generate_module, module_numbers
from fanuc_macro.generators.thread_snippet import module_from_document
from fanuc_macro.syntax.parser import parse_text
from fanuc_macro.threads import parse_designation, plan_from_tolerances, tolerances
from fanuc_macro.threads.identify import thread_words

ROOT = Path(__file__).resolve().parent.parent
SEEDS = ROOT / "tests" / "fixtures" / "seeds"
URI = "test:generated.nc"


def run(text: str) -> Analysis:
    analysis = analyse(text, URI)
    assert analysis.facts is not None
    assert analysis.facts.stopped is None
    return analysis


def motions(analysis: Analysis, code: str | None = None) -> list[Motion]:
    assert analysis.facts is not None
    return [m for m in analysis.facts.motions if code is None or m.code == code]


def line_of(text: str, pattern: str) -> int:
    """0-based line of the first line that starts with ``pattern``."""
    for number, line in enumerate(text.splitlines()):
        if line.startswith(pattern):
            return number
    raise AssertionError(f"no line starts with {pattern!r}")


def assert_clean(text: str) -> None:
    """What generated text must be, beyond passing the checker."""
    for line in text.splitlines():
        assert line.isascii(), line
        code = re.sub(r"\([^()]*\)", "", line)
        assert "(" not in code and ")" not in code, f"nested or unclosed comment: {line}"
        assert code == code.upper(), f"lower case outside a comment: {line}"
        for comment in re.findall(r"\(([^()]*)\)", line):
            # Upper case, but for the designation after THREAD, in the case of ISO 965-1.
            rest = re.sub(r"(?<=THREAD )M\S+", "", comment)
            assert rest == rest.upper(), line


def assert_no_diagnostics(text: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    diags = run(text).diagnostics
    assert diags == [], [(d.code, d.line + 1, d.message) for d in diags]
    path = tmp_path / "generated.nc"
    path.write_text(text, encoding="utf-8")
    capsys.readouterr()
    assert cli.main(["check", str(path)]) == 0
    assert capsys.readouterr().out == ""


# ---------------------------------------------------------------------------------------------
# Symmetric thread module (thread-math.md section 1)
# ---------------------------------------------------------------------------------------------


def test_m50x3_5g6g_external_module() -> None:
    module = build_module("M50x3-5g6g", 50)
    text = module.text
    assert text == generate_module("M50x3-5g6g", 50)
    assert module.main_number == 4009 and module.sub_number == 3331
    # Main program: the ISO values, es as a magnitude, and the call.
    for line in ("#100=50.", "#101=3.", "#102=50.", "#103=0.048", "#104=0.17", "M98 P0013331"):
        assert any(row.startswith(line + " ") for row in text.splitlines()), line
    assert "O4009 (" in text and "O3331 (" in text
    assert "#5=[0.2/3.]*SQRT[#4]" in text and "#6=[0.2/3.]*SQRT[#5]" in text
    assert "#12=8. " in text
    # Comments carry the executed values.
    for fragment in (
        "R=0.433",
        "H=1.907",
        "AP MAX=0.092",
        "AP MIN=0.020",
        "U=1.036 OF THE FIRST PASS",
        "88 ROUGH PASSES, 176 G92 CUTS",
        "186 G92 CUTS, FINAL X46.186",
        "8 SPRING PASSES AT X46.186",
    ):
        assert fragment in text, fragment
    assert module.rough_passes == 88
    assert module.g92_cuts == 186
    assert module.height == pytest.approx(1.9068, abs=1e-4)
    assert module.ap_max == pytest.approx(0.0921, abs=1e-4)
    assert module.ap_min == pytest.approx(0.0202, abs=1e-4)
    assert module.first_offset == pytest.approx(1.0361, abs=1e-4)
    assert module.final_x == pytest.approx(46.186, abs=1e-3)
    assert_clean(text)

    # Execute the final text again: the numbers in the comments are what it does.
    analysis = run(text)
    g92 = motions(analysis, "G92")
    assert len(g92) == 186
    assert g92[-1].words["X"] == pytest.approx(46.186, abs=1e-3)
    facts = analysis.facts
    assert facts is not None
    runs = facts.document(URI).runs
    assert runs[line_of(text, "N10 ")] == 88
    writes = facts.document(URI).writes
    assert writes[line_of(text, "#4=")][1].first == pytest.approx(module.height)


def test_m50x3_4h5h_internal_module() -> None:
    module = build_module("M50x3-4H5H", 50)
    text = module.text
    assert module.internal
    assert module.main_number == 4010 and module.sub_number == 3330
    assert "#103=0. " in text and "#104=0.18 " in text and "M98 P0013330 " in text
    assert "#11=#100-2.*[5./8.]*SIN[60]*#101" in text
    assert "H=1.777" in text and "83 ROUGH PASSES" in text and "176 G92 CUTS" in text
    assert "D1=46.752" in text
    assert module.rough_passes == 83
    assert module.g92_cuts == 176
    assert module.height == pytest.approx(1.7771, abs=1e-4)
    assert module.ap_max == pytest.approx(0.0889, abs=1e-4)
    assert module.first_offset == pytest.approx(0.9632, abs=1e-4)
    assert len(motions(run(text), "G92")) == 176
    assert_clean(text)


def test_m10x1_5_6g_table_values() -> None:
    text = generate_module("M10x1.5-6g", 20)
    rows = text.splitlines()
    assert any(row.startswith("#103=0.032 (ES=-0.032") for row in rows)
    assert any(row.startswith("#104=0.132 (TD2 GRADE 6") for row in rows)
    assert "#100=10. " in text and "#101=1.5 " in text


@pytest.mark.parametrize(
    ("designation", "length", "internal", "coefficient"),
    [
        ("M50x3-5g6g", 50.0, None, 0.2 / 3),
        ("M50x3-4H5H", 50.0, None, 0.2 / 3),
        ("M10x1.5-6g", 20.0, None, 0.2 / 3),
        ("M10-6H", 15.0, True, 0.2),  # all capitals, 6H or 6h: the side is said
        ("M24x2-6g", 30.0, None, 0.2),
        ("M64X6-6H", 80.0, True, 0.2 / 3),
        ("M3x0.5-6g", 8.0, None, 0.2),  # square-root rule never applies: MB701 noted
        ("M1.2x0.25-6h", 4.0, None, 0.2),  # a single rough pass
    ],
)
def test_module_matches_geometry_and_checks_clean(
    designation: str,
    length: float,
    internal: bool | None,
    coefficient: float,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    module = build_module(designation, length, internal, coefficient=coefficient)
    des = parse_designation(designation, internal=internal)
    plan = plan_from_tolerances(tolerances(des), length=length, coefficient=coefficient)
    assert module.nose_radius == pytest.approx(plan.nose_radius)
    assert module.height == pytest.approx(plan.height)
    assert module.ap_max == pytest.approx(plan.ap_max)
    assert module.ap_min == pytest.approx(plan.ap_min)
    assert module.first_offset == pytest.approx(plan.passes[0].offset)
    assert module.rough_passes == plan.rough_pass_count
    assert module.g92_cuts == plan.g92_cut_count
    assert_clean(module.text)
    assert_no_diagnostics(module.text, tmp_path, capsys)


@pytest.mark.parametrize(
    ("designation", "internal", "written", "is_internal"),
    [
        ("M50x3-5g6g", None, "M50x3-5g6g", False),
        ("M50X3-5G6G", False, "M50x3-5g6g", False),
        ("M50X3-5G6G", True, "M50x3-5G6G", True),
        ("M50X3-4H5H", None, "M50x3-4H5H", True),  # the seed paper's internal thread
        ("M10X1.5", True, "M10x1.5-6H", True),
        ("M24xPh4P2-6g-LH", None, "M24xPh4P2-6g-LH", False),
    ],
)
def test_a_generated_module_reads_back_as_written(
    designation: str, internal: bool | None, written: str, is_internal: bool
) -> None:
    text = generate_module(designation, 40, internal)
    header = text.splitlines()[1]
    assert f" THREAD {written} L=40)" in header
    # The comment alone says the thread and its side, by the case of its class.
    (form,) = [f for _w, f in thread_words(parse_text(header).blocks[0].parsed).designations]
    read = parse_designation(form)
    assert (read.canonical(), read.internal, read.internal_basis) == (written, is_internal, "case")
    # The checker takes the module's thread for that one.
    threads = analyse(text, URI).threads
    assert threads
    for thread in threads:
        assert thread.designation is not None and thread.designation.canonical() == written
        assert thread.internal is is_internal


def test_constant_branches_are_explained_only_when_needed() -> None:
    assert "IGNORE" not in generate_module("M50x3-5g6g", 50)
    # With the steel coefficient, for M3x0.5 every pass after the first adds ap(min): decided
    # for this thread, but by a depth that changes pass after pass, which the checker does
    # not call constant (MB701), so nothing needs explaining.
    steel = generate_module("M3x0.5-6g", 8, coefficient=0.2)
    assert "#5=[0.2]*SQRT[#4]" in steel and "IGNORE" not in steel
    # For M1.2x0.25 the loop runs once: its branches are constant, and said so where they are.
    tiny = generate_module("M1.2x0.25-6h", 4.0, coefficient=0.2)
    marked = [row for row in tiny.splitlines() if "IGNORE MB701" in row]
    assert [row.split(" (")[0] for row in marked] == [
        "IF[#8GE#6] THEN #9=#5*SQRT[#7]",
        "IF[#8LT#6] THEN #9=#9+#6",
        "IF[#9LT[#4-#6]] GOTO10",
    ]
    assert "ALWAYS FALSE" in marked[0] and "ALWAYS TRUE" in marked[1]


@pytest.mark.parametrize("spring", [0, 1, 2, 5])
def test_spring_passes_option(
    spring: int, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    module = build_module("M20x2.5-6g", 30, spring_passes=spring)
    assert module.g92_cuts == 2 * module.rough_passes + 2 + spring
    assert len(motions(run(module.text), "G92")) == module.g92_cuts
    assert (f"#12={spring}." in module.text) == (spring >= 2)
    assert ("N20 " in module.text) == (spring >= 1)
    assert_no_diagnostics(module.text, tmp_path, capsys)


def test_program_numbers_and_overrides() -> None:
    module = build_module(
        "M50X3-5G6G",
        50,
        internal=False,
        main_number=100,
        sub_number=1234,
        td2_override=0.2,
        deviation_override=-0.05,
    )
    text = module.text
    assert text.splitlines()[1].startswith("O0100 (MAIN - EXTERNAL THREAD M50x3-5g6g")
    assert "M98 P0011234 " in text and "\nO1234 (" in text
    assert "#103=0.05 (ES MAGNITUDE 0.05 GIVEN)" in text
    assert "#104=0.2 (TD2 0.2 GIVEN)" in text
    # Overrides make threads outside the tables possible.
    odd = build_module("M50x3.7-6g", 40, td2_override=0.2, deviation_override=0.05)
    assert odd.rough_passes > 0


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"designation": "M50x3-5q", "length": 50}, "position q is not defined"),
        ({"designation": "Tr20x4-7e", "length": 50}, "trapezoidal"),
        ({"designation": "M50x3.7-6g", "length": 50}, "3.7"),
        ({"designation": "M20x1.5-6g", "length": 20, "infeed": "zigzag"}, "infeed zigzag"),
        ({"designation": "M20x1.5-6g", "length": 20, "taper": 0.8}, "taper 0.8"),
        ({"designation": "M20x1.5-6g", "length": -1}, "length"),
        ({"designation": "M20x1.5-6g", "length": 20, "main_number": 5, "sub_number": 5}, "O0005"),
        ({"designation": "M20x1.5-6g", "length": 20, "coefficient": 0.0}, "coefficient"),
    ],
)
def test_module_bad_inputs(kwargs: dict[str, object], fragment: str) -> None:
    with pytest.raises(ValueError, match=re.escape(fragment)):
        generate_module(**kwargs)  # type: ignore[arg-type]


# ---------------------------------------------------------------------------------------------
# Arc thread by the fitting method (thread-math.md section 2)
# ---------------------------------------------------------------------------------------------


def test_arc_thread_paper_inputs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    program = build_arc_thread()
    text = program.text
    assert text == generate_arc_thread()
    analysis = run(text)
    by_program = Counter(m.program.split()[0] for m in motions(analysis, "G32"))
    assert by_program == {"O0003": 14, "O0005": 19}
    assert program.layer_cuts == (7, 7)
    assert program.finishing_cuts == 19
    # Layer 1: 51.24 and 134.82 deg in the paper (rounded intermediates); exactly 51.249 and
    # 134.847 (= 180 - ASIN[0.709]); the angles here come from the executed X/Z words.
    first, last = program.layer_angles[0]
    assert first == pytest.approx(51.24, abs=0.02)
    assert last == pytest.approx(134.82, abs=0.04)
    assert last == pytest.approx(180 - math.degrees(math.asin(0.709)), abs=0.01)
    assert program.finishing_angles[0] == pytest.approx(18.0, abs=0.01)
    assert program.finishing_angles[1] == pytest.approx(162.0, abs=0.01)
    assert "G65 P0003 A93.82 B113. C25. I10. J108. K50. D7. M3. R1.2 S300. T1. U1." in text
    assert "G54 S#19 M#13" in text  # not the paper's M#1
    assert "7 CUTS, ANGLE 51.25 TO 134.85 DEG" in text
    assert "19 CUTS, ANGLE 18.00 TO 162.00 DEG" in text
    assert_clean(text)
    assert_no_diagnostics(text, tmp_path, capsys)


def _cut_starts(analysis: Analysis, program: str) -> list[tuple[float, float]]:
    """(X, Z) where each G32 of ``program`` starts."""
    starts: list[tuple[float, float]] = []
    x = z = math.nan
    for m in motions(analysis):
        if not m.program.startswith(program):
            continue
        if m.code == "G32":
            starts.append((x, z))
        x = m.words.get("X", x)
        z = m.words.get("Z", z)
    return starts


def test_arc_thread_cuts_where_the_papers_programs_cut() -> None:
    ours = run(generate_arc_thread())
    paper_rough = run((SEEDS / "o2_arc_thread_roughing.nc").read_text(encoding="utf-8"))
    paper_finish = run((SEEDS / "o5_arc_thread_finishing.nc").read_text(encoding="utf-8"))
    rough = _cut_starts(ours, "O0003")
    expected_rough = _cut_starts(paper_rough, "O0003") + _cut_starts(paper_rough, "O0004")
    assert len(rough) == len(expected_rough) == 14
    for got, want in zip(rough, expected_rough, strict=True):
        assert got == pytest.approx(want, abs=2e-3)
    finish = _cut_starts(ours, "O0005")
    expected_finish = _cut_starts(paper_finish, "O0005")
    assert len(finish) == len(expected_finish) == 19
    for got, want in zip(finish, expected_finish, strict=True):
        # The paper starts at 18 deg exactly; ASIN[0.309] is 17.9984 deg.
        assert got == pytest.approx(want, abs=2e-3)
    ends = {m.words["Z"] for m in motions(ours, "G32")}
    assert ends == {-113.0}


def test_arc_thread_options() -> None:
    program = build_arc_thread(layers=[110.0, 106.0, 102.0], cuts_per_layer=5, finishing_cuts=10)
    assert program.layer_cuts == (5, 5, 5)
    assert program.finishing_cuts == 10
    assert len(motions(run(program.text), "G32")) == 25


@pytest.mark.parametrize(
    ("kwargs", "fragments"),
    [
        ({"layers": [130.0]}, ["roughing layer 1", "[[130-93.82]/2]/10", "1.809"]),
        ({"finishing_diameter": 70.0}, ["finishing", "[[70-93.82]/2]/10", "-1.191"]),
        ({"tool_radius": 10.0}, ["r = 10", "R = 10"]),
        ({"tool_radius": 12.0, "groove_radius": 10.0}, ["r = 12", "R = 10"]),
        ({"tool_radius": 6.0}, ["#11", "6/[10-6]", "1.5"]),
        ({"layers": []}, ["at least one"]),
        ({"cuts_per_layer": 0}, ["cuts per layer 0"]),
        ({"retract_x": 105.0}, ["retract X105", "108"]),
    ],
)
def test_arc_thread_bad_inputs(kwargs: dict[str, object], fragments: list[str]) -> None:
    with pytest.raises(ValueError) as info:
        generate_arc_thread(**kwargs)  # type: ignore[arg-type]
    for fragment in fragments:
        assert fragment in str(info.value)


# ---------------------------------------------------------------------------------------------
# Drum-shaped spiral groove (thread-math.md section 3)
# ---------------------------------------------------------------------------------------------


def _segment_line(text: str) -> int:
    return line_of(text, "G32 X[#[110+#10]")


def test_drum_groove_defaults() -> None:
    program = build_drum_groove(None, 12.0)
    text = program.text
    assert text == generate_drum_groove(None, 12.0)
    analysis = run(text)
    g32 = motions(analysis, "G32")
    segment = _segment_line(text)
    segments = [m for m in g32 if m.line == segment]
    assert len(segments) == 9 * 11  # 9 layers x 11 taper segments per pass
    assert len(g32) == 9 * 12  # plus one straight run-in per pass
    assert (program.passes, program.segments_per_pass, program.g32_cuts) == (9, 11, 108)
    # Pass k cuts through points 2..12 at depth k x 0.8 (radius).
    for k in range(9):
        chunk = segments[11 * k : 11 * (k + 1)]
        for m, (x, z) in zip(chunk, DRUM_PROFILE[1:], strict=True):
            assert m.words["X"] == pytest.approx(x - 2 * 0.8 * (k + 1), abs=1e-3)
            assert m.words["Z"] == pytest.approx(z, abs=1e-3)
            assert m.words["F"] == 12.0
    # The profile is passed in common variables #111-#122 / #131-#142.
    assert "#111=298.91 " in text and "#142=-160. " in text
    assert "G65 P0001 A12. B1. C9. D0.8 E-0.5 F12. K10. V330." in text
    assert "9 PASSES OF 11 TAPER SEGMENTS, 108 G32 BLOCKS" in text
    assert text.count("WHILE[") == 3
    assert_clean(text)


def test_drum_groove_cuts_per_layer_step_along_z() -> None:
    program = build_drum_groove(None, 12.0, cuts_per_layer=3, direction=-1)
    analysis = run(program.text)
    segment = _segment_line(program.text)
    segments = [m for m in motions(analysis, "G32") if m.line == segment]
    assert len(segments) == 9 * 3 * 11
    # Cut j of a layer is shifted j x 0.5 toward -Z (right to left, as the paper's T1).
    for j in range(3):
        first = segments[11 * j]
        assert first.words["Z"] == pytest.approx(DRUM_PROFILE[1][1] - 0.5 * j, abs=1e-3)
        assert first.words["X"] == pytest.approx(DRUM_PROFILE[1][0] - 1.6, abs=1e-3)


def test_drum_groove_check_is_clean_except_known_evaluator_bug() -> None:
    diags = run(generate_drum_groove(None, 12.0)).diagnostics
    others = [d for d in diags if not (d.code == "MB601" and "D gets 0.8" in d.message)]
    assert others == [], [(d.code, d.line + 1, d.message) for d in others]


def test_drum_groove_check_is_clean(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert_no_diagnostics(generate_drum_groove(None, 12.0), tmp_path, capsys)


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"points": [(300.0, 10.0), (301.0, 20.0), (302.0, 0.0)]}, "one direction"),
        ({"points": [(300.0, 10.0), (330.0, 0.0)]}, "steeper than 45 degrees"),
        ({"points": [(300.0, float(-i)) for i in range(20)]}, "20 profile points"),
        ({"points": None, "layers": 0}, "layers 0"),
        ({"points": None, "pitch": 0.0}, "pitch 0.0"),
        ({"points": None, "radial_step": 200.0}, "deep"),
    ],
)
def test_drum_groove_bad_inputs(kwargs: dict[str, object], fragment: str) -> None:
    kwargs.setdefault("pitch", 12.0)
    with pytest.raises(ValueError, match=re.escape(fragment)):
        generate_drum_groove(**kwargs)  # type: ignore[arg-type]


# ---------------------------------------------------------------------------------------------
# The module as a completion item
# ---------------------------------------------------------------------------------------------


def test_snippet_from_the_papers_main_programs() -> None:
    external = module_from_document((SEEDS / "o4009_external_m50x3.nc").read_text("utf-8"))
    assert external is not None
    assert "O4009 (MAIN - EXTERNAL THREAD M50x3-5g6g" in external
    assert "186 G92 CUTS" in external and "H=1.907" in external
    internal = module_from_document((SEEDS / "o4010_internal_m50x3.nc").read_text("utf-8"))
    assert internal is not None
    assert "O4010 (MAIN - INTERNAL THREAD M50x3-4H5H" in internal
    assert "176 G92 CUTS" in internal


def test_snippet_from_values_and_from_a_designation() -> None:
    values = "O0001\n#100=10.\n#101=1.5\n#102=2.*10.\n#103=0.032\n#104=0.132\nM30\n"
    module = module_from_document(values)
    assert module is not None
    assert "#102=20. " in module  # read by executing the document
    assert "#103=0.032 " in module and "#104=0.132 " in module
    assert "\nO0001 (MAIN - EXTERNAL THREAD M10x1.5 " in module  # the tables say 6g
    assert "M98 P0013331 " in module
    # A designation in a comment fills what the document does not assign.
    partial = module_from_document("O0001 (M10x1.5-6g)\n#100=10.\n#102=20.\nM30\n")
    assert partial is not None
    assert "#101=1.5 " in partial and "#103=0.032 " in partial and "#104=0.132 " in partial
    nut = module_from_document("O0002 (NUT M10X1.5-6H)\n#102=15.\nM30\n")
    assert nut is not None and "INTERNAL THREAD M10x1.5-6H" in nut and "#104=0.18 " in nut
    # All capitals, a class both kinds have, and nothing else telling the side: no module.
    assert module_from_document("O0001 (M10X1.5-6G)\n#100=10.\n#102=20.\nM30\n") is None


def test_snippet_none_without_values() -> None:
    assert module_from_document("O0001\n#1=10.\nM30\n") is None
    assert module_from_document("O0001\n#100=10.\nM30\n") is None  # no pitch, no length
    assert module_from_document("O0001 (M10X1.5-6G)\n#100=10.\nM30\n") is None  # no length


# ---------------------------------------------------------------------------------------------
# CLI
# ---------------------------------------------------------------------------------------------


def _harness(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="fanuc-macro")
    add_thread_command(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(argv)
    result: int = args.func(args)
    return result


def test_cli_thread_harness(capsys: pytest.CaptureFixture[str]) -> None:
    assert _harness(["thread", "M50x3-5g6g", "--length", "50"]) == 0
    out = capsys.readouterr().out
    assert out == generate_module("M50x3-5g6g", 50)
    assert _harness(
        ["thread", "M50X3-4H5H", "--internal", "--length", "50", "--coefficient", "steel",
         "--spring-passes", "3", "--main", "O10", "--sub", "20"]
    ) == 0  # fmt: skip
    out = capsys.readouterr().out
    assert "\nO0010 (" in out and "M98 P0010020 " in out and "#5=[0.2]*SQRT[#4]" in out
    assert "#12=3. " in out
    assert _harness(["thread", "M50x3-5g6g", "--length", "50", "--coefficient", "0.2/3"]) == 0
    assert "#5=[0.2/3.]*SQRT[#4]" in capsys.readouterr().out


def test_a_module_takes_the_numbers_its_file_does_not_have() -> None:
    seed = (SEEDS / "o4009_external_m50x3.nc").read_bytes()
    assert programs_in(seed) == {4009, 3331}
    assert programs_in("O1 (A)\nM30\n%\nO0002\nM99\n") == {1, 2}
    paper = module_numbers("M50x3-5g6g", None, frozenset())
    assert paper.numbers == (4009, 3331) and paper.note is None
    moved = module_numbers("M50x3-5g6g", None, programs_in(seed))
    assert moved.numbers == (4010, 3332)
    assert moved.note == (
        "O4009 and O3331 are in the file already: the main program is O4010 and the "
        "sub-program is O3332."
    )
    # The side from the designation, else from internal; one part moved, no two at one number.
    assert module_numbers("M20x1.5-6H", None, {3330}).numbers == (4010, 3331)
    assert module_numbers("M20X1.5-6H", True, {4010, 4011}).numbers == (4012, 3330)
    taken = free_numbers((("main program", 9999), ("macro", 9999)), {9999})
    assert taken.numbers == (9998, 9997) and taken.note is not None
    assert taken.note.startswith("O9999 and O9999 are in the file already")
    with pytest.raises(ValueError, match="every program number"):
        free_numbers((("main program", 5),), range(1, 10000))


def test_cli_thread_into_a_file_takes_free_numbers(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    target = tmp_path / "part.nc"
    target.write_bytes((SEEDS / "o4009_external_m50x3.nc").read_bytes())
    assert _harness(["thread", "M50x3-5g6g", "--length", "50", "--into", str(target)]) == 0
    captured = capsys.readouterr()
    assert captured.out == generate_module("M50x3-5g6g", 50, main_number=4010, sub_number=3332)
    assert "\nO4010 (" in captured.out and "M98 P0013332 " in captured.out
    assert captured.err == (
        "fanuc-macro thread: O4009 and O3331 are in the file already: the main program is "
        "O4010 and the sub-program is O3332.\n"
    )
    # A number the user gives is kept, or refused when the file has it.
    assert _harness(["thread", "M50x3-5g6g", "--length", "50", "--into", str(target),
                     "--sub", "3331"]) == 2  # fmt: skip
    assert capsys.readouterr().err == f"fanuc-macro thread: {target} has O3331 already\n"
    assert _harness(["thread", "M50x3-5g6g", "--length", "50", "--into", str(target),
                     "--main", "100"]) == 0  # fmt: skip
    captured = capsys.readouterr()
    assert "\nO0100 (" in captured.out and "M98 P0013332 " in captured.out
    assert captured.err == (
        "fanuc-macro thread: O3331 is in the file already: the sub-program is O3332.\n"
    )
    # A file without them: the paper's numbers, nothing said.
    empty = tmp_path / "empty.nc"
    empty.write_text("O1000\nM30\n")
    assert _harness(["thread", "M50x3-5g6g", "--length", "50", "--into", str(empty)]) == 0
    captured = capsys.readouterr()
    assert captured.out == generate_module("M50x3-5g6g", 50) and captured.err == ""
    missing = tmp_path / "missing.nc"
    assert _harness(["thread", "M50x3-5g6g", "--length", "50", "--into", str(missing)]) == 2
    assert capsys.readouterr().err.startswith(f"fanuc-macro thread: cannot read {missing}: ")


def test_cli_thread_bad_designation(capsys: pytest.CaptureFixture[str]) -> None:
    assert _harness(["thread", "M50x3-5q", "--length", "50"]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.count("\n") == 1
    assert captured.err.startswith("fanuc-macro thread: ")


def test_cli_thread_subprocess() -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "server")}
    command = [sys.executable, "-m", "fanuc_macro.cli", "thread", "M50x3-5g6g", "--length", "50"]
    done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout == generate_module("M50x3-5g6g", 50)
    bad = [sys.executable, "-m", "fanuc_macro.cli", "thread", "M50x3-5q", "--length", "50"]
    done = subprocess.run(bad, capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 2
    assert done.stdout == ""
    assert len(done.stderr.strip().splitlines()) == 1


# The command line's refusals, each a one-line message in the user's words (exit 2).
UNDECIDED_5G6G = (
    "fanuc-macro thread: M50X3-5G6G: the class 5G6G fits an external (5g6g) or an internal "
    "(5G6G) thread: say which with --external or --internal, or write the class in the "
    "standard's case: M50x3-5g6g external, M50x3-5G6G internal\n"
)
THREAD_COMMANDS: dict[tuple[str, ...], tuple[int, str]] = {
    # All capitals (as the seed paper and CNC comments write): the case may be lost.
    ("M50X3-5G6G",): (2, UNDECIDED_5G6G),
    ("M20X1.5-6H",): (2, "the class 6H fits an external (6h) or an internal (6H) thread"),
    ("M10-6G",): (2, "say which with --external or --internal"),
    ("M10x1.5",): (2, "M10x1.5 has no tolerance class, so it may be an external thread (6g)"),
    ("M50X3-5G6G", "--external"): (0, "O4009 (MAIN - EXTERNAL THREAD M50x3-5g6g L=40)"),
    ("M50X3-5G6G", "--internal"): (0, "O4010 (MAIN - INTERNAL THREAD M50x3-5G6G L=40)"),
    # A class only one kind has in ISO 965-1 decides.
    ("M50X3-4H5H",): (0, "O4010 (MAIN - INTERNAL THREAD M50x3-4H5H L=40)"),
    ("M50X3-6E",): (0, "O4009 (MAIN - EXTERNAL THREAD M50x3-6e L=40)"),
    # The standard's case decides.
    ("M50x3-5g6g",): (0, "O4009 (MAIN - EXTERNAL THREAD M50x3-5g6g L=40)"),
    ("M20x1.5-6H",): (0, "O4010 (MAIN - INTERNAL THREAD M20x1.5-6H L=40)"),
    ("M20x1.5-6H", "--internal"): (0, "O4010 (MAIN - INTERNAL THREAD M20x1.5-6H L=40)"),
    # A flag that contradicts the class.
    ("M50x3-5g6g", "--internal"): (
        2,
        "fanuc-macro thread: M50x3-5g6g is an external thread (its class 5g6g is in lower "
        "case), but --internal was given\n",
    ),
    ("M20x1.5-6H", "--external"): (2, "M20x1.5-6H is an internal thread (its class 6H is in"),
    ("M50X3-4H5H", "--external"): (
        2,
        "M50X3-4H5H is an internal thread (ISO 965-1 has no crest-diameter grade 5 for "
        "external threads), but --external was given",
    ),
    ("M50X3-6E", "--internal"): (2, "the position E only for external threads"),
}


def test_cli_thread_side_of_a_designation() -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "server")}
    started = {
        args: subprocess.Popen(
            [sys.executable, "-m", "fanuc_macro.cli", "thread", *args, "--length", "40"],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env=env,
        )
        for args in THREAD_COMMANDS
    }
    for args, process in started.items():
        out, err = process.communicate(timeout=120)
        status, expected = THREAD_COMMANDS[args]
        assert process.returncode == status, (args, err)
        if status == 0:
            assert out.splitlines()[1] == expected, args
            internal = "--internal" in args or ("--external" not in args and "INTERNAL" in expected)
            assert out == generate_module(args[0], 40, internal), args
            continue
        assert out == "", args
        assert err.count("\n") == 1 and err.startswith("fanuc-macro thread: "), err
        assert err == expected if expected.endswith("\n") else expected in err, err
        # The user's words, not Python's.
        assert not re.search(r"internal=|\bNone\b|\bTrue\b|\bFalse\b|'[^'\s]+'", err), err


def test_cli_thread_help_says_what_happens() -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "server")}
    command = [sys.executable, "-m", "fanuc_macro.cli", "thread", "--help"]
    done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 0
    text = " ".join(done.stdout.split())
    assert "needed only when the designation is all capitals" not in text
    for said in (
        "lower case external (5g6g), upper case internal (4H5H)",
        "a class only one kind has in ISO 965-1 decides (6E external, 4H5H internal)",
        "a class both kinds have (5G6G, 6H), or no class, is refused unless --external or "
        "--internal says which",
        "A flag that contradicts the class is refused",
    ):
        assert said in text, said


def test_drum_profile_fits_the_papers_crown_radius() -> None:
    from fanuc_macro.generators.drum_groove_generator import DRUM_PROFILE
    from fanuc_macro.threads.profile import fit_crown

    crown = fit_crown(DRUM_PROFILE)
    assert crown.radius == pytest.approx(3792.0, abs=0.5)  # the paper's R3792
    assert crown.max_deviation < 0.01
    bent = list(DRUM_PROFILE)
    bent[4] = (bent[4][0] + 0.5, bent[4][1])  # one point mistyped by 0.5 mm in diameter
    assert fit_crown(bent).max_deviation > 0.1
    with pytest.raises(ValueError, match="straight line"):
        fit_crown([(300.0, 0.0), (300.0, 10.0), (300.0, 20.0)])
    assert "CROWN R3792.2" in generate_drum_groove(None, 12.0)
