"""The SVG backplot (ide/plot.py) drawn from toolpaths made by hand: what it draws, where, and
with which links to the source."""

from __future__ import annotations

import itertools
import os
import re
import subprocess
import sys
import unicodedata
import xml.etree.ElementTree as ET
from collections import Counter
from pathlib import Path

import pytest

from fanuc_macro.evaluator.toolpath import UNKNOWN_START, LostTrack, Move, Toolpath
from fanuc_macro.ide.plot import (
    MAX_PASS_MAPS,
    NothingToPlot,
    PassMap,
    PassMark,
    backplot,
    plot_svg,
)

SVG = "{http://www.w3.org/2000/svg}"


def _elements(svg: str, kind: str | None = None) -> list[ET.Element]:
    root = ET.fromstring(svg)
    return [
        e for e in root.iter() if "data-kind" in e.attrib and kind in (None, e.get("data-kind"))
    ]


def _g92_pass() -> Toolpath:
    """The first G92 of O3331: in to X49.816 from X51 Z5.964, thread to Z-54.036, out, back."""
    start = {"X": 51.0, "Z": 5.964}
    cut_x = {"X": 49.816, "Z": 5.964}
    end = {"X": 49.816, "Z": -54.036}
    out = {"X": 51.0, "Z": -54.036}
    return Toolpath(
        [
            Move("rapid", start, cut_x, 40, "O3331", motion=0),
            Move("thread", cut_x, end, 40, "O3331", motion=0),
            Move("rapid", end, out, 40, "O3331", motion=0),
            Move("rapid", out, start, 40, "O3331", motion=0),
        ],
        lathe=True,
    )


def _points(e: ET.Element) -> list[list[tuple[float, float]]]:
    """The points of a path of straight lines (M and L commands), one list per subpath."""
    subpaths: list[list[tuple[float, float]]] = []
    for command, numbers in re.findall(r"([ML])([^ML]*)", e.get("d", "")):
        values = [float(v) for v in numbers.split()]
        pairs = list(zip(values[::2], values[1::2], strict=True))
        if command == "M":
            subpaths.append(pairs)
        else:
            subpaths[-1].extend(pairs)
    return subpaths


def _segments(e: ET.Element) -> list[tuple[float, float, float, float]]:
    """Each straight segment of a path as x1, y1, x2, y2."""
    return [(*a, *b) for points in _points(e) for a, b in itertools.pairwise(points)]


def test_a_lathe_cycle_is_drawn_z_across_and_x_up_with_a_link_per_move() -> None:
    svg = plot_svg(_g92_pass(), title="O3331")
    moves = _elements(svg)
    # The retract and the return, consecutive rapids of the same block, are one path.
    assert [e.get("data-kind") for e in moves] == ["rapid", "thread", "rapid"]
    assert {e.get("data-line") for e in moves} == {"41"}  # 1-based
    assert all(e.tag == f"{SVG}path" for e in moves)
    assert [len(_segments(e)) for e in moves] == [1, 1, 2]
    infeed, cut, retract, back = (s for e in moves for s in _segments(e))
    assert retract[3] < retract[1]  # out to X51: upwards
    # The infeed goes down (X smaller), the cut goes left along Z at one height.
    assert infeed[0] == pytest.approx(infeed[2]) and infeed[3] > infeed[1]
    assert cut[1] == pytest.approx(cut[3]) and cut[2] < cut[0]
    # One scale for both axes: 59.999 mm of Z against 0.592 mm of radius (1.184 of diameter).
    ratio = (cut[0] - cut[2]) / (infeed[3] - infeed[1])
    assert ratio == pytest.approx(60.0 / 0.592, rel=1e-3)
    assert back[2:] == pytest.approx(infeed[:2])
    root = ET.fromstring(svg)
    texts = [t.text or "" for t in root.iter(f"{SVG}text")]
    assert any("diameter" in t for t in texts)  # the X axis says what its numbers are
    assert "Z (mm)" in texts
    # The rapids are dashed, the thread has a colour of its own.
    style = root.find(f"{SVG}style")
    assert style is not None and style.text is not None
    assert re.search(r"\[data-kind=rapid\][^{]*\{[^}]*stroke-dasharray", style.text)
    assert re.search(r"\[data-kind=thread\][^{]*\{stroke:#[0-9a-f]{6}", style.text)


