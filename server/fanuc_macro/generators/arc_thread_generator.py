"""The large-pitch arc thread by the fitting method (seed 002): a main program, one G65
roughing macro called once per layer, one G65 finishing macro.  The cuts and angles in the
comments are read from executing the generated program."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..evaluator import Motion
from .generated_program import (
    Lines,
    entered,
    execute,
    num,
    program_number,
)

__all__ = ("ArcThreadProgram", "build_arc_thread", "generate_arc_thread")


@dataclass(frozen=True)
class ArcThreadProgram:
    """The generated arc-thread programs and what executing them gave (angles in degrees)."""

    text: str
    layer_cuts: tuple[int, ...]  # G32 cuts of each roughing layer
    layer_angles: tuple[tuple[float, float], ...]  # first and last tool-centre angle
    finishing_cuts: int
    finishing_angles: tuple[float, float]


def _asin_argument(what: str, expression: str, value: float) -> None:
    if not -1.0 <= value <= 1.0:
        raise ValueError(
            f"{what}: ASIN argument {expression} = {value:.6g} is outside -1..1 (alarm on the "
            "control); check the diameters and radii"
        )


def _edge_argument(centre: float, outer: float, radius: float) -> float:
    return ((centre - outer) / 2.0) / radius


def _inside_the_blank(
    outer: float, radius: float, layers: Sequence[float], finishing: float
) -> None:
    """Refuse grooves the blank cannot have.  Each groove is the circle of radius R about its
    centre at radius J/2 swept along the helix; the finished one is the finishing J's.

    - The finished centre below the outer diameter makes a groove of more than half a circle,
      narrower at its mouth than inside: a tool fed from outside would cut the lips.
    - The finished groove bottom J - 2R at or below 0 is past the axis.
    - A roughing centre below the finishing one cuts past the finished profile (same R, lower
      centre: lower everywhere).
    - A roughing groove whose bottom J - 2R is at or above the outer diameter cuts nothing, and
      one whose centre is not below every earlier layer's lies inside what they removed.
    """
    if finishing < outer:
        raise ValueError(
            f"finishing groove-centre diameter J{finishing:g} is below the outer diameter "
            f"{outer:g}: the groove would be more than a half circle, narrower at its mouth, "
            "and the tool would cut its lips"
        )
    if finishing - 2.0 * radius <= 0:
        raise ValueError(
            f"finishing groove-centre diameter J{finishing:g} with groove radius R{radius:g}: "
            f"the groove bottom J-2R = {finishing - 2.0 * radius:g} is at or past the axis"
        )
    for n, centre in enumerate(layers, 1):
        what = f"roughing layer {n} J{centre:g}"
        if centre < finishing:
            raise ValueError(
                f"{what} is below the finishing groove-centre diameter J{finishing:g}: "
                "it would cut past the finished profile"
            )
        if centre - 2.0 * radius >= outer:
            raise ValueError(
                f"{what}: its groove bottom J-2R = {centre - 2.0 * radius:g} is not below the "
                f"outer diameter {outer:g}, it cuts nothing"
            )
        earlier = min(layers[: n - 1], default=math.inf)
        if centre >= earlier:
            raise ValueError(
                f"{what} is not below an earlier layer's J{earlier:g}: it cuts nothing that "
                "layer did not"
            )


def _angles_from_motions(motions: Sequence[Motion], centre: float, run_in: float) -> list[float]:
    """Tool-centre angles of the cuts, from the rapid X and Z that precede each G32.

    X = centre - 2 (R-r) sin a and Z = run-in + (R-r) cos a, so a = atan2((centre-X)/2, Z-run-in).
    """
    angles: list[float] = []
    x: float | None = None
    z: float | None = None
    for m in motions:
        if m.code == "G32":
            if x is None or z is None:
                raise RuntimeError("a G32 cut without its start point")
            angles.append(math.degrees(math.atan2((centre - x) / 2.0, z - run_in)))
        else:
            x = m.words.get("X", x)
            z = m.words.get("Z", z)
    return angles


def _fitting_macro(out: Lines, number: int, finishing: bool) -> None:
    """One G65 macro for a roughing layer (O3 of the paper) or the finishing (O5)."""
    if finishing:
        out.add(f"O{number:04d}", "ARC THREAD FINISHING - G65 MACRO, FITTING METHOD")
    else:
        out.add(f"O{number:04d}", "ARC THREAD ROUGHING LAYER - G65 MACRO, FITTING METHOD")
    out.add("", "A=#1 THREAD OD, B=#2 CUT END DISTANCE, C=#3 PITCH, I=#4 GROOVE RADIUS")
    out.add("", "J=#5 GROOVE CENTRE DIAMETER, K=#6 RUN-IN Z, D=#7 NUMBER OF CUTS")
    out.add("", "M=#13 SPINDLE M CODE, R=#18 TOOL NOSE RADIUS, S=#19 SPINDLE SPEED")
    out.add("", "T=#20 TOOL, U=#21 OFFSET, V=#22 RETRACT X, X=#24 Z=#26 START POINT")
    out.add("#10=ASIN[[[#5-#1]/2]/#4]", "RIGHT EDGE ANGLE")
    if finishing:
        out.add("#15=180-#10", "LEFT EDGE ANGLE, LAST CUT")
        out.add("#12=[#15-#10]/[#7-1]", "ANGLE STEP")
    else:
        out.add("#11=ASIN[#18/[#4-#18]]", "TANGENCY CORRECTION")
        out.add("#12=[180-2*#10+#11]/#7", "ANGLE STEP")
        out.add("#14=#10-#11", "TOOL TANGENT TO THE RIGHT EDGE")
    out.add("G54 S#19 M#13", "SPINDLE SPEED AND DIRECTION")
    out.add("T[#20*100+#21]", "TOOL AND OFFSET")
    out.add("G00 X#24 Z#26", "START POINT")
    # A counter, not an accumulated angle compared with the last one: a sum of steps can
    # overshoot the end angle by a rounding error and lose the last cut.
    out.add("#30=0" if finishing else "#30=1", "CUT COUNTER")
    if finishing:
        out.add("WHILE[#30LT#7]DO1", "ONE CUT PER ANGLE")
        out.add("#16=#10+#30*#12", "TOOL CENTRE ANGLE OF THIS CUT")
    else:
        out.add("WHILE[#30LE#7]DO1", "ONE CUT PER ANGLE")
        out.add("#16=#14+#30*#12", "TOOL CENTRE ANGLE OF THIS CUT")
    out.add("G00 Z[#6+[#4-#18]*COS[#16]]", "Z START OF THIS CUT")
    out.add("X[#5-2*[#4-#18]*SIN[#16]]", "X OF THIS CUT")
    out.add("G32 Z-#2 F#3", "CUT")
    out.add("G00 X#22", "RETRACT")
    out.add("#30=#30+1", "NEXT CUT")
    out.add("END1")
    out.add("G00 X#24 Z#26", "BACK TO THE START POINT")
    out.add("M99", "BACK TO THE MAIN PROGRAM")


@dataclass(frozen=True)
class _ArcCall:
    """The arguments of one G65 call of a fitting-method macro (letters as the paper's #n)."""

    outer: float  # A #1
    length: float  # B #2
    pitch: float  # C #3
    radius: float  # I #4
    run_in: float  # K #6
    spindle_m: int  # M #13
    retract_x: float  # V #22
    start_x: float  # X #24
    start_z: float  # Z #26

    def block(
        self, macro: int, centre: float, cuts: int, tool_radius: float, speed: int, tool: int
    ) -> str:
        # I, J, K in this order: both argument specifications read them as #4, #5, #6.
        words = [
            f"G65 P{macro:04d}",
            f"A{num(self.outer)}",
            f"B{num(self.length)}",
            f"C{num(self.pitch)}",
            f"I{num(self.radius)}",
            f"J{num(centre)}",
            f"K{num(self.run_in)}",
            f"D{cuts}.",
            f"M{self.spindle_m}.",
            f"R{num(tool_radius)}",
            f"S{speed}.",
            f"T{tool}.",
            f"U{tool}.",
            f"V{num(self.retract_x)}",
            f"X{num(self.start_x)}",
            f"Z{num(self.start_z)}",
        ]
        return " ".join(words)


def build_arc_thread(
    outer_diameter: float = 93.82,
    groove_radius: float = 10.0,
    tool_radius: float = 1.2,
    pitch: float = 25.0,
    length: float = 113.0,
    layers: Sequence[float] = (108.0, 103.0),
    cuts_per_layer: int = 7,
    finishing_diameter: float = 100.0,
    finishing_cuts: int = 19,
    *,
    run_in: float = 50.0,
    finishing_tool_radius: float | None = None,
    rough_speed: int = 300,
    finishing_speed: int = 400,
    spindle_m: int = 3,
    rough_tool: int = 1,
    finishing_tool: int = 2,
    retract_x: float = 140.0,
    start_x: float = 150.0,
    start_z: float = 100.0,
    main_number: int = 2,
    rough_number: int = 3,
    finishing_number: int = 5,
) -> ArcThreadProgram:
    """:func:`generate_arc_thread` with the measured cuts and angles."""
    spec = _ArcThreadSpec(
        outer_diameter=outer_diameter,
        groove_radius=groove_radius,
        tool_radius=tool_radius,
        pitch=pitch,
        length=length,
        layers=tuple(layers),
        cuts_per_layer=cuts_per_layer,
        finishing_diameter=finishing_diameter,
        finishing_cuts=finishing_cuts,
        run_in=run_in,
        finishing_tool_radius=tool_radius
        if finishing_tool_radius is None
        else finishing_tool_radius,
        rough_speed=rough_speed,
        finishing_speed=finishing_speed,
        spindle_m=spindle_m,
        rough_tool=rough_tool,
        finishing_tool=finishing_tool,
        retract_x=retract_x,
        start_x=start_x,
        start_z=start_z,
        main_number=main_number,
        rough_number=rough_number,
        finishing_number=finishing_number,
    )
    _check_arc_sizes(spec)
    _check_arc_machine(spec)
    _check_arc_geometry(spec)
    facts = execute(_render_arc_thread(spec, {}).text()).facts
    assert facts is not None
    layer_cuts, layer_angles, fin_angles = _arc_cuts(spec, facts.motions)
    notes = {
        f"layer{n}": f"J{c:g}: {k} CUTS, ANGLE {a:.2f} TO {b:.2f} DEG"
        for n, (c, k, (a, b)) in enumerate(zip(layers, layer_cuts, layer_angles, strict=True), 1)
    }
    notes["finish"] = (
        f"J{finishing_diameter:g}: {len(fin_angles)} CUTS, ANGLE "
        f"{fin_angles[0]:.2f} TO {fin_angles[-1]:.2f} DEG"
    )
    return ArcThreadProgram(
        text=_render_arc_thread(spec, notes).text(),
        layer_cuts=tuple(layer_cuts),
        layer_angles=tuple(layer_angles),
        finishing_cuts=len(fin_angles),
        finishing_angles=(fin_angles[0], fin_angles[-1]),
    )


@dataclass(frozen=True)
class _ArcThreadSpec:
    """The arc thread's parameters, as :func:`build_arc_thread` takes them."""

    outer_diameter: float
    groove_radius: float  # R
    tool_radius: float  # r of the roughing tool
    pitch: float
    length: float
    layers: tuple[float, ...]  # the roughing layers' groove-centre diameters J
    cuts_per_layer: int
    finishing_diameter: float
    finishing_cuts: int
    run_in: float
    finishing_tool_radius: float
    rough_speed: int
    finishing_speed: int
    spindle_m: int
    rough_tool: int
    finishing_tool: int
    retract_x: float
    start_x: float
    start_z: float
    main_number: int
    rough_number: int
    finishing_number: int


def _check_arc_sizes(spec: _ArcThreadSpec) -> None:
    """Refuses sizes that are not positive numbers, or a tool not smaller than the groove."""
    big_r, r_fin = spec.groove_radius, spec.finishing_tool_radius
    positive = (
        ("outer diameter", spec.outer_diameter),
        ("groove radius R", big_r),
        ("tool nose radius r", spec.tool_radius),
        ("finishing tool nose radius r", r_fin),
        ("pitch", spec.pitch),
        ("length", spec.length),
    )
    for name, value in positive:
        if not value > 0 or not math.isfinite(value):
            raise ValueError(f"{name} {value!r} must be a positive number")
    for name, r in (("tool", spec.tool_radius), ("finishing tool", r_fin)):
        if not r < big_r:
            raise ValueError(
                f"{name} nose radius r = {r:g} must be smaller than the groove radius R = {big_r:g}"
            )
    if not spec.layers:
        raise ValueError("give at least one roughing layer (groove-centre diameter)")
    for name, value in (
        *positive,
        ("run-in", spec.run_in),
        ("retract X", spec.retract_x),
        ("start X", spec.start_x),
        ("start Z", spec.start_z),
        ("finishing diameter", spec.finishing_diameter),
        *((f"roughing layer {n} J", j) for n, j in enumerate(spec.layers, 1)),
    ):
        entered(name, value)


def _check_arc_machine(spec: _ArcThreadSpec) -> None:
    """Refuses counts, speeds, tools and program numbers the control does not take, and a
    retract or start point that does not clear the part."""
    if not 1 <= spec.cuts_per_layer <= 999:
        raise ValueError(f"cuts per layer {spec.cuts_per_layer} must be 1-999")
    if not 2 <= spec.finishing_cuts <= 999:
        raise ValueError(f"finishing cuts {spec.finishing_cuts} must be 2-999")
    if spec.spindle_m not in (3, 4):
        raise ValueError(f"spindle M code {spec.spindle_m} must be 3 or 4")
    speeds = (("roughing speed", spec.rough_speed), ("finishing speed", spec.finishing_speed))
    for name, speed in speeds:
        if not 1 <= speed <= 99999:
            raise ValueError(f"{name} S{speed} is outside 1-99999")
    for name, t in (("roughing tool", spec.rough_tool), ("finishing tool", spec.finishing_tool)):
        # The macros call T[#20*100+#21]: a tool and its offset of two digits each.
        if not 1 <= t <= 99:
            raise ValueError(f"{name} T{t} is outside 1-99")
    main_number, rough_number = spec.main_number, spec.rough_number
    finishing_number = spec.finishing_number
    numbers = {
        program_number(main_number, "main"),
        program_number(rough_number, "roughing macro"),
        program_number(finishing_number, "finishing macro"),
    }
    if len(numbers) != 3:
        raise ValueError(
            f"the main program O{main_number:04d}, the roughing macro O{rough_number:04d} and "
            f"the finishing macro O{finishing_number:04d} need three different numbers"
        )
    highest = max([*spec.layers, spec.finishing_diameter, spec.outer_diameter])
    retract_x, start_x = spec.retract_x, spec.start_x
    if not retract_x > highest or not start_x >= retract_x:
        raise ValueError(
            f"retract X{retract_x:g} must clear the largest diameter {highest:g} the tool "
            f"reaches, and the start point X{start_x:g} must not be below it"
        )


def _check_arc_geometry(spec: _ArcThreadSpec) -> None:
    """Refuses a groove whose macros would take ASIN past 1, a layer outside the blank, or a
    run-in that starts a cut past the thread's end."""
    big_r, tool_radius, outer = spec.groove_radius, spec.tool_radius, spec.outer_diameter
    tangency = tool_radius / (big_r - tool_radius)
    _asin_argument(
        "tangency correction #11",
        f"r/[R-r] = {tool_radius:g}/[{big_r:g}-{tool_radius:g}]",
        tangency,
    )
    for n, centre in enumerate(spec.layers, 1):
        arg = _edge_argument(centre, outer, big_r)
        _asin_argument(
            f"roughing layer {n} J{centre:g}",
            f"[[{centre:g}-{outer:g}]/2]/{big_r:g}",
            arg,
        )
    finishing = spec.finishing_diameter
    _asin_argument(
        f"finishing J{finishing:g}",
        f"[[{finishing:g}-{outer:g}]/2]/{big_r:g}",
        _edge_argument(finishing, outer, big_r),
    )
    _inside_the_blank(outer, big_r, spec.layers, finishing)
    lowest_start = spec.run_in - (big_r - min(tool_radius, spec.finishing_tool_radius))
    if not lowest_start > -spec.length:
        raise ValueError(
            f"run-in Z{spec.run_in:g} and length {spec.length:g}: a cut would start at Z"
            f"{lowest_start:g}, not before its end Z-{spec.length:g}"
        )


def _render_arc_thread(spec: _ArcThreadSpec, notes: Mapping[str, str]) -> Lines:
    """The main program (a call per roughing layer, then the finishing call) and the two
    fitting macros; ``notes`` adds measured numbers to the calls' comments."""
    common = _ArcCall(
        outer=spec.outer_diameter,
        length=spec.length,
        pitch=spec.pitch,
        radius=spec.groove_radius,
        run_in=spec.run_in,
        spindle_m=spec.spindle_m,
        retract_x=spec.retract_x,
        start_x=spec.start_x,
        start_z=spec.start_z,
    )
    out = Lines()
    out.add("%")
    out.add(
        f"O{spec.main_number:04d}",
        f"ARC THREAD BY THE FITTING METHOD - R{spec.groove_radius:g} P{spec.pitch:g}",
    )
    for n, centre in enumerate(spec.layers, 1):
        call = common.block(
            spec.rough_number,
            centre,
            spec.cuts_per_layer,
            spec.tool_radius,
            spec.rough_speed,
            spec.rough_tool,
        )
        out.add(call, f"ROUGH LAYER {n} {notes.get(f'layer{n}', '')}", key=f"layer{n}")
    call = common.block(
        spec.finishing_number,
        spec.finishing_diameter,
        spec.finishing_cuts,
        spec.finishing_tool_radius,
        spec.finishing_speed,
        spec.finishing_tool,
    )
    out.add(call, f"FINISHING {notes.get('finish', '')}", key="finish")
    out.add("M05", "SPINDLE STOP")
    out.add("M30", "END OF PROGRAM")
    _fitting_macro(out, spec.rough_number, finishing=False)
    _fitting_macro(out, spec.finishing_number, finishing=True)
    out.add("%")
    return out


def _arc_cuts(
    spec: _ArcThreadSpec, motions: Sequence[Motion]
) -> tuple[list[int], list[tuple[float, float]], list[float]]:
    """From the executed motions: each roughing layer's cuts and its first and last angle,
    and the finishing cuts' angles."""
    rough_name = f"O{spec.rough_number:04d}"
    fin_name = f"O{spec.finishing_number:04d}"
    rough_motions = [m for m in motions if m.program.startswith(rough_name)]
    fin_motions = [m for m in motions if m.program.startswith(fin_name)]
    # Each layer's cuts come in order; split them with the known centre diameters.
    layer_cuts: list[int] = []
    layer_angles: list[tuple[float, float]] = []
    cuts_by_layer = _split_by_calls(rough_motions, len(spec.layers))
    for n, (centre, chunk) in enumerate(zip(spec.layers, cuts_by_layer, strict=True), 1):
        angles = _angles_from_motions(chunk, centre, spec.run_in)
        if not angles:
            raise RuntimeError(f"roughing layer {n} made no cut")
        layer_cuts.append(len(angles))
        layer_angles.append((angles[0], angles[-1]))
    fin_angles = _angles_from_motions(fin_motions, spec.finishing_diameter, spec.run_in)
    if not fin_angles:
        raise RuntimeError("the finishing macro made no cut")
    return layer_cuts, layer_angles, fin_angles


def _split_by_calls(motions: Sequence[Motion], calls: int) -> list[list[Motion]]:
    """Split one macro's motions into its calls: each call starts with a rapid to X Z."""
    chunks: list[list[Motion]] = []
    for m in motions:
        starts = m.code == "G00" and "X" in m.words and "Z" in m.words
        # The macro's first and last blocks are both 'G00 X#24 Z#26': a call starts at the
        # first of the pair, i.e. when the previous chunk already ended with its return.
        if starts and (not chunks or _chunk_closed(chunks[-1])):
            chunks.append([m])
        elif chunks:
            chunks[-1].append(m)
    if len(chunks) != calls:
        raise RuntimeError(f"expected {calls} macro calls in the motions, found {len(chunks)}")
    return chunks


def _chunk_closed(chunk: Sequence[Motion]) -> bool:
    last = chunk[-1]
    return len(chunk) > 1 and last.code == "G00" and "X" in last.words and "Z" in last.words


def generate_arc_thread(
    outer_diameter: float = 93.82,
    groove_radius: float = 10.0,
    tool_radius: float = 1.2,
    pitch: float = 25.0,
    length: float = 113.0,
    layers: Sequence[float] = (108.0, 103.0),
    cuts_per_layer: int = 7,
    finishing_diameter: float = 100.0,
    finishing_cuts: int = 19,
    **options: Any,
) -> str:
    """Main program + roughing G65 macro (called once per layer) + finishing G65 macro.

    Defaults are the paper's part: thread OD 93.82, groove radius R 10, tool nose radius r
    1.2, pitch 25, cut to Z-113 from a run-in Z of 50, roughing layers with groove centres on
    diameters 108 and 103 (7 cuts each), finishing on the centre diameter 100 (19 cuts).
    ``options``: the keyword arguments of :func:`build_arc_thread`.  Raises ValueError when
    r >= R, an ASIN argument leaves -1..1 or a groove is not one the blank can have
    (``_inside_the_blank``).
    """
    return build_arc_thread(
        outer_diameter,
        groove_radius,
        tool_radius,
        pitch,
        length,
        layers,
        cuts_per_layer,
        finishing_diameter,
        finishing_cuts,
        **options,
    ).text
