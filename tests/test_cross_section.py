"""The cross-section a thread's passes cut, against closed forms and the seed paper's numbers,
and the verdicts read from it (MB817-MB821) through the CLI and the language server."""

from __future__ import annotations

import bisect
import json
import math
import random
import re
import subprocess
import sys
from pathlib import Path

import pytest
from lsprotocol import types
from pytest_lsp import LanguageClient

from fanuc_macro.analysis import analyse
from fanuc_macro.evaluator.facts import Motion
from fanuc_macro.rules import thread_cut, threading
from fanuc_macro.threads.cross_section import ToolShape, cut_cross_section
from test_lsp import client, codes, diagnostics, hover, open_text, start

__all__ = ["client"]  # the fixture, imported for the tests here

ROOT = Path(__file__).resolve().parent.parent
SEEDS = ROOT / "tests" / "fixtures" / "seeds"
SIN60 = math.sqrt(3.0) / 2.0


def _pass(
    x: float, start_z: float = 5.0, code: str = "G92", tool_angle: float | None = None
) -> Motion:
    return Motion(
        "O1", 3, code, {"X": x, "F": 2.0}, x=x, z=-30.0, start_z=start_z, tool_angle=tool_angle
    )


@pytest.mark.parametrize("internal", [False, True])
@pytest.mark.parametrize("radius", [0.0, 0.1, 0.25])
@pytest.mark.parametrize("pitch", [1.0, 2.0, 3.5])
def test_one_v_cut_has_the_pitch_diameter_of_the_closed_form(
    internal: bool, radius: float, pitch: float
) -> None:
    # A V of 60° whose rounded tip is at X: d2 = X − 2r + H outside, D2 = X + 2r − H inside
    # (the virtual sharp apex lies r below the tip), once the groove is deeper than H/2.
    big_h = SIN60 * pitch
    x = 40.0 if not internal else 30.0
    blank = x + 2.2 * big_h if not internal else x - 2.2 * big_h
    cut = cut_cross_section([_pass(x)], pitch, internal, blank, ToolShape(60.0, radius))
    assert cut is not None
    expected = x + 2.0 * radius - big_h if internal else x - 2.0 * radius + big_h
    assert cut.pitch_diameter == pytest.approx(expected, abs=1e-9)
    assert cut.root_diameter == pytest.approx(x, abs=1e-9)


def test_a_sharp_v_removes_the_triangle_it_makes() -> None:
    depth = 1.2  # radius
    cut = cut_cross_section([_pass(50.0 - 2 * depth)], 4.0, False, 50.0, ToolShape(60.0, 0.0))
    assert cut is not None
    assert cut.area == pytest.approx(depth * depth * math.tan(math.radians(30.0)), rel=1e-12)


def test_passes_above_the_blank_are_in_the_air_and_spring_passes_remove_nothing() -> None:
    passes = [_pass(x) for x in (21.0, 20.4, 19.6, 19.0, 18.6, 18.6)]
    cut = cut_cross_section(passes, 2.0, False, 20.0, ToolShape(60.0, 0.25))
    assert cut is not None
    assert [c.index for c in cut.in_the_air()] == [0, 1]
    assert cut.cuts[-1].area == 0.0
    deciding = cut.deciding()
    assert deciding is not None and deciding.index == 4
    assert sum(c.area for c in cut.cuts) == pytest.approx(cut.area)


def test_the_second_start_of_a_two_start_thread_makes_it_a_thread_of_half_the_lead() -> None:
    # Lead 3, pitch 1.5: the second start's passes one pitch along give the profile of a
    # one-start thread of pitch 1.5, over one lead.
    xs = (19.2, 18.6, 18.2)
    two = [_pass(x, 5.0) for x in xs] + [_pass(x, 6.5) for x in xs]
    one = [_pass(x, 5.0) for x in xs]
    tool = ToolShape(60.0, 0.2)
    cut_two = cut_cross_section(two, 3.0, False, 20.0, tool)
    cut_one = cut_cross_section(one, 1.5, False, 20.0, tool)
    assert cut_two is not None and cut_one is not None
    assert cut_two.pitch_diameter == pytest.approx(cut_one.pitch_diameter, abs=1e-9)
    only_one_start = cut_cross_section(one, 3.0, False, 20.0, tool)
    assert only_one_start is not None and only_one_start.pitch_diameter > 19.9


