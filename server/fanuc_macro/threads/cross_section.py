"""The cross-section a thread job cuts: each pass's tool profile taken out of the blank.

Seen in the axial plane over one lead, a threading pass leaves the tool's profile (a V of the
thread's included angle, its tip rounded by the nose radius) at the pass's radial depth and at
its place along the lead: its start Z (or its start angle Q) modulo the lead, and for a pass of
G76 the cycle's shift along the flank. Every tool enters radially, from outside an external
thread and from the axis side of an internal one, so the material left is bounded by a function
of the axial place ``u``: an external thread keeps the radii ``r <= h(u)``, an internal one
``r >= h(u)``. That function is kept exactly, as a polyline over one lead: the lower (external)
or upper (internal) envelope of the blank and the tools' profiles, each profile a polyline too
(its nose arc in :data:`NOSE_SEGMENTS` chords, within 0.1 % of its radius). A pass
changes the polyline only where its profile goes below it, and what it removes there is the
area between the two. Plain Python, as the editor's bundled server has no numpy or shapely:
the polyline is exact where a raster of the lead is not, 55-80 µs a pass, and 26-30 times
faster than shapely's polygons of the same cut (``bench/bench_cross_section.py``; a numpy
raster of 4,096 samples a lead ran 2-3 times faster than the polyline but placed the passes
to a sample and needs numpy).

The simple pitch diameter (ISO 5408: where the groove's width is half the pitch) is where the
groove, the places the cut went past a radius, fills half the lead. Multi-start threads are
cut over one lead with each start's passes at their own place, so the half holds over the lead.

Lengths are the program's (mm, or inches in G20); areas the square of them.
"""

from __future__ import annotations

import math
from bisect import bisect_left, bisect_right
from collections.abc import Sequence
from dataclasses import dataclass
from functools import partial
from itertools import compress
from typing import ClassVar

from ..database import TableKey
from ..database import current as current_database
from ..evaluator.facts import Motion
from ..program.index import ProgramIndex
from ..translation import tr
from .geometry import nose_radius_range
from .identify import Thread
from .module_shape import D1_FACTOR
from .surface import TurnedSurface
from .surface import tapered as cuts_a_cone

# The nose arc's chords: the arc from the tip to the flank (60° of it for a 60° tool) in
# pieces of 5°, whose sagitta is 0.1 % of the radius.
NOSE_SEGMENTS = 12
# The flank's rise per unit of offset of a round insert's edge past its half circle.
VERTICAL = 1e9
# The vertices of a pass's window looked at together for where its edge may go below them.
HOT_RUN = 16
# A pass removing less than this share of the thread's whole area removes nothing (the
# rounding of an edge that touches the profile).
NOTHING = 1e-6


@dataclass(frozen=True, slots=True)
class ToolShape:
    """The threading tool's profile: its included angle (degrees) and nose radius."""

    included_angle: float
    nose_radius: float

    def edge(self) -> tuple[tuple[tuple[float, float], ...], float]:
        """The tool's edge from its tip outwards, as (axial offset, rise above the tip) at the
        nose arc's chord ends, and the flank's rise per unit of offset beyond the last."""
        half = math.radians(self.included_angle / 2.0)
        r = self.nose_radius
        # A round insert (no angle) rises straight up past its nose's half circle.
        slope = 1.0 / math.tan(half) if half > 0.0 else VERTICAL
        if r <= 0.0:
            return ((0.0, 0.0),), slope
        top = math.pi / 2.0 - half  # the arc from the tip to where the flank is its tangent
        points = tuple(
            (r * math.sin(top * k / NOSE_SEGMENTS), r * (1.0 - math.cos(top * k / NOSE_SEGMENTS)))
            for k in range(NOSE_SEGMENTS + 1)
        )
        return points, slope


@dataclass(frozen=True, slots=True)
class PassCut:
    """What one pass removed: its index among the job's passes and its area; where along the
    lead it cut and its tip's radius."""

    index: int
    area: float
    place: float = 0.0
    tip: float = 0.0


