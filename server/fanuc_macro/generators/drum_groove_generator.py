"""The drum-shaped spiral groove (seed 003): chained taper threads (continuous G32) through the
profile points, layer by layer, in one G65 macro.  The pass and cut counts in the comments are
read from executing the generated program."""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..threads.profile import CrownFit, fit_crown
from .generated_program import (
    Lines,
    count_of,
    entered,
    execute,
    num,
    program_number,
)

__all__ = ("DRUM_PROFILE", "DrumGrooveProgram", "build_drum_groove", "generate_drum_groove")

# Seed 003, table 1: the drum profile (X diameter, Z), 5 segments right of Z0, 6 left.
DRUM_PROFILE: tuple[tuple[float, float], ...] = (
    (298.91, 205.0),
    (302.104, 173.0),
    (304.83, 140.0),
    (307.092, 105.0),
    (308.708, 70.0),
    (309.677, 35.0),
    (310.0, 0.0),
    (309.677, -35.0),
    (308.708, -70.0),
    (307.092, -105.0),
    (304.83, -140.0),
    (303.246, -160.0),
)


# Profile points live in common variables: X of point i in #[110+i], Z in #[130+i].  #100-#149
# exist on every control without the extended-common option, so at most 19 points fit.
_X_BASE = 110
_Z_BASE = 130
_MAX_POINTS = 19


@dataclass(frozen=True)
class DrumGrooveProgram:
    """The generated drum-groove programs and what executing them gave."""

    text: str
    passes: int  # cuts through the whole profile
    segments_per_pass: int  # taper-thread G32 segments through the profile points
    g32_cuts: int  # every G32 block executed (run-in blocks included)
    crown: CrownFit | None = None  # the best-fit circle of the points (None: a line)
    motion_blocks: int = 0  # motion blocks executed (G00, G32): each a block of a plain program
    setup_blocks: int = 0  # what a plain program needs besides: O, T, S M03, M05, M30
    program_blocks: int = 0  # blocks of the generated text (comment lines and % not counted)

    @property
    def plain_blocks(self) -> int:
        """The blocks of the same cut written out without a macro."""
        return self.motion_blocks + self.setup_blocks


def build_drum_groove(
    points: Sequence[tuple[float, float]] | None,
    pitch: float,
    layers: int = 9,
    radial_step: float = 0.8,
    axial_step: float = 0.5,
    *,
    cuts_per_layer: int = 1,
    direction: int = -1,
    run_in: float = 10.0,
    clearance: float = 10.0,
    spindle_speed: int = 80,
    tool: int = 1,
    main_number: int = 10,
    macro_number: int = 1,
) -> DrumGrooveProgram:
    """:func:`generate_drum_groove` with the measured pass and cut counts."""
    pts = [(float(x), float(z)) for x, z in (DRUM_PROFILE if points is None else points)]
    if not 2 <= len(pts) <= _MAX_POINTS:
        many = "point" if len(pts) == 1 else "points"
        raise ValueError(f"{len(pts)} profile {many}: give 2-{_MAX_POINTS}")
    spec = _DrumSpec(
        points=tuple(pts),
        pitch=pitch,
        layers=layers,
        radial_step=radial_step,
        axial_step=axial_step,
        cuts_per_layer=cuts_per_layer,
        direction=direction,
        run_in=run_in,
        clearance=clearance,
        spindle_speed=spindle_speed,
        tool=tool,
        main_number=main_number,
        macro_number=macro_number,
    )
    _check_drum_values(spec)
    _check_drum_profile(spec)
    try:
        crown: CrownFit | None = fit_crown(pts)
    except ValueError:
        crown = None  # two points, or points on a line: a taper, not a crown
    draft = _render_drum_groove(spec, crown, {})
    facts = execute(draft.text()).facts
    assert facts is not None
    g32 = [m for m in facts.motions if m.code == "G32"]
    segment_line = draft.at["segment"]
    segments = sum(1 for m in g32 if m.line == segment_line)
    passes = sum(1 for m in g32 if m.line == draft.at["runin"])
    if passes == 0 or segments % passes:
        raise RuntimeError("executing the drum groove macro gave no whole passes")
    # What a plain program would be: every motion the run made, a block each, and the main
    # program's blocks that are neither motion nor macro (the run knows no other kind here).
    setup_blocks = 5  # O, T, G97 S M03, M05, M30
    motion_blocks = len(facts.motions)
    program_blocks = sum(1 for line in draft.lines if line != "%" and not line.startswith("("))
    notes = {
        "call": f"X {count_of(cuts_per_layer, 'CUT')} = {count_of(passes, 'PASS')} OF "
        f"{count_of(segments // passes, 'TAPER SEGMENT')}, {len(g32)} G32 BLOCKS",
        "blocks": f"THIS PROGRAM: {program_blocks} BLOCKS; WRITTEN OUT WITHOUT A MACRO: "
        f"{motion_blocks} MOTION + {setup_blocks} SET-UP = {motion_blocks + setup_blocks} BLOCKS",
    }
    return DrumGrooveProgram(
        text=_render_drum_groove(spec, crown, notes).text(),
        passes=passes,
        segments_per_pass=segments // passes,
        g32_cuts=len(g32),
        crown=crown,
        motion_blocks=motion_blocks,
        setup_blocks=setup_blocks,
        program_blocks=program_blocks,
    )


