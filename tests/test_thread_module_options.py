"""The symmetric thread module's extensions (seed 000, "参数调整方法"): flank infeed, taper,
multi-start and left-hand threads.

Every check here is made on the passes the evaluator runs from the generated text: where each
G92 starts and ends, its X and R, against the geometry of the thread asked for.  The module
without options is the paper's text (tests/test_thread_generator.py holds its numbers).
"""

from __future__ import annotations

import itertools
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.cli.thread import INFEED_CHOICES
from fanuc_macro.evaluator import Motion
from fanuc_macro.generators.thread_generator import (
    INFEEDS,
    ThreadModule,
    build_module,
    generate_module,
)
from fanuc_macro.rules.threading import EPS

ROOT = Path(__file__).resolve().parent.parent
URI = "test:module-options.nc"
LENGTH = 30.0
DESIGNATIONS = ("M24x2-6g", "M50x3-6H", "M24xPh4P2-6g", "M20x2-6g-LH", "M24xPh6P2-6H-LH")


def g92(module: ThreadModule) -> list[Motion]:
    analysis = analyse(module.text, URI)
    assert analysis.facts is not None and analysis.facts.stopped is None
    return [m for m in analysis.facts.motions if m.code == "G92"]


def lines_with(module: ThreadModule, comment: str) -> set[int]:
    return {n for n, text in enumerate(module.lines) if f"({comment}" in text}


def run_in(lead: float, length: float) -> float:
    """delta1 of the paper's sub-program: 2 P + P + FIX[L/P] P - L, with the lead for P."""
    return 3.0 * lead + math.floor(length / lead) * lead - length


def end_z(m: Motion, passes: list[Motion]) -> float:
    """The Z a pass ends at; a block that repeats the cycle with X alone keeps the Z in force."""
    if "W" in m.words or "Z" in m.words:
        assert m.z is not None
        return m.z
    before = passes[passes.index(m) - 1]
    return end_z(before, passes)


def taper_r(m: Motion, passes: list[Motion]) -> float:
    if "R" in m.words:
        return m.words["R"]
    return taper_r(passes[passes.index(m) - 1], passes)


@pytest.mark.parametrize(
    ("designation", "infeed", "taper"),
    list(itertools.product(DESIGNATIONS, INFEEDS, (0.0, 1.0 / 16.0, -1.0 / 32.0))),
)
def test_every_option_runs_and_checks_clean(designation: str, infeed: str, taper: float) -> None:
    module = build_module(designation, LENGTH, infeed=infeed, taper=taper)
    analysis = analyse(module.text, URI)
    found = [(d.code, d.line + 1, d.message) for d in analysis.diagnostics]
    assert found == []
    assert module.rough_passes > 10
    for line in module.lines:
        assert line.isascii() and len(line) < 128, line


def test_no_option_is_the_papers_module() -> None:
    for designation in ("M50x3-5g6g", "M50x3-6H"):
        plain = generate_module(designation, 40)
        assert generate_module(designation, 40, infeed="symmetric", taper=0.0) == plain
        assert "#105" not in plain and "#106" not in plain and "WHILE" not in plain


@pytest.mark.parametrize("infeed", list(INFEEDS))
def test_the_infeed_picks_the_flank_of_each_rough_pass(infeed: str) -> None:
    module = build_module("M50x3-5g6g", 40, infeed=infeed)
    passes = g92(module)
    cut_lines = lines_with(module, "CUT)")
    rough = [m for m in passes if m.line in cut_lines]
    straight = next(m for m in passes if m.line in lines_with(module, "STRAIGHT INFEED ROUGH"))
    assert straight.start_z is not None
    # Where each rough pass starts along Z against the straight passes' start: -u or +u.
    offsets = [m.start_z - straight.start_z for m in rough if m.start_z is not None]
    assert len(offsets) == len(rough)
    u = abs(offsets[0])
    assert u == pytest.approx(module.first_offset, abs=0.001)
    signs = [math.copysign(1.0, o) for o in offsets if abs(o) > 0.002]
    if infeed == "symmetric":
        assert len(rough) == 2 * module.rough_passes
        assert signs[:4] == [-1.0, 1.0, -1.0, 1.0]
    elif infeed == "alternate":
        assert len(rough) == module.rough_passes
        assert signs[:4] == [-1.0, 1.0, -1.0, 1.0]
    else:
        assert len(rough) == module.rough_passes
        assert set(signs) == {-1.0 if infeed == "left" else 1.0}
    # Every depth is deeper than the one before, down to the straight passes.
    xs = [m.x for m in rough if m.x is not None]
    step = 2 if infeed == "symmetric" else 1
    assert all(b < a for a, b in itertools.pairwise(xs[::step]))
    assert straight.x is not None and straight.x < xs[-1] - EPS