@dataclass(frozen=True, slots=True)
class CrossSection:
    # Its passes are their indexes: a copy of a job whose changed passes agree on what the cut
    # reads (CUT_READS) takes the earlier job's cut as it is (ThreadJob.remember).
    HOLDS_NO_MOTION: ClassVar[bool] = True

    lead: float
    internal: bool
    blank: float  # diameter the passes cut into: external its outside, internal its bore
    tool: ToolShape
    cuts: tuple[PassCut, ...]  # every pass that had an X, in order
    profile: tuple[tuple[float, float], ...]  # (u, h(u)) over one lead, radius
    pitch_diameter: float
    root_diameter: float  # external: the least diameter cut (d3); internal: the greatest
    crest_diameter: float  # what is left of the blank
    # Worked out once (the rules read them on every analysis): the whole area removed, the
    # pass that removed most, and the first and last that removed anything (places in cuts).
    area: float = 0.0
    largest_at: int | None = None
    first_removing: int | None = None
    last_removing: int | None = None

    @staticmethod
    def summed(cuts: Sequence[PassCut]) -> tuple[float, int | None, int | None, int | None]:
        """``area``, ``largest_at``, ``first_removing``, ``last_removing`` of ``cuts``."""
        area = sum(c.area for c in cuts)
        largest = max(range(len(cuts)), key=lambda k: cuts[k].area, default=None)
        floor = NOTHING * max(area, 1e-12)
        removing = [k for k, c in enumerate(cuts) if c.area > floor]
        return (
            area,
            largest,
            (removing[0] if removing else None),
            (removing[-1] if removing else None),
        )

    def largest(self) -> PassCut | None:
        return None if self.largest_at is None else self.cuts[self.largest_at]

    def removing(self) -> list[PassCut]:
        """The passes that removed material."""
        floor = NOTHING * max(self.area, 1e-12)
        return [c for c in self.cuts if c.area > floor]

    def in_the_air(self) -> list[PassCut]:
        """The passes before the first one that touches the material."""
        first = self.first_removing
        return list(self.cuts if first is None else self.cuts[:first])

    def deciding(self) -> PassCut | None:
        """The last pass that removed material: the one that left the finished flanks."""
        return None if self.last_removing is None else self.cuts[self.last_removing]

    def past_the_flank(self) -> tuple[PassCut, float] | None:
        """The pass that cut farthest past the flanks of the deepest pass, and by how much
        (radius): one shifted along the lead by more than its shallower depth allows, whose
        flank then lies outside the finished one. None when every pass lies within it."""
        deepest = max(self.cuts, key=lambda c: c.tip, default=None) if self.internal else None
        if not self.internal:
            deepest = min(self.cuts, key=lambda c: c.tip, default=None)
        if deepest is None:
            return None
        slope = 1.0 / math.tan(math.radians(self.tool.included_angle / 2.0))
        found: tuple[PassCut, float] | None = None
        for c in self.removing():
            apart = abs(c.place - deepest.place) % self.lead
            apart = min(apart, self.lead - apart)
            # Far along the flanks the edges differ by the depth between the tips, less the
            # rise of the flank over the shift.
            shallower = (deepest.tip - c.tip) if self.internal else (c.tip - deepest.tip)
            past = slope * apart - shallower
            if past > 0.0 and (found is None or past > found[1]):
                found = (c, past)
        return found


def pass_place(
    m: Motion, lead: float, root_x: float | None, x: float | None = None
) -> float | None:
    """Where along the lead a pass cuts: its start angle Q (0.001°, G32 and G92), else its
    start Z; a G76 pass is shifted along the flank by its depth above the cycle's last pass
    (``tan(a/2)`` per unit of depth, its tool angle a)."""
    q = m.words.get("Q") if m.code != "G76" else None
    if q:
        place = q / 360000.0 * lead
    elif m.start_z is not None:
        place = m.start_z
    else:
        return None
    x = m.x if x is None else x
    if m.code == "G76" and m.tool_angle and root_x is not None and x is not None:
        place += abs(x - root_x) / 2.0 * math.tan(math.radians(m.tool_angle / 2.0))
    return place % lead


def cut_cross_section(
    passes: list[Motion],
    lead: float,
    internal: bool,
    blank: float,
    tool: ToolShape,
    before: Sequence[Motion] = (),
    frame: TurnedSurface | None = None,
) -> CrossSection | None:
    """The cross-section ``passes`` cut in a blank of diameter ``blank``, after the passes
    ``before`` (an earlier job on the same thread: what they removed is not the job's); None
    when no pass has an X, or the lead is not a length. ``frame``: a taper thread's turned
    cone, in whose frame each pass's X is read (at the cone's place)."""
    if not lead > 0.0 or not math.isfinite(lead):
        return None
    # A G76 record that is no pass of its cycle stands for a cycle whose passes are not known
    # (the control refused it, or its words are not known): it cuts nothing that can be drawn.
    cutting = [(i, m) for i, m in enumerate(passes) if _cuts(m)]
    if not cutting:
        return None
    at = {id(m): (m.x if frame is None else frame.frame_x(m)) for m in [*before, *passes]}
    xs = [x for _i, m in cutting if (x := at[id(m)]) is not None]
    root_x = max(xs) if internal else min(xs)
    # An internal thread is the external one mirrored: values are -r, and the tool's edge
    # rises away from the axis as an external tool's rises towards it.
    sign = -1.0 if internal else 1.0
    profile = _Profile(lead, sign * blank / 2.0, *tool.edge())
    cuts: list[PassCut] = []
    first_place: float | None = None
    earlier = [(-1, m) for m in before if _cuts(m)]
    for i, m in [*earlier, *cutting]:
        x = at[id(m)]
        assert x is not None
        place = pass_place(m, lead, root_x, x)
        if place is None:
            place = first_place if first_place is not None else 0.0
        if first_place is None:
            first_place = place
        removed = profile.cut(place, sign * x / 2.0)
        if i >= 0:
            cuts.append(PassCut(i, removed, place, x / 2.0))
    values = profile.values
    lowest, highest = min(values), max(values)
    pitch = 2.0 * sign * profile.half_measure()
    return CrossSection(
        lead,
        internal,
        blank,
        tool,
        tuple(cuts),
        tuple(zip(profile.places, (sign * v for v in values), strict=True)),
        pitch,
        2.0 * sign * lowest,
        2.0 * sign * highest,
        *CrossSection.summed(cuts),
    )


def _cuts(m: Motion) -> bool:
    return m.x is not None and (m.code != "G76" or m.cycle_pass > 0)