def test_consecutive_moves_of_one_kind_by_one_block_are_one_path() -> None:
    # A G76 block's two passes (line 10), two feeds of blocks of their own, a subprogram's.
    a, b, c, d = (
        {"X": x, "Z": z} for x, z in ((51.0, 5.0), (49.0, 5.0), (49.0, -50.0), (51.0, -50.0))
    )
    e, f = {"X": 48.0, "Z": 5.0}, {"X": 48.0, "Z": -50.0}
    g, h, k = {"X": 60.0, "Z": 5.0}, {"X": 60.0, "Z": 0.0}, {"X": 62.0, "Z": 0.0}
    moves = [
        *(Move(kind, p, q, 9, "O1") for kind, p, q in (("rapid", a, b), ("thread", b, c))),
        *(Move(kind, p, q, 9, "O1") for kind, p, q in (("rapid", c, d), ("rapid", d, a))),
        *(Move(kind, p, q, 9, "O1") for kind, p, q in (("rapid", a, e), ("thread", e, f))),
        *(Move(kind, p, q, 9, "O1") for kind, p, q in (("rapid", f, d), ("rapid", d, a))),
        Move("feed", a, g, 10, "O1"),
        Move("feed", g, h, 11, "O1"),
        Move("feed", h, k, 2, "O2"),
    ]
    svg = plot_svg(Toolpath(moves, lathe=True))
    drawn = _elements(svg)
    assert [e.get("data-kind") for e in drawn] == [
        *("rapid", "thread", "rapid", "thread", "rapid"),
        *("feed", "feed", "feed"),
    ]
    assert [e.get("data-line") for e in drawn] == ["10"] * 5 + ["11", "12", "3"]
    # The pass's retract, the return and the next pass's infeed are one path of 3 segments.
    assert [len(_segments(e)) for e in drawn] == [1, 1, 3, 1, 2, 1, 1, 1]
    root = ET.fromstring(svg)
    groups = [g for g in root.iter(f"{SVG}g") if "data-program" in g.attrib]
    assert [(g.get("data-program"), len(g)) for g in groups] == [("O1", 7), ("O2", 1)]


def test_a_program_of_many_threads_draws_the_first_pass_maps_and_counts_the_rest() -> None:
    maps = [PassMap(f"T{i}", "O1", False, (PassMark(40, 49.0, 5.0),)) for i in range(25)]
    root = ET.fromstring(plot_svg(_g92_pass(), passes=maps))
    views = [g.get("data-view") for g in root.iter(f"{SVG}g") if g.get("data-view")]
    assert views == ["toolpath", *["passes"] * MAX_PASS_MAPS, "more-passes"]
    (more,) = (g for g in root.iter(f"{SVG}g") if g.get("data-view") == "more-passes")
    assert more.get("data-count") == str(25 - MAX_PASS_MAPS)


def test_the_x_ticks_of_a_lathe_read_as_diameters() -> None:
    path = Toolpath(
        [Move("feed", {"X": 0.0, "Z": 0.0}, {"X": 100.0, "Z": -50.0}, 0, "O1")], lathe=True
    )
    root = ET.fromstring(plot_svg(path))
    texts = [t.text or "" for t in root.iter(f"{SVG}text")]
    assert "100" in texts  # the diameter 100 is the top of the radius 50 drawn
    assert "-50" in texts  # and Z across


def _arc(clockwise: bool, end: dict[str, float]) -> Toolpath:
    return Toolpath(
        [
            Move(
                "arc",
                {"X": 10.0, "Y": 0.0},
                end,
                3,
                "O1",
                centre={"X": 0.0, "Y": 0.0},
                clockwise=clockwise,
                plane="XY",
            )
        ],
        lathe=False,
    )


def _arc_flags(svg: str) -> list[tuple[int, int]]:
    (path,) = _elements(svg, "arc")
    assert path.tag == f"{SVG}path"
    return [
        (int(m.group(1)), int(m.group(2)))
        for m in re.finditer(r"A[\d.]+ [\d.]+ 0 (\d) (\d)", path.get("d", ""))
    ]


def test_an_arc_in_the_view_turns_the_way_g02_and_g03_say() -> None:
    # From 3 o'clock to 6 o'clock about the origin: G02 a quarter turn (clockwise on the
    # screen, SVG's sweep 1), G03 three quarters (large arc, sweep 0).
    assert _arc_flags(plot_svg(_arc(True, {"X": 0.0, "Y": -10.0}))) == [(0, 1)]
    assert _arc_flags(plot_svg(_arc(False, {"X": 0.0, "Y": -10.0}))) == [(1, 0)]


