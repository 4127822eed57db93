"""The machine's setup as a run changes it: the plane, radius compensation, the spindle speed
clamp, the tool in the spindle and its length offset, the skip signal.

:class:`Setup` is frozen: a block that changes it makes a new one, so that a checkpoint keeps
it by reference. The verdicts on it (:mod:`.motion` reports them) are here as functions of the
setup and one block: the geometry of an arc, a compensation started on an arc, a cut near the
centre in G96 with no clamp, a length offset of another tool.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType

from ..translation import tr
from .toolpath import PLANE_AXES, Plane
from .values import Value, fmt

# FANUC's radius compensation codes (group 07): G40 cancel, G41 left, G42 right.
COMPENSATION_CODES = frozenset({40.0, 41.0, 42.0})
PLANES: Mapping[float, Plane] = MappingProxyType({17.0: "XY", 18.0: "XZ", 19.0: "YZ"})
# How far apart the start's and the end's distances from an arc's centre may be before the
# control stops with PS0020 OVER TOLERANCE OF RADIUS: parameter 3410 sets it on the control
# (0i-MF/0i-TF "Circular interpolation"); the value a machine has is its builder's. These are
# taken as a usual setting, 0.02 mm or 0.001 inch (unverified: no manual gives a default).
ARC_TOLERANCE_MM = 0.02
ARC_TOLERANCE_INCH = 0.001

Place = tuple[str, int]  # a block: its document and line


@dataclass(frozen=True, slots=True)
class Setup:
    """What the run knows of the machine's setup; None where it is not known (after a call
    the analysis cannot follow)."""

    plane: Plane = "XY"  # G17 at power on (a lathe works in G18, its ZX plane)
    # Radius compensation: G40, G41 or G42 in force (None: not known); the block that asked
    # for it; whether it has started (the first move after G41/G42, the start-up block).
    compensation: float | None = 40.0
    compensation_at: Place | None = None
    compensation_started: bool = False
    left_on_told: bool = False  # compensation left on already reported (until G40)
    # A lathe's maximum spindle speed clamp (G50 S) set in this run; None: not known.
    clamped: bool | None = False
    clamp_speed: float | None = None  # its S (rpm), when the run knows it
    # G96 near the centre already reported in this run (once until a clamp).
    unclamped_told: bool = False
    # The tool the last T word selected, which the next M06 loads (a mill's); None: none.
    selected: float | None = None
    # The tool in the spindle after the last M06 (None: no change seen, or not known), the
    # change's block, the H of the length offset called since (None: none yet), and whether a
    # cut with no offset after it was reported.
    tool: float | None = None
    tool_at: Place | None = None
    length_offset: float | None = None
    length_told: bool = False
    # An earlier tool change of the run had its offset called with H equal to T (the shop
    # numbers offsets by tools), or called one at all.
    offset_by_tool: bool = False
    offset_used: bool = False
    # The feed mode the run set, G98/G94 per minute or G99/G95 per revolution (None: not set
    # by the run), the block that set it, and whether a feed of the other's size was told.
    feed_mode: tuple[float, str, int] | None = None
    feed_told: bool = False
    # The modal F was given by a lathe's threading block: a lead, which the next G01 without
    # F runs at (not a feed written for a cut).
    lead_feed: bool = False
    # A length offset of another number than the tool's, told once the program shows it
    # numbers offsets by tools (a D equal to the tool, a later tool's H equal to its T): its
    # document, program, line, width, message and the tool.
    pending_offset: tuple[str, int, int, int, str, float] | None = None
    # A feed move with the spindle stopped, told once the tool is known to cut (MB611): its
    # document, program, line, width and message.
    pending_cut: tuple[str, int, int, int, str] | None = None
    # The M29 block of rigid tapping, until its tapping cycle (G84, G74) runs.
    rigid_at: Place | None = None
    # A G31 ran in this run, so the skip position #5061 and on holds its result (None: not
    # known, after a call the analysis cannot follow).
    skipped: bool | None = False

    def shifted(self, line: Callable[[str, int], int]) -> Setup:
        """The setup with its blocks' lines renumbered (an edit added or removed lines)."""
        at, tool_at, cut = self.compensation_at, self.tool_at, self.pending_cut
        mode, offset, rigid = self.feed_mode, self.pending_offset, self.rigid_at
        if (
            at is None
            and tool_at is None
            and cut is None
            and mode is None
            and offset is None
            and rigid is None
        ):
            return self
        return replace(
            self,
            rigid_at=None if rigid is None else (rigid[0], line(*rigid)),
            pending_offset=None
            if offset is None
            else (
                offset[0],
                line(offset[0], offset[1]),
                line(offset[0], offset[2]),
                offset[3],
                offset[4],
                offset[5],
            ),
            feed_mode=None if mode is None else (mode[0], mode[1], line(mode[1], mode[2])),
            compensation_at=None if at is None else (at[0], line(*at)),
            tool_at=None if tool_at is None else (tool_at[0], line(*tool_at)),
            pending_cut=None
            if cut is None
            else (cut[0], line(cut[0], cut[1]), line(cut[0], cut[2]), cut[3], cut[4]),
        )

    def after_unknown_call(self) -> Setup:
        """A call the analysis cannot follow may have changed anything but the plane's use."""
        return Setup(
            plane=self.plane,
            compensation=None,
            clamped=None,
            unclamped_told=self.unclamped_told,
            offset_by_tool=self.offset_by_tool,
            offset_used=self.offset_used,
            skipped=None,
            feed_told=self.feed_told,
        )