class _Profile:
    """What is left of the material over one lead, as an external thread's: a polyline of
    ``values`` at ``places`` from 0 to the lead (the last place the lead, its value the first's),
    below which the material is. A tool cuts what lies above its edge."""

    __slots__ = ("corners", "dirty", "edge", "lead", "nose", "places", "slope", "top", "values")

    def __init__(
        self, lead: float, top: float, edge: tuple[tuple[float, float], ...], slope: float
    ) -> None:
        self.lead = lead
        self.places = [0.0, lead]
        self.values = [top, top]
        self.top: float | None = top  # max(values), None when a cut has changed them since
        self.edge = edge
        self.slope = slope
        # The nose's chord ends either side of the centre line, left to right.
        self.corners = [(-u, r) for u, r in reversed(edge[1:])] + list(edge)
        # The places of the vertices whose neighbours may lie on a line through them (not
        # looked at since a neighbour changed): the others keep their place when a pass's
        # window goes over them and the edge stays above.
        self.dirty: set[float] = set()
        # The nose's radius, from its last chord end (u, h): u² + (r - h)² = r².
        # At least the last chord end's offset, so that the arc is defined out to it (a
        # larger radius's arc is flatter: still below the chords).
        u, h = edge[-1]
        self.nose = max((u * u + h * h) / (2.0 * h), u) if h > 0.0 else 0.0

    def _reach(self, height: float) -> float:
        """How far from its centre line the edge stays below ``height`` above the tip."""
        edge = self.edge
        last_offset, last_rise = edge[-1]
        if height >= last_rise:
            return last_offset + (height - last_rise) / self.slope
        k = bisect_left([r for _u, r in edge], height)
        (u0, r0), (u1, r1) = edge[k - 1], edge[k]
        return u0 + (u1 - u0) * (height - r0) / (r1 - r0)

    def cut(self, place: float, tip: float) -> float:
        """Takes a pass whose tip is at ``tip`` and centre line at ``place``; the area it
        removes."""
        top = self.top
        if top is None:
            top = self.top = max(self.values)
        if tip >= top:  # most passes of a long job, once the profile is below them
            return 0.0
        lead = self.lead
        reach = min(self._reach(top - tip), lead / 2.0)
        # Narrowed to the highest the profile comes within that reach: on a profile cut by
        # many passes the crest left far off no longer widens every pass's window.
        near = self._highest_within(place - reach, place + reach)
        if tip >= near:
            return 0.0
        if near < top:
            reach = min(self._reach(near - tip), reach)
        start, end = place - reach, place + reach
        if start < 0.0:
            pieces = [(start + lead, lead, lead), (0.0, end, 0.0)]
        elif end > lead:
            pieces = [(start, lead, 0.0), (0.0, end - lead, -lead)]
        else:
            pieces = [(start, end, 0.0)]
        removed = 0.0
        for a, b, shift in pieces:
            if b > a:
                removed += self._cut_between(a, b, place + shift, tip)
        first, last = self.values[0], self.values[-1]
        if self.top is not None and max(first, last) >= self.top:
            self.top = None
        self.values[-1] = self.values[0] = min(first, last)
        if len(self.places) > 2:
            self.dirty.update((self.places[1], self.places[-2]))
        return removed

    def _highest_within(self, start: float, end: float) -> float:
        """At least the profile's highest over [start, end] (a window of at most a lead, its
        ends possibly past 0 or the lead): the highest of its vertices in it and the two either
        side, between which its ends lie."""
        places, values = self.places, self.values
        lead = self.lead
        if start < 0.0:
            spans = [(start + lead, lead), (0.0, end)]
        elif end > lead:
            spans = [(start, lead), (0.0, end - lead)]
        else:
            spans = [(start, end)]
        highest = -math.inf
        for a, b in spans:
            lo = max(bisect_right(places, a) - 1, 0)
            hi = bisect_left(places, b) + 1
            highest = max(highest, max(values[lo:hi]))
        return highest

    def _cut_between(self, a: float, b: float, centre: float, tip: float) -> float:
        """The pass's edge (centre line at ``centre``) taken out over [a, b]; the area.

        The old profile at a, its vertices inside (a, b), and at b, with the edge's nose
        corners inside (a, b) merged in, are walked in order: each keeps its old value or takes
        the edge's, with the crossings between, and a vertex on the line through its neighbours
        is dropped. The edge goes below the profile at few of them (the window is as wide as
        the profile's highest point allows), so the stretches where it cannot, of vertices
        whose neighbours were found not to line up when they were made (``dirty`` holds those
        that were not), are copied as they are: what the walk would do with them."""
        places, values = self.places, self.values
        lo = bisect_right(places, a)
        hi = bisect_left(places, b)
        pu, pv, corners = self._window(a, b, lo, hi, centre, tip)
        full, near = self._walked(pu, pv, corners, a, b, centre, tip)
        new_at = self._edge_at
        out_u: list[float] = []
        out_v: list[float] = []
        replaced: list[int] = []
        area = 0.0
        d0 = 0.0
        u0 = 0.0
        plain = 0  # trailing vertices of out that are the window's old ones, appended in turn
        n = len(pu)
        f = 0
        k = 0
        while k < n:
            if plain >= 2 and full[f] > k:
                # The last of the window is always walked, so full[f] ends the stretch.
                end = full[f]
                out_u += pu[k:end]
                out_v += pv[k:end]
                u0 = pu[end - 1]
                d0 = pv[end - 1] - new_at(u0, centre, tip) if end - 1 in near else -1.0
                k = end
                continue
            u = pu[k]
            v_old = pv[k]
            corner = corners.get(k)
            if corner is not None:
                new = corner
            elif k in near:
                new = new_at(u, centre, tip)
            else:
                # The edge is above the vertex and its neighbours: no crossing, no area.
                new = math.inf
            d1 = v_old - new
            crossed = False
            if k:
                if (d0 > 0.0) != (d1 > 0.0) and d0 != d1:
                    t = d0 / (d0 - d1)
                    cross = u0 + (u - u0) * t
                    if u0 < cross < u:
                        _append(out_u, out_v, cross, pv[k - 1] + (v_old - pv[k - 1]) * t, replaced)
                        crossed = True
                if d0 >= 0.0 and d1 >= 0.0:
                    area += (d0 + d1) / 2.0 * (u - u0)
                elif d0 > 0.0 or d1 > 0.0:
                    positive, negative = (d0, d1) if d0 > 0.0 else (d1, d0)
                    area += positive * positive / (positive - negative) / 2.0 * (u - u0)
            v = v_old if d1 <= 0.0 else new
            # _append, inline: this runs for every vertex walked.
            appended = True
            if len(out_u) >= 2:
                p0, q0, p1, q1 = out_u[-2], out_v[-2], out_u[-1], out_v[-1]
                if u > p0 and abs(q0 + (v - q0) * (p1 - p0) / (u - p0) - q1) <= 1e-12:
                    out_u[-1], out_v[-1] = u, v
                    replaced.append(len(out_u) - 1)
                    appended = False
            if appended:
                out_u.append(u)
                out_v.append(v)
            if corner is not None or d1 > 0.0 or k == 0:
                plain = 0
            else:
                plain = plain + 1 if appended and not crossed else 1
            d0, u0 = d1, u
            k += 1
            if full[f] < k:
                f += 1
        # Splice: the old vertices strictly inside (a, b) give way to the new ones; a and b
        # themselves are vertices from now on.
        left = lo - 1 if places[lo - 1] == a else lo
        right = hi + 1 if hi < len(places) and places[hi] == b else hi
        # The highest point: where it was when the window did not hold it, else found again.
        top = self.top
        if top is not None:
            top = max(top, *out_v) if max(values[left:right], default=top - 1.0) < top else None
        self.top = top
        places[left:right] = out_u
        values[left:right] = out_v
        # Every vertex inside was walked or copied with its neighbours: those whose right
        # neighbour took a dropped vertex's place, a, b and their outer neighbours were not.
        dirty = self.dirty
        dirty.difference_update(out_u[1:-1])
        dirty.update([out_u[p - 1] for p in replaced], (out_u[0], out_u[-1]))
        if left >= 1:
            dirty.add(places[left - 1])
        after = left + len(out_u)
        if after < len(places):
            dirty.add(places[after])
        return area

    def _window(
        self, a: float, b: float, lo: int, hi: int, centre: float, tip: float
    ) -> tuple[list[float], list[float], dict[int, float]]:
        """The old profile at a, its vertices in (a, b) and at b, with the nose corners inside
        (a, b) merged in (their old value from the segment they lie on): places, old values,
        and the corners' edge values by their position."""
        old_u = [a, *self.places[lo:hi], b]
        old_v = [self._at(a, lo), *self.values[lo:hi], self._at(b, hi)]
        pu: list[float] = []
        pv: list[float] = []
        corners: dict[int, float] = {}
        start = 0
        for cu_offset, rise in self.corners:
            cu = centre + cu_offset
            if not a < cu < b:
                continue
            j = bisect_right(old_u, cu, start)  # the first old vertex past the corner
            pu += old_u[start:j]
            pv += old_v[start:j]
            u0, v0 = old_u[j - 1], old_v[j - 1]
            corners[len(pu)] = tip + rise
            pu.append(cu)
            pv.append(v0 + (old_v[j] - v0) * (cu - u0) / (old_u[j] - u0))
            start = j
        pu += old_u[start:]
        pv += old_v[start:]
        return pu, pv, corners

    def _walked(
        self,
        pu: list[float],
        pv: list[float],
        corners: dict[int, float],
        a: float,
        b: float,
        centre: float,
        tip: float,
    ) -> tuple[list[int], set[int]]:
        """The positions of the window the walk must take one by one: the ends, the corners,
        the vertices the edge may go below (and the two after each, whose neighbours may
        change), and those after a vertex whose neighbours are not known to be out of line;
        and those next to where the edge may go below, whose edge value the walk needs."""
        n = len(pu)
        marks = bytearray(n + 2)  # two past the end: the marks after the last are dropped
        marks[0:3] = b"\x01\x01\x01"
        marks[n - 1] = 1
        for c in corners:
            marks[c] = marks[c + 1] = marks[c + 2] = 1
        hot = self._hot(pu, pv, a, b, centre, tip)
        near: set[int] = set()
        for p in hot:
            near.update((p - 1, p, p + 1))
            marks[p] = marks[p + 1] = marks[p + 2] = 1
        dirty = self.dirty.intersection(pu) if self.dirty else ()
        for u in dirty:
            p = bisect_left(pu, u)
            while p < n and pu[p] == u:
                marks[p + 1] = 1
                p += 1
        return list(compress(range(n), marks)), near

    def _hot(
        self, pu: list[float], pv: list[float], a: float, b: float, centre: float, tip: float
    ) -> list[int]:
        """The positions of the window where the edge may go below the profile. The nose's
        chords lie above its arc, and the flank is straight: a vertex at or below those, with
        a margin far above their rounding, keeps its value."""
        last_offset, last_rise = self.edge[-1]
        slope = self.slope
        r = self.nose
        rr = r * r
        reach = abs(a - centre) + abs(b - centre)
        margin = 1e-9 * (abs(tip) + last_offset * slope + reach * slope + 1.0) + 1e-7 * r
        if not math.isfinite(margin + centre):
            return list(range(len(pu)))
        low = tip - margin

        def below(o: float) -> float:  # the edge's least rise above ``low`` at offset o
            if o < last_offset:
                return r - math.sqrt(rr - o * o)
            return last_rise + (o - last_offset) * slope

        hot: list[int] = []
        n = len(pu)
        sqrt = math.sqrt
        # By runs of vertices: a run whose highest is below the edge where it comes nearest
        # the centre line is passed over whole.
        for i in range(0, n, HOT_RUN):
            j = min(i + HOT_RUN, n)
            h = max(pv[i:j]) - low
            if h <= 0.0:
                continue
            first, last = pu[i], pu[j - 1]
            o = first - centre if first >= centre else (centre - last if last < centre else 0.0)
            if h <= below(o):
                continue
            for p in range(i, j):  # below(), inline: this runs for most vertices walked
                h = pv[p] - low
                if h <= 0.0:
                    continue
                u = pu[p]
                o = u - centre if u >= centre else centre - u
                if o < last_offset:
                    if h > r - sqrt(rr - o * o):
                        hot.append(p)
                elif h > last_rise + (o - last_offset) * slope:
                    hot.append(p)
        return hot

    def _edge_at(self, u: float, centre: float, tip: float) -> float:
        """The pass's edge at ``u`` (:func:`_edge_rise` above ``tip``, as the walk takes it)."""
        edge = self.edge
        last_offset, last_rise = edge[-1]
        offset = u - centre if u >= centre else centre - u
        if offset >= last_offset:
            return tip + last_rise + (offset - last_offset) * self.slope
        e = bisect_right(edge, (offset, math.inf))
        (e0, r0), (e1, r1) = edge[e - 1], edge[e]
        return tip + (r0 + (r1 - r0) * (offset - e0) / (e1 - e0))

    def _at(self, u: float, k: int) -> float:
        """The profile at ``u``, on the segment that ends at vertex ``k`` (the first past u)."""
        places, values = self.places, self.values
        k = min(max(k, 1), len(places) - 1)
        u0, u1 = places[k - 1], places[k]
        if u1 == u0:
            return values[k]
        return values[k - 1] + (values[k] - values[k - 1]) * (u - u0) / (u1 - u0)

    def half_measure(self) -> float:
        """The value below which the profile lies over half the lead: the pitch line.

        The measure below a level rises linearly between two neighbouring values of the
        vertices (a sloped segment across them adds its width over its rise) and jumps at a
        level segment's value by its width: one sweep up the values finds the least level where
        it reaches half the lead."""
        places, values = self.places, self.values
        jumps: dict[float, float] = {}
        rate_changes: dict[float, float] = {}
        for u0, u1, v0, v1 in zip(places, places[1:], values, values[1:], strict=False):
            width = u1 - u0
            if width <= 0.0:
                continue
            if v0 == v1:
                jumps[v0] = jumps.get(v0, 0.0) + width
                continue
            low, high = (v0, v1) if v0 < v1 else (v1, v0)
            rate = width / (high - low)
            rate_changes[low] = rate_changes.get(low, 0.0) + rate
            rate_changes[high] = rate_changes.get(high, 0.0) - rate
        half = self.lead / 2.0
        measure = rate = 0.0
        level = min(values)
        for next_level in sorted({*jumps, *rate_changes}):
            if next_level > level:
                rising = measure + rate * (next_level - level)
                if rising >= half and rate > 0.0:
                    return min(level + (half - measure) / rate, next_level)
                measure, level = rising, next_level
            measure += jumps.get(next_level, 0.0)
            if measure >= half:
                return next_level
            rate += rate_changes.get(next_level, 0.0)
        return level


