"""The cycle time: how long each run of a program keeps the machine busy.

Worked out of a run's toolpath (:mod:`.toolpath`: the moves with the canned cycles expanded,
and the timed events) and its motion records (the F, the spindle speed and the feed mode in
force at each block), with the machine's figures from the settings (``Config``):

- a feed (G01, an arc, a canned cycle's cut) at F mm/min (G94, a lathe's G98), or at F mm/rev
  times the spindle speed (G95, a lathe's G99): the speed in G97 is S; in G96 it follows the
  diameter, n = 1000 V / (π D) (V m/min, D mm; 12 V / (π D) in ft/min and inches), clamped by
  the G50 S in force and the machine's maximum speed (FANUC 0i-TF/0i-MF Operator's Manual,
  "Feed functions", "Constant surface speed control", "Clamp of maximum spindle speed");
- a threading pass (G32, G92's and G76's threading legs) along its longer axis at F (the
  lead) times the spindle speed, per minute, whatever the feed mode (0i-TF "Threading");
- a rapid (G00 and the cycles' rapid legs) as non-interpolated positioning: each axis at its
  own rate (``rapid_rate_x`` and on), the move taking as long as its slowest axis;
- a dwell (G04) its time; a tool change the settings' seconds; an M code the seconds the
  settings give it (none by default).

A lathe's X is a diameter: the X axis moves half its change. G20's lengths are inches, their
feeds inches per minute or per revolution; the rapid rates are in mm/min. What the model
leaves out: acceleration and deceleration, the look-ahead's corner slowing, the overrides,
the spindle's ramp-up, the control's block processing time, the thread's chamfer (G92, G76)
and the drilling cycles' shifts; a dwell in revolutions; a move whose F or spindle speed the
run cannot know is counted, not timed (:attr:`CycleTime.untimed`).
"""

from __future__ import annotations

import math
from array import array
from bisect import bisect_right
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from ..config import Config
from ..translation import tr
from .facts import POWER_ON_FEED_MODE, Facts, Motion
from .toolpath import PLANE_AXES, Move, TimedEvent, Toolpath

MM_PER_INCH = 25.4
# The feed modes in which F is a feed per revolution: a lathe's G99, a mill's G95.
PER_REVOLUTION = frozenset({99.0, 95.0})
# The pieces an arc's diameter is followed in, in G96 (where the speed follows it).
ARC_PIECES = 32
# The parts of a cycle time, in the order a breakdown is shown.
PARTS = ("cutting", "threading", "rapid", "dwell", "tool change", "M codes")
# Each part as a user reads it.
PART_NAMES: Mapping[str, str] = MappingProxyType(
    {
        "cutting": tr("cutting"),
        "threading": tr("threading"),
        "rapid": tr("rapid"),
        "dwell": tr("dwell"),
        "tool change": tr("tool change"),
        "M codes": tr("M codes"),
    }
)


@dataclass(slots=True)
class Breakdown:
    """Seconds by part of the cycle: the cutting feeds, the threading passes, the rapids,
    the dwells, the tool changes and the M codes the settings time."""

    cutting: float = 0.0
    threading: float = 0.0
    rapid: float = 0.0
    dwell: float = 0.0
    tool_change: float = 0.0
    m_codes: float = 0.0

    @property
    def total(self) -> float:
        return (
            self.cutting
            + self.threading
            + self.rapid
            + self.dwell
            + self.tool_change
            + self.m_codes
        )

    def parts(self) -> dict[str, float]:
        """Each part by name (:data:`PARTS`), in seconds."""
        values = (
            self.cutting,
            self.threading,
            self.rapid,
            self.dwell,
            self.tool_change,
            self.m_codes,
        )
        return dict(zip(PARTS, values, strict=True))

    def add(self, part: str, seconds: float) -> None:
        name = _ATTRIBUTES[part]
        setattr(self, name, getattr(self, name) + seconds)