def test_a_full_circle_is_drawn_as_two_halves() -> None:
    assert _arc_flags(plot_svg(_arc(False, {"X": 10.0, "Y": 0.0}))) == [(0, 0), (0, 0)]


def test_an_arc_seen_edge_on_is_a_line_through_its_points() -> None:
    path = _arc(True, {"X": 0.0, "Y": -10.0})
    path.moves[0] = Move(
        "arc",
        {"X": 10.0, "Y": 0.0, "Z": 0.0},
        {"X": 0.0, "Y": -10.0, "Z": 0.0},
        3,
        "O1",
        centre={"X": 0.0, "Y": 0.0, "Z": 0.0},
        clockwise=True,
        plane="XY",
    )
    svg = plot_svg(path, plane="XZ")
    (line,) = _elements(svg, "arc")
    assert line.tag == f"{SVG}path" and "A" not in line.get("d", "")
    (points,) = _points(line)
    assert len(points) >= 5


def test_moves_without_a_place_in_the_view_are_left_out_and_counted() -> None:
    path = Toolpath(
        [
            Move("rapid", {"X": 0.0, "Y": 0.0}, {"X": 5.0, "Y": 5.0}, 1, "O1"),
            Move("feed", {"Z": 2.0}, {"Z": -1.0}, 2, "O1"),
        ],
        lathe=False,
    )
    svg = plot_svg(path)
    assert [e.get("data-line") for e in _elements(svg)] == ["2"]
    assert "1 of 2 moves" in svg
    with pytest.raises(NothingToPlot, match="nothing to plot in YZ"):
        plot_svg(path, plane="YZ")


def test_where_the_path_lost_track_is_marked_with_its_reason() -> None:
    path = Toolpath(
        [Move("feed", {"X": 0.0, "Y": 0.0}, {"X": 5.0, "Y": 5.0}, 7, "O1")],
        lost=[LostTrack(7, "O1", ("Z",), "no absolute Z before this block")],
        lathe=False,
    )
    (mark,) = _elements(plot_svg(path), "lost")
    assert mark.get("data-line") == "8"
    title = mark.find(f"{SVG}title")
    assert title is not None and "no absolute Z" in (title.text or "")


def test_the_same_toolpath_gives_the_same_bytes() -> None:
    assert plot_svg(_g92_pass()) == plot_svg(_g92_pass())


def test_a_pass_map_shows_each_pass_depth_and_cut() -> None:
    passes = PassMap(
        "M50x3",
        "O3331",
        internal=False,
        passes=(
            PassMark(40, 49.0, 5.964),
            PassMark(41, 48.4, 6.1),
            PassMark(42, 48.0, 5.8),
        ),
        major=50.0,
        pitch=3.0,
    )
    svg = plot_svg(_g92_pass(), passes=[passes])
    root = ET.fromstring(svg)
    views = [g.get("data-view") for g in root.iter(f"{SVG}g") if g.get("data-view")]
    assert views == ["toolpath", "passes"]
    marks = _elements(svg, "pass")
    assert [m.get("data-depth") for m in marks] == ["0.5", "0.8", "1."]
    assert [m.get("data-line") for m in marks] == ["41", "42", "43"]
    cuts = _elements(svg, "cut")
    assert [c.get("data-cut") for c in cuts] == ["0.5", "0.3", "0.2"]
    # The tips move along Z with the pass's start: symmetric infeed shows left and right.
    tips = [float(m.get("cx", "nan")) for m in marks]
    assert tips[1] > tips[0] > tips[2]
    assert _elements(svg, "profile")  # the basic 60-degree groove of an identified thread


# ---- fanuc-macro plot, as a subprocess -------------------------------------------------------

SEEDS = Path(__file__).parent / "fixtures" / "seeds"