def _edge_rise(edge: tuple[tuple[float, float], ...], slope: float, offset: float) -> float:
    """A tool's edge (:meth:`ToolShape.edge`) above its tip at an axial ``offset``."""
    offset = abs(offset)
    last_offset, last_rise = edge[-1]
    if offset >= last_offset:
        return last_rise + (offset - last_offset) * slope
    k = bisect_right(edge, (offset, math.inf))
    (u0, r0), (u1, r1) = edge[k - 1], edge[k]
    return r0 + (r1 - r0) * (offset - u0) / (u1 - u0)


def penetration(cut: CrossSection, place: float, tip: float) -> float:
    """How far (radius) a pass of ``cut``'s tool, its tip at radius ``tip`` and its centre line
    at ``place`` along the lead, reaches past the profile ``cut`` left: 0 within it."""
    edge, slope = cut.tool.edge()
    sign = -1.0 if cut.internal else 1.0
    lead = cut.lead
    us = [u for u, _h in cut.profile]
    hs = [sign * h for _u, h in cut.profile]  # as an external thread's: material below
    low = sign * tip
    # The profile's vertices and the nose's chord ends: between them both are straight.
    places = set(us)
    for offset, _rise in edge:
        places.update(((place + offset) % lead, (place - offset) % lead))
    worst = 0.0
    for u in places:
        apart = abs(u - place) % lead
        apart = min(apart, lead - apart)
        k = min(max(bisect_right(us, u), 1), len(us) - 1)
        u0, u1 = us[k - 1], us[k]
        h = hs[k] if u1 == u0 else hs[k - 1] + (hs[k] - hs[k - 1]) * (u - u0) / (u1 - u0)
        worst = max(worst, h - (low + _edge_rise(edge, slope, apart)))
    return worst