def arc_fault(
    start: Mapping[str, Value],
    end: Mapping[str, Value],
    values: Mapping[str, Value],
    plane: Plane,
    lathe: bool,
    inch: bool,
) -> tuple[str, str] | None:
    """Why the control cannot cut a G02/G03 from ``start`` to ``end`` (kind, what is wrong,
    with the values), or None: it can, or the run does not know enough to say.

    With R: the end must be within 2|R| of the start (the chord at most the diameter). With
    I J K (the centre's offset from the start; a lathe's I a radius): the end's distance from
    the centre must be the start's, within the control's tolerance (PS0020). With neither, an
    arc to another point has no centre (PS0022)."""
    (u_axis, u_word), (v_axis, v_word) = PLANE_AXES[plane]
    su, sv, eu, ev = start.get(u_axis), start.get(v_axis), end.get(u_axis), end.get(v_axis)
    if not (type(su) is float and type(sv) is float and type(eu) is float and type(ev) is float):
        return None
    # A lathe's X is a diameter: the geometry in radius.
    scale = 0.5 if lathe and v_axis == "X" else 1.0
    sv, ev = sv * scale, ev * scale
    tolerance = ARC_TOLERANCE_INCH if inch else ARC_TOLERANCE_MM
    radius = values.get("R")
    if "R" in values:
        if type(radius) is not float or radius == 0.0:
            return None
        half = math.hypot(eu - su, ev - sv) / 2.0
        if half - abs(radius) <= tolerance:
            return None
        return (
            "radius",
            tr(
                "R{radius} is shorter than half the distance to the end point, {half} {unit}: "
                "no arc of that radius reaches it",
                radius=fmt(radius),
                half=fmt(round(half, 4)),
                unit=unit_of(inch),
            ),
        )
    u_off, v_off = values.get(u_word), values.get(v_word)
    if u_off is None and v_off is None:
        if eu == su and ev == sv:
            return None  # no move in the plane (a block of G02 words off it)
        words = " ".join(sorted((u_word, v_word)))
        return (
            "no-centre",
            tr(
                "it gives neither R nor {words}, and the end point is elsewhere",
                words=words,
            ),
        )
    if (u_off is not None and type(u_off) is not float) or (
        v_off is not None and type(v_off) is not float
    ):
        return None
    cu = su + (u_off if type(u_off) is float else 0.0)
    cv = sv + (v_off if type(v_off) is float else 0.0)
    r_start = math.hypot(su - cu, sv - cv)
    r_end = math.hypot(eu - cu, ev - cv)
    if abs(r_end - r_start) <= tolerance:
        return None
    centre = f"{u_axis}{fmt(round(cu, 4))} {v_axis}{fmt(round(cv / scale, 4))}"
    given = " ".join(sorted((u_word, v_word)))
    unit = unit_of(inch)
    return (
        "centre",
        tr(
            "the end point is {end} {unit} from the centre ({centre}) that {words} give, the "
            "start {start} {unit}",
            end=fmt(round(r_end, 4)),
            unit=unit,
            centre=centre,
            words=given,
            start=fmt(round(r_start, 4)),
        ),
    )


def moves_in_plane(values: Mapping[str, Value], plane: Plane, lathe: bool) -> bool:
    """Whether a block's words move an axis of the compensation plane."""
    (u_axis, _), (v_axis, _) = PLANE_AXES[plane]
    if u_axis in values or v_axis in values:
        return True
    if lathe:
        return ("U" in values and v_axis == "X") or ("W" in values and u_axis == "Z")
    return False


# A feed's size that belongs to the other mode: below 1 mm/min (0.04 inch/min) no cut is
# meant per minute; above 5 mm (0.2 inch) per revolution none is meant per revolution, threads
# aside (their F is the lead). Judgement, not a FANUC limit.
SLOWEST_PER_MINUTE: Mapping[bool, float] = MappingProxyType({False: 1.0, True: 0.04})
LARGEST_PER_REV: Mapping[bool, float] = MappingProxyType({False: 5.0, True: 0.2})


def feed_unit_fault(feed: float, per_rev: bool, inch: bool) -> str | None:
    """Why a cutting feed looks like the other mode's value, or None."""
    if per_rev and feed > LARGEST_PER_REV[inch]:
        return tr(
            "{feed} {unit} per revolution, a feed per minute's size",
            feed=fmt(feed),
            unit=unit_of(inch),
        )
    if not per_rev and 0.0 < feed < SLOWEST_PER_MINUTE[inch]:
        return tr(
            "{feed} {unit} per minute, a feed per revolution's size",
            feed=fmt(feed),
            unit=unit_of(inch),
        )
    return None


def unit_of(inch: bool) -> str:
    """The unit of lengths as a message says it: mm, or inch in G20."""
    return tr("inch") if inch else "mm"


def speed_at(surface_speed: float, diameter: float, inch: bool) -> float:
    """The spindle speed (rpm) G96's surface speed asks for at a diameter: V = π D n / 1000
    (m/min, mm), V = π D n / 12 (ft/min, inch); infinite at the centre or past it."""
    if diameter <= 0.0:
        return math.inf
    return (12.0 if inch else 1000.0) * surface_speed / (math.pi * diameter)