def _plot(tmp_path: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(Path(__file__).parents[1] / "server")
    return subprocess.run(
        [sys.executable, "-m", "fanuc_macro.cli", "plot", *args],
        cwd=tmp_path,
        env=env,
        encoding="utf-8",
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )


def test_plot_of_the_seed_module_draws_every_g92_cut_and_its_pass_map(tmp_path: Path) -> None:
    done = _plot(tmp_path, str(SEEDS / "o4009_external_m50x3.nc"))
    assert done.returncode == 0, done.stderr
    svg = (tmp_path / "o4009_external_m50x3.svg").read_text(encoding="utf-8")
    root = ET.fromstring(svg)
    moves = _elements(svg)
    kinds = Counter(e.get("data-kind") for e in moves)
    assert kinds["thread"] == 186  # every G92 pass of O3331
    assert kinds["pass"] == 186 and kinds["cut"] == 186
    views = [g.get("data-view") for g in root.iter(f"{SVG}g") if g.get("data-view")]
    assert views == ["toolpath", "passes"]
    # Every drawn move links to a line of the file.
    lines = len((SEEDS / "o4009_external_m50x3.nc").read_text(encoding="utf-8").splitlines())
    linked = [e for e in moves if e.get("data-kind") != "profile"]
    assert all(1 <= int(e.get("data-line", "0")) <= lines for e in linked)
    assert "1011 moves" in done.stderr and "thread 186" in done.stderr
    # The start before the first absolute X and Z is normal: counted, not a line of its own.
    assert done.stderr.splitlines() == [
        "o4009_external_m50x3.svg: 1010 of 1011 moves drawn in XZ (feed 265, rapid 560, thread"
        " 186); 1 not drawn: it starts before the first absolute X and Z (the tool's place at the"
        " start is not known)"
    ]


def test_plot_to_standard_output_in_another_plane(tmp_path: Path) -> None:
    done = _plot(tmp_path, str(SEEDS / "o5_arc_thread_finishing.nc"), "-o", "-", "--plane", "XZ")
    assert done.returncode == 0, done.stderr
    assert Counter(e.get("data-kind") for e in _elements(done.stdout))["thread"] == 19


def test_plot_of_a_program_without_moves_says_so_and_exits_2(tmp_path: Path) -> None:
    empty = tmp_path / "empty.nc"
    empty.write_text("%\nO0001\n#1=2\nM30\n%\n", encoding="utf-8")
    done = _plot(tmp_path, str(empty))
    assert done.returncode == 2
    assert "nothing to plot" in done.stderr
    assert not (tmp_path / "empty.svg").exists()
    missing = _plot(tmp_path, "no-such-file.nc")
    assert missing.returncode == 2 and "no such file" in missing.stderr


def test_plot_of_a_g71_draws_its_layers_and_g70_its_profile(tmp_path: Path) -> None:
    """The stock removal cycle through the command line: G71's feeds are its seven layers and
    the semi-finishing pass, linked to the G71 block; G70 runs the profile, each cut linked to
    its own block, and returns to the start point from the G70 block."""
    program = tmp_path / "g71.nc"
    blocks = [
        "%",
        "O0001",
        "G00 X50. Z2.",
        "G71 U2. R0.5",
        "G71 P10 Q20 U0.4 W0.1 F0.25",
        "N10 G00 X20.",
        "G01 Z-10.",
        "X40.",
        "N20 Z-30.",
        "G70 P10 Q20",
        "G00 X100.",
        "M30",
        "%",
    ]
    program.write_text("\n".join(blocks) + "\n", encoding="utf-8")
    done = _plot(tmp_path, str(program))
    assert done.returncode == 0, done.stderr
    moves = _elements((tmp_path / "g71.svg").read_text(encoding="utf-8"))
    by_line = Counter((int(e.get("data-line", "0")), e.get("data-kind")) for e in moves)
    g71 = blocks.index("G71 P10 Q20 U0.4 W0.1 F0.25") + 1
    assert by_line[(g71, "feed")] == 7 + 1  # X46 ... X22, then the semi-finish
    g70 = blocks.index("G70 P10 Q20") + 1
    profile = [blocks.index(b) + 1 for b in ("G01 Z-10.", "X40.", "N20 Z-30.")]
    assert [by_line[(line, "feed")] for line in profile] == [1, 1, 1]
    assert by_line[(g70, "rapid")] == 1 and by_line[(g70, "feed")] == 0


# ---- what a reader of the drawing is told ----------------------------------------------------

# A mill's program: a plate's outline in X and Y, no Z.
MILL_OUTLINE = (
    "%\nO1001 (PLATE OUTLINE)\nG90 G00 X0. Y0.\nG01 X50. F300.\nY30.\nX20. Y60.\nX0.\nY0.\nM30\n%\n"
)
# A turning program that returns to the reference point three times.
G28_TURNING = [
    "%",
    "O0002 (TURN)",
    "G00 X50. Z2.",
    "G01 Z-20. F0.2",
    "X60.",
    "G28 U0. W0.",
    "G00 X50. Z2.",
    "G01 Z-30.",
    "X62.",
    "G28 U0. W0.",
    "G00 X80. Z5.",
    "G01 Z-10.",
    "G28 U0.",
    "G00 X90.",
    "M30",
    "%",
]


def _root(svg: str) -> ET.Element:
    return ET.fromstring(svg)


def _with(root: ET.Element, attribute: str, value: str | None = None) -> list[ET.Element]:
    return [
        e for e in root.iter() if e.get(attribute) is not None and value in (None, e.get(attribute))
    ]


def _text(e: ET.Element) -> str:
    return "".join(e.itertext())


def test_the_legend_names_every_kind_of_move_drawn_and_every_mark(tmp_path: Path) -> None:
    done = _plot(tmp_path, str(SEEDS / "o4009_external_m50x3.nc"), "-o", "-")
    assert done.returncode == 0, done.stderr
    root = _root(done.stdout)
    legend = [(g.get("data-legend"), _text(g)) for g in _with(root, "data-legend")]
    assert legend == [
        ("rapid", "rapid"),
        ("feed", "feed"),
        ("thread", "threading"),
        ("start", "start"),
        ("end", "end"),
        ("direction", "direction of travel"),
        # The run's cycle time last (tests/test_cycle_time.py works it out by hand).
        ("cycle-time", "cycle time 10 min 1.3 s"),
    ]
    # Each kind's sample is styled as its moves are: the rapid's line dashed like the rapids.
    samples = {g.get("data-legend"): g[0] for g in _with(root, "data-legend")}
    assert all(samples[k].get("class") == k for k in ("rapid", "feed", "thread"))
    style = root.find(f"{SVG}style")
    assert style is not None and style.text is not None
    assert re.search(r"\[data-kind=rapid\],\.legend \.rapid\{[^}]*stroke-dasharray", style.text)
    assert samples["start"].tag == f"{SVG}circle" and samples["end"].tag == f"{SVG}rect"
    # The marks are not moves: the links of the moves by kind are as they were.
    assert all(e.get("data-kind") is None for e in _with(root, "data-legend"))


def _arrow(e: ET.Element) -> tuple[tuple[float, float], tuple[float, float]]:
    """An arrow's tip and the middle of its base."""
    values = [float(v) for v in re.findall(r"-?[\d.]+", e.get("d", ""))]
    tip, b1, b2 = values[0:2], values[2:4], values[4:6]
    return (tip[0], tip[1]), ((b1[0] + b2[0]) / 2, (b1[1] + b2[1]) / 2)


def test_the_start_the_end_and_the_direction_of_travel_are_marked() -> None:
    # An L seen from above: a rapid to the right from X0 Y0 to X40, a feed up to Y30.
    path = Toolpath(
        [
            Move("rapid", {"X": 0.0, "Y": 0.0}, {"X": 40.0, "Y": 0.0}, 2, "O1"),
            Move("feed", {"X": 40.0, "Y": 0.0}, {"X": 40.0, "Y": 30.0}, 3, "O1"),
        ],
        lathe=False,
    )
    root = _root(plot_svg(path))
    rapid, feed = _elements(plot_svg(path))
    ((first, *_),) = _points(rapid)
    ((*_, last),) = _points(feed)
    (start,) = _with(root, "data-mark", "start")
    (end,) = _with(root, "data-mark", "end")
    assert start.tag == f"{SVG}circle" and start.get("data-line") == "3"
    assert (float(start.get("cx", "nan")), float(start.get("cy", "nan"))) == pytest.approx(first)
    assert end.tag == f"{SVG}rect" and end.get("data-line") == "4"
    size = float(end.get("width", "nan"))
    centre = (float(end.get("x", "nan")) + size / 2, float(end.get("y", "nan")) + size / 2)
    assert centre == pytest.approx(last)
    arrows = _with(root, "data-mark", "direction")
    assert [a.get("data-line") for a in arrows] == ["3", "4"]
    (tip, base), (up_tip, up_base) = (_arrow(a) for a in arrows)
    # On its move, pointing the way the tool goes: right along the rapid, up the feed.
    assert tip[1] == pytest.approx(first[1]) and tip[0] > base[0]
    assert up_tip[0] == pytest.approx(last[0]) and up_tip[1] < up_base[1]


def test_plot_says_in_one_line_for_each_cause_which_moves_it_leaves_out(tmp_path: Path) -> None:
    """The start of the run, before the first absolute position, is counted in the summary;
    each other cause is one line at the first block where it happened, not a line a block."""
    program = tmp_path / "g28.nc"
    program.write_text("\n".join(G28_TURNING) + "\n", encoding="utf-8")
    done = _plot(tmp_path, str(program))
    assert done.returncode == 0, done.stderr
    g28 = G28_TURNING.index("G28 U0. W0.") + 1
    assert done.stderr.splitlines() == [
        f"{program}:{g28}: G28 returns to the reference point, whose work coordinates are not"
        " known: 3 moves not drawn (also lines 10 and 13)",
        "g28.svg: 5 of 9 moves drawn in XZ (feed 5, rapid 4); 1 not drawn: it starts before the"
        " first absolute X and Z (the tool's place at the start is not known)",
    ]
    root = _root((tmp_path / "g28.svg").read_text(encoding="utf-8"))
    (notes,) = (g for g in root.iter(f"{SVG}g") if g.get("class") == "notes")
    assert " ".join(_text(t) for t in notes) == (
        "1 move not drawn: it starts before the first absolute X and Z (the tool's place at the"
        f" start is not known) line {g28}: G28 returns to the reference point, whose work"
        " coordinates are not known: 3 moves not drawn (also lines 10 and 13)"
    )
    title = next(t for t in root.iter(f"{SVG}text") if t.get("class") == "title")
    assert _text(title) == "g28.nc (XZ, 5 of 9 moves drawn)"
    # The start is marked as the start, not as a place where the path lost track.
    assert [
        e.get("data-line") for e in _elements(ET.tostring(root, encoding="unicode"), "lost")
    ] == [
        str(g28),
        "10",
        "13",
    ]


def test_a_move_not_drawn_is_put_down_to_the_latest_loss_of_its_axis() -> None:
    a, b, c = {"X": 10.0, "Z": 0.0}, {"X": 10.0, "Z": -5.0}, {"X": 20.0, "Z": -5.0}
    path = Toolpath(
        [
            Move("rapid", {}, a, 1, "O1"),  # from where the run began
            Move("feed", a, b, 2, "O1"),
            Move("rapid", b, {"Z": -5.0}, 3, "O1"),  # G53 X: X lost
            Move("rapid", {"Z": -5.0}, c, 4, "O1"),
            Move("rapid", c, {}, 5, "O1"),  # G28: both lost
            Move("rapid", {}, {"X": 20.0}, 6, "O1"),
            Move("rapid", {"X": 20.0, "Z": 3.0}, {"X": 30.0, "Z": 3.0}, 8, "O1"),  # placed again
            # The next run starts where the last ended, for all the analysis knows.
            Move("rapid", {}, {"X": 30.0, "Z": 3.0}, 1, "O2"),
        ],
        lost=[
            LostTrack(1, "O1", ("X", "Z"), UNKNOWN_START, at=0),
            LostTrack(3, "O1", ("X",), "G53 moves in machine coordinates", at=2),
            LostTrack(5, "O1", ("X", "Z"), "G28 returns to the reference point", at=4),
            LostTrack(7, "O1", (), "G75's passes are not drawn", at=6),
            LostTrack(1, "O2", ("X", "Z"), UNKNOWN_START, at=7),
        ],
        lathe=True,
        runs=[(0, 0), (7, 4)],
    )
    drawing = backplot(path)
    assert (drawing.drawn, drawing.total, drawing.before_start) == (2, 8, 2)
    assert drawing.start_axes == ("X", "Z")
    # The G53's own move and the next, which starts at an X not known; the G28's and the next.
    assert [(n.reason, n.sites, n.hidden) for n in drawing.notes] == [
        ("G53 moves in machine coordinates", (("", 3),), 2),
        ("G28 returns to the reference point", (("", 5),), 2),
        ("G75's passes are not drawn", (("", 7),), 0),
    ]


def test_the_depth_chart_draws_a_bar_for_each_pass_it_counts_on_a_scale(tmp_path: Path) -> None:
    """O5 cuts along an arc: its depth grows and falls again, and its first and last pass are
    at the depth it is measured from. Each of its 19 passes is a bar as high as the pass is
    deep, on a scale of depth ticks."""
    done = _plot(tmp_path, str(SEEDS / "o5_arc_thread_finishing.nc"), "-o", "-")
    assert done.returncode == 0, done.stderr
    root = _root(done.stdout)
    (view,) = _with(root, "data-view", "passes")
    title = next(t for t in view.iter(f"{SVG}text") if t.get("class") == "title")
    said = int(re.findall(r"(\d+) passes", _text(title))[0])
    assert said == 19 == int(view.get("data-passes", "0"))
    (chart,) = _with(view, "data-chart", "depth")
    bars = _with(chart, "data-kind", "cut")
    assert len(bars) == said == int(chart.get("data-bars", "0"))
    assert len({b.get("x") for b in bars}) == said  # side by side, none over another
    assert all(float(b.get("height", "0")) > 0 for b in bars)
    (ticks,) = _with(chart, "data-axis", "depth")
    labels = [
        (float(t.get("data-value", "nan")), float(t.get("y", "nan")))
        for t in ticks.iter(f"{SVG}text")
    ]
    values = [v for v, _ in labels]
    assert len(values) >= 3 and values[0] == 0 and values == sorted(values)
    # Evenly spaced, upwards; a bar's height is its depth on that scale.
    pixels = (labels[0][1] - labels[1][1]) / (values[1] - values[0])
    assert all(
        (y0 - y1) == pytest.approx(pixels * (v1 - v0), abs=0.02)
        for (v0, y0), (v1, y1) in itertools.pairwise(labels)
    )
    depths = [float(b.get("data-depth", "nan")) for b in bars]
    assert max(depths) == pytest.approx(6.081)
    assert values[-1] + values[1] > max(depths)  # the scale reaches the deepest bar
    for bar, depth in zip(bars, depths, strict=True):
        if depth:
            assert float(bar.get("height", "nan")) == pytest.approx(depth * pixels, abs=0.05)
    assert depths.count(0) == 2
    caption = " ".join(_text(t) for t in view.iter(f"{SVG}text") if t.get("class") == "note")
    assert "19 bars" in caption and "2 passes at depth 0: a flat mark" in caption


def _text_boxes(svg: str) -> tuple[list[tuple[float, float, float, float, str]], float]:
    """Each text's box by a simple estimate (0.6 em a character, 1 em a wide one; 0.8 em above
    the baseline, 0.2 below), and the drawing's width."""
    root = _root(svg)
    boxes = []
    for t in root.iter(f"{SVG}text"):
        text = _text(t)
        size = 14.0 if t.get("class") == "title" else 12.0
        width = sum(size if unicodedata.east_asian_width(ch) in "WF" else 0.6 * size for ch in text)
        anchor = t.get("text-anchor", "start")
        shift = {"start": 0.0, "middle": width / 2, "end": width}[anchor]
        turned = re.fullmatch(r"translate\((\S+) (\S+)\) rotate\(-90\)", t.get("transform", ""))
        if turned:  # read upwards: the text runs up from its place
            x, y = float(turned.group(1)), float(turned.group(2))
            boxes.append((x - 0.8 * size, y - width + shift, x + 0.2 * size, y + shift, text))
            continue
        x, y = float(t.get("x", "nan")) - shift, float(t.get("y", "nan"))
        boxes.append((x, y - 0.8 * size, x + width, y + 0.2 * size, text))
    return boxes, float(root.get("width", "nan"))


def test_no_label_overlaps_another_or_leaves_the_drawing(tmp_path: Path) -> None:
    long_name = tmp_path / (
        "a_plate_outline_with_a_name_longer_than_the_drawing_is_wide_" * 2 + ".nc"
    )
    long_name.write_text(MILL_OUTLINE, encoding="utf-8")
    files = [SEEDS / f"{name}.nc" for name in ("o2_arc_thread_roughing", "o4009_external_m50x3")]
    for path in [*files, long_name]:
        done = _plot(tmp_path, str(path), "-o", "-")
        assert done.returncode == 0, done.stderr
        boxes, width = _text_boxes(done.stdout)
        assert len(boxes) > 10
        for box in boxes:
            assert box[0] >= 0 and box[2] <= width, box
        for a, b in itertools.combinations(boxes, 2):
            overlap = a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]
            assert not overlap, (path.name, a, b)