def _append(us: list[float], vs: list[float], u: float, v: float, replaced: list[int]) -> bool:
    """Appends a vertex, first dropping the last one when it lies on the line from the one
    before it to this (the old profile's vertices an edge passed below): whether it was
    appended, else its position is put in ``replaced``."""
    if len(us) >= 2:
        u0, v0, u1, v1 = us[-2], vs[-2], us[-1], vs[-1]
        if u > u0 and abs(v0 + (v - v0) * (u1 - u0) / (u - u0) - v1) <= 1e-12:
            us[-1], vs[-1] = u, v
            replaced.append(len(us) - 1)
            return False
    us.append(u)
    vs.append(v)
    return True


# The cuts made lately, by what they were made of: an edit undone (a bracket typed again)
# gives a job of new passes with the values of one cut two analyses ago. A cache table of the
# current database (dropped with the others); at most CUTS_KEPT entries.
_CUTS: TableKey[tuple[object, ...], CrossSection | None] = TableKey("threads.cuts", cache=True)
CUTS_KEPT = 32


def _cut_seen(
    passes: list[Motion],
    lead: float,
    internal: bool,
    blank: float,
    tool: ToolShape,
    before: Sequence[Motion],
    prints: list[tuple[object, ...]],
    frame: TurnedSurface | None = None,
) -> CrossSection | None:
    """:func:`cut_cross_section`, or the cut of passes of the same values made lately;
    ``prints``: the passes' and ``before``'s fingerprints, once they are taken (one for the
    cuts of every nose radius)."""
    if not prints:
        prints += [_fingerprint(before), _fingerprint(passes)]
    key = (lead, internal, blank, tool, frame, *prints)
    table = current_database().table(_CUTS)
    if key in table:
        return table[key]
    found = table[key] = cut_cross_section(passes, lead, internal, blank, tool, before, frame)
    while len(table) > CUTS_KEPT:
        del table[next(iter(table))]
    return found