def test_g76_passes_step_along_the_flank_by_their_tool_angle() -> None:
    # With a = 60 and a 60° insert every pass's leading flank lies on the last one's: the cut
    # is the last pass's V. A cycle told a = 80 shifts the passes further than the flank and
    # widens the groove: the pitch diameter comes out smaller.
    xs = (19.4, 19.0, 18.7, 18.45, 18.3, 18.3)

    def g76(angle: float) -> list[Motion]:
        passes = [_pass(x, code="G76", tool_angle=angle) for x in xs]
        for n, m in enumerate(passes, 1):
            m.cycle_pass = n  # the cycle's own passes
        return passes

    tool = ToolShape(60.0, 0.2)
    radial = cut_cross_section([_pass(x) for x in xs], 1.5, False, 20.0, tool)
    flank = cut_cross_section(g76(60.0), 1.5, False, 20.0, tool)
    wide = cut_cross_section(g76(80.0), 1.5, False, 20.0, tool)
    assert radial is not None and flank is not None and wide is not None
    assert flank.pitch_diameter == pytest.approx(radial.pitch_diameter, abs=1e-9)
    assert wide.pitch_diameter < radial.pitch_diameter - 0.02


def _trace_threads(path: Path) -> list[dict[str, object]]:
    done = subprocess.run(
        [sys.executable, "-m", "fanuc_macro.cli", "trace", "--format", "json", str(path)],
        capture_output=True,
        text=True,
        check=True,
        env={"PYTHONPATH": str(ROOT / "server"), "PATH": "/usr/bin:/bin"},
    )
    threads = json.loads(done.stdout)["summary"]["threads"]
    assert isinstance(threads, list)
    return threads


@pytest.mark.parametrize(
    ("seed", "pitch_diameter", "limits"),
    [
        # Seed paper 000's module cuts the middle of the class: d2 basic − es − Td2/2.
        ("o4009_external_m50x3.nc", 47.918, (47.833, 48.003)),
        ("o4010_internal_m50x3.nc", 48.141, (48.051, 48.231)),
    ],
)
def test_the_trace_gives_the_seed_modules_pitch_diameters(
    seed: str, pitch_diameter: float, limits: tuple[float, float]
) -> None:
    (thread,) = _trace_threads(SEEDS / seed)
    assert thread["thread"] in ("M50x3-5g6g", "M50x3-4H5H")
    assert "designation" in str(thread["known_from"])
    cut = thread["cut"]
    assert isinstance(cut, dict)
    assert cut["pitch_diameter"][0] == pytest.approx(pitch_diameter, abs=0.003)
    assert cut["limits"] == pytest.approx(list(limits), abs=0.001)
    assert cut["verdict"] == "within" and cut["passes_in_air"] == 0
    largest = cut["largest_pass"]
    assert largest["area"] > 0 and largest["line"] > 0


def test_a_thread_not_identified_says_why_in_the_trace(tmp_path: Path) -> None:
    path = tmp_path / "plain.nc"
    path.write_text("O1\nG97 S500 M03\nG00 X22. Z5.\nG92 X19. Z-20. F2.\nX18.\nM30\n", "utf-8")
    (thread,) = _trace_threads(path)
    assert thread["identified"] is False and "cut" not in thread
    assert "size is not known" in str(thread["why_not"])


# MB808's example, its height's es term mended (es/2), with a variable of the running depth
# (#5) that a shape reader could take for the height: the passes cut the class's middle.
MB808_RIGHT = (
    re.search(r"```nc\n(.*?)```", threading.MB808_DOC.example, re.S)
    .group(1)  # type: ignore[union-attr]
    .replace("#103*2.", "#103/2.")
    .replace("#9=0.15\n", "#5=0.35\n#9=0.15\n", 1)
)


def test_a_height_formula_is_reported_only_as_the_cause_of_a_cut_out_of_class() -> None:
    assert "#5=0.35" in MB808_RIGHT and "#103/2." in MB808_RIGHT
    right = analyse(MB808_RIGHT, "right.nc")
    assert not {d.code for d in right.diagnostics} & {"MB808", "MB817", "MB801"}
    # The height taken ×2 for es: the last pass goes too deep, the cut is past the class.
    wrong = analyse(MB808_RIGHT.replace("#103/2.", "#103*2."), "wrong.nc")
    found = {d.code: d for d in wrong.diagnostics}
    assert "MB808" in found and "the passes cut a pitch diameter of" in found["MB808"].message
    assert "MB817" not in found  # the formula is named as the cause


def test_a_clamp_that_holds_every_pass_at_one_speed_is_no_g96_thread() -> None:
    text = (
        "O1 (M24X2-6G)\nG50 S1200\nG96 S150 M03\nG00 X26. Z5.\nG92 X23.3 Z-30. F2.\n"
        "X22.8\nX22.4\nX22.\nX21.7\nX21.6\nG00 X100. Z100.\nM30\n"
    )
    assert "MB820" not in {d.code for d in analyse(text, "clamped.nc").diagnostics}
    unclamped = text.replace("G50 S1200\n", "G50 S3000\n")
    assert "MB820" in {d.code for d in analyse(unclamped, "unclamped.nc").diagnostics}


