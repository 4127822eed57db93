"""The surface a thread is cut in, as the program turned it before the thread.

A lathe program usually turns the diameter (or bores the hole, or turns the cone of a taper
thread) with another tool just before it threads it. Where it does, that surface is the
thread's blank: what the first pass meets, whatever the thread's designation says, and the
only blank known for a thread whose designation is not. It is read from the feed moves
before the thread's first pass in the same execution of the program: straight cuts (``G01``
along Z or on a cone) and turning cycles (``G90``, with its taper R).

Each pass of a taper thread is a line in the ZX plane too; the passes of one job are
parallel (one R), so the thread is seen in the frame of its deepest pass: at each Z the
surface's height above that pass, the blank the highest of them along the thread (where the
thread cuts most air it also cuts the most metal).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from ..evaluator.facts import Motion

# Moves that turn a surface: a feed move, or a turning cycle with its taper R.
CONE_CODES = frozenset({"G01", "G90"})
# How near the deepest pass a move must be to be the surface the thread is cut in, in pitches
# on the diameter (a thread's whole height is about 0.65 of the pitch, radius: 1.3 pitches on
# the diameter): a move farther off is a move in the air, the part's other side, or a
# shoulder the thread ends before.
NEAR_PITCHES = 2.0
# Where along the thread the surface is read: this many places, from 5 % to 95 % of where
# the deepest pass and the turned moves meet (the ends are where a chamfer or a shoulder
# meets the thread).
SAMPLES = 19
# Shares of the thread's length at whose ends no sample is taken.
END_MARGIN = 0.05
# The share of the thread's length the turned moves must reach: less, and what was turned is
# a chamfer or a collar, not the thread's surface.
COVER = 0.4


@dataclass(frozen=True, slots=True)
class Line:
    """A straight cut in the ZX plane: diameter x0 at z0 to x1 at z1."""

    z0: float
    x0: float
    z1: float
    x1: float

    @property
    def slope(self) -> float:
        """The diameter's change per unit of Z."""
        return (self.x1 - self.x0) / (self.z1 - self.z0) if self.z1 != self.z0 else 0.0

    def x_at(self, z: float) -> float:
        return self.x0 + self.slope * (z - self.z0)

    @property
    def span(self) -> tuple[float, float]:
        return min(self.z0, self.z1), max(self.z0, self.z1)

    def covers(self, z: float) -> bool:
        low, high = self.span
        return low <= z <= high


def thread_line(m: Motion) -> Line | None:
    """A threading pass's cut, from where it starts to where it ends: for a taper thread a
    cone, for a parallel one a line at its X; None without its X or Z."""
    if m.x is None or m.z is None or m.start_z is None or m.z == m.start_z:
        return None
    if m.code in ("G92", "G76"):
        # The cycle cuts from X + 2R at its start Z to X at its end Z (0i-TF "Threading
        # cycle").
        r = m.words.get("R") or 0.0
        return Line(m.start_z, m.x + 2.0 * r, m.z, m.x)
    if m.code in ("G32", "G33") and m.start_x is not None:
        return Line(m.start_z, m.start_x, m.z, m.x)
    return Line(m.start_z, m.x, m.z, m.x)


def tapered(m: Motion) -> bool:
    """Whether a threading pass cuts a cone (a cycle's R, a G32 whose X changes along Z):
    :func:`thread_line`'s ends differ, without making the line (every pass of a job is asked
    on every analysis)."""
    if m.x is None or m.z is None or m.start_z is None or m.z == m.start_z:
        return False
    if m.code in ("G92", "G76"):
        return bool(m.words.get("R"))
    return m.code in ("G32", "G33") and m.start_x is not None and m.start_x != m.x


def cone_line(m: Motion) -> Line | None:
    """The cut of a turning move along Z (straight or a cone), or None for another move."""
    if m.code not in CONE_CODES or m.x is None or m.z is None:
        return None
    if m.start_x is None or m.start_z is None or m.z == m.start_z:
        return None
    if m.code == "G90":
        r = m.words.get("R") or 0.0
        return Line(m.start_z, m.x + 2.0 * r, m.z, m.x)
    return Line(m.start_z, m.start_x, m.z, m.x)


@dataclass(frozen=True, slots=True)
class TurnedSurface:
    """The surface turned for a thread, in the frame of its deepest pass ``deepest``: at the
    place ``z``, the blank's diameter ``blank`` (the pass's X there plus the surface's
    greatest height above it along the thread, or for an internal thread its least);
    ``line``: the first line (0-based) of the moves that turned it."""

    z: float
    blank: float
    line: int
    deepest: Line

    def frame_x(self, m: Motion) -> float | None:
        """A pass's X in the frame: where its line is at the place ``z``."""
        line = thread_line(m)
        if line is None or line.x0 == line.x1:
            return m.x
        return line.x_at(self.z)


