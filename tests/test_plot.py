"""The SVG backplot (ide/plot.py) drawn from toolpaths made by hand: what it draws, where, and
with which links to the source."""

from __future__ import annotations

import itertools
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from collections import Counter
from pathlib import Path

import pytest

from fanuc_macro.evaluator.toolpath import LostTrack, Move, Toolpath
from fanuc_macro.ide.plot import MAX_PASS_MAPS, NothingToPlot, PassMap, PassMark, plot_svg

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
    assert re.search(r"\[data-kind=rapid\]\{[^}]*stroke-dasharray", style.text)
    assert re.search(r"\[data-kind=thread\]\{stroke:#[0-9a-f]{6}", style.text)


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
    assert "lost track of X, Z" in done.stderr  # no start position before the first move


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