# MB817's example: an M20x2.5-6g cut to X17.3, too shallow for its class.
SHALLOW = re.search(r"```nc\n(.*?)```", thread_cut.MB817_DOC.example, re.S).group(1)  # type: ignore[union-attr]


async def test_the_editor_shows_the_cut_and_withdraws_the_verdict_when_mended(
    client: LanguageClient,
) -> None:
    await start(client, None)
    uri = "untitled:shallow.nc"
    open_text(client, uri, SHALLOW)
    found = await diagnostics(client, uri, lambda d: "MB817" in codes(d))
    verdict = next(d for d in found if d.code == "MB817")
    assert verdict.range.start.line == 8 and "above d2 max 18.334" in verdict.message
    text = await hover(client, uri, 8, 1)
    assert "the cut (nose radius 0.3125–0.3600" in text and "too shallow for" in text
    mended = SHALLOW.replace("X17.3\n", "X17.3\nX17.\nX16.8\n")
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=2),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=mended)],
        )
    )
    await diagnostics(client, uri, lambda d: "MB817" not in codes(d))
    assert "within 18.164–18.334" in await hover(client, uri, 10, 1)


def test_the_plot_draws_the_cut_and_the_class_limits(tmp_path: Path) -> None:
    svg = tmp_path / "o4009.svg"
    subprocess.run(
        [
            sys.executable,
            "-m",
            "fanuc_macro.cli",
            "plot",
            str(SEEDS / "o4009_external_m50x3.nc"),
            "-o",
            str(svg),
        ],
        capture_output=True,
        text=True,
        check=True,
        env={"PYTHONPATH": str(ROOT / "server"), "PATH": "/usr/bin:/bin"},
    )
    drawing = svg.read_text("utf-8")
    assert drawing.count('data-kind="cut-profile"') == 1
    assert 'data-diameter="47.833"' in drawing and 'data-diameter="48.003"' in drawing
    assert "blue: the groove the passes cut" in drawing


PLAIN = ROOT / "tests" / "fixtures" / "thread_cut_variants" / "g92_plain_clean.nc"


def test_the_trace_says_the_blank_the_program_turned() -> None:
    (thread,) = _trace_threads(PLAIN)
    assert thread["identified"] is False  # no designation: cut on what was turned
    cut = thread["cut"]
    assert isinstance(cut, dict)
    assert cut["blank"] == 23.8 and cut["blank_from"] == "the diameter turned at line 13"
    assert cut["crest_diameter"] == 23.8 and cut["passes_in_air"] == 0


async def test_the_editor_shows_the_turned_blank_and_the_passes_in_the_air(
    client: LanguageClient,
) -> None:
    await start(client, None)
    uri = "untitled:plain.nc"
    text = PLAIN.read_text("utf-8")
    open_text(client, uri, text)
    await diagnostics(client, uri, lambda d: True)
    shown = await hover(client, uri, 19, 1)  # the first G92 pass
    assert "blank 23.800 (the diameter turned at line 13)" in shown
    air = text.replace("G92 X23.3 Z-32. F2.\n", "G92 X26. Z-32. F2.\nX25.2\nX24.4\nX23.3\n")
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=2),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=air)],
        )
    )
    found = await diagnostics(client, uri, lambda d: "MB818" in codes(d))
    (verdict,) = [d for d in found if d.code == "MB818"]
    assert verdict.range.start.line == 19
    assert "outside the blank X23.8 (the diameter turned at line 13)" in verdict.message


def _random_cuts(seed: int) -> list[tuple[list[str], list[str], list[str]]]:
    """Many passes at scattered places and depths on profiles of several tools: each profile's
    vertices and the passes' areas, exactly (as hex)."""
    from fanuc_macro.threads.cross_section import _Profile

    rng = random.Random(seed)
    found = []
    for lead, angle, radius in [(3.0, 60.0, 0.375), (1.5, 55.0, 0.0), (2.0, 0.0, 0.3)]:
        profile = _Profile(lead, 25.0, *ToolShape(angle, radius).edge())
        areas = []
        for k in range(150):
            place = rng.random() * lead if k % 3 else (k * 0.37 * lead) % lead
            areas.append(profile.cut(place, 25.0 - 0.6 * lead * rng.random() ** 0.5).hex())
        found.append((areas, [u.hex() for u in profile.places], [v.hex() for v in profile.values]))
    return found


