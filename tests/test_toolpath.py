"""The toolpath the evaluator records on request: positions, arcs, canned cycles expanded into
the control's moves, and where the path lost track. The numbers are worked out by hand in the
comments (FANUC 0i-TF / 0i-MF operator's manuals), or the seed papers' (thread-math.md)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fanuc_macro.config import Config
from fanuc_macro.evaluator import Facts, evaluate
from fanuc_macro.evaluator.run import tracks_positions
from fanuc_macro.evaluator.toolpath import Move, Toolpath
from fanuc_macro.evaluator.values import Unknown
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import parse_text
from view_payload import unpacked

ROOT = Path(__file__).resolve().parents[1]
SEEDS = ROOT / "tests" / "fixtures" / "seeds"
VARIANTS = ROOT / "tests" / "fixtures" / "thread_variants"
LATHE = Config()
MILL = Config(controller="0i-MF")


def evaluated(text: str, config: Config = LATHE, uri: str = "t.nc") -> Facts:
    doc = parse_text(text, uri)
    return evaluate([(uri, doc, build_index(doc))], config, toolpath=True)


def path_of(text: str, config: Config = LATHE) -> Toolpath:
    path = evaluated(text, config).toolpath
    assert path is not None
    return path


def program(*blocks: str) -> str:
    return "%\nO1000\n" + "\n".join(blocks) + "\nM30\n%\n"


def line_of(text: str, block: str) -> int:
    """The 0-based line of ``block`` in ``text``."""
    return text.splitlines().index(block)


def ends(path: Toolpath, line: int) -> list[tuple[str, dict[str, float]]]:
    return [(m.kind, m.end) for m in path.moves if m.line == line]


def seed_path(name: str, folder: Path = SEEDS) -> tuple[Facts, Toolpath]:
    file = folder / name
    facts = evaluated(file.read_text("utf-8"), uri=str(file))
    assert facts.toolpath is not None
    return facts, facts.toolpath


# ---- off by default ------------------------------------------------------------------------


def test_no_toolpath_unless_asked() -> None:
    text = program("G00 X10. Z5.", "G01 Z-5. F0.2")
    doc = parse_text(text, "t.nc")
    plain = evaluate([("t.nc", doc, build_index(doc))])
    assert plain.toolpath is None
    with_path = evaluated(text)
    assert with_path.toolpath is not None and len(with_path.toolpath.moves) == 2
    # The motion records are the same either way.
    assert [(m.line, m.code, m.words, m.x, m.z) for m in plain.motions] == [
        (m.line, m.code, m.words, m.x, m.z) for m in with_path.motions
    ]


# ---- the seeds' numbers ----------------------------------------------------------------------


def test_first_g92_of_o3331_from_its_start_point_and_back() -> None:
    facts, path = seed_path("o4009_external_m50x3.nc")
    first = next(i for i, m in enumerate(facts.motions) if m.code == "G92")
    moves = [m for m in path.moves if m.motion == first]
    assert [(m.kind, m.start, m.end) for m in moves] == [
        ("rapid", {"X": 51.0, "Z": 5.964}, {"X": 49.816, "Z": 5.964}),
        ("thread", {"X": 49.816, "Z": 5.964}, {"X": 49.816, "Z": -54.036}),
        ("rapid", {"X": 49.816, "Z": -54.036}, {"X": 51.0, "Z": -54.036}),
        ("rapid", {"X": 51.0, "Z": -54.036}, {"X": 51.0, "Z": 5.964}),
    ]
    assert all(m.cycle == "G92" and m.program == "O3331" for m in moves)
    # Every one of the 186 G92 cuts is four moves, the modal repeat "X[#100-2.*#4]" too.
    cuts = [m for m in path.moves if m.cycle == "G92"]
    assert len(cuts) == 4 * 186 and sum(m.kind == "thread" for m in cuts) == 186


def test_arc_thread_first_layer_cuts() -> None:
    _, path = seed_path("o2_arc_thread_roughing.nc")
    threads = [m for m in path.moves if m.kind == "thread" and m.program == "O0003"]
    xs = [m.start["X"] for m in threads]
    assert len(xs) == 7
    assert xs[0] == 94.274 and xs[-1] == 95.522
    assert all(m.end == {"X": m.start["X"], "Z": -113.0} for m in threads)


def test_o5_finishing_cuts_start_at_their_diameters() -> None:
    _, path = seed_path("o5_arc_thread_finishing.nc")
    threads = [m for m in path.moves if m.kind == "thread"]
    assert len(threads) == 19
    assert threads[0].start == {"X": 94.561, "Z": 58.369}  # 100 - 17.6 sin 18°, 50 + 8.8 cos 18°
    for n, move in enumerate(threads):
        angle = math.radians(18 + 8 * n)
        assert move.start["X"] == pytest.approx(100 - 17.6 * math.sin(angle), abs=0.0011)
        assert move.start["Z"] == pytest.approx(50 + 8.8 * math.cos(angle), abs=0.0011)


def test_g76_passes_with_their_retract_and_return() -> None:
    facts, path = seed_path("g76_clean.nc", VARIANTS)
    passes = [i for i, m in enumerate(facts.motions) if m.code == "G76"]
    assert len(passes) == 11
    for i in passes:
        moves = [m for m in path.moves if m.motion == i]
        x = round(facts.motions[i].x or math.nan, 3)
        assert [(m.kind, m.end) for m in moves] == [
            ("rapid", {"X": x, "Z": 5.0}),
            ("thread", {"X": x, "Z": -30.0}),
            ("rapid", {"X": 32.0, "Z": -30.0}),
            ("rapid", {"X": 32.0, "Z": 5.0}),
        ]
    assert [m.motion for m in path.moves if m.cycle == "G76"] == [i for i in passes for _ in "abcd"]


# ---- lathe -----------------------------------------------------------------------------------


def test_lathe_absolute_and_incremental() -> None:
    text = program("G00 X100. Z10.", "G01 U-20. W-5. F0.2", "X60.", "W-10.")
    path = path_of(text)
    assert [m.end for m in path.moves] == [
        {"X": 100.0, "Z": 10.0},
        {"X": 80.0, "Z": 5.0},
        {"X": 60.0, "Z": 5.0},
        {"X": 60.0, "Z": -5.0},
    ]
    assert [m.kind for m in path.moves] == ["rapid", "feed", "feed", "feed"]
    assert path.moves[1].start is path.moves[0].end  # moves share their positions
    assert all(m.plane == "XZ" for m in path.moves)


def test_lathe_arc_with_r_of_both_signs() -> None:
    # In radius: from (Z0, X10) to (Z-10, X20), R10: the centre is (Z0, X20) for a G02 of 90°
    # and (Z-10, X10) past 180°; X in the move is the diameter.
    for radius, centre in (("R10.", {"X": 40.0, "Z": 0.0}), ("R-10.", {"X": 20.0, "Z": -10.0})):
        text = program("G00 X20. Z0.", f"G02 X40. Z-10. {radius} F0.1")
        arc = path_of(text).moves[-1]
        assert (arc.kind, arc.start, arc.end) == (
            "arc",
            {"X": 20.0, "Z": 0.0},
            {"X": 40.0, "Z": -10.0},
        )
        assert arc.centre == centre and arc.clockwise is True


def test_lathe_arc_with_i_k_radius_i() -> None:
    # I is a radius: centre X = 20 + 2*5 = 30 (diameter), Z = 0 + K.
    text = program("G00 X20. Z0.", "G03 X30. Z-5. I5. K-5. F0.1")
    arc = path_of(text).moves[-1]
    assert arc.centre == {"X": 30.0, "Z": -5.0} and arc.clockwise is False


def test_g90_taper_and_its_modal_repeat() -> None:
    # G90 from A (X50 Z2): rapid to X40+2R = 36, cut to (40, -20), out to X50, back to Z2;
    # the next block changes X only: Z-20 and R-2 stay in force.
    text = program("G00 X50. Z2.", "G90 X40. Z-20. R-2. F0.2", "X35.", "G00 X100.")
    path = path_of(text)
    lines = text.splitlines()
    assert ends(path, lines.index("G90 X40. Z-20. R-2. F0.2")) == [
        ("rapid", {"X": 36.0, "Z": 2.0}),
        ("feed", {"X": 40.0, "Z": -20.0}),
        ("feed", {"X": 50.0, "Z": -20.0}),
        ("rapid", {"X": 50.0, "Z": 2.0}),
    ]
    assert ends(path, lines.index("X35.")) == [
        ("rapid", {"X": 31.0, "Z": 2.0}),
        ("feed", {"X": 35.0, "Z": -20.0}),
        ("feed", {"X": 50.0, "Z": -20.0}),
        ("rapid", {"X": 50.0, "Z": 2.0}),
    ]
    # G00 ends the cycle: X100 is a rapid.
    assert ends(path, lines.index("G00 X100.")) == [("rapid", {"X": 100.0, "Z": 2.0})]


def test_g94_facing_with_taper() -> None:
    # G94 from A (X60 Z5): rapid in Z to Z-2+R = -3, face to (20, -2), back to Z5, out to X60.
    text = program("G00 X60. Z5.", "G94 X20. Z-2. R-1. F0.2", "Z-4.")
    path = path_of(text)
    assert ends(path, line_of(text, "G94 X20. Z-2. R-1. F0.2")) == [
        ("rapid", {"X": 60.0, "Z": -3.0}),
        ("feed", {"X": 20.0, "Z": -2.0}),
        ("feed", {"X": 20.0, "Z": 5.0}),
        ("rapid", {"X": 60.0, "Z": 5.0}),
    ]
    assert ends(path, line_of(text, "Z-4.")) == [
        ("rapid", {"X": 60.0, "Z": -5.0}),
        ("feed", {"X": 20.0, "Z": -4.0}),
        ("feed", {"X": 20.0, "Z": 5.0}),
        ("rapid", {"X": 60.0, "Z": 5.0}),
    ]


def test_g92_with_incremental_end_and_taper() -> None:
    # U-4 from X30: the thread ends at X26; R-1: it starts at X24 (26 + 2R).
    text = program("G00 X30. Z3.", "G92 U-4. W-23. R-1. F1.5")
    path = path_of(text)
    assert ends(path, line_of(text, "G92 U-4. W-23. R-1. F1.5")) == [
        ("rapid", {"X": 24.0, "Z": 3.0}),
        ("thread", {"X": 26.0, "Z": -20.0}),
        ("rapid", {"X": 30.0, "Z": -20.0}),
        ("rapid", {"X": 30.0, "Z": 3.0}),
    ]


# ---- G70-G73: the lathe's cycles that cut to a profile ---------------------------------------

G71_STEPS = (
    "G00 X50. Z2.",
    "G71 U2. R0.5",
    "G71 P10 Q20 U0.4 W0.1 F0.25",
    "N10 G00 X20.",
    "G01 Z-10.",
    "X40.",
    "N20 Z-30.",
)


def cycle_moves(path: Toolpath, line: int) -> list[tuple[str, float, float]]:
    return [(m.kind, m.end["X"], m.end["Z"]) for m in path.moves if m.line == line]


def test_g71_layers_escape_and_semi_finish_of_a_two_step_profile() -> None:
    text = program(*G71_STEPS, "M30")
    path = path_of(text)
    moves = cycle_moves(path, line_of(text, "G71 P10 Q20 U0.4 W0.1 F0.25"))
    # The profile moved by the allowance (Δu/2 = 0.2 in radius, +0.4 in X; Δw = +0.1 in Z):
    # X20.4 from Z2.1 to Z-9.9, the shoulder to X40.4, X40.4 to Z-29.9. Layers Δd = 2 deep
    # (a radius: 4 in X) from A's X50: X46, 42, 38, 34, 30, 26, 22; X18 would pass the
    # profile's X20.4, which the semi-finishing pass reaches. X46 and X42 lie above the
    # profile's largest X40.4: cut to its end, Z-29.9; the others to the shoulder, Z-9.9.
    # Each layer: in at rapid (N10 is G00), cut, escape e = 0.5 at 45° (X +1, Z +0.5), back
    # to A's Z2 at rapid.
    expected: list[tuple[str, float, float]] = []
    for x, z in ((46, -29.9), (42, -29.9), (38, -9.9), (34, -9.9), (30, -9.9), (26, -9.9)):
        expected += [("rapid", x, 2.0), ("feed", x, z), ("rapid", x + 1, z + 0.5)]
        expected += [("rapid", x + 1, 2.0)]
    expected += [("rapid", 22.0, 2.0), ("feed", 22.0, -9.9), ("rapid", 23.0, -9.4)]
    expected += [("rapid", 23.0, 2.0)]
    # Rough cutting as finishing along the moved profile, then back to A.
    expected += [("rapid", 20.4, 2.1), ("feed", 20.4, -9.9), ("feed", 40.4, -9.9)]
    expected += [("feed", 40.4, -29.9), ("rapid", 50.0, 2.0)]
    assert moves == expected
    assert len([m for m in moves if m[0] == "feed"]) == 7 + 3  # seven layers, three stretches
    # The profile is read, not run: no motion of its blocks, and the run goes on after N20.
    facts = evaluated(text)
    assert [m.code for m in facts.motions] == ["G00", "G71", "G71"]
    runs = facts.document("t.nc").runs
    assert all(runs.get(line_of(text, b)) == 1 for b in G71_STEPS[3:])


def test_g70_runs_the_profile_and_returns_to_its_start() -> None:
    text = program(*G71_STEPS, "G70 P10 Q20", "G00 X100.")
    facts = evaluated(text)
    path = facts.toolpath
    assert path is not None
    g70 = line_of(text, "G70 P10 Q20")
    finishing = [(m.line, m.kind, m.end) for m in path.moves if m.cycle == "G70"]
    assert finishing == [
        (line_of(text, "N10 G00 X20."), "rapid", {"X": 20.0, "Z": 2.0}),
        (line_of(text, "G01 Z-10."), "feed", {"X": 20.0, "Z": -10.0}),
        (line_of(text, "X40."), "feed", {"X": 40.0, "Z": -10.0}),
        (line_of(text, "N20 Z-30."), "feed", {"X": 40.0, "Z": -30.0}),
        (g70, "rapid", {"X": 50.0, "Z": 2.0}),  # back to the start point
    ]
    # The evaluator ran the profile's blocks after the G70 (their motions follow its record),
    # then the block after the G70, from the start point.
    codes = [(m.line, m.code) for m in facts.motions]
    assert codes[3:] == [
        (g70, "G70"),
        (line_of(text, "N10 G00 X20."), "G00"),
        (line_of(text, "G01 Z-10."), "G01"),
        (line_of(text, "X40."), "G01"),
        (line_of(text, "N20 Z-30."), "G01"),
        (line_of(text, "G00 X100."), "G00"),
    ]
    last = facts.motions[-1]
    assert (last.start_x, last.start_z) == (50.0, 2.0)
    assert ends(path, line_of(text, "G00 X100.")) == [("rapid", {"X": 100.0, "Z": 2.0})]
    runs = facts.document("t.nc").runs
    assert runs[line_of(text, "X40.")] == 2  # read by the G71, run by the G70
    continuous(path)


def test_g72_layers_in_z() -> None:
    text = program(
        "G00 X52. Z2.",
        "G72 W2. R0.5",
        "G72 P10 Q20 U0.4 W0.2 F0.2",
        "N10 G00 Z-6.",
        "G01 X30.",
        "Z0.",
        "N20 X10.",
        "M30",
    )
    moves = cycle_moves(path_of(text), line_of(text, "G72 P10 Q20 U0.4 W0.2 F0.2"))
    # The moved profile: Z-5.8 from X52.4 to X30.4, up to Z0.2, to X10.4. Layers 2 deep in
    # Z from Z2: Z0, -2, -4 (Z-6 would pass Z-5.8); each cut along X to the shoulder X30.4,
    # escape 0.5 at 45° (Z +0.5, X +1), back to A's X52.
    expected: list[tuple[str, float, float]] = []
    for z in (0.0, -2.0, -4.0):
        expected += [("rapid", 52.0, z), ("feed", 30.4, z), ("rapid", 31.4, z + 0.5)]
        expected += [("rapid", 52.0, z + 0.5)]
    expected += [("rapid", 52.4, -5.8), ("feed", 30.4, -5.8), ("feed", 30.4, 0.2)]
    expected += [("feed", 10.4, 0.2), ("rapid", 52.0, 2.0)]
    assert moves == expected


def test_g73_repeats_the_profile_moved_less_each_time() -> None:
    text = program(
        "G00 X60. Z5.",
        "G73 U3. W1. R3",
        "G73 P10 Q20 U0.4 W0.1 F0.2",
        "N10 G00 X20. Z2.",
        "G01 Z-10.",
        "N20 X40. Z-20.",
        "M30",
    )
    moves = cycle_moves(path_of(text), line_of(text, "G73 P10 Q20 U0.4 W0.1 F0.2"))
    # d = 3 passes, moved by Δi·(d-k)/(d-1) + Δu/2 in radius and Δk·(d-k)/(d-1) + Δw in Z:
    # (3.2, 1.1), (1.7, 0.6), (0.2, 0.1); each from A (X60 Z5) and back to it.
    expected: list[tuple[str, float, float]] = []
    for dx, dz in ((6.4, 1.1), (3.4, 0.6), (0.4, 0.1)):
        expected += [("rapid", 20.0 + dx, round(2.0 + dz, 3))]
        expected += [("feed", 20.0 + dx, round(-10.0 + dz, 3))]
        expected += [("feed", 40.0 + dx, round(-20.0 + dz, 3)), ("rapid", 60.0, 5.0)]
    assert moves == expected


def test_g71_with_an_arc_in_its_profile_cuts_to_the_arc() -> None:
    text = program(
        "G00 X40. Z2.",
        "G71 U2. R0.5",
        "G71 P10 Q20 U0. W0. F0.2",
        "N10 G00 X20.",
        "G01 Z-10.",
        "N20 G02 X40. Z-20. R10.",
        "M30",
    )
    moves = cycle_moves(path_of(text), line_of(text, "G71 P10 Q20 U0. W0. F0.2"))
    # The arc: centre Z-10 X40 (radius 10 in radius terms, from r10 to r20). The layer at X36
    # (r18) meets it where (z+10)^2 + (18-20)^2 = 100 on the arc's side z < -10: z = -10 -
    # sqrt(96).
    cuts = [(x, z) for kind, x, z in moves if kind == "feed"]
    assert cuts[0] == (36.0, round(-10.0 - math.sqrt(96.0), 3))
    assert [x for x, _ in cuts[:4]] == [36.0, 32.0, 28.0, 24.0]
    arc = [m for m in path_of(text).moves if m.kind == "arc" and m.cycle == "G71"]
    assert len(arc) == 1 and arc[0].centre == {"X": 40.0, "Z": -10.0}


def test_g71_type_ii_profile_is_a_note() -> None:
    text = program(
        "G00 X50. Z2.",
        "G71 U2. R0.5",
        "G71 P10 Q20 U0.4 W0.1 F0.25",
        "N10 G00 X20. Z2.",
        "N20 G01 Z-10.",
        "M30",
    )
    path = path_of(text)
    line = line_of(text, "G71 P10 Q20 U0.4 W0.1 F0.25")
    notes = [lt.reason for lt in path.lost if lt.line == line]
    assert len(notes) == 1 and "type II profile not drawn" in notes[0]
    assert not [m for m in path.moves if m.line == line]


def test_g71_whose_profile_label_is_missing_is_a_note() -> None:
    text = program(
        "G00 X50. Z2.",
        "G71 U2. R0.5",
        "G71 P10 Q30 U0.4 W0.1 F0.25",
        "N10 G00 X20.",
        "N20 G01 Z-10.",
        "G70 P10 Q40",
        "M30",
    )
    facts = evaluated(text)
    path = facts.toolpath
    assert path is not None
    g71 = line_of(text, "G71 P10 Q30 U0.4 W0.1 F0.25")
    notes = [lt.reason for lt in path.lost if lt.line == g71]
    assert notes == ["G71: no N30 (its Q) after N10 in O1000: its passes are not drawn"]
    g70 = [lt.reason for lt in path.lost if lt.line == line_of(text, "G70 P10 Q40")]
    assert g70 == ["G70: no N40 (its Q) after N10 in O1000: the finishing pass is not drawn"]
    # The evaluator goes on after the cycle, as it did: the blocks after it run.
    assert [m.code for m in facts.motions] == ["G00", "G71", "G71", "G00", "G01", "G70"]
    # The same without the toolpath: no crash, the same motions.
    doc = parse_text(text, "t.nc")
    plain = evaluate([("t.nc", doc, build_index(doc))])
    assert [m.code for m in plain.motions] == [m.code for m in facts.motions]


def test_profile_with_a_macro_statement_is_run_as_before() -> None:
    text = program(
        "G00 X50. Z2.",
        "G71 U2. R0.5",
        "G71 P10 Q20 U0.4 W0.1 F0.25",
        "N10 G00 X20.",
        "#1=5.",
        "N20 G01 Z-#1",
        "M30",
    )
    facts = evaluated(text)
    assert facts.toolpath is not None
    g71 = line_of(text, "G71 P10 Q20 U0.4 W0.1 F0.25")
    notes = [lt.reason for lt in facts.toolpath.lost if lt.line == g71]
    assert len(notes) == 1 and "does not follow in a profile (line 7)" in notes[0]
    assert [m.code for m in facts.motions] == ["G00", "G71", "G71", "G00", "G01"]


def test_g28_loses_the_axes_it_returns() -> None:
    text = program("G00 X100. Z50.", "G28 U0. W0.", "G00 X40.", "Z5.", "W-2.")
    path = path_of(text)
    g28 = line_of(text, "G28 U0. W0.")
    assert not [m for m in path.moves if m.line == g28]  # U0 W0: the intermediate point is here
    lost = [lt for lt in path.lost if lt.line == g28]
    assert len(lost) == 1 and lost[0].axes == ("X", "Z") and "reference point" in lost[0].reason
    after = [m for m in path.moves if m.line > g28]
    assert [(m.start, m.end) for m in after] == [
        ({}, {"X": 40.0}),
        ({"X": 40.0}, {"X": 40.0, "Z": 5.0}),
        ({"X": 40.0, "Z": 5.0}, {"X": 40.0, "Z": 3.0}),
    ]


def test_g50_sets_the_position_without_a_move() -> None:
    text = program("G50 X200. Z100.", "G00 X50. Z2.")
    path = path_of(text)
    assert [(m.start, m.end) for m in path.moves] == [
        ({"X": 200.0, "Z": 100.0}, {"X": 50.0, "Z": 2.0})
    ]
    assert path.lost == []  # the start was set, not unknown


def test_lost_track_at_the_start_and_on_an_unknown_value() -> None:
    # A subprogram alone: its arguments are unknown, and so is where the tool starts.
    text = "%\nO1000\nG00 Z5.\nX10.\nX#1\nG01 Z-10. F0.2\nX30.\nM99\n%\n"
    path = path_of(text)
    assert [(m.start, m.end) for m in path.moves] == [
        ({}, {"Z": 5.0}),
        ({"Z": 5.0}, {"Z": 5.0, "X": 10.0}),
        ({"Z": 5.0, "X": 10.0}, {"Z": 5.0}),  # X#1: X goes where the analysis cannot say
        ({"Z": 5.0}, {"Z": -10.0}),
        ({"Z": -10.0}, {"Z": -10.0, "X": 30.0}),
    ]
    assert [(lt.line, lt.axes) for lt in path.lost] == [(2, ("Z",)), (3, ("X",)), (4, ("X",))]
    assert "run begins" in path.lost[0].reason and "run begins" in path.lost[1].reason
    assert "not known" in path.lost[2].reason


def test_g53_and_another_work_offset_lose_track() -> None:
    text = program("G54 G00 X10. Z10.", "G53 X0.", "G00 X20.", "G55", "G00 Z3.")
    path = path_of(text)
    reasons = {lt.line: (lt.axes, lt.reason) for lt in path.lost}
    assert reasons[line_of(text, "G53 X0.")][0] == ("X",)
    assert reasons[line_of(text, "G55")][0] == ("X", "Z")
    assert path.moves[-1].start == {} and path.moves[-1].end == {"Z": 3.0}


# ---- mill ------------------------------------------------------------------------------------


def test_mill_g91_moves() -> None:
    text = program("G90 G00 X0. Y0. Z10.", "G91 G01 X10. Y5. F100.", "X-3.", "G90 Z2.")
    path = path_of(text, MILL)
    assert [m.end for m in path.moves] == [
        {"X": 0.0, "Y": 0.0, "Z": 10.0},
        {"X": 10.0, "Y": 5.0, "Z": 10.0},
        {"X": 7.0, "Y": 5.0, "Z": 10.0},
        {"X": 7.0, "Y": 5.0, "Z": 2.0},
    ]
    assert all(m.plane == "XY" for m in path.moves)


@pytest.mark.parametrize(
    ("plane", "words", "centre"),
    [
        # XY, from (0, 0) to (10, 10): G02 R10 turns about (10, 0), R-10 about (0, 10).
        ("G17", "G02 X10. Y10. R10.", {"X": 10.0, "Y": 0.0, "Z": 0.0}),
        ("G17", "G02 X10. Y10. R-10.", {"X": 0.0, "Y": 10.0, "Z": 0.0}),
        ("G17", "G03 X10. Y10. R10.", {"X": 0.0, "Y": 10.0, "Z": 0.0}),
        ("G17", "G02 X10. Y10. I10.", {"X": 10.0, "Y": 0.0, "Z": 0.0}),
        # ZX: the plane's axes are Z then X (G03 counter-clockwise seen from +Y).
        ("G18", "G03 X10. Z10. R10.", {"X": 10.0, "Y": 0.0, "Z": 0.0}),
        ("G18", "G03 X10. Z10. I10.", {"X": 10.0, "Y": 0.0, "Z": 0.0}),
        # YZ: Y then Z (seen from +X).
        ("G19", "G02 Y10. Z10. R10.", {"X": 0.0, "Y": 10.0, "Z": 0.0}),
        ("G19", "G02 Y10. Z10. J10.", {"X": 0.0, "Y": 10.0, "Z": 0.0}),
    ],
)
def test_mill_arcs_in_each_plane(plane: str, words: str, centre: dict[str, float]) -> None:
    text = program("G90 G00 X0. Y0. Z0.", f"{plane} {words} F100.")
    arc = path_of(text, MILL).moves[-1]
    assert arc.kind == "arc" and arc.centre == centre
    assert arc.plane == {"G17": "XY", "G18": "XZ", "G19": "YZ"}[plane]
    assert arc.clockwise is words.startswith("G02")


def test_full_circle_with_i() -> None:
    text = program("G90 G00 X0. Y0. Z0.", "G02 I5. F100.")
    arc = path_of(text, MILL).moves[-1]
    assert arc.start == arc.end == {"X": 0.0, "Y": 0.0, "Z": 0.0}
    assert arc.centre == {"X": 5.0, "Y": 0.0, "Z": 0.0}


def test_mill_g28_through_the_intermediate_point() -> None:
    text = program("G90 G00 X5. Y5. Z20.", "G91 G28 Z10.", "G90 G00 X1.")
    path = path_of(text, MILL)
    g28 = line_of(text, "G91 G28 Z10.")
    assert ends(path, g28) == [("rapid", {"X": 5.0, "Y": 5.0, "Z": 30.0})]
    assert [lt.axes for lt in path.lost if lt.line == g28] == [("Z",)]
    assert path.moves[-1].end == {"X": 1.0, "Y": 5.0}


def drill(*blocks: str) -> list[tuple[str, dict[str, float]]]:
    text = program("G90 G00 X0. Y0. Z50.", *blocks, "G80")
    path = path_of(text, MILL)
    return [(m.kind, m.end) for m in path.moves if m.line > 2 and m.cycle]


def at(x: float, y: float, z: float) -> dict[str, float]:
    return {"X": x, "Y": y, "Z": z}


def test_g81_g99_then_g98() -> None:
    assert drill("G99 G81 X10. Y10. Z-5. R2. F100.", "X20.", "G98 X30.") == [
        ("rapid", at(10, 10, 50)),
        ("rapid", at(10, 10, 2)),
        ("feed", at(10, 10, -5)),
        ("rapid", at(10, 10, 2)),  # G99: back to the R point
        ("rapid", at(20, 10, 2)),
        ("feed", at(20, 10, -5)),
        ("rapid", at(20, 10, 2)),
        ("rapid", at(30, 10, 2)),
        ("feed", at(30, 10, -5)),
        ("rapid", at(30, 10, 50)),  # G98: back to the initial level
    ]


def test_g83_pecks_back_to_r() -> None:
    # R2 to Z-10 by Q4: depths -2, -6, -10; after each peck up to R, down to 1 mm above.
    assert drill("G98 G83 Z-10. R2. Q4. F100.") == [
        ("rapid", at(0, 0, 2)),
        ("feed", at(0, 0, -2)),
        ("rapid", at(0, 0, 2)),
        ("rapid", at(0, 0, -1)),
        ("feed", at(0, 0, -6)),
        ("rapid", at(0, 0, 2)),
        ("rapid", at(0, 0, -5)),
        ("feed", at(0, 0, -10)),
        ("rapid", at(0, 0, 50)),
    ]


def test_g73_pecks_back_off_a_little() -> None:
    assert drill("G99 G73 Z-10. R2. Q4. F100.") == [
        ("rapid", at(0, 0, 2)),
        ("feed", at(0, 0, -2)),
        ("rapid", at(0, 0, -1)),
        ("feed", at(0, 0, -6)),
        ("rapid", at(0, 0, -5)),
        ("feed", at(0, 0, -10)),
        ("rapid", at(0, 0, 2)),
    ]


def test_g85_feeds_out_and_g91_repeats_with_k() -> None:
    assert drill("G99 G85 X5. Z-3. R1. F50.") == [
        ("rapid", at(5, 0, 50)),
        ("rapid", at(5, 0, 1)),
        ("feed", at(5, 0, -3)),
        ("feed", at(5, 0, 1)),
    ]
    # G91: R-48 from the initial level 50 is 2, Z-12 from there is -10; K3 steps X by 10.
    holes = drill("G91 G99 G81 X10. Z-12. R-48. K3 F100.")
    assert [end for kind, end in holes if kind == "feed"] == [
        at(10, 0, -10),
        at(20, 0, -10),
        at(30, 0, -10),
    ]


def test_g80_ends_the_cycle() -> None:
    text = program("G90 G00 X0. Y0. Z50.", "G81 X10. Z-5. R2. F100.", "G80", "X20.")
    path = path_of(text, MILL)
    assert ends(path, line_of(text, "X20.")) == [("rapid", at(20, 0, 50))]


# ---- the path is continuous ------------------------------------------------------------------


def continuous(path: Toolpath) -> None:
    previous: Move | None = None
    for move in path.moves:
        if previous is not None:
            for axis, value in move.start.items():
                if axis in previous.end:
                    assert previous.end[axis] == value, (previous, move)
        previous = move


@pytest.mark.parametrize(
    "file",
    sorted(SEEDS.glob("*.nc")) + sorted(VARIANTS.glob("*.nc")),
    ids=lambda p: p.name,
)
def test_seed_paths_are_continuous(file: Path) -> None:
    facts, path = seed_path(file.name, file.parent)
    assert bool(path.moves) == bool(facts.motions)
    continuous(path)


LATHE_BLOCKS = [
    "G00 X{a} Z{b}",
    "G01 U{c} W{c} F0.2",
    "G01 X{a}",
    "W{c}",
    "G02 X{a} Z{b} R{r}",
    "G03 U{c} W{c} R-{r}",
    "G02 X{a} Z{b} I{c} K{c}",
    "G90 X{a} Z{b} R{c}",
    "X{a}",
    "G92 X{a} W{c} F1.5",
    "G94 X{a} Z{b}",
    "G28 U0 W0",
    "G00 X#1",
    "G04 X1.",
]
MILL_BLOCKS = [
    "G90 G00 X{a} Y{b} Z{a}",
    "G91 G01 X{c} Y{c} F100.",
    "G90 G01 Z{b}",
    "G17 G02 X{a} Y{b} R{r}",
    "G18 G03 X{a} Z{b} R-{r}",
    "G19 G02 Y{a} Z{b} J{c}",
    "G98 G81 X{a} Y{b} Z{c} R{a}",
    "G99 G83 X{a} Z-{r} R{r} Q{r}",
    "G73 Y{b} Z{c} R{a} Q1.5",
    "X{c}",
    "G80",
    "G91 G28 Z0",
    "G53 X0",
]


@settings(max_examples=150, deadline=None, derandomize=True, database=None)
@given(
    lathe=st.booleans(),
    picks=st.lists(
        st.tuples(
            st.integers(0, 13),
            st.integers(-50, 50),
            st.integers(-50, 50),
            st.integers(-20, 20),
            st.integers(1, 30),
        ),
        min_size=1,
        max_size=25,
    ),
)
def test_random_programs_have_continuous_paths(
    lathe: bool, picks: list[tuple[int, int, int, int, int]]
) -> None:
    blocks = LATHE_BLOCKS if lathe else MILL_BLOCKS
    lines = [
        blocks[i % len(blocks)].format(a=f"{a}.", b=f"{b}.", c=f"{c}.", r=f"{r}.")
        for i, a, b, c, r in picks
    ]
    path = path_of(program(*lines), LATHE if lathe else MILL)
    continuous(path)
    for move in path.moves:
        if move.kind == "arc":
            assert move.centre is not None
        for point in (move.start, move.end):
            assert all(math.isfinite(v) for v in point.values())


# ---- #5001-#5003: the block end position read from the tracked path -------------------------


def written(text: str, config: Config = LATHE, toolpath: bool = False) -> dict[int, object]:
    """What each assignment of the run wrote, by line (its last value)."""
    doc = parse_text(text, "t.nc")
    facts = evaluate([("t.nc", doc, build_index(doc))], config, toolpath=toolpath)
    return {line: summary.last for line, (_n, summary) in facts.document("t.nc").writes.items()}


@pytest.mark.parametrize("toolpath", [False, True])
def test_block_end_position_after_absolute_and_incremental_mill_moves(toolpath: bool) -> None:
    text = program(
        "G90 G00 X10. Y20. Z5.",
        "#100=#5001",
        "#101=#5002",
        "#102=#5003",
        "G91 G01 X5. Y-3. F100.",
        "#103=#5001",
        "#104=#5002",
        "#105=#5003",
    )
    got = written(text, MILL, toolpath)
    reads = zip(range(100, 106), (5001, 5002, 5003) * 2, strict=True)
    at = [line_of(text, f"#{n}=#{v}") for n, v in reads]
    assert [got[line] for line in at] == [10.0, 20.0, 5.0, 15.0, 17.0, 5.0]


def test_block_end_position_on_a_lathe_is_x_then_z() -> None:
    text = program("G00 X40. Z2.", "#100=#5001", "#101=#5002", "U-10. W-5.", "#102=#5001+#5002")
    got = written(text)
    assert got[line_of(text, "#100=#5001")] == 40.0
    assert got[line_of(text, "#101=#5002")] == 2.0
    assert got[line_of(text, "#102=#5001+#5002")] == 30.0 + -3.0


def test_block_end_position_after_a_cycle_is_its_start_point() -> None:
    text = program(*G71_STEPS, "#100=#5001", "#101=#5002", "M30")
    got = written(text)
    assert (got[line_of(text, "#100=#5001")], got[line_of(text, "#101=#5002")]) == (50.0, 2.0)


def test_block_end_position_unknown_where_the_path_lost_track() -> None:
    text = program(
        "#100=#5001",  # before any move
        "G00 X40. Z2.",
        "G28 U0. W0.",
        "#101=#5001",
        "#102=#5041",  # the current position is not followed
        "G00 X30.",
        "#103=#5001",
        "#104=#5002",
    )
    got = written(text)
    for line in ("#100=#5001", "#101=#5001", "#102=#5041", "#104=#5002"):
        value = got[line_of(text, line)]
        assert isinstance(value, Unknown), line
    assert got[line_of(text, "#103=#5001")] == 30.0


def test_block_end_position_unknown_after_a_call_the_analysis_cannot_follow() -> None:
    text = program("G00 X40. Z2.", "M98 P9999", "#100=#5001")
    assert isinstance(written(text)[line_of(text, "#100=#5001")], Unknown)


def test_the_path_is_followed_only_for_programs_that_read_the_block_end() -> None:
    reader = parse_text("%\nO9001\n#100=#5001\nM99\n%\n", "r.nc")
    caller = parse_text(program("G00 X40. Z2.", "M98 P9001"), "c.nc")
    other = parse_text(program("G00 X40. Z2.", "#100=#5041"), "o.nc")
    docs = [(d.uri, d, build_index(d)) for d in (reader, caller, other)]
    assert tracks_positions(docs)
    assert tracks_positions(docs, "c.nc")  # calls O9001, which reads #5001
    assert not tracks_positions(docs, "o.nc")
    assert not tracks_positions(docs[1:])


def test_block_end_position_of_a_word_finer_than_the_increment_is_unknown() -> None:
    # Z2.3182 is Z2.318 on a metric control (0.001 mm) but Z2.3182 in inches: not known
    # unless the program says G20; X40. is the same in both.
    text = program("G00 X40. Z2.3182", "#100=#5001", "#101=#5002")
    got = written(text)
    assert got[line_of(text, "#100=#5001")] == 40.0
    assert isinstance(got[line_of(text, "#101=#5002")], Unknown)
    inch = program("G20", "G00 X4. Z2.3182", "#101=#5002")
    assert written(inch)[line_of(inch, "#101=#5002")] == 2.3182


@settings(max_examples=120, deadline=None, derandomize=True, database=None)
@given(
    first=st.integers(4, 30),
    steps=st.lists(st.tuples(st.integers(0, 12), st.integers(1, 15)), min_size=1, max_size=6),
    above=st.integers(1, 30),
    depth=st.sampled_from(["0.5", "1.", "1.5", "2.5"]),
    escape=st.sampled_from(["0.2", "0.5", "1."]),
    allowance=st.sampled_from([("0.", "0."), ("0.4", "0.1"), ("0.6", "0.2")]),
)
def test_random_g71_profiles_are_cut_without_gouging(
    first: int,
    steps: list[tuple[int, int]],
    above: int,
    depth: str,
    escape: str,
    allowance: tuple[str, str],
) -> None:
    """A monotonic profile (X rising as Z falls, external turning): every layer lies between
    the start point and the profile moved by the allowance, ends where that profile reaches
    its level (or at its end), and no layer goes past it."""
    points = [(float(first), 0.0)]
    for dx, dz in steps:
        x, z = points[-1]
        points.append((x + 2.0 * dx, z - dz))
    top = max(x for x, _ in points) + 2.0 * above
    blocks = [f"N10 G00 X{points[0][0]:g}."]
    blocks += [f"G01 X{x:g}. Z{z:g}." for x, z in points[1:-1]]
    blocks += [f"N20 G01 X{points[-1][0]:g}. Z{points[-1][1]:g}."]
    du, dw = allowance
    text = program(
        f"G00 X{top:g}. Z0.",
        f"G71 U{depth} R{escape}",
        f"G71 P10 Q20 U{du} W{dw} F0.2",
        *blocks,
        "M30",
    )
    path = path_of(text)
    continuous(path)
    line = line_of(text, f"G71 P10 Q20 U{du} W{dw} F0.2")
    moves = [m for m in path.moves if m.line == line]
    assert moves and moves[-1].end == {"X": top, "Z": 0.0}  # back at the start point
    shifted = [(x + float(du), z + float(dw)) for x, z in points]
    # The semi-finishing pass begins with the move to the moved profile's start.
    finishing = max(
        i for i, m in enumerate(moves) if m.end == {"X": shifted[0][0], "Z": shifted[0][1]}
    )
    layers = [m for m in moves[:finishing] if m.kind == "feed"]
    assert all(m.start["X"] == m.end["X"] and m.start["Z"] == 0.0 for m in layers)
    expected = math.ceil((top - shifted[0][0]) / (2.0 * float(depth)) - 1e-9) - 1
    assert len(layers) <= expected
    for m in layers:
        x, z_end = m.end["X"], m.end["Z"]
        assert shifted[0][0] < x < top
        # The profile before the layer's end lies below its level: no gouge.
        assert all(px <= x + 1e-3 for px, pz in shifted if pz > z_end + 1e-3)
        # It ends where the profile reaches the level, or at the profile's end.
        assert z_end == pytest.approx(shifted[-1][1], abs=2e-3) or any(
            abs(pz - z_end) < 2e-3 or (px >= x - 1e-3 and pz <= z_end + 1e-3) for px, pz in shifted
        )


def test_the_views_arc_segments_are_written_to_a_tenth_of_a_micron() -> None:
    from fanuc_macro.ide.toolpath_view import ARC_DECIMALS, view_data

    arc = Move(
        "arc",
        {"X": 10.0, "Y": 0.0, "Z": -1.0},
        {"X": 0.0, "Y": 10.0, "Z": -1.0},
        3,
        "O1",
        centre={"X": 0.0, "Y": 0.0, "Z": -1.0},
        clockwise=False,
        plane="XY",
    )
    segments = unpacked(view_data(Toolpath([arc], lathe=False), "file:///a.nc"))
    assert len(segments["kind"]) == 18  # a quarter of 72 segments a turn
    # The arc's pieces meet: 19 points, each segment from its point to the next.
    points = segments["points"]
    assert len(points) == 19 * 3 and segments["point"] == list(range(18))
    assert all(v == round(v, ARC_DECIMALS) for v in points)
    assert points[:3] == [10.0, 0.0, -1.0] and points[-3:] == [0.0, 10.0, -1.0]
    # On the circle, to the rounding.
    for i in range(0, len(points), 3):
        assert math.hypot(points[i], points[i + 1]) == pytest.approx(10.0, abs=1e-4)


def test_the_view_joins_moves_that_meet_and_keeps_a_lathes_unknown_y() -> None:
    from fanuc_macro.ide.toolpath_view import view_data

    # A lathe's G92 pass (O3331's first, diameters 51 and 49.816): X drawn as a radius.
    moves = [
        Move("rapid", {"X": 51.0, "Z": 5.964}, {"X": 49.816, "Z": 5.964}, 40, "O1"),
        Move("thread", {"X": 49.816, "Z": 5.964}, {"X": 49.816, "Z": -54.036}, 40, "O1"),
        Move("rapid", {"X": 49.816, "Z": -54.036}, {"X": 51.0, "Z": -54.036}, 40, "O1"),
        # After a gap (an unknown position, say): its own start point.
        Move("feed", {"X": 60.0, "Z": 0.0}, {"X": 60.0, "Z": -1.0}, 41, "O2", uri="file:///b.nc"),
    ]
    data = view_data(Toolpath(moves, lathe=True), "file:///a.nc")
    s = unpacked(data)
    assert data["paths"] == ["file:///a.nc", "file:///b.nc"] and data["count"] == 4
    kinds = data["kinds"]
    assert [kinds[k] for k in s["kind"]] == ["rapid", "thread", "rapid", "feed"]
    assert s["line"] == [40, 40, 40, 41] and s["path"] == [0, 0, 0, 1]
    assert s["point"] == [0, 1, 2, 4]
    xyz = [tuple(s["points"][i : i + 3]) for i in range(0, len(s["points"]), 3)]
    assert len(xyz) == 6 and all(math.isnan(y) for _, y, _ in xyz)
    assert [(x, z) for x, _, z in xyz] == [
        (25.5, 5.964),
        (24.908, 5.964),
        (24.908, -54.036),
        (25.5, -54.036),
        (30.0, 0.0),
        (30.0, -1.0),
    ]


def _view(text: str, config: Config = LATHE) -> dict[str, Any]:
    from fanuc_macro.ide.toolpath_view import toolpath_view

    doc = parse_text(text, "t.nc")
    return dict(toolpath_view("t.nc", doc, build_index(doc), config=config))


def test_the_views_segments_name_their_block_with_its_code_feed_and_speed() -> None:
    text = program(
        "G21 G97 S800 M03",
        "G00 X40. Z2.",
        "G01 Z-20. F0.2",
        "G96 S180",
        "G02 X50. Z-25. R5.",
    )
    data = _view(text)
    s = unpacked(data)
    lines = s["line"]
    motion = s["motion"]
    # Every segment of a block belongs to that block's motion record.
    for line in set(lines):
        assert len({motion[i] for i, n in enumerate(lines) if n == line}) == 1
    by_line = {lines[i]: motion[i] for i in range(len(lines))}
    feed_line = line_of(text, "G01 Z-20. F0.2")
    arc_line = line_of(text, "G02 X50. Z-25. R5.")
    g01, g02 = by_line[feed_line], by_line[arc_line]
    assert s["block_code"][g01] == "G01" and s["block_feed"][g01] == 0.2
    assert s["block_speed"][g01] == 800.0 and s["block_surface"][g01] == 0
    # G96: the surface speed, said so; the feed stays in force.
    assert s["block_code"][g02] == "G02" and s["block_feed"][g02] == 0.2
    assert s["block_speed"][g02] == 180.0 and s["block_surface"][g02] == 1
    rapid = by_line[line_of(text, "G00 X40. Z2.")]
    assert math.isnan(s["block_feed"][rapid])
    assert data["units_stated"] is True and data["units_note"] == ""


def test_the_view_says_when_it_assumes_the_unit_and_why() -> None:
    # No G20/G21 and a path 1.5 across: the sizes of a part in inches.
    small = _view(program("G00 X1.5 Z0.1", "G01 Z-1.2 F0.004"))
    assert small["units"] == "mm" and small["units_stated"] is False
    assert small["units_note"].startswith("assumed mm: the program states neither G20 nor G21")
    assert "as a part in inches would be" in small["units_note"]
    # A large part: the unit is still assumed, with no word on inches.
    large = _view(program("G00 X80. Z2.", "G01 Z-120. F0.2"))
    assert large["units_stated"] is False and "inches" not in large["units_note"]
    # A G20 in a comment states nothing; G20 in a block does.
    assert (
        _view(program("(G20 NOT HERE)", "G00 X1. Z0.1", "G01 Z-1. F0.004"))["units_stated"] is False
    )
    stated = _view(program("G20", "G00 X1. Z0.1", "G01 Z-1. F0.004"))
    assert stated["units"] == "inch" and stated["units_stated"] is True


def test_the_view_gives_the_stock_the_tool_and_the_threads_cross_section() -> None:
    from fanuc_macro.ide.toolpath_view import toolpath_view

    file = SEEDS / "o4009_external_m50x3.nc"
    doc = parse_text(file.read_text("utf-8"), "t.nc")
    data = toolpath_view("t.nc", doc, build_index(doc), config=LATHE)
    assert "error" not in data
    stock = data["stock"]
    assert stock is not None and stock["diameter"] == 50.0 and stock["front"] == 0.0
    assert stock["back"] < -50.0 and "M50x3" in stock["source"]
    tool = data["tool"]
    assert tool is not None and tool["angle"] == 60.0
    assert tool["radius"] == pytest.approx(0.433, abs=1e-3) and tool["line"] >= 0
    (thread,) = data["threads"]
    assert thread["name"].startswith("M50x3") and not thread["internal"]
    # The cut over one lead: radii within the blank and under the root's depth.
    profile = thread["profile"]
    assert len(profile) > 10
    assert all(-1.5 - 1e-9 <= u <= 1.5 + 1e-9 for u, _ in profile)
    assert all(23.0 < r <= 25.0 + 1e-9 for _, r in profile)
    assert thread["band"] is not None and thread["band"][0] < thread["band"][1] < 50.0


def test_the_stock_diameter_setting_gives_the_bar_the_view_draws() -> None:
    """A shop's bar (fanuc-macro.view.stockDiameter, [view] stock-diameter) over the program's
    blank; along Z, the cuts' length as without it; a mill draws no bar."""
    from dataclasses import replace

    from fanuc_macro.ide.toolpath_view import toolpath_view

    file = SEEDS / "o4009_external_m50x3.nc"
    doc = parse_text(file.read_text("utf-8"), "t.nc")
    index = build_index(doc)
    plain = toolpath_view("t.nc", doc, index, config=LATHE)
    bar = toolpath_view("t.nc", doc, index, config=replace(LATHE, stock_diameter=55.0))
    assert "error" not in plain and "error" not in bar
    assert plain["stock"] is not None and bar["stock"] is not None
    assert bar["stock"]["diameter"] == 55.0 and "stockDiameter" in bar["stock"]["source"]
    assert (bar["stock"]["front"], bar["stock"]["back"]) == (
        plain["stock"]["front"],
        plain["stock"]["back"],
    )
    assert Config.from_settings({"view": {"stockDiameter": 42}}).stock_diameter == 42.0
    assert Config.from_settings({}).stock_diameter == math.inf
    mill = _view(
        "O1\nG90 G17 G54\nG00 X0 Y0 Z5.\nG01 Z-1. F100\nX20. Y10.\nM30\n",
        replace(LATHE, stock_diameter=55.0),
    )
    assert mill["lathe"] is False and mill["stock"] is None