def _fingerprint(passes: Sequence[Motion]) -> tuple[object, ...]:
    return tuple(
        (
            m.x,
            m.start_x,
            m.start_z,
            m.words.get("Q"),
            m.words.get("R"),
            m.code,
            m.cycle_pass,
            m.tool_angle,
        )
        for m in passes
    )


# What of a pass its cut depends on: its X, where it starts along the lead (Z, or the start
# angle Q), its lead F, and for G76 which pass of the cycle it is and the cycle's tool angle;
# for a taper thread its taper (R, or the X it starts at).
CUT_READS = ("x", "start_x", "start_z", "Q", "R", "F", "code", "cycle_pass", "tool_angle")

# ISO 68-1's included angle of the metric profile, the only one the identified threads have.
METRIC_ANGLE = 60.0


def blank_diameter(thread: Thread) -> float | None:
    """What the passes cut into: the designation's major diameter outside, its basic minor
    diameter D1 inside (the largest outside and the smallest bore a part of the thread's
    size can have, so that a pass outside it cuts nothing on any such part)."""
    if thread.major is None or thread.pitch is None:
        return None
    return thread.major - D1_FACTOR * thread.pitch if thread.internal else thread.major


def blank_source(thread: Thread) -> str:
    """Where the blank of :func:`thread_cuts` comes from, for a message."""
    surface = thread.surface
    if surface is not None:
        line = surface.line + 1
        if thread.job.taper is not None:
            return tr("the cone turned at line {line}, at Z{z:.4g}", line=line, z=surface.z)
        if thread.internal or thread.job.internal:
            return tr("the bore turned at line {line}", line=line)
        return tr("the diameter turned at line {line}", line=line)
    if thread.internal:
        return tr("basic minor diameter D1 of {thread}", thread=thread.name)
    return tr("{thread}'s major diameter", thread=thread.name)


