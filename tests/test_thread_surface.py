"""The surface a program turns for its thread, taper pipe designations, and the round tool's
reach past a traced profile: the blank of the cut (threads/surface.py), ISO 7-1 and NPT
(threads/pipe.py), and MB824's measure (cross_section.penetration)."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.threads.cross_section import (
    ToolShape,
    cut_cross_section,
    penetration,
    thread_cuts,
)
from fanuc_macro.threads.identify import Thread
from fanuc_macro.threads.pipe import pipe_threads

VARIANTS = Path(__file__).resolve().parent / "fixtures" / "thread_cut_variants"


def _only_thread(name: str) -> Thread:
    path = VARIANTS / name
    threads = analyse(path.read_text("utf-8"), path.as_uri()).threads
    assert len(threads) == 1
    return threads[0]


@pytest.mark.parametrize(
    ("text", "standard", "kind", "size", "pitch"),
    [
        ("NIPPLE R1/2 ISO 7-1", "ISO 7-1", "R", Fraction(1, 2), 25.4 / 14),
        ("SOCKET Rc 3/4", "ISO 7-1", "Rc", Fraction(3, 4), 25.4 / 14),
        ("RP1", "ISO 7-1", "Rp", Fraction(1), 25.4 / 11),
        ("PT1/4", "ISO 7-1", "R", Fraction(1, 4), 25.4 / 19),
        ("1/2 NPT", "NPT", "NPT", Fraction(1, 2), 25.4 / 14),
        ('3/4"NPT', "NPT", "NPT", Fraction(3, 4), 25.4 / 14),
        ("1-1/4 NPT", "NPT", "NPT", Fraction(5, 4), 25.4 / 11.5),
        ("1/2-14 NPTF", "NPT", "NPT", Fraction(1, 2), 25.4 / 14),
        ("NPT 2", "NPT", "NPT", Fraction(2), 25.4 / 11.5),
    ],
)
def test_pipe_designations(
    text: str, standard: str, kind: str, size: Fraction, pitch: float
) -> None:
    (found,) = pipe_threads(text)
    assert (found.standard, found.kind, found.size) == (standard, kind, size)
    assert found.pitch == pytest.approx(pitch)
    assert found.taper == (0.0 if kind == "Rp" else 1.0 / 16.0)
    assert found.angle == (55.0 if standard == "ISO 7-1" else 60.0)


@pytest.mark.parametrize("text", ["R0.5 ARC", "M20X1.5-6G", "G02 R12.", "R25 NOSE", "NPT 7/16"])
def test_what_is_no_pipe_designation(text: str) -> None:
    assert pipe_threads(text) == []


def test_the_diameter_turned_for_a_thread_is_its_blank() -> None:
    thread = _only_thread("g92_plain_clean.nc")
    assert thread.designation is None and thread.surface is not None
    assert thread.surface.blank == pytest.approx(23.8)
    assert thread.surface.line + 1 == 13  # G01 X23.8 Z0, then Z-35.
    (cut, *_) = thread_cuts(thread)
    assert cut.blank == pytest.approx(23.8)
    assert cut.crest_diameter == pytest.approx(23.8)


def test_a_taper_is_cut_in_the_frame_of_its_cone() -> None:
    thread = _only_thread("r_half_g76_clean.nc")
    surface = thread.surface
    assert thread.pipe is not None and thread.pipe.kind == "R" and surface is not None
    # The cone turned from X20.44 at Z0 to X21.44 at Z-16 stands 2.324 mm (diameter, twice
    # G76's height P1162) above the deepest pass all along it.
    assert surface.blank - surface.deepest.x_at(surface.z) == pytest.approx(2.324, abs=1e-3)
    (cut,) = thread_cuts(thread)  # one tool: ISO 7-1's root round
    assert cut.tool == ToolShape(55.0, pytest.approx(0.137329 * 25.4 / 14))
    assert not cut.in_the_air()


def test_an_internal_taper_reads_its_bore() -> None:
    thread = _only_thread("rc_1_g76_clean.nc")
    surface = thread.surface
    assert thread.internal and thread.pipe is not None and surface is not None
    # The bore from X30.29 at Z-0.1 to X29.166 at Z-18, under a root of X32.124 at Z-18.
    assert surface.deepest.x_at(surface.z) - surface.blank == pytest.approx(2.958, abs=1e-3)


def test_round_tool_reach_past_a_profile() -> None:
    tool = ToolShape(0.0, 1.0)
    first = cut_cross_section(_passes([(20.0, 2.0)]), 8.0, False, 24.0, tool)
    assert first is not None
    # The same pass again reaches nothing past what it left; 0.3 deeper, 0.3.
    assert penetration(first, 2.0, 10.0) == pytest.approx(0.0, abs=1e-9)
    assert penetration(first, 2.0, 9.7) == pytest.approx(0.3, abs=1e-9)
    # Shifted 0.5 along the lead at the same depth: it cuts the wall the first left standing,
    # from its tip's height 1 - sqrt(1 - 0.5²) up to the blank (radius 12).
    assert penetration(first, 2.5, 10.0) == pytest.approx(1.0 + math.sqrt(0.75), abs=0.01)


def _passes(cuts: list[tuple[float, float]]) -> list:  # type: ignore[type-arg]
    from fanuc_macro.evaluator.facts import Motion

    return [
        Motion("O1", k, "G32", {}, x=x, z=-30.0, start_x=x, start_z=z)
        for k, (x, z) in enumerate(cuts)
    ]