@dataclass(frozen=True)
class _DrumSpec:
    """The drum groove's parameters, as :func:`build_drum_groove` takes them."""

    points: tuple[tuple[float, float], ...]  # the profile: (X diameter, Z)
    pitch: float
    layers: int
    radial_step: float
    axial_step: float
    cuts_per_layer: int
    direction: int  # -1 right to left, +1
    run_in: float
    clearance: float
    spindle_speed: int
    tool: int
    main_number: int
    macro_number: int

    @property
    def sense(self) -> float:
        """+1: the profile is cut toward -Z."""
        return math.copysign(1.0, self.points[0][1] - self.points[1][1])

    @property
    def retract_x(self) -> float:
        return max(x for x, _ in self.points) + 2.0 * self.clearance

    @property
    def start_z(self) -> float:
        return self.points[0][1] + self.sense * self.run_in


def _check_drum_values(spec: _DrumSpec) -> None:
    """Refuses sizes, counts, a tool and program numbers the control does not take."""
    pitch, radial_step, axial_step, run_in = (
        spec.pitch,
        spec.radial_step,
        spec.axial_step,
        spec.run_in,
    )
    for name, value in (("pitch", pitch), ("radial step", radial_step), ("run-in", run_in)):
        if not value > 0 or not math.isfinite(value):
            raise ValueError(f"{name} {value!r} must be a positive number")
    if not axial_step >= 0 or not math.isfinite(axial_step):
        raise ValueError(f"axial step {axial_step!r} must not be negative")
    for name, value in (
        ("pitch", pitch),
        ("radial step", radial_step),
        ("axial step", axial_step),
        ("run-in", run_in),
        ("clearance", spec.clearance),
        *((f"point {i} X", x) for i, (x, _) in enumerate(spec.points, 1)),
        *((f"point {i} Z", z) for i, (_, z) in enumerate(spec.points, 1)),
    ):
        entered(name, value)
    layers, cuts_per_layer = spec.layers, spec.cuts_per_layer
    if not 1 <= layers <= 999 or not 1 <= cuts_per_layer <= 999:
        raise ValueError(f"layers {layers} and cuts per layer {cuts_per_layer} must be 1-999")
    if spec.direction not in (-1, 1):
        raise ValueError(f"direction {spec.direction} must be -1 (right to left) or +1")
    if not spec.clearance > 0:
        raise ValueError(f"clearance {spec.clearance!r} must be positive")
    if not 1 <= spec.spindle_speed <= 99999:
        raise ValueError(f"spindle speed S{spec.spindle_speed} is outside 1-99999")
    if not 1 <= spec.tool <= 99:
        raise ValueError(f"tool T{spec.tool} is outside 1-99")
    if program_number(spec.main_number, "main") == program_number(spec.macro_number, "macro"):
        raise ValueError(f"the main program and the macro are both O{spec.main_number:04d}")


def _check_drum_profile(spec: _DrumSpec) -> None:
    """Refuses a profile G32 cannot follow (Z turning back, a segment steeper than 45
    degrees), or layers deeper than the smallest radius."""
    sense = spec.sense
    for i, ((x0, z0), (x1, z1)) in enumerate(itertools.pairwise(spec.points), 1):
        dz = z0 - z1
        if dz == 0 or math.copysign(1.0, dz) != sense:
            raise ValueError(
                f"profile points {i} (Z{z0:g}) and {i + 1} (Z{z1:g}): Z must change in one "
                "direction along the whole profile"
            )
        if abs(x1 - x0) / 2.0 >= abs(dz):
            raise ValueError(
                f"segment {i}-{i + 1} (X{x0:g} Z{z0:g} to X{x1:g} Z{z1:g}) is steeper than "
                "45 degrees: G32 F would be the lead along X, not Z"
            )
    depth = spec.layers * spec.radial_step
    lowest = min(x for x, _ in spec.points)
    if 2.0 * depth >= lowest:
        raise ValueError(
            f"{spec.layers} layers x {spec.radial_step:g} = {depth:g} mm deep is more than the "
            f"radius of the smallest profile diameter {lowest:g}"
        )


def _render_drum_groove(spec: _DrumSpec, crown: CrownFit | None, notes: Mapping[str, str]) -> Lines:
    """The main program and the macro; ``notes`` adds the measured counts to the comments."""
    out = Lines()
    out.add("%")
    _render_drum_main(out, spec, crown, notes)
    _render_drum_macro(out, spec)
    out.add("%")
    return out