_ATTRIBUTES: Mapping[str, str] = MappingProxyType(
    {
        "cutting": "cutting",
        "threading": "threading",
        "rapid": "rapid",
        "dwell": "dwell",
        "tool change": "tool_change",
        "M codes": "m_codes",
    }
)


@dataclass(slots=True)
class RunTime:
    """One run of an entry program: its time by part, its tool changes, and the moves whose
    time cannot be known (no F, no spindle speed)."""

    uri: str
    program_line: int
    program: str
    breakdown: Breakdown = field(default_factory=Breakdown)
    tool_changes: int = 0
    untimed: int = 0

    @property
    def seconds(self) -> float:
        return self.breakdown.total


@dataclass(slots=True)
class CycleTime:
    """The time of every run of an evaluation. ``before[i]`` is the time the runs took
    before motion record ``i``'s block began (its last entry: the whole); ``in_program`` the
    seconds spent in each program's own blocks, by (document, first line)."""

    runs: list[RunTime]
    total: Breakdown
    before: array[float]
    in_program: dict[tuple[str, int], float]
    untimed: int = 0

    def so_far(self, motion: int) -> float:
        """The seconds before motion record ``motion`` (past the last: the whole)."""
        before = self.before
        return before[min(max(motion, 0), len(before) - 1)]

    def run_of(self, uri: str, program_line: int) -> RunTime | None:
        """The first run of the program at ``program_line`` of ``uri`` as an entry."""
        for run in self.runs:
            if run.uri == uri and run.program_line == program_line:
                return run
        return None


def cycle_time(facts: Facts, config: Config) -> CycleTime | None:
    """The cycle time of ``facts``'s runs (None: the evaluation recorded no toolpath)."""
    path = facts.toolpath
    if path is None:
        return None
    motions = facts.motions
    total = Breakdown()
    # The seconds of each motion record's moves, and of the events after each record.
    of_motion = [0.0] * (len(motions) + 1)
    in_program: dict[tuple[str, int], float] = {}
    runs: list[RunTime] = []
    starts = path.starts or []
    move_starts = [s.moves for s in starts]
    event_starts = [s.events for s in starts]
    for start in starts:
        runs.append(RunTime(start.uri, start.program_line, start.program))
    untimed = 0
    last_motion = 0
    for index, move in enumerate(path.moves):
        run = runs[bisect_right(move_starts, index) - 1] if runs else None
        motion = motions[move.motion] if 0 <= move.motion < len(motions) else None
        timed = move_seconds(move, motion, path, config)
        if timed is None:
            untimed += 1
            if run is not None:
                run.untimed += 1
            continue
        part, seconds = timed
        total.add(part, seconds)
        if run is not None:
            run.breakdown.add(part, seconds)
        if move.motion >= 0:
            last_motion = move.motion
        of_motion[last_motion] += seconds
        if motion is not None:
            key = (motion.uri, motion.program_line)
            in_program[key] = in_program.get(key, 0.0) + seconds
    # An event ran after the block that made motion record ``motions - 1``: it comes before
    # record ``motions``'s block.
    event_before = [0.0] * (len(motions) + 1)
    for index, event in enumerate(path.events):
        run = runs[bisect_right(event_starts, index) - 1] if runs else None
        part, seconds = event_seconds(event, config)
        total.add(part, seconds)
        if run is not None:
            run.breakdown.add(part, seconds)
            if event.kind == "tool change":
                run.tool_changes += 1
        event_before[min(event.motions, len(motions))] += seconds
        key = (event.uri, event.program_line)
        in_program[key] = in_program.get(key, 0.0) + seconds
    before = array("d", [0.0] * (len(motions) + 1))
    elapsed = 0.0
    for i in range(len(motions) + 1):
        elapsed += event_before[i]
        before[i] = elapsed
        elapsed += of_motion[i]
    before[len(motions)] = total.total
    return CycleTime(runs, total, before, in_program, untimed)


def event_seconds(event: TimedEvent, config: Config) -> tuple[str, float]:
    """A timed event's part of the cycle and its seconds."""
    if event.kind == "dwell":
        return "dwell", event.seconds
    if event.kind == "tool change":
        return "tool change", config.tool_change_seconds
    return "M codes", dict(config.m_code_seconds).get(event.code, 0.0)