def test_a_mill_program_read_as_a_lathe_is_drawn_in_xy_and_says_so(tmp_path: Path) -> None:
    outline = tmp_path / "outline.nc"
    outline.write_text(MILL_OUTLINE, encoding="utf-8")
    done = _plot(tmp_path, str(outline), "--controller", "0i-TF")
    assert done.returncode == 0, done.stderr
    root = _root((tmp_path / "outline.svg").read_text(encoding="utf-8"))
    assert [g.get("data-plane") for g in _with(root, "data-view", "toolpath")] == ["XY"]
    assert done.stderr.splitlines()[0] == (
        f"{outline}: drawn in XY: the path makes no move in XZ, a lathe's usual view (a mill's"
        " program? --controller 0i-MF); --plane chooses the view"
    )
    assert "moves drawn in XY" in done.stderr.splitlines()[-1]
    # With plunges in Z too, the outline goes further in XY than the plunges in XZ.
    pocket = tmp_path / "pocket.nc"
    blocks = MILL_OUTLINE.splitlines()
    blocks[3:3] = ["G00 Z2.", "G01 Z-3. F100."]
    pocket.write_text("\n".join([*blocks, ""]), encoding="utf-8")
    plunged = _plot(tmp_path, str(pocket), "--controller", "0i-TF")
    assert plunged.returncode == 0, plunged.stderr
    assert "drawn in XY: the path goes further in XY than in XZ" in plunged.stderr
    # The default, 0i-F, reads it as the mill its Y moves show: XY, nothing to say.
    default = _plot(tmp_path, str(pocket))
    assert default.returncode == 0, default.stderr
    assert "drawn in XY:" not in default.stderr and "moves drawn in XY" in default.stderr
    # On a mill, XY is the usual view: nothing to say about it.
    milled = _plot(tmp_path, str(pocket), "--controller", "0i-MF")
    assert milled.returncode == 0, milled.stderr
    assert "drawn in XY:" not in milled.stderr and "moves drawn in XY" in milled.stderr
    # A lathe's program stays in XZ.
    turned = _plot(tmp_path, str(SEEDS / "o1_radial_layers.nc"), "-o", "-")
    assert [g.get("data-plane") for g in _with(_root(turned.stdout), "data-view", "toolpath")] == [
        "XZ"
    ]
    assert [line for line in turned.stderr.splitlines() if ": drawn in" in line] == []