def test_a_one_flank_module_cuts_the_same_thread_as_the_papers() -> None:
    paper = build_module("M24x2-6g", LENGTH)
    for infeed in ("alternate", "left", "right"):
        module = build_module("M24x2-6g", LENGTH, infeed=infeed)
        assert module.final_x == paper.final_x
        assert module.height == paper.height
        # Half the cuts: one per rough pass, where the paper makes two.
        assert module.g92_cuts < paper.g92_cuts


@pytest.mark.parametrize(("designation", "internal"), [("M24x2-6g", False), ("M24x2-6H", True)])
@pytest.mark.parametrize("infeed", ["symmetric", "left"])
def test_a_taper_cuts_every_pass_along_the_cone(
    designation: str, internal: bool, infeed: str
) -> None:
    taper = 1.0 / 16.0
    module = build_module(designation, LENGTH, infeed=infeed, taper=taper)
    assert f"#106={taper:g}" in module.text
    passes = g92(module)
    lead, pitch = 2.0, 2.0
    delta2 = lead
    # The cone's diameter at z: the nominal (external) or minor (internal) at Z0, growing
    # toward -Z for an external thread and shrinking for an internal one.
    minor = 24.0 - 2.0 * 5.0 / 8.0 * math.sin(math.radians(60.0)) * pitch
    reference = minor if internal else 24.0
    grows = -1.0 if internal else 1.0

    def cone(z: float) -> float:
        return reference + grows * taper * -z

    depth_sign = 1.0 if internal else -1.0
    for m in passes:
        z = end_z(m, passes)
        assert m.x is not None and m.start_z is not None
        # R is the radius at the cut's start less the one at its end: the cut follows the cone.
        r = taper_r(m, passes)
        assert r == pytest.approx((cone(m.start_z) - cone(z)) / 2.0, abs=0.001)
        # Each pass's depth is measured from the cone where it ends.
        depth = depth_sign * (m.x - cone(z)) / 2.0
        assert 0.0 < depth <= module.height + 0.001
    last = passes[-1]
    assert last.x is not None
    assert end_z(last, passes) == pytest.approx(-LENGTH - delta2)
    assert depth_sign * (last.x - cone(-LENGTH - delta2)) / 2.0 == pytest.approx(
        module.height, abs=0.001
    )
    assert module.final_x == pytest.approx(last.x, abs=EPS)  # as the control rounds it
    assert f"X{last.words['X']:.3f} Z{-LENGTH - delta2:.3f}" in module.call_line()


@pytest.mark.parametrize("designation", ["M24xPh4P2-6g", "M24xPh6P2-6H"])
def test_each_start_is_one_pitch_further_and_ends_where_the_first_does(designation: str) -> None:
    module = build_module(designation, LENGTH)
    starts = 2 if "Ph4" in designation else 3
    lead, pitch = 2.0 * starts, 2.0
    single = build_module(designation.replace(f"Ph{starts * 2}P2", "2"), LENGTH)
    # The depth comes from the pitch, not the lead: the same thread height and final X.
    assert module.height == single.height
    assert module.final_x == single.final_x
    passes = g92(module)
    assert {m.words["F"] for m in passes} == {lead}
    assert len(passes) == starts * single.g92_cuts
    per_start = len(passes) // starts
    firsts = [passes[n * per_start] for n in range(starts)]
    first_z = [m.start_z for m in firsts]
    assert all(z is not None for z in first_z)
    for n, z in enumerate(first_z):
        assert z == pytest.approx(first_z[0] + n * pitch)  # type: ignore[operator]
    # Every start's straight passes (the rough passes step along Z by u) end at the same Z,
    # past the thread by the run-out delta2 (the lead).
    straight = [m for m in passes if m.line not in lines_with(module, "CUT)")]
    assert len(straight) == starts * (len(passes) // starts - 2 * single.rough_passes)
    assert {round(end_z(m, passes), 6) for m in straight} == {round(-LENGTH - lead, 6)}
    assert f"{starts} STARTS OF {per_start} G92 CUTS" in module.call_line()
    # The run-in is the paper's formula with the lead.
    delta1 = run_in(lead, LENGTH)
    assert firsts[0].start_z == pytest.approx(delta1 - module.first_offset, abs=0.001)


@pytest.mark.parametrize("designation", ["M20x2-6g-LH", "M20x2-6H-LH"])
def test_a_left_hand_thread_is_cut_toward_plus_z(designation: str) -> None:
    module = build_module(designation, LENGTH)
    right = build_module(designation.removesuffix("-LH"), LENGTH)
    assert module.final_x == right.final_x and module.g92_cuts == right.g92_cuts
    assert "M03" in module.text and "LEFT HAND" in module.text
    passes = g92(module)
    lead = 2.0
    cuts = lines_with(module, "CUT)")
    for m in passes:
        assert m.start_z is not None
        assert end_z(m, passes) > m.start_z  # toward +Z
        if m.line not in cuts:  # the straight passes: the rough ones step along Z by u
            assert end_z(m, passes) == pytest.approx(lead)  # the run-out past Z0
    straight = next(m for m in passes if m.line in lines_with(module, "STRAIGHT INFEED ROUGH"))
    assert straight.start_z == pytest.approx(-LENGTH - run_in(lead, LENGTH))


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"infeed": "both"}, "infeed both is not one of"),
        ({"taper": 0.6}, "taper 0.6"),
        ({"taper": math.nan}, "taper nan"),
    ],
)
def test_option_refusals(kwargs: dict[str, object], fragment: str) -> None:
    with pytest.raises(ValueError, match=fragment):
        build_module("M24x2-6g", LENGTH, **kwargs)  # type: ignore[arg-type]