def thread_cuts(thread: Thread, before: Sequence[Motion] = ()) -> list[CrossSection]:
    """The cross-section of a thread job, for each nose radius the tool may have: the
    program's, else each end of ISO 965-1's range for the side (0.125P-0.144P outside,
    0-0.072P inside), so that a verdict that holds for both holds for any tool that may cut
    the thread; a taper pipe thread's tool has its standard's root round. The blank is the
    surface the program turned for the thread where it did (:mod:`.surface`), else the
    identified ISO metric thread's designation (:func:`blank_diameter`); a thread with
    neither is not cut. ``before``: the passes of earlier jobs on the same thread
    (:func:`thread_chains`), cut first; a job without them keeps its cut with it."""
    job = thread.job
    lead = job.lead
    pitch = thread.cut_pitch
    surface = thread.surface
    # A cycle's passes are tapered by its R (the job's ``taper``); G32's by their X.
    tapered = job.taper is not None or (
        not job.is_cycle
        and job.remember(
            "tapered",
            lambda: any(cuts_a_cone(m) for m in job.passes),
            ("x", "z", "start_x", "start_z", "R", "code"),
        )
    )
    if lead is None or pitch is None or thread.lead_conflict or (tapered and surface is None):
        return []
    if surface is not None:
        blank: float | None = surface.blank
    elif thread.identified:
        blank = blank_diameter(thread)
    else:
        blank = None
    internal = thread.internal if thread.internal is not None else job.internal
    if blank is None or internal is None:
        return []
    frame = surface if tapered else None
    pipe = thread.pipe
    if pipe is not None:
        angle, radii = pipe.angle, [pipe.nose_round * pitch]
    else:
        angle = _tool_angle(thread)
        if thread.nose_radius is not None and thread.nose_radius >= 0.0:
            radii = [thread.nose_radius]
        else:
            radii = list(dict.fromkeys(nose_radius_range(pitch, internal=internal)))
    found: list[CrossSection] = []
    prints: list[tuple[object, ...]] = []
    for r in radii:
        tool = ToolShape(angle, r)
        make = partial(_cut_seen, job.passes, lead, internal, blank, tool, before, prints, frame)
        cut = (
            make()
            if before
            else job.remember(("cross-section", internal, blank, tool, frame), make, CUT_READS)
        )
        if cut is not None:
            found.append(cut)
    return found


def _tool_angle(thread: Thread) -> float:
    """The tool's included angle: ISO 68-1's for an identified metric thread, else G76's
    tool angle a where the cycle gives one (the insert's angle the passes step along), else
    the 60° of the metric and Unified forms (an assumption for a thread whose form is not
    known: unverified)."""
    if thread.identified:
        return METRIC_ANGLE
    for m in thread.job.passes:
        if m.code == "G76" and m.tool_angle:
            return m.tool_angle
    return METRIC_ANGLE


# Half the least input increment (IS-B, mm): differences below it are the control's rounding.
EPS = 0.0005


@dataclass(frozen=True, slots=True)
class PitchVerdict:
    """The cut's pitch diameter against the class: ``side`` "tight" (an external thread above
    d2 max, an internal one below D2 min, by more than the class's width: its GO gauge does
    not go, and a wear offset would not be the fix), "loose" (past the other limit: its
    NO-GO gauge goes) or "" (within); over the nose radii :func:`thread_cuts` takes."""

    side: str
    least: float
    greatest: float
    limits: tuple[float, float]
    cuts: tuple[CrossSection, ...]


def class_limits(thread: Thread) -> tuple[float, float] | None:
    """The pitch diameters the thread's class allows. A class not known stands for any: the
    loosest class's limit on the loose side, the basic pitch diameter (classes h and H) on
    the tight one."""
    band = thread.pitch_band()
    if band is None or thread.major is None or thread.pitch is None:
        return None
    if thread.class_exact:
        return band
    basic = thread.major - 0.75 * thread.fundamental_height
    return (basic, band[1]) if thread.internal else (band[0], basic)


def pitch_verdict(thread: Thread, before: Sequence[Motion] = ()) -> PitchVerdict | None:
    if not thread.identified:
        return None
    cuts = thread_cuts(thread, before)
    limits = class_limits(thread)
    if not cuts or limits is None:
        return None
    found = [c.pitch_diameter for c in cuts]
    least, greatest = min(found), max(found)
    low, high = limits
    # A thread left shallow is gauged on the machine and the wear offset corrected: within
    # the class's own width of its limit that is the usual start (a program cut to the basic
    # profile's depth). Beyond it the program's depth is wrong.
    width = high - low
    side = ""
    if thread.internal:
        if greatest < low - width - EPS:
            side = "tight"
        elif least > high + EPS:
            side = "loose"
    elif least > high + width + EPS:
        side = "tight"
    elif greatest < low - EPS:
        side = "loose"
    return PitchVerdict(side, least, greatest, limits, tuple(cuts))


@dataclass(frozen=True, slots=True)
class CutSummary:
    """What a thread's passes cut, for the trace, the hover and the plot: the pitch diameter,
    root and crest (two values each when the nose radius is not known: the ends of its range),
    the class limits, the pass with the largest area and the passes in the air."""

    pitch_diameter: tuple[float, ...]
    root_diameter: tuple[float, ...]
    crest_diameter: float
    nose_radius: tuple[float, ...]
    nose_radius_known: bool
    limits: tuple[float, float] | None
    verdict: str  # "within", "tight", "loose" ("" without limits)
    area: float
    largest_pass: Motion
    largest_index: int
    largest_area: float
    in_the_air: int
    blank: float  # the diameter the passes cut into (a taper's: where its cone is read)
    blank_from: str  # where it is known from


def cut_summary(thread: Thread, before: Sequence[Motion] = ()) -> CutSummary | None:
    cuts = thread_cuts(thread, before)
    if not cuts:
        return None
    verdict = pitch_verdict(thread, before)
    # The first cut: with the program's nose radius, or with the low end of the range.
    first = cuts[0]
    largest = first.largest()
    if largest is None:
        return None
    return CutSummary(
        tuple(c.pitch_diameter for c in cuts),
        tuple(c.root_diameter for c in cuts),
        first.crest_diameter,
        tuple(c.tool.nose_radius for c in cuts),
        thread.nose_radius is not None,
        None if verdict is None else verdict.limits,
        "" if verdict is None else (verdict.side or "within"),
        first.area,
        thread.job.passes[largest.index],
        largest.index,
        largest.area,
        min(len(c.in_the_air()) for c in cuts),
        first.blank,
        blank_source(thread),
    )