def move_seconds(
    move: Move, motion: Motion | None, path: Toolpath, config: Config
) -> tuple[str, float] | None:
    """A move's part of the cycle and its seconds; None when the run does not know enough
    (the F, the spindle speed, where an axis was) to time it."""
    inch = motion.inch if motion is not None else path.inch
    lathe = path.lathe
    if move.kind == "rapid":
        return "rapid", _rapid_minutes(move, lathe, inch, config) * 60.0
    if motion is None:
        return None
    feed = motion.words.get("F")
    if feed is None or feed <= 0.0:
        return None
    if move.kind == "thread":
        # The lead is along the longer axis, which moves at F x rpm (0i-TF "Threading").
        length = max(_distances(move, lathe).values(), default=0.0)
        rpm = _thread_speed(move, motion, config)
        if rpm is None:
            return None
        return "threading", length / (feed * rpm) * 60.0
    mode = motion.feed_mode if motion.feed_mode is not None else POWER_ON_FEED_MODE[lathe]
    if move.kind == "arc":
        pieces = _arc_pieces(move, lathe)
        if pieces is None:
            return None
    else:
        pieces = [_straight(move, lathe)]
    if mode not in PER_REVOLUTION:
        return "cutting", sum(length for length, _, _ in pieces) / feed * 60.0
    minutes = 0.0
    for length, d0, d1 in pieces:
        piece = _per_revolution_minutes(length, d0, d1, feed, motion, config)
        if piece is None:
            return None
        minutes += piece
    return "cutting", minutes * 60.0


def _distances(move: Move, lathe: bool) -> dict[str, float]:
    """How far each axis known at both ends moves (a lathe's X: half the diameter's
    change)."""
    out: dict[str, float] = {}
    for axis, end in move.end.items():
        start = move.start.get(axis)
        if start is None:
            continue
        out[axis] = abs(end - start) * (0.5 if lathe and axis == "X" else 1.0)
    return out


def _rapid_minutes(move: Move, lathe: bool, inch: bool, config: Config) -> float:
    """Non-interpolated positioning: each axis at its rapid rate, the move as long as the
    slowest axis (0i-TF/0i-MF "Positioning (G00)"; the linear interpolation type, a
    parameter's choice, would take as long as the path at the rate's limits)."""
    rates = {"X": config.rapid_rate_x, "Y": config.rapid_rate_y, "Z": config.rapid_rate_z}
    scale = MM_PER_INCH if inch else 1.0
    return max(
        (d * scale / rates[a] for a, d in _distances(move, lathe).items() if a in rates),
        default=0.0,
    )


def _straight(move: Move, lathe: bool) -> tuple[float, float | None, float | None]:
    """A straight move's length and its diameters at the start and the end (a lathe's X)."""
    length = math.sqrt(sum(d * d for d in _distances(move, lathe).values()))
    return length, move.start.get("X"), move.end.get("X")


