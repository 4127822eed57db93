"""The toolpath: where the tool goes, move by move, in work coordinates.

A ``Move`` is one straight or circular stretch of the tool's path: a rapid, a feed, a
threading pass or an arc. Positions are absolute work coordinates in the program's units; on
a lathe X is a diameter, as the program writes it. An axis the evaluator cannot place (no
absolute start, an unknown value) is absent from the move's positions, and the ``Toolpath``
says where it lost track of it.

The kinematics below are pure functions of the path's modal state (``PathModal``) and a
block's words: ``block_steps`` gives the block's moves and updates the state. The evaluator
calls them through a ``Recorder`` when it is asked for a toolpath (``evaluate(...,
toolpath=True)``), after its own handling of the block; a run without it pays one test per NC
block. The path is the programmed one: tool offsets, tool nose radius compensation (G40-G42)
and a thread's chamfer are not applied, nor scaling (G51), mirror image (G51.1) or
coordinate rotation (G68).

Sources: FANUC Series 0i-TF Operator's Manual (B-64604EN), "Interpolation functions"
(G00-G03, G32), "Reference position" (G28), "Coordinate system" (G50, G53, G54-G59), "Canned
cycle for lathe" (G90, G92, G94), "Multiple repetitive cycle" (G70-G76: G70-G73 in
:mod:`.stock_removal`); FANUC Series 0i-MF
Operator's Manual (B-64604EN, M series part), "Absolute and incremental programming",
"Plane selection", "Canned cycle for drilling" (G73-G89, G98/G99). What they leave to the
machine builder (parameters) is marked unverified where the path depends on it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Literal

from ..translation import tr
from . import stock_removal
from .direct_drawing import missing_coordinate
from .facts import Motion
from .values import Unknown, Value

MoveKind = Literal["rapid", "feed", "thread", "arc"]
MOVE_KINDS: tuple[MoveKind, ...] = ("rapid", "feed", "thread", "arc")

Plane = Literal["XY", "XZ", "YZ"]

# Moves kept per toolpath: a G76 or a peck cycle is many moves per block.
MAX_MOVES = 1_000_000


@dataclass(frozen=True, slots=True)
class Move:
    """One stretch of the path; ``line`` is the 0-based line of the block that made it."""

    kind: MoveKind
    start: dict[str, float]
    end: dict[str, float]
    line: int
    program: str
    uri: str = ""
    # Arcs: the centre (absolute, same axes as the positions) and the direction, seen along
    # the axis normal to the arc's plane as the control sees it (G02 clockwise).
    centre: dict[str, float] | None = None
    clockwise: bool | None = None
    plane: Plane = "XY"
    # Which motion record of the trace the move belongs to (its index in Facts.motions):
    # a canned cycle is one record of several moves.
    motion: int = -1
    # The canned cycle the move is a part of ("G92", "G76", "G81"; "" for a plain move).
    cycle: str = ""


@dataclass(frozen=True, slots=True)
class LostTrack:
    """Where the path stops being known for some axes, and why. ``axes`` is empty for a note
    that keeps the position: moves the path does not draw (a G74's pecks, a G71 of a type II
    profile)."""

    line: int
    program: str
    axes: tuple[str, ...]
    reason: str
    uri: str = ""
    # How many moves the path had when it lost track: the moves from this index on are the
    # ones it can leave undrawn (-1: not said).
    at: int = -1


TimedKind = Literal["dwell", "tool change", "M code"]


@dataclass(frozen=True, slots=True)
class TimedEvent:
    """A block that takes the machine time without moving the tool: a G04 dwell, a tool
    change (a lathe's T of another tool, a mill's M06), an M code the settings time
    (``Config.m_code_seconds``). The cycle time (:mod:`.cycle_time`) gives each its seconds."""

    kind: TimedKind
    line: int
    program: str
    uri: str
    program_line: int  # first line of the program the block belongs to
    moves: int  # the moves of the path before it
    motions: int  # the motion records of the run when it ran (its block's own included)
    seconds: float = 0.0  # a dwell's time (the others' are the settings')
    code: float = 0.0  # the M code, or the tool a change loads


@dataclass(frozen=True, slots=True)
class RunStart:
    """Where a run (an entry program) begins in the toolpath: its program, and the moves,
    timed events and motion records before it."""

    uri: str
    program_line: int
    program: str
    moves: int
    events: int
    motions: int


def dwell_seconds(values: Mapping[str, Value]) -> float | None:
    """A G04's time: X or U in seconds, P in milliseconds (FANUC 0i-TF/0i-MF Operator's
    Manual, "Dwell (G04)": P takes no decimal point, its unit is 0.001 s). None when the block
    gives no known time. X without a decimal point is read as the evaluator reads it (a
    control in pocket calculator mode; otherwise in the least input increment, unverified);
    a dwell in revolutions (G95 with the parameter DWL set) is not read."""
    for address, scale in (("X", 1.0), ("U", 1.0), ("P", 0.001)):
        value = values.get(address)
        if value is not None:
            return value * scale if type(value) is float and value >= 0.0 else None
    return None


# The reason of the note on the axes placed for the first time: before it, the tool stood
# where the run began, which the program does not say.
UNKNOWN_START = tr(
    "where the tool stands when the run begins is not known: the path starts at the first "
    "absolute position of each axis"
)
# The reason of the note on the axes an axis word whose value is not known moves.
UNKNOWN_WORD = tr("the value of the axis word is not known")


@dataclass(slots=True)
class Toolpath:
    """Every move of a run, in the order the control makes them."""

    moves: list[Move] = field(default_factory=list)
    lost: list[LostTrack] = field(default_factory=list)
    lathe: bool = True
    inch: bool = False  # G20 in force at the first move: the positions are in inches
    truncated: bool = False  # more moves than kept
    # Where the tool stood at a motion record that makes no move (its index in Facts.motions:
    # a cycle's first block): the trace shows it there.
    standing: dict[int, dict[str, float]] = field(default_factory=dict)
    # What the variables a motion record's block reads held when it ran (its index in
    # Facts.motions: ``{101: 3.5}``; ``None`` vacant): the trace shows them with the block.
    values: dict[int, dict[int, Value]] = field(default_factory=dict)
    # Where each run (an entry program) begins: the index of its first move and of its first
    # ``lost``. Where the tool stands is not known again at each.
    runs: list[tuple[int, int]] = field(default_factory=list)
    # Each run's program and first move, event and motion record, in the order of ``runs``.
    starts: list[RunStart] = field(default_factory=list)
    # The blocks that take time without a move, in the order they ran (see TimedEvent).
    events: list[TimedEvent] = field(default_factory=list)

    def axes(self) -> tuple[str, ...]:
        """The axes any move places, in X, Y, Z order."""
        seen = {a for m in self.moves for a in (*m.start, *m.end)}
        return tuple(a for a in "XYZ" if a in seen)


# ---- the path's modal state ------------------------------------------------------------------

LATHE_AXES = ("X", "Z", "Y")
MILL_AXES = ("X", "Y", "Z")
# A lathe's incremental addresses in G-code system A (0i-TF "Absolute and incremental
# programming"): U, W, V for X, Z, Y.
LATHE_INCREMENTAL: Mapping[str, str] = MappingProxyType({"X": "U", "Z": "W", "Y": "V"})
LINEAR_KINDS: Mapping[float, MoveKind] = MappingProxyType(
    {
        0.0: "rapid",
        1.0: "feed",
        31.0: "feed",  # skip function: a linear feed, stopped by the signal (drawn whole)
        32.0: "thread",
        33.0: "thread",
        34.0: "thread",  # variable lead: straight, as G32
    }
)
LATHE_CYCLE_CODES = (90.0, 92.0, 94.0)
# The mill's drilling cycles (group 09, 0i-MF "Canned cycle for drilling").
DRILLING = frozenset({73.0, 74.0, 76.0, 81.0, 82.0, 83.0, 84.0, 85.0, 86.0, 87.0, 88.0, 89.0})
# Drilling cycles that feed back out to the R point (tapping G74/G84, boring G85/G89); the
# others leave the bottom at rapid (G86 with the spindle stopped, G76 after its shift).
FEED_OUT = frozenset({74.0, 84.0, 85.0, 89.0})
# The lathe's multiple repetitive cycles G70-G75 (G76 is drawn from its passes): G70-G73 are
# drawn from their profile (see stock_removal), G74 and G75 are not.
NOT_EXPANDED = frozenset({70.0, 71.0, 72.0, 73.0, 74.0, 75.0})
PROFILE_CYCLES = frozenset({70.0, 71.0, 72.0, 73.0})
# What a profile block of G70-G73 may not command (0i-TF "Multiple repetitive cycle",
# limitations: one-shot G codes but G04, the threading and canned cycles; the control stops
# with an alarm, unverified which).
NOT_IN_PROFILE = frozenset(
    {10.0, 27.0, 28.0, 30.0, 31.0, 32.0, 33.0, 34.0, 50.0, 52.0, 53.0, 90.0, 92.0, 94.0}
    | {70.0, 71.0, 72.0, 73.0, 74.0, 75.0, 76.0}
)
# Codes whose block's axis words are no move: G04 dwell (X, U: its time in seconds; P in
# milliseconds), G10 programmable data input (the values it sets), G22 stored stroke check (the
# limits), G51 scaling (its centre), G51.1 programmable mirror image (its axis), G68
# coordinate rotation (its centre). From the G code lists of FANUC's 0i-TF/0i-MF operator's
# manuals as commonly described; unverified against the manuals' text.
NOT_MOVES = frozenset({4.0, 10.0, 22.0, 51.0, 51.1, 68.0})
# G71/G72's escape e when no block of the program sets it: parameter 5133, set by the machine
# builder; 1 mm (0.04 inch) here (unverified).
ESCAPE_MM = 1.0
WORK_OFFSETS = frozenset({54.0, 55.0, 56.0, 57.0, 58.0, 59.0})
# G73's retract after each peck (parameter 5114) and G83's clearance above the last depth
# (parameter 5115): set by the machine builder; 1 mm (0.04 inch) here (unverified).
PECK_RETRACT_MM = 1.0
MAX_REPEATS = 1000  # K of a drilling cycle: more holes than this are cut short


@dataclass(slots=True, eq=False)
class PathModal:
    """What the path knows between blocks: positions of the known axes (a new dict at every
    change, so moves can share them), and the modal codes that decide what a word means."""

    lathe: bool
    position: dict[str, float] = field(default_factory=dict)
    absolute: bool = True  # G90 (mill); a lathe in G-code system A has U/W instead
    plane: Plane = "XY"
    inch: bool = False
    motion: float | None = None  # group 01, the lathe's G90/G92/G94 included
    # G90/G92/G94: X, Z (absolute) and R stay in force for the blocks that repeat the cycle
    # (0i-TF "Canned cycle for lathe": the data of X (U), Z (W) and R are modal).
    cycle_words: dict[str, float] = field(default_factory=dict)
    drilling: float | None = None  # the mill's group 09 code in force
    drill_words: dict[str, float] = field(default_factory=dict)  # Z, R, Q of the cycle
    return_to_initial: bool = True  # G98 (default at power on); G99: the R point
    initial_z: float | None = None  # the initial level of the drilling cycle
    work_offset: float | None = None
    # The multiple repetitive cycles' modal data from their first blocks: G71 U(Δd) R(e) and
    # G72 W(Δd) R(e) set the same two (parameters 5132 and 5133); G73 U(Δi) W(Δk) R(d)
    # (parameters 5135, 5136, 5137). None: the parameter's, not known.
    depth_of_cut: float | None = None
    escape: float | None = None
    pattern: tuple[float | None, float | None, float | None] = (None, None, None)
    # The axes whose last word had more decimals than the least input increment (Z.3182 in
    # mm): the position is rounded (Z0.318), as a metric control rounds it, but the program
    # may be run in inches, where it is not: such a block end position is not known.
    inexact: frozenset[str] = frozenset()

    def __post_init__(self) -> None:
        if self.lathe:
            self.plane = "XZ"

    @property
    def axes(self) -> tuple[str, ...]:
        return LATHE_AXES if self.lathe else MILL_AXES

    def q(self, value: float) -> float:
        """A position at the least input increment (IS-B): 0.001 mm, 0.0001 inch."""
        return round(value, 4 if self.inch else 3) + 0.0  # no -0.0


Point = dict[str, float]
# One move of a block: kind, start, end, centre, clockwise, which of the block's motion
# records it belongs to (a G76's pass; 0 otherwise), the cycle's code ("" for none).
Step = tuple[MoveKind, Point, Point, Point | None, bool | None, int, str]
Loss = tuple[tuple[str, ...], str]


def _word(values: Mapping[str, Value], address: str) -> float | Unknown | None:
    v = values.get(address)
    return v if isinstance(v, float | Unknown) else None


class _Block:
    """The moves of one block as they are worked out: each starts where the last ended."""

    __slots__ = ("lost", "modal", "steps")

    def __init__(self, modal: PathModal) -> None:
        self.modal = modal
        self.steps: list[Step] = []
        self.lost: list[Loss] = []

    def go(
        self,
        kind: MoveKind,
        end: Point,
        centre: Point | None = None,
        clockwise: bool | None = None,
        record: int = 0,
        cycle: str = "",
    ) -> None:
        modal = self.modal
        start = modal.position
        if end == start and centre is None:
            return  # no motion (an arc with a centre and the same end is a full circle)
        self.steps.append((kind, start, end, centre, clockwise, record, cycle))
        modal.position = end

    def lose(self, axes: Sequence[str], reason: str) -> None:
        position = self.modal.position
        gone = tuple(a for a in axes if a in position)
        if gone:
            self.modal.position = {a: v for a, v in position.items() if a not in gone}
            self.lost.append((gone, reason))

    def note(self, reason: str) -> None:
        self.lost.append(((), reason))


def _targets(
    block: _Block, values: Mapping[str, Value], absolute: bool | None = None
) -> tuple[Point, bool]:
    """Where the block's axis words send the tool (the other axes stay), and whether any axis
    word is there. An axis whose word is unknown, or incremental from an unknown place, is
    lost (absent from the point)."""
    modal = block.modal
    here = modal.position
    end = dict(here)
    commanded = False
    unknown: list[str] = []
    if absolute is None:
        absolute = modal.absolute
    lathe = modal.lathe
    digits = 4 if modal.inch else 3  # PathModal.q, inline: once per axis word of every block
    for axis in LATHE_AXES if lathe else MILL_AXES:
        value = values.get(axis)
        incremental: Value | None = None
        if lathe:
            incremental = values.get(LATHE_INCREMENTAL[axis])
        elif not absolute:
            value, incremental = None, value
        if value is not None:
            if isinstance(value, float):
                commanded = True
                end[axis] = placed = round(value, digits) + 0.0
                _rounded(modal, axis, placed, value)
                continue
            if isinstance(value, Unknown):
                commanded = True
                unknown.append(axis)
                end.pop(axis, None)
                continue
        if incremental is not None:
            if isinstance(incremental, float):
                commanded = True
                start = here.get(axis)
                if start is not None:
                    written = start + incremental
                    end[axis] = placed = round(written, digits) + 0.0
                    _rounded(modal, axis, placed, written)
            elif isinstance(incremental, Unknown):
                commanded = True
                unknown.append(axis)
                end.pop(axis, None)
    if unknown:
        gone = tuple(a for a in unknown if a in here)
        if gone:
            block.lost.append((gone, UNKNOWN_WORD))
    return end, commanded


def _rounded(modal: PathModal, axis: str, placed: float, written: float) -> None:
    """Keep ``modal.inexact`` up to date: whether the axis's last word had digits below the
    least input increment, which the position drops."""
    if abs(placed - written) > 1e-9:
        if axis not in modal.inexact:
            modal.inexact = modal.inexact | {axis}
    elif axis in modal.inexact:
        modal.inexact = modal.inexact - {axis}


# ---- arcs ------------------------------------------------------------------------------------

# The two axes of each plane, in the order that makes G03 counter-clockwise (the third axis
# pointing at the viewer: Z for XY, Y for ZX, X for YZ; 0i-MF "Plane selection"); with the
# word of the centre's offset along each (I J K).
PLANE_AXES: Mapping[Plane, tuple[tuple[str, str], tuple[str, str]]] = MappingProxyType(
    {
        "XY": (("X", "I"), ("Y", "J")),
        "XZ": (("Z", "K"), ("X", "I")),
        "YZ": (("Y", "J"), ("Z", "K")),
    }
)


def arc_centre(
    start: Point,
    end: Point,
    values: Mapping[str, Value],
    clockwise: bool,
    plane: Plane,
    lathe: bool,
) -> Point | None:
    """The centre of a G02/G03 (the start's other axes kept), or None when it cannot be
    known: an unknown R or I J K, an unknown start or end in the plane, neither R nor I J K.

    R: the radius, negative for an arc of more than 180° (0i-MF "Circular interpolation";
    for the lathe the same sign rule is taken, unverified); R wins over I J K when both are
    given. I J K: the centre's offset from the start, incremental; a lathe's I is a radius.
    On a lathe X is a diameter: the geometry is worked in radius.
    """
    (u_axis, u_word), (v_axis, v_word) = PLANE_AXES[plane]
    if not (u_axis in start and v_axis in start and u_axis in end and v_axis in end):
        return None
    # A lathe's X in radius for the geometry (it is the v axis of the lathe's ZX plane).
    scale = 0.5 if lathe and v_axis == "X" else 1.0
    su, sv = start[u_axis], start[v_axis] * scale
    eu, ev = end[u_axis], end[v_axis] * scale
    radius = values.get("R")
    if isinstance(radius, Unknown):
        return None
    if isinstance(radius, float):
        du, dv = eu - su, ev - sv
        chord = math.hypot(du, dv)
        if chord == 0.0 or radius == 0.0:
            return None  # an arc of 0°: FANUC makes no move
        # The centre lies on the chord's perpendicular bisector: left of the chord (seen in
        # the plane, counter-clockwise positive) for a G03 of at most 180°; a G02, or R < 0,
        # takes the other side.
        half = chord / 2.0
        # A radius shorter than half the chord: the centre at the chord's middle (the
        # control raises an alarm past a tolerance, parameter 3410; unverified).
        height = math.sqrt(max(0.0, radius * radius - half * half))
        side = -1.0 if clockwise else 1.0
        if radius < 0:
            side = -side
        cu = (su + eu) / 2.0 - side * height * dv / chord
        cv = (sv + ev) / 2.0 + side * height * du / chord
    else:
        u_off, v_off = values.get(u_word), values.get(v_word)
        if isinstance(u_off, Unknown) or isinstance(v_off, Unknown):
            return None
        if not isinstance(u_off, float) and not isinstance(v_off, float):
            return None  # FANUC: alarm PS0022 (neither R nor I, J, K)
        cu = su + (u_off if isinstance(u_off, float) else 0.0)
        cv = sv + (v_off if isinstance(v_off, float) else 0.0)
    out = dict(start)
    out[u_axis] = cu
    out[v_axis] = cv / scale
    return out


# ---- one block -------------------------------------------------------------------------------


# The blocks of a G70-G73's profile N(ns)..N(nf) as the evaluator read them: each block's
# words and G codes; or why the evaluator could not follow the profile.
ProfileBlock = tuple[Mapping[str, Value], Sequence[float]]
Profile = Sequence[ProfileBlock] | str


def block_steps(
    modal: PathModal,
    values: Mapping[str, Value],
    g_codes: Sequence[float],
    passes: Sequence[float | None] = (),
    profile: Profile | None = None,
) -> tuple[list[Step], list[Loss]]:
    """The moves one block makes from ``modal``'s state, which it updates; and the axes it
    loses track of, with why. ``passes``: a lathe G76's pass diameters (from the evaluator's
    ``cycles.g76_depths``), one motion record each. ``profile``: a G71-G73's profile blocks
    (G70's profile is run by the evaluator, block by block)."""
    block = _Block(modal)
    lathe = modal.lathe
    one_shot: float | None = None
    for g in g_codes:
        if g in (17.0, 18.0, 19.0) and not lathe:
            modal.plane = "XY" if g == 17.0 else "XZ" if g == 18.0 else "YZ"
        elif g == 20.0:
            modal.inch = True
        elif g == 21.0:
            modal.inch = False
        elif g in LINEAR_KINDS or g in (2.0, 3.0) or (lathe and g in LATHE_CYCLE_CODES):
            if g == 31.0:
                one_shot = g
            else:
                modal.motion = g
                if g not in LATHE_CYCLE_CODES:
                    modal.cycle_words = {}
            if not lathe:
                modal.drilling = None  # a group 01 code ends a drilling cycle (0i-MF)
        elif not lathe and g in (90.0, 91.0):
            modal.absolute = g == 90.0
        elif not lathe and g in (98.0, 99.0):
            modal.return_to_initial = g == 98.0
        elif not lathe and g == 80.0:
            modal.drilling = None
        elif not lathe and g in DRILLING:
            if modal.drilling is None:
                modal.initial_z = modal.position.get("Z")
            modal.drilling = g
        elif g in WORK_OFFSETS:
            if modal.work_offset is not None and modal.work_offset != g:
                block.lose(
                    modal.axes, tr("G{code:g} selects another work coordinate system", code=g)
                )
            modal.work_offset = g
        elif (
            g in NOT_MOVES
            or g in (27.0, 28.0, 30.0, 52.0, 53.0)
            or (lathe and g in (50.0, 76.0))
            or (lathe and g in NOT_EXPANDED)
        ):
            one_shot = g
        elif not lathe and g == 92.0:
            one_shot = 50.0  # the mill's coordinate system setting is the lathe's G50
    if one_shot is not None:
        _one_shot(block, one_shot, values, passes, profile)
    elif not lathe and modal.drilling is not None:
        _drill(block, values)
    elif modal.motion is not None:
        _modal_motion(block, modal.motion, values)
    return block.steps, block.lost


def _one_shot(
    block: _Block,
    code: float,
    values: Mapping[str, Value],
    passes: Sequence[float | None],
    profile: Profile | None = None,
) -> None:
    modal = block.modal
    if code in (28.0, 30.0):
        # Through the intermediate point to the reference point (0i-TF "Reference position
        # return"): the axes named go there at rapid; where the reference point is in work
        # coordinates the analysis does not know.
        middle, commanded = _targets(block, values)
        if not commanded:
            return
        block.go("rapid", middle)
        named = [
            a for a in modal.axes if a in values or (modal.lathe and LATHE_INCREMENTAL[a] in values)
        ]
        block.lose(
            named,
            tr(
                "G{code:g} returns to the reference point, whose work coordinates are not known",
                code=code,
            )
            if code == 28.0
            else tr(
                "G{code:g} returns to the second reference point, whose work coordinates are "
                "not known",
                code=code,
            ),
        )
    elif code == 52.0:
        named = [a for a in modal.axes if a in values]
        block.lose(named, tr("G52 sets a local coordinate system (not followed)"))
    elif code == 53.0:
        named = [a for a in modal.axes if a in values]
        block.lose(named, tr("G53 moves in machine coordinates; the work offset is not known"))
    elif code == 50.0:
        # Coordinate system setting (lathe G50, mill G92): the tool's position becomes the
        # words' values, without a move (0i-TF "Setting a workpiece coordinate system").
        position = dict(modal.position)
        for axis in modal.axes:
            v = values.get(axis)
            if isinstance(v, float):
                position[axis] = placed = modal.q(v)
                _rounded(modal, axis, placed, v)
            elif isinstance(v, Unknown):
                position.pop(axis, None)
        modal.position = position
    elif code == 31.0:
        end, _ = _targets(block, values)
        block.go("feed", end)
    elif code == 27.0:
        end, _ = _targets(block, values)
        block.go("rapid", end)
    elif code == 76.0:
        _g76(block, values, passes)
    elif code in PROFILE_CYCLES:
        _profile_cycle(block, code, values, profile)
    elif code in NOT_EXPANDED and _has_axis(modal, values):
        block.note(
            tr(
                "G{code:g}'s passes are not drawn; the tool is back at the cycle's start point "
                "after it",
                code=code,
            )
        )
    # NOT_MOVES (a G04 dwell, whose X is seconds; a G10) make no move.


def _cycle_data(modal: PathModal, code: float, values: Mapping[str, Value]) -> None:
    """The first block of G71 ``U(Δd) R(e)``, G72 ``W(Δd) R(e)``, G73 ``U(Δi) W(Δk) R(d)``:
    modal data, kept until another value is given (an unknown one: not known)."""
    if code in (71.0, 72.0):
        depth = _word(values, "U" if code == 71.0 else "W")
        if depth is not None:
            modal.depth_of_cut = abs(depth) if isinstance(depth, float) else None
        escape = _word(values, "R")
        if escape is not None:
            modal.escape = abs(escape) if isinstance(escape, float) else None
    elif code == 73.0:
        old = modal.pattern
        new: list[float | None] = list(old)
        for n, address in enumerate("UWR"):
            v = _word(values, address)
            if v is not None:
                new[n] = v if isinstance(v, float) else None
        modal.pattern = (new[0], new[1], new[2])


def _profile_cycle(
    block: _Block, code: float, values: Mapping[str, Value], profile: Profile | None
) -> None:
    """G70-G73 (see :mod:`.stock_removal`). G70's moves are its profile's blocks, which the
    evaluator runs; G71-G73's are worked out here from the profile the evaluator read."""
    modal = block.modal
    name = f"G{code:g}"
    if not ("P" in values and "Q" in values):
        _cycle_data(modal, code, values)
        return
    if isinstance(profile, str):
        block.note(
            tr("{code}: {why}: the finishing pass is not drawn", code=name, why=profile)
            if code == 70.0
            else tr("{code}: {why}: its passes are not drawn", code=name, why=profile)
        )
        return
    if code == 70.0 or profile is None:
        return  # G70: its profile's blocks come next, as the evaluator runs them
    legs = _profile_legs(block, code, values, profile)
    for kind, end, centre, clockwise in legs:
        assert kind in MOVE_KINDS
        block.go(kind, end, centre, clockwise, cycle=name)


def _profile_contour(
    block: _Block, name: str, scratch: PathModal, profile: Sequence[ProfileBlock]
) -> tuple[str, list[stock_removal.Segment]] | None:
    """How a G70-G73 profile is approached (``rapid``, ``feed``) and its contour from A' to B;
    None, with the block's note why, when it cannot be drawn."""
    approach: str | None = None
    contour: list[stock_removal.Segment] = []
    for n, (words, codes) in enumerate(profile):
        refused = next((g for g in codes if g in NOT_IN_PROFILE), None)
        if refused is not None:
            block.note(
                tr(
                    "{code}'s profile commands G{refused:g}, which a profile may not hold "
                    "(the control stops with an alarm): its passes are not drawn",
                    code=name,
                    refused=refused,
                )
            )
            return None
        steps, lost = block_steps(scratch, words, codes)
        if any(axes for axes, _ in lost) or "X" not in scratch.position:
            block.note(
                tr("{code}'s profile goes where the analysis cannot follow: not drawn", code=name)
            )
            return None
        for kind, s, e, centre, clockwise, _record, _cycle in steps:
            if n == 0:
                approach = kind
            else:
                contour.append((kind, s, e, centre, clockwise))
        if n == 0 and approach is None:
            approach = "rapid" if scratch.motion == 0.0 else "feed"
    if approach not in ("rapid", "feed"):
        block.note(
            tr(
                "{code}'s profile does not begin with G00 or G01 (the control stops with an "
                "alarm): its passes are not drawn",
                code=name,
            )
        )
        return None
    if not contour:
        block.note(tr("{code}'s profile makes no move after its first block: not drawn", code=name))
        return None
    return approach, contour


def _profile_legs(
    block: _Block, code: float, values: Mapping[str, Value], profile: Sequence[ProfileBlock]
) -> list[stock_removal.Leg]:
    modal = block.modal
    name = f"G{code:g}"
    start = modal.position
    if "X" not in start or "Z" not in start:
        block.note(tr("{code}'s start point is not known: its passes are not drawn", code=name))
        return []
    allowance: list[float] = []  # Δu (a diameter), Δw
    for address in "UW":
        v = _word(values, address)
        if isinstance(v, Unknown):
            block.note(
                tr(
                    "{code}'s finishing allowance {address} is not known: not drawn",
                    code=name,
                    address=address,
                )
            )
            return []
        allowance.append(v or 0.0)
    # The profile, from the start point: the ns block's move to A', then A' to B.
    scratch = PathModal(modal.lathe, dict(start), True, modal.plane, modal.inch, modal.motion)
    read = _profile_contour(block, name, scratch, profile)
    if read is None:
        return []
    approach, contour = read
    if code == 73.0:
        escape_x, escape_z, divisions = modal.pattern
        if escape_x is None or escape_z is None or divisions is None:
            block.note(
                tr(
                    "G73's escape or number of divisions is a parameter's (5135-5137), no "
                    "G73 U W R block gives it: its passes are not drawn"
                )
            )
            return []
        count = min(stock_removal.MAX_LAYERS, round(divisions))
        if count < 1:
            block.note(tr("G73's number of divisions is less than 1: not drawn"))
            return []
        return stock_removal.pattern(
            start, approach, contour, escape_x, escape_z, count, allowance[0], allowance[1], modal.q
        )
    facing = code == 72.0
    first = profile[0][0]
    if any(a in first for a in (("X", "U") if facing else ("Z", "W"))):
        block.note(
            tr(
                "{code}'s profile begins with a block that names {axis} too: type II "
                "(pockets), type II profile not drawn",
                code=name,
                axis="X" if facing else "Z",
            )
        )
        return []
    if not stock_removal.monotonic(contour):
        block.note(
            tr(
                "{code}'s profile is not monotonic in X and Z, as type I needs (the control "
                "stops with an alarm, PS0064 or PS0329, unverified): not drawn",
                code=name,
            )
        )
        return []
    # One-block form (Series 10/11 program format, parameter 0001#1 FCV): D is Δd.
    depth = _word(values, "D")
    if isinstance(depth, Unknown):
        block.note(tr("{code}'s depth of cut D is not known: its passes are not drawn", code=name))
        return []
    depth_of_cut = abs(depth) if isinstance(depth, float) else modal.depth_of_cut
    if depth_of_cut is None or depth_of_cut == 0.0:
        block.note(
            tr(
                "{code}'s depth of cut is parameter 5132's, no {code} {address} R block gives "
                "it: its passes are not drawn",
                code=name,
                address="W" if facing else "U",
            )
        )
        return []
    escape = modal.escape
    if escape is None:
        escape = ESCAPE_MM / (25.4 if modal.inch else 1.0)
        block.note(
            tr(
                "{code}'s escape e is parameter 5133's, not in the program: drawn as "
                "{escape:g} (unverified)",
                code=name,
                escape=escape,
            )
        )
    legs, short = stock_removal.layers(
        start,
        approach,
        contour,
        facing,
        depth_of_cut,
        escape,
        allowance[0],
        allowance[1],
        modal.q,
    )
    if short:
        block.note(
            tr(
                "{code} has more than {layers} layers: cut short",
                code=name,
                layers=stock_removal.MAX_LAYERS,
            )
        )
    return legs


def _has_axis(modal: PathModal, values: Mapping[str, Value]) -> bool:
    if any(a in values for a in modal.axes):
        return True
    return modal.lathe and any(LATHE_INCREMENTAL[a] in values for a in modal.axes)


def _modal_motion(block: _Block, code: float, values: Mapping[str, Value]) -> None:
    modal = block.modal
    if code in LATHE_CYCLE_CODES:
        if _has_axis(modal, values):
            _lathe_cycle(block, code, values)
        return
    end, commanded = _targets(block, values)
    if ",A" in values and code in (0.0, 1.0):
        _end_by_angle(block, values, end)
    circle = code in (2.0, 3.0) and any(isinstance(values.get(w), float) for w in "IJK")
    if not commanded and not circle:
        return
    if code in (2.0, 3.0):
        clockwise = code == 2.0
        centre = arc_centre(modal.position, end, values, clockwise, modal.plane, modal.lathe)
        if centre is None:
            # Drawn straight, and said so when the start was known.
            if all(a in modal.position for a in end):
                block.note(
                    tr("G{code:02g}'s centre is not known: drawn as a straight move", code=code)
                )
            block.go("feed", end)
        else:
            block.go("arc", end, {a: modal.q(v) for a, v in centre.items()}, clockwise)
        return
    block.go(LINEAR_KINDS.get(code, "feed"), end)


# The axes of the angle ",A": the plane's first (the angle's zero) and second.
_ANGLE_AXES: Mapping[Plane, tuple[str, str]] = MappingProxyType(
    {"XY": ("X", "Y"), "XZ": ("Z", "X"), "YZ": ("Y", "Z")}
)


def _end_by_angle(block: _Block, values: Mapping[str, Value], end: Point) -> None:
    """A move with ",A" and one of its plane's axes: the other axis's end on the line at that
    angle through the start (a lathe's X a diameter); lost when it cannot be worked out."""
    modal = block.modal
    first, second = ("Z", "X") if modal.lathe else _ANGLE_AXES[modal.plane]

    def given(axis: str) -> bool:
        return axis in values or (modal.lathe and LATHE_INCREMENTAL[axis] in values)

    if given(first) == given(second):
        return
    missing = second if given(first) else first
    angle = values[",A"]
    here = modal.position
    found = None
    if (
        isinstance(angle, float)
        and first in here
        and second in here
        and (first if given(first) else second) in end
    ):
        found = missing_coordinate(
            (here[first], here[second]),
            end[first] if given(first) else None,
            end[second] if given(second) else None,
            angle,
            2.0 if modal.lathe and second == "X" else 1.0,
        )
    if found is None:
        if end.pop(missing, None) is not None:
            block.lost.append(((missing,), tr("the angle ,A does not give the end of the move")))
        return
    end[missing] = modal.q(found)


def _lathe_cycle(block: _Block, code: float, values: Mapping[str, Value]) -> None:
    """G90 (turning), G92 (threading), G94 (facing), 0i-TF "Canned cycle for lathe": four
    moves from the start point A and back to it. G90/G92: rapid in X to the cut's start
    (X + 2R, R a radius), cut to (X, Z), out in X to A's diameter, rapid back in Z. G94:
    rapid in Z to Z + R, face to (X, Z), back in Z to A's Z, rapid out in X. The X, Z and R
    of the last block stay in force for a block that only changes some of them."""
    modal = block.modal
    words = modal.cycle_words
    start = modal.position
    name = f"G{code:g}"
    end, _ = _targets(block, values)
    for axis in ("X", "Z"):
        if axis in values or LATHE_INCREMENTAL[axis] in values:
            if axis in end:
                words[axis] = end[axis]
            else:
                words.pop(axis, None)
    r = values.get("R")
    if isinstance(r, float):
        words["R"] = r
    elif isinstance(r, Unknown):
        words["R"] = math.nan
    x, z, taper = words.get("X"), words.get("Z"), words.get("R", 0.0)
    x0, z0 = start.get("X"), start.get("Z")
    if x is None or z is None or x0 is None or z0 is None or math.isnan(taper):
        block.note(
            tr(
                "{code}'s start point or end point is not known: the cycle is not drawn",
                code=name,
            )
        )
        return
    cut: MoveKind = "thread" if code == 92.0 else "feed"
    out: MoveKind = "rapid" if code == 92.0 else "feed"
    if code == 94.0:
        block.go("rapid", {**start, "Z": modal.q(z + taper)}, cycle=name)
        block.go("feed", {**start, "X": x, "Z": z}, cycle=name)
        block.go("feed", {**start, "X": x, "Z": z0}, cycle=name)
    else:
        block.go("rapid", {**start, "X": modal.q(x + 2.0 * taper)}, cycle=name)
        block.go(cut, {**start, "X": x, "Z": z}, cycle=name)
        block.go(out, {**start, "X": x0, "Z": z}, cycle=name)
    block.go("rapid", start, cycle=name)


def _g76(block: _Block, values: Mapping[str, Value], passes: Sequence[float | None]) -> None:
    """G76's cutting block (0i-TF "Multiple threading cycle (G76)"): each pass from the start
    point A: rapid in X to the pass's diameter, thread to Z, rapid out in X to A's diameter,
    rapid back in Z to A. With R(i) (a radius) the thread is a taper: the pass starts
    2i off its end's diameter. The control moves each pass's start along the flank (one-edge
    infeed, by the tool angle) and chamfers the end: neither is drawn."""
    modal = block.modal
    if not passes:
        return  # the first block: parameters only
    start = modal.position
    end, _ = _targets(block, values)
    z, x0, z0 = end.get("Z"), start.get("X"), start.get("Z")
    if z is None or x0 is None or z0 is None or any(p is None for p in passes):
        block.note(tr("G76's start point or end point is not known: its passes are not drawn"))
        return
    taper = values.get("R")
    i = taper if isinstance(taper, float) else 0.0
    for n, pass_x in enumerate(passes):
        assert pass_x is not None
        x = modal.q(pass_x)
        block.go("rapid", {**start, "X": modal.q(x + 2.0 * i)}, record=n, cycle="G76")
        block.go("thread", {**start, "X": x, "Z": z}, record=n, cycle="G76")
        block.go("rapid", {**start, "X": x0, "Z": z}, record=n, cycle="G76")
        block.go("rapid", start, record=n, cycle="G76")


def _drill(block: _Block, values: Mapping[str, Value]) -> None:
    """The holes of the mill's drilling cycle in force (0i-MF "Canned cycle for drilling"),
    for a block with X, Y, Z or R: rapid to X Y, rapid down to the R point, in to Z, out to
    the R point (G99) or the initial level (G98), at rapid or, tapping and boring (G74 G84
    G85 G89), at feed to the R point. In G91, R is from the initial level and Z from the R
    point. G73 and G83 peck by Q: G73 backs off by a parameter's distance after each peck,
    G83 goes back to the R point and down again to that distance above the last depth. K
    repeats the hole (in G91 at each increment of X Y; K0 drills none). G76 and G87's shift,
    G87's back boring and G88's manual return are not drawn: they are drawn as a G81."""
    modal = block.modal
    code = modal.drilling
    assert code is not None
    name = f"G{code:g}"
    words = modal.drill_words
    for address in ("Z", "R", "Q"):
        v = values.get(address)
        if isinstance(v, float):
            words[address] = v
        elif isinstance(v, Unknown):
            words.pop(address, None)
    if not any(a in values for a in ("X", "Y", "Z", "R")):
        return  # no hole: a block of other words
    repeats = values.get("K")
    count = 1 if not isinstance(repeats, float) else min(MAX_REPEATS, max(0, round(repeats)))
    initial = modal.initial_z
    if initial is None:
        initial = modal.initial_z = modal.position.get("Z")
    r, z = words.get("R"), words.get("Z")
    flat = {a: v for a, v in values.items() if a in ("X", "Y")}
    if r is None or z is None or initial is None:
        block.lose(("Z",), tr("{code}'s R point, Z or initial level is not known", code=name))
        end, _ = _targets(block, flat)
        block.go("rapid", end, cycle=name)
        return
    r_level, bottom = (r, z) if modal.absolute else (initial + r, initial + r + z)
    r_level, bottom = modal.q(r_level), modal.q(bottom)
    retract = PECK_RETRACT_MM / (25.4 if modal.inch else 1.0)
    peck = abs(words.get("Q", 0.0)) if code in (73.0, 83.0) else 0.0
    total = abs(r_level - bottom)
    sign = -1.0 if bottom < r_level else 1.0  # the way in, from R towards Z

    def at(depth: float) -> Point:
        return {**modal.position, "Z": modal.q(r_level + sign * depth)}

    for _ in range(count):
        above, _commanded = _targets(block, flat)
        block.go("rapid", above, cycle=name)
        block.go("rapid", at(0.0), cycle=name)
        if peck > 0.0:
            depth = 0.0
            for _peck in range(MAX_REPEATS):
                if depth > 0.0 and code == 83.0:
                    block.go("rapid", at(max(0.0, depth - retract)), cycle=name)
                depth = min(depth + peck, total)
                block.go("feed", at(depth), cycle=name)
                if depth >= total - 1e-9:
                    break
                if code == 73.0:
                    block.go("rapid", at(max(0.0, depth - retract)), cycle=name)
                else:
                    block.go("rapid", at(0.0), cycle=name)
        else:
            block.go("feed", at(total), cycle=name)
        if code in FEED_OUT:
            block.go("feed", at(0.0), cycle=name)
        level = modal.q(initial) if modal.return_to_initial else r_level
        block.go("rapid", {**modal.position, "Z": level}, cycle=name)
        if modal.absolute:
            flat = {}  # K drills the same hole again (G90)


# ---- the recorder ----------------------------------------------------------------------------


class Recorder:
    """Builds a run's ``Toolpath`` from the blocks the evaluator runs: one ``block`` call per
    NC block, after the evaluator made its motion records of it. With ``keep`` False it only
    follows where the tool is (for ``#5001``-``#5003``, see :meth:`block_end`): no move is
    kept."""

    __slots__ = (
        "_finishing",
        "_seen",
        "_tool",
        "_unplaced",
        "keep",
        "modal",
        "timed_codes",
        "toolpath",
    )

    def __init__(
        self, lathe: bool, keep: bool = True, timed_codes: frozenset[float] = frozenset()
    ) -> None:
        self.toolpath = Toolpath(lathe=lathe)
        self.modal = PathModal(lathe)
        self.keep = keep
        self.timed_codes = timed_codes  # the M codes whose blocks are timed events
        self._tool: float | None = None  # a lathe's tool the last T selected, in this run
        self._seen = 0  # motion records before the block
        self._unplaced: set[str] = set(self.modal.axes)
        # A G70 under way: its start point, its motion record, line, program and document.
        self._finishing: tuple[Point, int, int, str, str] | None = None

    def begin_run(
        self, motions: int, lathe: bool | None = None, entry: tuple[str, int, str] = ("", -1, "")
    ) -> None:
        """A new run (an entry program, on a lathe or a mill; ``entry``: its document, first
        line and name): where the machine stands and its tool are not known again."""
        self.modal = PathModal(self.modal.lathe if lathe is None else lathe)
        self._unplaced = set(self.modal.axes)
        self._tool = None
        path = self.toolpath
        path.runs.append((len(path.moves), len(path.lost)))
        path.starts.append(RunStart(*entry, len(path.moves), len(path.events), motions))
        self._seen = motions
        self._finishing = None

    def timed(
        self,
        where: tuple[str, str, int, int],
        values: Mapping[str, Value],
        g_codes: Sequence[float],
        m_codes: Sequence[float],
        motions: int,
    ) -> None:
        """The timed events of the block just run (``where``: its program, document, line and
        program's first line): a G04's dwell, a tool change, the M codes of ``timed_codes``.
        A lathe's T changes the tool when it selects another than the run's last T (the tool
        of a four-digit Txxyy is xx, 0i-TF "Tool function"; the first T of a run counts, the
        turret's place before it not being known); a mill's M06 changes it."""
        if not self.keep:
            return
        program, uri, line, program_line = where
        events = self.toolpath.events
        at = len(self.toolpath.moves)
        if 4.0 in g_codes:
            seconds = dwell_seconds(values)
            if seconds is not None:
                events.append(
                    TimedEvent("dwell", line, program, uri, program_line, at, motions, seconds)
                )
        if self.modal.lathe:
            t = values.get("T")
            if type(t) is float and t > 0.0:
                tool = t // 100.0 if t >= 100.0 else t
                if tool and tool != self._tool:
                    self._tool = tool
                    events.append(
                        TimedEvent(
                            "tool change", line, program, uri, program_line, at, motions, 0.0, tool
                        )
                    )
        for m in m_codes:
            if m == 6.0 and not self.modal.lathe:
                t = values.get("T")
                tool = t if type(t) is float else 0.0
                events.append(
                    TimedEvent(
                        "tool change", line, program, uri, program_line, at, motions, 0.0, tool
                    )
                )
            if m in self.timed_codes:
                events.append(
                    TimedEvent("M code", line, program, uri, program_line, at, motions, 0.0, m)
                )

    def block_end(self, axis: int) -> float | None:
        """Where the last block sent axis number ``axis`` (1 for #5001): the programmed
        position in work coordinates, as FANUC's block end position #5001-#5020 gives it
        (Custom Macro, "System variables: position information"); None when not known. The
        axes are numbered X, Z on a lathe and X, Y, Z on a mill, the usual order of
        parameter 1020 (unverified: the machine builder's)."""
        modal = self.modal
        names = ("X", "Z") if modal.lathe else ("X", "Y", "Z")
        if not 1 <= axis <= len(names):
            return None
        name = names[axis - 1]
        if name in modal.inexact:
            return None  # rounded as in mm; in inches it would not be (see PathModal.inexact)
        return modal.position.get(name)

    def lose_all(self, line: int, program: str, uri: str, reason: str) -> None:
        """Every axis lost: a call the analysis cannot follow moved the tool."""
        modal = self.modal
        gone = tuple(a for a in modal.axes if a in modal.position)
        if gone:
            modal.position = {}
            if self.keep:
                path = self.toolpath
                path.lost.append(LostTrack(line, program, gone, reason, uri, len(path.moves)))

    def end_profile(self) -> None:
        """The end of a G70's profile: the control returns to the cycle's start point at
        rapid (0i-TF "Finishing cycle (G70)")."""
        finishing = self._finishing
        self._finishing = None
        if finishing is None:
            return
        start, motion, line, program, uri = finishing
        modal = self.modal
        here = modal.position
        modal.position = start
        moves = self.toolpath.moves
        if not self.keep or here == start:
            return
        if len(moves) >= MAX_MOVES:
            self.toolpath.truncated = True
            return
        moves.append(
            Move("rapid", here, start, line, program, uri, None, None, modal.plane, motion, "G70")
        )

    def block(
        self,
        program: str,
        uri: str,
        line: int,
        values: Mapping[str, Value],
        g_codes: Sequence[float],
        motions: Sequence[Motion],
        profile: Profile | None = None,
        read: dict[int, Value] | None = None,
    ) -> None:
        """The moves of the block just run; ``motions``: the run's motion records, those the
        block made at the end. ``profile``: a G70-G73's profile (see ``block_steps``); for a
        G70, an empty one says that the evaluator runs its blocks next, and calls
        :meth:`end_profile` after them. ``read``: what the variables the block reads held."""
        first = self._seen
        made = len(motions) - first
        self._seen = len(motions)
        modal = self.modal
        passes: list[float | None] = []
        if modal.lathe and 76.0 in g_codes and made:
            passes = [m.x for m in motions[first:]]
        steps, lost = block_steps(modal, values, g_codes, passes, profile)
        if profile is not None and not isinstance(profile, str) and 70.0 in g_codes:
            self._finishing = (modal.position, first if made else -1, line, program, uri)
        if not self.keep:
            return
        path = self.toolpath
        if read:
            for i in range(first, first + made):
                path.values[i] = read
        for axes, reason in lost:
            path.lost.append(LostTrack(line, program, axes, reason, uri, len(path.moves)))
        unplaced = self._unplaced
        placed = (
            [a for a in modal.axes if a in unplaced and a in modal.position] if unplaced else []
        )
        if placed:
            unplaced.difference_update(placed)
            if steps:  # not a coordinate system setting (G50), which says where the tool is
                path.lost.append(
                    LostTrack(line, program, tuple(placed), UNKNOWN_START, uri, len(path.moves))
                )
        if not steps:
            for i in range(first, first + made):
                path.standing[i] = modal.position
            return
        moves = path.moves
        if not moves:
            path.inch = modal.inch
        plane = modal.plane
        finishing = "G70" if self._finishing is not None else ""
        for kind, start, end, centre, clockwise, record, cycle in steps:
            if len(moves) >= MAX_MOVES:
                path.truncated = True
                return
            motion = first + min(record, made - 1) if made else -1
            moves.append(
                Move(
                    kind,
                    start,
                    end,
                    line,
                    program,
                    uri,
                    centre,
                    clockwise,
                    plane,
                    motion,
                    cycle or finishing,
                )
            )