def _values(values: tuple[float, ...], digits: int = 3) -> str:
    low, high = min(values), max(values)
    if high - low < 0.5 * 10.0**-digits:
        return f"{low:.{digits}f}"
    return f"{low:.{digits}f}–{high:.{digits}f}"


def describe_cut(thread: Thread, before: Sequence[Motion] = ()) -> str | None:
    """The cut's lines of a thread's hover (Markdown list items)."""
    summary = cut_summary(thread, before)
    if summary is None:
        return None
    which = "D2" if thread.internal else "d2"
    tool = (
        f"nose radius {_values(summary.nose_radius, 4)}"
        if summary.nose_radius_known
        else f"nose radius {_values(summary.nose_radius, 4)}, ISO 965-1's range (not given)"
    )
    lines = [f"- the cut ({tool}): {which} {_values(summary.pitch_diameter)}"]
    if summary.limits is not None:
        low, high = summary.limits
        state = {"within": "within", "tight": "too shallow for", "loose": "past"}[summary.verdict]
        lines[0] += f", {state} {low:.3f}–{high:.3f}"
    lines.append(
        f"- blank {summary.blank:.3f} ({summary.blank_from}); "
        f"root {_values(summary.root_diameter)}, crest {summary.crest_diameter:.3f}; "
        f"{summary.area:.3f} mm² removed, the most by line {summary.largest_pass.line + 1} "
        f"({summary.largest_area:.3f} mm²)"
    )
    if summary.in_the_air:
        lines.append(f"- {summary.in_the_air} passes before the first cut are in the air")
    return "\n".join(lines)


@dataclass(frozen=True, slots=True)
class Chain:
    """Where a job stands among the jobs that cut one thread: the passes of those before it,
    and whether one after it goes on cutting the thread."""

    before: tuple[Motion, ...]
    continued: bool


NO_CHAIN = Chain((), False)


def thread_chains(threads: Sequence[Thread], index: ProgramIndex | None = None) -> dict[int, Chain]:
    """The jobs that cut the same thread one after the other (a main program's passes and a
    subprogram's that finishes them; a roughing and a finishing tool), by ``id`` of their
    thread: the same document, side and lead, over a common stretch of Z (a quarter of the
    shorter), in one program or in a program and one it calls (``index``: the document's
    programs; without it, one program). Jobs alone are left out."""
    spans = [_z_span(t) for t in threads]
    related = _calling(index) if index is not None else set()
    found: dict[int, Chain] = {}
    for i, thread in enumerate(threads):
        same = [
            j
            for j, other in enumerate(threads)
            if j != i
            and _one_execution(thread, other, related)
            and _same_thread(thread, other, spans[i], spans[j])
        ]
        if not same:
            continue
        before = tuple(m for j in same if j < i for m in threads[j].job.passes)
        found[id(thread)] = Chain(before, any(j > i for j in same))
    return found


def _calling(index: ProgramIndex) -> set[tuple[int, int]]:
    """The pairs of programs (their first lines) of which one calls the other."""
    by_number = {p.number: p.first_line for p in index.programs if p.number is not None}
    pairs: set[tuple[int, int]] = set()
    for program in index.programs:
        for call in program.calls:
            callee = by_number.get(call.program) if call.program is not None else None
            if callee is not None:
                pairs.add((program.first_line, callee))
                pairs.add((callee, program.first_line))
    return pairs


def _one_execution(a: Thread, b: Thread, related: set[tuple[int, int]]) -> bool:
    """Whether two jobs may be of one execution: one program's, or a program's and the one it
    calls (two main programs of a file are two parts)."""
    first_a, first_b = a.job.program_line, b.job.program_line
    return first_a == first_b or (first_a, first_b) in related


def _z_span(thread: Thread) -> tuple[float, float] | None:
    job = thread.job
    return job.remember("z span", partial(_passes_span, job.passes), ("z", "start_z"))


def _passes_span(passes: Sequence[Motion]) -> tuple[float, float] | None:
    zs = [z for m in passes for z in (m.z, m.start_z) if z is not None]
    return (min(zs), max(zs)) if zs else None


def _same_thread(
    a: Thread,
    b: Thread,
    span_a: tuple[float, float] | None,
    span_b: tuple[float, float] | None,
) -> bool:
    lead_a, lead_b = a.job.lead, b.job.lead
    if a.job.uri != b.job.uri or lead_a is None or lead_b is None or abs(lead_a - lead_b) > 1e-9:
        return False
    side_a = a.internal if a.internal is not None else a.job.internal
    side_b = b.internal if b.internal is not None else b.job.internal
    if side_a is None or side_a != side_b or span_a is None or span_b is None:
        return False
    common = min(span_a[1], span_b[1]) - max(span_a[0], span_b[0])
    shorter = min(span_a[1] - span_a[0], span_b[1] - span_b[0])
    return common >= 0.25 * shorter - 1e-9 and shorter > 0.0