def test_a_plane_asked_for_without_moves_names_the_planes_that_have_some(tmp_path: Path) -> None:
    outline = tmp_path / "outline.nc"
    outline.write_text(MILL_OUTLINE, encoding="utf-8")
    done = _plot(tmp_path, str(outline), "--plane", "YZ")
    assert done.returncode == 2
    assert done.stderr == (
        f"fanuc-macro: {outline}: no move of the trace has a known Y and Z: nothing to plot in"
        " YZ; the path has moves in XY (--plane XY)\n"
    )
    assert not (tmp_path / "outline.svg").exists()


def test_names_in_the_drawing_cannot_become_attributes() -> None:
    hostile = 'O<A" onfocus="x">'
    a, b = {"X": 50.0, "Z": 0.0}, {"X": 50.0, "Z": -20.0}
    path = Toolpath(
        [Move("thread", a, b, 0, hostile, uri='B" onload="y.nc')],
        lost=[LostTrack(0, hostile, ("Z",), 'why" onclick="z', 'C" onmouseover="w.nc', at=1)],
        lathe=True,
    )
    maps = [PassMap('T" onblur="v', hostile, False, (PassMark(0, 49.0, 5.0),))]
    svg = plot_svg(path, passes=maps, title=hostile, main_uri="main.nc")
    root = _root(svg)
    names = [name for e in root.iter() for name in e.attrib]
    assert names and not [n for n in names if n.lower().startswith("on")]
    assert {e.get("data-program") for e in _with(root, "data-program")} == {hostile}
    assert {e.get("data-path") for e in _with(root, "data-path")} == {
        'B" onload="y.nc',
        'C" onmouseover="w.nc',
    }


def test_each_program_run_starts_unknown_not_lost_by_the_run_before(tmp_path: Path) -> None:
    """A file of two programs is two runs: the second's first move starts before its first
    absolute position, whatever the first run's last G28 did."""
    program = tmp_path / "two.nc"
    program.write_text(
        "%\nO0001\nG00 X50. Z2.\nG01 Z-20. F0.2\nG28 U0. W0.\nM30\n%\n"
        "O0002\nG00 X40. Z2.\nG01 Z-10.\nM30\n%\n",
        encoding="utf-8",
    )
    done = _plot(tmp_path, str(program))
    assert done.returncode == 0, done.stderr
    assert done.stderr.splitlines() == [
        "two.svg: 2 of 4 moves drawn in XZ (feed 2, rapid 2); 2 not drawn: they start before the"
        " first absolute X and Z (the tool's place at the start is not known)"
    ]