@dataclass(frozen=True, slots=True)
class SurfaceWanted:
    """A thread whose turned surface is asked for: its passes (of one side), its pitch."""

    passes: Sequence[Motion]
    internal: bool
    pitch: float
    least_x: float  # the passes' least X: below 0, X is given on the far side of the axis


# The codes a thread's first pass has.
THREAD_CODES = frozenset({"G32", "G33", "G92", "G76"})


def motion_key(m: Motion) -> tuple[object, ...]:
    """What tells a motion of a run from the others: a job kept from an earlier analysis holds
    records of the same values, not the run's own."""
    return (m.uri, m.run, m.line, m.code, m.cycle_pass, m.x, m.z, m.start_x, m.start_z)


def turned_surfaces(
    wanted: Sequence[SurfaceWanted], motions: Sequence[Motion]
) -> list[TurnedSurface | None]:
    """The surface the program turned for each thread of ``wanted`` (in order), from the
    moves before the thread's first pass in the same execution of its program; None where no
    move turned it near the thread's depth over the thread's length. One walk over
    ``motions``, up to the last thread's first pass."""
    found: list[TurnedSurface | None] = [None] * len(wanted)
    waiting: dict[tuple[object, ...], list[int]] = {}
    for k, w in enumerate(wanted):
        if w.passes and w.pitch > 0.0 and w.least_x >= 0.0:
            # (X given on the far side of the axis is not the diameter this reads.)
            waiting.setdefault(motion_key(w.passes[0]), []).append(k)
    # The turning moves seen so far, by document and execution.
    turned: dict[tuple[str, int], list[tuple[int, Line]]] = {}
    for m in motions:
        if not waiting:
            break
        ks = waiting.pop(motion_key(m), None) if m.code in THREAD_CODES else None
        if ks is not None:
            moves = turned.get((m.uri, m.run), [])
            for k in ks:
                w = wanted[k]
                found[k] = _surface(w.passes, moves, w.internal, w.pitch)
            continue
        if m.code in CONE_CODES:
            cone = cone_line(m)
            if cone is not None:
                turned.setdefault((m.uri, m.run), []).append((m.line, cone))
    return found


def _surface(
    passes: Sequence[Motion],
    turned: Sequence[tuple[int, Line]],
    internal: bool,
    pitch: float,
) -> TurnedSurface | None:
    if not turned:
        return None
    cutting = [m for m in passes if m.x is not None and m.z is not None and m.z != m.start_z]
    if not cutting:
        return None
    deepest_line = thread_line((max if internal else min)(cutting, key=lambda m: m.x or 0.0))
    if deepest_line is None:
        return None
    deepest = deepest_line
    low, high = deepest.span
    moves = [(n, c) for n, c in turned if c.span[1] >= low and c.span[0] <= high]
    if not moves:
        return None
    # Where the moves and the thread meet: the thread's run-in in front of the part is in
    # the air whatever was turned.
    start = max(low, min(c.span[0] for _l, c in moves))
    end = min(high, max(c.span[1] for _l, c in moves))
    if end - start < COVER * (high - low):
        return None
    near = NEAR_PITCHES * pitch
    # The surface's height above the deepest pass (an internal thread's depth below it) at
    # each place along the thread; the moves that turned it.
    heights: list[float] = []
    used: set[int] = set()
    for k in range(SAMPLES):
        z = start + (end - start) * (END_MARGIN + (1.0 - 2.0 * END_MARGIN) * k / (SAMPLES - 1))
        root = deepest.x_at(z)
        found: tuple[float, int] | None = None
        for line_no, cone in moves:
            if not cone.covers(z):
                continue
            # How far the move is from the root, towards the material's outside.
            height = cone.x_at(z) - root if not internal else root - cone.x_at(z)
            if height < 0.0:
                continue  # a move past the root (a groove, the part's other side)
            if found is None or height < found[0]:
                found = (height, line_no)
        if found is not None and found[0] <= near:
            heights.append(found[0])
            used.add(found[1])
    # A surface over less than half the thread is not the thread's (a chamfer, a collar).
    if len(heights) * 2 < SAMPLES:
        return None
    middle = (start + end) / 2.0
    height = max(heights)
    blank = deepest.x_at(middle) + (-height if internal else height)
    return TurnedSurface(middle, blank, min(used), deepest)
