"""The toolpath the evaluator records on request: positions, arcs, canned cycles expanded into
the control's moves, and where the path lost track. The numbers are worked out by hand in the
comments (FANUC 0i-TF / 0i-MF operator's manuals), or the seed papers' (thread-math.md)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fanuc_macro.config import Config
from fanuc_macro.evaluator import Facts, evaluate
from fanuc_macro.evaluator.toolpath import Move, Toolpath
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import parse_text

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


def test_g71_is_a_note_not_a_loss() -> None:
    text = program(
        "G00 X50. Z2.",
        "G71 U1.5 R0.5",
        "G71 P10 Q20 U0.4 W0.1 F0.25",
        "N10 G00 X20.",
        "N20 G01 Z-10.",
    )
    path = path_of(text)
    notes = [lt for lt in path.lost if lt.line == line_of(text, "G71 P10 Q20 U0.4 W0.1 F0.25")]
    assert len(notes) == 1 and notes[0].axes == () and "not drawn" in notes[0].reason
    assert not [m for m in path.moves if m.line in (3, 4)]  # the G71 blocks move nowhere drawn


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
    segments = view_data(Toolpath([arc], lathe=False), "file:///a.nc")["segments"]
    assert len(segments["kind"]) == 18  # a quarter of 72 segments a turn
    values = [v for v in (*segments["start"], *segments["end"]) if v is not None]
    assert all(v == round(v, ARC_DECIMALS) for v in values)
    assert segments["start"][:3] == [10.0, 0.0, -1.0] and segments["end"][-3:] == [0.0, 10.0, -1.0]
    # On the circle, to the rounding.
    for i in range(0, len(segments["start"]), 3):
        x, y = segments["start"][i], segments["start"][i + 1]
        assert math.hypot(x, y) == pytest.approx(10.0, abs=1e-4)