def _arc_pieces(move: Move, lathe: bool) -> list[tuple[float, float | None, float | None]] | None:
    """An arc (a helix when a third axis moves) as pieces of equal angle: each piece's length
    and its diameters (a lathe's X) at its ends; None when its centre is not known."""
    centre = move.centre
    if centre is None:
        return None
    (u_axis, _), (v_axis, _) = PLANE_AXES[move.plane]
    start, end = move.start, move.end
    if not all(a in p for p in (start, end, centre) for a in (u_axis, v_axis)):
        return None
    # A lathe's X in radius, as the geometry is worked (toolpath.arc_centre).
    su, sv = start[u_axis], start[v_axis] * (0.5 if lathe and v_axis == "X" else 1.0)
    eu, ev = end[u_axis], end[v_axis] * (0.5 if lathe and v_axis == "X" else 1.0)
    cu, cv = centre[u_axis], centre[v_axis] * (0.5 if lathe and v_axis == "X" else 1.0)
    radius = math.hypot(su - cu, sv - cv)
    a0 = math.atan2(sv - cv, su - cu)
    a1 = math.atan2(ev - cv, eu - cu)
    # G03 turns counter-clockwise in the plane's (u, v); a start equal to the end is a full
    # circle.
    span = (a0 - a1) % math.tau if move.clockwise else (a1 - a0) % math.tau
    span = span or math.tau
    height = sum(abs(end[a] - start[a]) for a in end if a in start and a not in (u_axis, v_axis))
    length = math.hypot(radius * span, height)
    if not lathe or "X" not in (u_axis, v_axis):
        return [(length, start.get("X"), end.get("X"))]
    sign = -1.0 if move.clockwise else 1.0
    diameters = []
    for i in range(ARC_PIECES + 1):
        angle = a0 + sign * span * i / ARC_PIECES
        point = (cu + radius * math.cos(angle), cv + radius * math.sin(angle))
        diameters.append(2.0 * (point[1] if v_axis == "X" else point[0]))
    piece = length / ARC_PIECES
    return [(piece, diameters[i], diameters[i + 1]) for i in range(ARC_PIECES)]


def _clamp(motion: Motion, config: Config) -> float:
    """The highest speed the spindle turns at in G96: the G50 S in force and the machine's."""
    clamp = motion.speed_clamp
    limit = config.max_spindle_speed
    return min(limit, clamp) if clamp is not None else limit


def _per_revolution_minutes(
    length: float,
    d0: float | None,
    d1: float | None,
    feed: float,
    motion: Motion,
    config: Config,
) -> float | None:
    """Minutes of a straight stretch fed at ``feed`` per revolution from diameter ``d0`` to
    ``d1``: in G97 at S; in G96 the speed n = k / D, k = 1000 V / π (12 V / π in inches),
    clamped at c, so dt = ds / (F n): at c below D* = k / c, and D ds / (F k) above, whose
    integral along the stretch is its length times the mean diameter (D is linear in s)."""
    if length == 0.0:
        return 0.0
    if motion.rpm is not None:
        return length / (feed * motion.rpm) if motion.rpm > 0.0 else None
    surface = motion.surface_speed
    if surface is None or surface <= 0.0 or d0 is None or d1 is None:
        return None
    k = (12.0 if motion.inch else 1000.0) * surface / math.pi
    clamp = _clamp(motion, config)
    knee = k / clamp if clamp > 0.0 else math.inf  # the diameter below which c holds
    low, high = sorted((abs(d0), abs(d1)))
    if high <= knee:
        return length / (feed * clamp) if math.isfinite(clamp) else None
    if low >= knee or low == high:
        return length * (low + high) / 2.0 / (feed * k)
    clamped = (knee - low) / (high - low)  # the share of the stretch below D*
    return length * clamped / (feed * clamp) + length * (1.0 - clamped) * (knee + high) / 2.0 / (
        feed * k
    )


def _thread_speed(move: Move, motion: Motion, config: Config) -> float | None:
    """The spindle speed a threading pass turns at: S in G97; in G96 the speed at the
    pass's diameter, clamped (threads are cut in G97 as a rule: a G96 speed follows X)."""
    if motion.rpm is not None:
        return motion.rpm if motion.rpm > 0.0 else None
    surface = motion.surface_speed
    diameter = move.end.get("X")
    if surface is None or surface <= 0.0 or diameter is None or diameter <= 0.0:
        return None
    speed = (12.0 if motion.inch else 1000.0) * surface / (math.pi * diameter)
    return min(speed, _clamp(motion, config))


def minutes_seconds(seconds: float) -> str:
    """``6 min 12.4 s``, ``12.4 s`` under a minute: to 0.1 s."""
    tenths = round(seconds * 10.0)
    minutes, rest = divmod(tenths, 600)
    if minutes:
        return tr("{minutes} min {seconds:.1f} s", minutes=minutes, seconds=rest / 10.0)
    return tr("{seconds:.1f} s", seconds=rest / 10.0)