@pytest.mark.parametrize(
    ("header", "radius"),
    [
        ("(T1 D=10. CR=0. - ZMIN=-5. - FLAT END MILL)", 5.0),
        ("(TOOL - 1 DIA. OFF. - 1 LEN. - 1 DIA. - 12.)", 6.0),
        ("(T2 Ø8 DRILL)", 4.0),
        ("(ROUGHING, WIDTH=10)", None),
    ],
)
def test_a_mills_cutter_is_drawn_at_the_diameter_its_tool_list_gives(
    header: str, radius: float | None
) -> None:
    mill = _view(f"O1\n{header}\nG90 G17 G54\nG00 X0 Y0 Z5.\nG01 Z-1. F100\nX20. Y10.\nM30\n")
    assert mill["lathe"] is False
    tool = mill["tool"]
    if radius is None:
        assert tool is None
    else:
        assert tool is not None and tool["radius"] == radius and tool["line"] == 1
        assert tool["source"] == "the diameter in the comment at line 2"


def test_a_program_with_no_move_says_why_nothing_is_drawn() -> None:
    nothing = _view("O1\n#1 = 2\nM30\n")
    assert nothing["empty"] is True and nothing["error"].startswith("the program makes no move")
    blank = _view("\n")
    assert blank["empty"] is True and "holds no blocks" in blank["error"]


def test_the_view_gives_the_first_threads_cut_not_every_one() -> None:
    from fanuc_macro.generators.drum_groove_generator import build_drum_groove
    from fanuc_macro.ide.toolpath_view import MAX_VIEW_THREADS

    # Seed 003's drum groove: every chained G32 segment a one-pass thread to the rules.
    text = build_drum_groove(None, 12.0, layers=2, cuts_per_layer=2).text
    data = _view(text)
    names = [t["name"] for t in data["threads"]]
    assert len(names) == MAX_VIEW_THREADS
    # In the order the run cut them: the first thread's first pass first.
    lines = [t["line"] for t in data["threads"]]
    assert lines[0] == min(
        unpacked(data)["line"][i]
        for i, k in enumerate(unpacked(data)["kind"])
        if data["kinds"][k] == "thread"
    )