@pytest.mark.parametrize("seed", [1, 2])
def test_the_walk_that_copies_untouched_stretches_cuts_what_the_whole_walk_cuts(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    from fanuc_macro.threads import cross_section

    quick = _random_cuts(seed)

    # Every position walked one by one and its edge value worked out: the plain walk.
    def everything(self: object, pu: list[float], *_: object) -> tuple[list[int], set[int]]:
        return list(range(len(pu))), set(range(-1, len(pu) + 1))

    monkeypatch.setattr(cross_section._Profile, "_walked", everything)
    assert quick == _random_cuts(seed)


def _profile_at(places: list[float], values: list[float], u: float) -> float:
    k = min(max(bisect.bisect_right(places, u), 1), len(places) - 1)
    u0, u1 = places[k - 1], places[k]
    if u1 == u0:
        return values[k]
    return values[k - 1] + (values[k] - values[k - 1]) * (u - u0) / (u1 - u0)


@pytest.mark.parametrize("seed", [3, 4])
def test_a_window_narrowed_to_the_crest_near_the_pass_cuts_what_the_whole_reach_cuts(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A pass's window reaches as far as its edge may go below the highest the profile comes
    near it, not its highest anywhere: the same areas and the same profile (to rounding) as
    windows as wide as the profile's highest point allows."""
    from fanuc_macro.threads import cross_section

    def cuts() -> list[tuple[list[float], list[float], list[float]]]:
        rng = random.Random(seed)
        found = []
        for lead, angle, radius in [(3.0, 60.0, 0.375), (1.5, 55.0, 0.0), (2.0, 0.0, 0.3)]:
            profile = cross_section._Profile(lead, 25.0, *ToolShape(angle, radius).edge())
            areas = []
            # Deep passes at scattered places first, as a long job's, then shallower ones.
            for k in range(300):
                depth = 0.6 * lead * (1.0 - k / 400.0) * rng.random() ** 0.3
                areas.append(profile.cut(rng.random() * lead, 25.0 - depth))
            found.append((areas, list(profile.places), list(profile.values)))
        return found

    narrowed = cuts()
    monkeypatch.setattr(cross_section._Profile, "_highest_within", lambda *_: math.inf)
    wide = cuts()
    for (areas, places, values), (w_areas, w_places, w_values) in zip(narrowed, wide, strict=True):
        assert areas == pytest.approx(w_areas, rel=1e-9, abs=1e-12)
        assert sum(1 for a in areas if a == 0.0) > 10  # passes the narrowed window skips
        for u in sorted({*places, *w_places}):
            here = _profile_at(places, values, u)
            assert here == pytest.approx(_profile_at(w_places, w_values, u), abs=1e-9)


def _half_by_halving(places: list[float], values: list[float], lead: float) -> float:
    """The pitch line by bisection of the measure below a level: the reference."""

    def below(level: float) -> float:
        total = 0.0
        for u0, u1, v0, v1 in zip(places, places[1:], values, values[1:], strict=False):
            low, high = min(v0, v1), max(v0, v1)
            if level >= high:
                total += u1 - u0
            elif level > low:
                total += (u1 - u0) * (level - low) / (high - low)
        return total

    lo, hi = min(values), max(values)
    for _ in range(60):
        mid = (lo + hi) / 2.0
        lo, hi = (mid, hi) if below(mid) < lead / 2.0 else (lo, mid)
    return (lo + hi) / 2.0


@pytest.mark.parametrize("seed", [5, 6, 7])
def test_the_pitch_line_is_where_the_measure_below_reaches_half_the_lead(seed: int) -> None:
    from fanuc_macro.threads import cross_section

    rng = random.Random(seed)
    for lead, angle, radius in [(3.0, 60.0, 0.375), (1.5, 55.0, 0.0), (2.0, 0.0, 0.3)]:
        profile = cross_section._Profile(lead, 25.0, *ToolShape(angle, radius).edge())
        for k in range(1, 60):
            profile.cut(rng.random() * lead, 25.0 - 0.6 * lead * rng.random() ** 0.5)
            if k % 7 == 0:
                want = _half_by_halving(profile.places, profile.values, lead)
                assert profile.half_measure() == pytest.approx(want, abs=1e-9)
    # A profile of level stretches: the measure jumps at a level, which is the pitch line.
    steps = cross_section._Profile(2.0, 5.0, *ToolShape(60.0, 0.0).edge())
    steps.places, steps.values = [0.0, 0.5, 0.5, 2.0], [4.0, 4.0, 5.0, 5.0]
    assert steps.half_measure() == 5.0
    steps.values = [4.0, 4.0, 5.0, 5.0]
    steps.places = [0.0, 1.5, 1.5, 2.0]
    assert steps.half_measure() == 4.0