def _render_drum_main(
    out: Lines, spec: _DrumSpec, crown: CrownFit | None, notes: Mapping[str, str]
) -> None:
    """The main program: the profile points into #111-, the tool, and the macro's call."""
    pts = spec.points
    out.add(f"O{spec.main_number:04d}", "DRUM SPIRAL GROOVE - CHAINED TAPER THREADS")
    last = len(pts)
    xs = f"#{_X_BASE + 1}-#{_X_BASE + last}"
    zs = f"#{_Z_BASE + 1}-#{_Z_BASE + last}"
    out.add("", f"PROFILE: X IN {xs}, Z IN {zs}")
    if crown is not None:
        out.add(
            "",
            f"CROWN R{crown.radius:.1f} (BEST-FIT CIRCLE, POINTS WITHIN "
            f"{crown.max_deviation:.3f} MM OF IT)",
        )
    if "blocks" in notes:
        out.add("", notes["blocks"])
    for i, (x, z) in enumerate(pts, 1):
        out.add(f"#{_X_BASE + i}={num(x)}", f"POINT {i} X")
        out.add(f"#{_Z_BASE + i}={num(z)}", f"POINT {i} Z")
    out.add(f"T{spec.tool:02d}{spec.tool:02d}", "GROOVING TOOL")
    out.add(f"G97 S{spec.spindle_speed} M03", "SPINDLE")
    retract_x, start_z = num(spec.retract_x), num(spec.start_z)
    out.add(f"G00 X{retract_x} Z{start_z}", "START POINT")
    call = " ".join(
        [
            f"G65 P{spec.macro_number:04d}",
            f"A{last}.",
            f"B{spec.cuts_per_layer}.",
            f"C{spec.layers}.",
            f"D{num(spec.radial_step)}",
            f"E{num(spec.direction * spec.axial_step)}",
            f"F{num(spec.pitch)}",
            f"K{num(spec.sense * spec.run_in)}",
            f"V{retract_x}",
        ]
    )
    out.add(call, f"{count_of(spec.layers, 'LAYER')} {notes.get('call', '')}", key="call")
    out.add(f"G00 X{retract_x} Z{start_z}", "BACK TO THE START POINT")
    out.add("M05", "SPINDLE STOP")
    out.add("M30", "END OF PROGRAM")


def _render_drum_macro(out: Lines, spec: _DrumSpec) -> None:
    """The macro: layers of cuts, each a run-in and a G32 taper thread to every point."""
    out.add(f"O{spec.macro_number:04d}", "DRUM GROOVE - LAYERS OF CHAINED G32 TAPER THREADS")
    out.add("", f"A=#1 POINTS: X IN #{_X_BASE}+I, Z IN #{_Z_BASE}+I, B=#2 CUTS PER LAYER")
    out.add("", "C=#3 LAYERS, D=#7 RADIAL STEP, E=#8 AXIAL STEP PER CUT, F=#9 PITCH")
    out.add("", "K=#6 RUN-IN BEFORE POINT 1, V=#22 RETRACT X")
    out.add("#30=1.", "LAYER")
    out.add("WHILE[#30LE#3]DO1", "EACH LAYER")
    out.add("#31=#30*#7", "RADIAL DEPTH OF THE LAYER")
    out.add("#32=0.", "CUT OF THE LAYER")
    out.add("WHILE[#32LT#2]DO2", "EACH CUT OF THE LAYER")
    out.add("#33=#32*#8", "AXIAL SHIFT OF THE CUT")
    out.add(f"G00 Z[#{_Z_BASE + 1}+#33+#6]", "RUN-IN START")
    out.add(f"X[#{_X_BASE + 1}-2.*#31]", "DEPTH OF THE LAYER")
    out.add(f"G32 Z[#{_Z_BASE + 1}+#33] F#9", "RUN-IN TO POINT 1", key="runin")
    out.add("#10=2.", "NEXT POINT")
    out.add("WHILE[#10LE#1]DO3", "THROUGH THE PROFILE")
    out.add(
        f"G32 X[#[{_X_BASE}+#10]-2.*#31] Z[#[{_Z_BASE}+#10]+#33]",
        "TAPER THREAD TO THE POINT",
        key="segment",
    )
    out.add("#10=#10+1.")
    out.add("END3")
    out.add("G00 X#22", "RETRACT")
    out.add("#32=#32+1.")
    out.add("END2")
    out.add("#30=#30+1.")
    out.add("END1")
    out.add("M99", "BACK TO THE MAIN PROGRAM")


def generate_drum_groove(
    points: Sequence[tuple[float, float]] | None,
    pitch: float,
    layers: int = 9,
    radial_step: float = 0.8,
    axial_step: float = 0.5,
    **options: Any,
) -> str:
    """A main program and one G65 macro that cut the drum groove layer by layer.

    ``points`` are (X diameter, Z) of the profile (None: the paper's 12 points); each
    pass is a straight G32 run-in to point 1 and a chain of G32 taper threads through the
    rest, at the layer's depth (``radial_step`` per layer, radius).  ``cuts_per_layer``
    cuts per layer step ``axial_step`` along Z (``direction`` -1: right to left, as the
    paper's T1).  The paper does not give the pitch (its figure 2 is lost): pass it.
    """
    return build_drum_groove(
        points,
        pitch,
        layers,
        radial_step,
        axial_step,
        **options,
    ).text