def cli(*args: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "server")}
    command = [sys.executable, "-m", "fanuc_macro.cli", *args]
    return subprocess.run(command, capture_output=True, text=True, env=env, timeout=120)


def test_the_command_line_offers_every_infeed() -> None:
    assert tuple(INFEEDS) == INFEED_CHOICES


def test_the_command_line_takes_the_options(tmp_path: Path) -> None:
    done = cli(
        "thread", "M24xPh4P2-6g-LH", "--length", "30", "--infeed", "alternate", "--taper", "1:16"
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout == generate_module(
        "M24xPh4P2-6g-LH", 30, infeed="alternate", taper=1.0 / 16.0
    )
    path = tmp_path / "module.nc"
    path.write_text(done.stdout, encoding="utf-8")
    checked = cli("check", str(path))
    assert checked.returncode == 0 and checked.stdout == "", checked.stdout
    flipped = cli("thread", "M24x2-6g", "--length", "30", "--taper=-1:16")
    assert flipped.returncode == 0 and "#106=-0.0625" in flipped.stdout


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (("--taper", "1:x"), "the taper is a ratio or a number (e.g. 1:16"),
        (("--taper", "0.7"), "taper 0.7"),
        (("--infeed", "both"), "invalid choice: 'both'"),
        (("--td2", "0.12345"), "Td2/TD2 0.12345 has more than 4 decimals"),
    ],
)
def test_the_command_line_refuses_bad_options(args: tuple[str, ...], fragment: str) -> None:
    done = cli("thread", "M24x2-6g", "--length", "30", *args)
    assert done.returncode == 2
    assert done.stdout == ""
    assert fragment in done.stderr


TAPER_PASSES = """O1200 (TAPER THREAD 1:16)
G97 S500 M03
G00 X32. Z5.
G92 X29.6 W-40. R-1.25 F2.
X29.4
G00 Z3.
G92 X{shifted} W-40. R-1.25 F2.
G00 Z5.
G92 X29.2 W-40. R-1.25 F2.
X29.
G00 X100. Z100.
M30
"""


def test_taper_passes_moved_along_z_compare_on_the_cone() -> None:
    # Started 2 mm further left, the pass ends where the cone is 0.125 mm larger: X29.505 is
    # 0.01 mm deeper than X29.4 on the cone, though a larger X.
    deeper = analyse(TAPER_PASSES.format(shifted="29.505"), URI)
    assert [d for d in deeper.diagnostics if d.code == "MB803"] == []
    shallower = analyse(TAPER_PASSES.format(shifted="29.55"), URI)
    found = [d for d in shallower.diagnostics if d.code == "MB803"]
    assert len(found) == 1 and found[0].line == 6
    assert "0.013 mm shallower" in found[0].message


def test_a_repeated_taper_cycle_keeps_its_end_z_and_r(tmp_path: Path) -> None:
    # "X29.4" repeats the G92 above it: the control cuts the same cone to the same Z.
    path = tmp_path / "taper.nc"
    path.write_text(TAPER_PASSES.format(shifted="29.3"), encoding="utf-8")
    done = cli("trace", str(path), "--format", "json")
    assert done.returncode == 0, done.stderr
    cuts = [m for m in json.loads(done.stdout)["motions"] if m["code"] == "G92"]
    repeat = next(m for m in cuts if m["line"] == 5)
    assert repeat["words"] == {"X": 29.4, "F": 2.0, "R": -1.25}
    thread = next(move for move in repeat["moves"] if move["kind"] == "thread")
    assert thread["start"] == {"X": pytest.approx(26.9), "Z": 5.0}
    assert thread["end"] == {"X": 29.4, "Z": pytest.approx(-35.0)}
