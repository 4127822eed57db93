"""The backplot: a program's toolpath drawn as SVG (``fanuc-macro plot``).

Rapids dashed, feeds solid, threading passes and arcs in colours of their own, a legend that
says so, the start and the end of the path marked and arrows for the direction of travel, with
axes in the program's units and a scale bar. A lathe is drawn in its XZ plane as machinists draw
it (Z across, X up, as a radius: the program's X is a diameter, and its tick labels say so); a
mill in its XY plane. Without a plane asked for, the plane is chosen from the moves the path
makes (``choose_plane``): a mill's program read as a lathe's is drawn in XY. Under the drawing,
one line for each cause of moves it leaves out, with the blocks where it happened (where the
analysis lost track of the tool, a cycle it does not draw), and one line counting the moves that
start before the run's first absolute position of an axis (where the tool stands when a run
begins is not known: normal, and not a line for each axis or block).

For a threading program a second view follows: the pass map of each thread (the depth of every
pass, and the infeed diagram: where the tool's tip is in the groove at each pass, and for an
identified thread the groove the passes cut, its cross-section, with the class's pitch-diameter
limits), of the first ``MAX_PASS_MAPS`` threads, the others counted.

Every drawn element carries ``data-line`` (the 1-based line of its block) and ``data-kind`` (a
move's kind, or what a pass map's element shows), so that a viewer can link it to the source; the
marks on the path (start, end, direction) carry ``data-mark`` instead. A move is a ``<path>``,
consecutive moves of one kind made by one block (a canned cycle's retract and return) one path;
the moves of each run of one program are in a ``<g data-program>``. A 200,000-block posted file
is 200,000 small elements.

Text is laid out with an estimate of its width (``text_width``): labels do not run into each
other or off the drawing, a long title is shortened in the middle, a caption wraps. The drawing
is a pure function of the toolpath and the threads: the same program gives the same bytes
(coordinates are written at a fixed precision).
"""

from __future__ import annotations

import contextvars
import math
import unicodedata
from bisect import bisect_right
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import NamedTuple
from xml.sax.saxutils import escape, quoteattr

from ..config import Config
from ..evaluator.cycle_time import cycle_time, minutes_seconds
from ..evaluator.facts import Motion
from ..evaluator.toolpath import MAX_MOVES, UNKNOWN_START, LostTrack, Move, Plane, Toolpath
from ..evaluator.values import fmt_address
from ..program.index import ProgramIndex
from ..program.machine_kind import machine_config
from ..syntax.parser import quiet_gc
from ..syntax.tree import Document
from ..threads.cross_section import NO_CHAIN, class_limits, thread_chains, thread_cuts
from ..threads.identify import Thread
from ..translation import joined, render, tr, tr_n
from .trace import run_with_toolpath

# The drawing's size in SVG user units (pixels): the path is fitted into a box this wide (less
# the margins) and ``_BOX_HEIGHT`` high, under the title and the legend.
WIDTH = 960.0
MARGIN_LEFT = 78.0
MARGIN_RIGHT = 24.0
MARGIN_BOTTOM = 66.0  # tick labels, the axis title, the scale bar
# An arc drawn out of its own plane is drawn as a polyline of this many segments per turn.
ARC_SEGMENTS_PER_TURN = 72
# The pass maps drawn after the toolpath: a chain of G32 segments (seed 003's drum groove) is
# thousands of one-pass threads to the rules.
MAX_PASS_MAPS = 20
# Direction arrows: at most this many, on moves at least this long on the drawing (pixels).
MAX_ARROWS = 40
ARROW_MIN_LENGTH = 24.0
# The lines of sites a note lists before it counts the rest.
MAX_SITES = 5

FONT_SIZE = 12.0
TITLE_SIZE = 14.0
LINE_HEIGHT = 16.0
STYLE = (
    "text{font:12px sans-serif;fill:#222}"
    ".title{font-weight:bold;font-size:14px}"
    ".axis{stroke:#444;stroke-width:1}"
    ".grid{stroke:#ddd;stroke-width:0.5}"
    ".zero{stroke:#999;stroke-width:0.8;stroke-dasharray:2 2}"
    ".moves path,.legend line{fill:none;stroke-width:1.2;stroke-linecap:round}"
    "[data-kind=rapid],.legend .rapid{stroke:#888;stroke-dasharray:5 4}"
    "[data-kind=feed],.legend .feed{stroke:#1f5fbf}"
    "[data-kind=arc],.legend .arc{stroke:#1f8f4f}"
    "[data-kind=thread],.legend .thread{stroke:#d2411f;stroke-width:1.6}"
    ".lost{fill:#fff;stroke:#b00;stroke-width:1.5}"
    ".start{fill:#fff;stroke:#222;stroke-width:2.5}"
    ".end{fill:#222;stroke:#fff;stroke-width:1}"
    ".arrow{fill:#222;stroke:#fff;stroke-width:0.8;stroke-linejoin:round}"
    ".note{fill:#444}"
    ".pass{fill:#d2411f;stroke:none}"
    ".tool{fill:none;stroke:#d2411f;stroke-width:0.8;opacity:0.6}"
    ".profile{fill:#f3e9e4;stroke:#555;stroke-width:1}"
    ".cut{fill:none;stroke:#1d4e89;stroke-width:1.4}"
    ".band{stroke:#1d4e89;stroke-width:0.8;stroke-dasharray:4 3}"
    ".bar{fill:#f0b8a6;stroke:#a33;stroke-width:0.6}.thin{stroke:none}"
    ".cap{fill:#c2452a;stroke:none}"
)

# What the legend calls each kind of move.
KIND_NAMES: Mapping[str, str] = MappingProxyType(
    {"rapid": tr("rapid"), "feed": tr("feed"), "arc": tr("arc"), "thread": tr("threading")}
)

# Which axes are across and up in each view, as machinists draw them: a lathe's XZ view has Z
# across and X up (the rear-turret convention of FANUC's lathe manuals, unverified for a front
# turret: it is the same picture upside down); a mill's views are seen from +Z, -Y and +X.
_VIEW_AXES: Mapping[tuple[bool, Plane], tuple[str, str]] = MappingProxyType(
    {
        (True, "XZ"): ("Z", "X"),
        (True, "XY"): ("X", "Y"),
        (True, "YZ"): ("Y", "Z"),
        (False, "XY"): ("X", "Y"),
        (False, "XZ"): ("X", "Z"),
        (False, "YZ"): ("Y", "Z"),
    }
)
# The planes in the order a machine's drawing prefers them: its usual view first.
_PLANES: Mapping[bool, tuple[Plane, ...]] = MappingProxyType(
    {True: ("XZ", "XY", "YZ"), False: ("XY", "XZ", "YZ")}
)
# The axes of each arc plane in the order in which G02 turns clockwise, seen from the plane's
# positive normal (FANUC: G17 X-Y seen from +Z, G18 Z-X from +Y, G19 Y-Z from +X).
_ARC_AXES: Mapping[Plane, tuple[str, str]] = MappingProxyType(
    {"XY": ("X", "Y"), "XZ": ("Z", "X"), "YZ": ("Y", "Z")}
)


class NothingToPlot(Exception):
    """The trace has no move whose position in the view's plane is known."""


# ---- text ------------------------------------------------------------------------------------

# The language the drawing being made speaks: set by ``backplot`` for the drawing's making.
_LOCALE: contextvars.ContextVar[str] = contextvars.ContextVar("plot_locale", default="en")


def _say(text: str) -> str:
    """``text`` in the language of the drawing being made."""
    return render(text, _LOCALE.get())


def _wide(char: str) -> bool:
    return unicodedata.east_asian_width(char) in "WF"


def text_width(text: str, size: float = FONT_SIZE, bold: bool = False) -> float:
    """A generous estimate of the width of ``text`` in pixels: 0.62 em a character (sans-serif
    digits are 0.55 to 0.64 em), 1 em a wide one (CJK), a tenth more in bold."""
    em = 0.0
    for ch in text:
        em += 1.0 if unicodedata.east_asian_width(ch) in "WF" else 0.62
    return em * size * (1.1 if bold else 1.0)


def shorten(text: str, width: float, size: float = FONT_SIZE, bold: bool = False) -> str:
    """``text``, or its start and end with an ellipsis between, no wider than ``width``."""
    if text_width(text, size, bold) <= width:
        return text
    keep = len(text)
    while keep > 1:
        keep -= 1
        head, tail = text[: (keep + 1) // 2], text[len(text) - keep // 2 :]
        shortened = f"{head}…{tail}"
        if text_width(shortened, size, bold) <= width:
            return shortened
    return "…"


def wrap(text: str, width: float, size: float = FONT_SIZE) -> list[str]:
    """``text`` in lines no wider than ``width``, broken between words (a word wider than a line
    is shortened)."""
    if any(_wide(c) for c in text):
        return _wrap_wide(text, width, size)
    lines: list[str] = []
    line = ""
    for word in text.split():
        candidate = f"{line} {word}" if line else word
        if line and text_width(candidate, size) > width:
            lines.append(line)
            candidate = word
        line = candidate
    if line:
        lines.append(line)
    return [shorten(line, width, size) for line in lines]


# Never first on a line: closing punctuation, the long vowel mark and small kana.
_CLOSING = frozenset("，。；：、）》」』！？ーぁぃぅぇぉっゃゅょァィゥェォッャュョ")
_OPENING = frozenset("（《「『“")  # never last on a line


def _wrap_wide(text: str, width: float, size: float) -> list[str]:
    """``wrap`` for a Chinese or Japanese text: a line may break between any two of its
    characters (not before closing punctuation nor after opening), or at a space."""
    tokens: list[str] = []  # a space, or a wide character or a word, with its punctuation
    after_word = False
    opening = ""
    for char in " ".join(text.split()):
        if char in _CLOSING and tokens and tokens[-1] != " " and not opening:
            tokens[-1] += char
            after_word = False
            continue
        if char in _OPENING:
            opening += char
            continue
        word = char != " " and not _wide(char)
        if word and after_word and not opening:
            tokens[-1] += char
        else:
            tokens.append(opening + char)
            opening = ""
        after_word = word
    if opening:
        tokens.append(opening)
    lines: list[str] = []
    line = ""
    for token in tokens:
        if line.strip() and token != " " and text_width(line + token, size) > width:
            lines.append(line.rstrip())
            line = ""
        if line or token != " ":
            line += token
    if line.strip():
        lines.append(line.rstrip())
    return [shorten(line, width, size) for line in lines]


def _text(x: float, y: float, text: str, anchor: str = "start", cls: str = "") -> str:
    klass = f' class="{cls}"' if cls else ""
    middle = "" if anchor == "start" else f' text-anchor="{anchor}"'
    return f'<text{klass} x="{_num(x)}" y="{_num(y)}"{middle}>{escape(text)}</text>'


# ---- what the drawing shows and leaves out --------------------------------------------------


@dataclass(frozen=True, slots=True)
class PassMark:
    """One threading pass in a pass map: its block, its depth and where its tip is along Z."""

    line: int  # 0-based
    x: float  # the diameter the pass cuts at
    z: float | None  # where the pass starts along Z (its infeed's axial place)


@dataclass(frozen=True, slots=True)
class PassMap:
    """The passes of one thread, as the second view draws them."""

    name: str
    program: str
    internal: bool
    passes: tuple[PassMark, ...]
    major: float | None = None  # the nominal diameter, when the thread is identified
    pitch: float | None = None
    # The cross-section the passes cut (threads/cross_section.py): (offset along the lead
    # from the deepest pass, radius) over one lead, the deepest pass's index, and the class's
    # pitch diameters (least, greatest).
    cut: tuple[tuple[float, float], ...] = ()
    cut_pass: int | None = None
    band: tuple[float, float] | None = None


@dataclass(frozen=True, slots=True)
class PlotNote:
    """A cause of what the drawing leaves out or draws otherwise than the control moves: the
    blocks where it happened (in the order of the run) and the moves it leaves undrawn (0 for a
    cycle the path does not draw, which makes no move)."""

    reason: str
    sites: tuple[tuple[str, int], ...]  # (uri, 0-based line)
    hidden: int = 0

    def text(self, main_uri: str = "", first_site: bool = True) -> str:
        """The note in one line: ``line 12: <reason>: 3 moves not drawn (also lines 40, 88)``,
        the site's file named when it is not ``main_uri``; without the first site when
        ``first_site`` is false (a caller that puts it in front)."""
        text: str = self.reason
        if self.hidden:
            text = tr(
                "{reason}: {moves} not drawn",
                reason=text,
                moves=tr_n("{count} move", "{count} moves", self.hidden),
            )
        more = self.sites[1:]
        if more:
            shown = _sites(more[:MAX_SITES], main_uri)
            if len(more) > MAX_SITES:
                shown = tr("{sites} and {more} more", sites=shown, more=len(more) - MAX_SITES)
            text = tr("{note} (also {sites})", note=text, sites=shown)
        if first_site and self.sites:
            text = tr("{site}: {note}", site=_site(self.sites[0], main_uri), note=text)
        return text


def _site(site: tuple[str, int], main_uri: str) -> str:
    uri, line = site
    return tr("line {line}", line=line + 1) if not uri or uri == main_uri else f"{uri}:{line + 1}"


def _sites(sites: Sequence[tuple[str, int]], main_uri: str) -> str:
    """``line 40``, ``lines 40, 88 and 90``, or each site with its file when one is not
    ``main_uri``."""
    if all(not uri or uri == main_uri for uri, _ in sites):
        lines = [str(line + 1) for _, line in sites]
        if len(lines) == 1:
            return tr("line {line}", line=lines[0])
        return tr("lines {lines}", lines=_and(lines))
    return _and([_site(site, main_uri) for site in sites])


def _and(items: Sequence[str]) -> str:
    if len(items) == 1:
        return items[0]
    return tr("{items} and {last}", items=joined(", ", items[:-1]), last=items[-1])


@dataclass(frozen=True, slots=True)
class Backplot:
    """The drawing and what a user is told about it."""

    svg: str
    plane: Plane
    # Why the plane was chosen, when none was asked for and it is not the machine's usual one.
    plane_reason: str | None
    drawn: int  # moves drawn
    total: int  # moves the run made
    # The moves not drawn because they start where the tool stood when the run began, which
    # the program does not say: before the first absolute position of these axes.
    before_start: int
    start_axes: tuple[str, ...]
    notes: tuple[PlotNote, ...]

    def summary(self, counts: str = "") -> str:
        """``1010 of 1011 moves drawn in XZ (counts)``, and why the others are not when it is
        that the start is not known."""
        text: str = tr(
            "{drawn} of {total} moves drawn in {plane}",
            drawn=self.drawn,
            total=self.total,
            plane=self.plane,
        )
        if counts:
            text = tr("{summary} ({counts})", summary=text, counts=counts)
        if self.before_start:
            why = _start_text(self.before_start, self.start_axes, moves=False)
            text = tr("{summary}; {why}", summary=text, why=why)
        return text


def _start_text(count: int, axes: Sequence[str], moves: bool = True) -> str:
    """Why ``count`` moves are not drawn: they start where the tool stood when the run began."""
    if moves:
        return tr_n(
            "{count} move not drawn: it starts before the first absolute {axes} (the tool's"
            " place at the start is not known)",
            "{count} moves not drawn: they start before the first absolute {axes} (the tool's"
            " place at the start is not known)",
            count,
            axes=_and(axes),
        )
    return tr_n(
        "{count} not drawn: it starts before the first absolute {axes} (the tool's place at"
        " the start is not known)",
        "{count} not drawn: they start before the first absolute {axes} (the tool's place at"
        " the start is not known)",
        count,
        axes=_and(axes),
    )


def pass_maps(threads: Sequence[Thread], index: ProgramIndex | None = None) -> list[PassMap]:
    """A pass map for every thread of an analysis whose passes have a known diameter, with
    the cross-section of an identified thread's cut (``index``: the document's programs, for
    the jobs that cut one thread from a program and one it calls)."""
    maps = []
    chains = thread_chains(threads, index)
    for thread in threads:
        job = thread.job
        kept = [p for p in job.passes if p.x is not None]
        marks = tuple(PassMark(p.line, p.x, p.start_z) for p in kept if p.x is not None)
        if not marks:
            continue
        internal = thread.internal if thread.internal is not None else bool(job.internal)
        cut, cut_pass, band = _cut_of(thread, chains.get(id(thread), NO_CHAIN).before, kept)
        maps.append(
            PassMap(
                thread.name,
                job.program,
                internal,
                marks,
                thread.major,
                thread.pitch,
                cut,
                cut_pass,
                band,
            )
        )
    return maps


def _cut_of(
    thread: Thread, before: Sequence[Motion], kept: list[Motion]
) -> tuple[tuple[tuple[float, float], ...], int | None, tuple[float, float] | None]:
    """The cut's profile about the deepest pass, that pass's place among the drawn passes,
    and the class's pitch diameters."""
    cuts = thread_cuts(thread, before)
    if not cuts:
        return (), None, None
    cut = cuts[0]
    deepest = (max if cut.internal else min)(cut.cuts, key=lambda c: c.tip, default=None)
    if deepest is None:
        return (), None, None
    lead = cut.lead
    around = sorted(
        (((u - deepest.place + lead / 2.0) % lead) - lead / 2.0, h) for u, h in cut.profile
    )
    index = next((k for k, m in enumerate(kept) if m is thread.job.passes[deepest.index]), None)
    return tuple(around), index, class_limits(thread)


# ---- geometry ------------------------------------------------------------------------------


def _num(value: float) -> str:
    """An SVG coordinate at a fixed precision, so that the output is the same everywhere."""
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def geometric(toolpath: Toolpath, point: dict[str, float]) -> dict[str, float]:
    """A position in the drawing's geometry: a lathe's X diameter as a radius."""
    if toolpath.lathe and "X" in point:
        return {**point, "X": point["X"] / 2.0}
    return point


def arc_points(
    toolpath: Toolpath, move: Move, decimals: int | None = None
) -> tuple[list[dict[str, float]], float] | None:
    """Points along an arc (a helix when the third axis moves), start and end included, and
    the angle it turns through (radians, negative clockwise); rounded to ``decimals``."""
    centre = move.centre
    if centre is None:
        return None
    start = geometric(toolpath, move.start)
    end = geometric(toolpath, move.end)
    c = geometric(toolpath, centre)
    a, b = _ARC_AXES[move.plane]
    if not all(k in p for p in (start, end, c) for k in (a, b)):
        return None
    t0 = math.atan2(start[b] - c[b], start[a] - c[a])
    t1 = math.atan2(end[b] - c[b], end[a] - c[a])
    radius = math.hypot(start[a] - c[a], start[b] - c[b])
    # Clockwise turns the angle down; a start equal to the end is a full circle.
    if move.clockwise:
        span = (t0 - t1) % math.tau or math.tau
        span = -span
    else:
        span = (t1 - t0) % math.tau or math.tau
    steps = max(4, math.ceil(abs(span) / math.tau * ARC_SEGMENTS_PER_TURN))
    # The other axes known at both ends go linearly from the start to the end (a helix).
    third = [(k, start[k], end[k] - start[k]) for k in start if k not in (a, b) and k in end]
    ca, cb, cos, sin = c[a], c[b], math.cos, math.sin
    # Rounded as n / 10**decimals: the float nearest that decimal, as round() gives, faster.
    scale, floor = (10.0**decimals, math.floor) if decimals is not None else (0.0, None)
    points = []
    for i in range(steps + 1):
        f = i / steps
        t = t0 + span * f
        p = {a: ca + radius * cos(t), b: cb + radius * sin(t)}
        for k, k0, dk in third:
            p[k] = k0 + dk * f
        if floor is not None:
            p = {k: floor(v * scale + 0.5) / scale for k, v in p.items()}
        points.append(p)
    points[-1] = {**points[-1], a: end[a], b: end[b]}
    return points, span


# ---- the plane -------------------------------------------------------------------------------


def _extent(toolpath: Toolpath, plane: Plane, any_move: bool = False) -> tuple[int, float]:
    """How many moves have a place in the plane's view, and how far they go in it (the
    drawing's geometry; an arc by its chord, a full circle by its circumference). With
    ``any_move``, stops at the first move that goes somewhere in the plane."""
    across, up = _VIEW_AXES[(toolpath.lathe, plane)]
    h_scale = 0.5 if toolpath.lathe and across == "X" else 1.0
    v_scale = 0.5 if toolpath.lathe and up == "X" else 1.0
    count, length = 0, 0.0
    for move in toolpath.moves:
        start, end = move.start, move.end
        h0, v0, h1, v1 = start.get(across), start.get(up), end.get(across), end.get(up)
        if h0 is None or v0 is None or h1 is None or v1 is None:
            continue
        count += 1
        step = math.hypot((h1 - h0) * h_scale, (v1 - v0) * v_scale)
        centre = move.centre
        if not step and centre is not None and set(_ARC_AXES[move.plane]) == {across, up}:
            hc, vc = centre.get(across, h0), centre.get(up, v0)
            step = math.tau * math.hypot((h0 - hc) * h_scale, (v0 - vc) * v_scale)
        length += step
        if any_move and step:
            break
    return count, length


_LATHE_VIEW = tr("a lathe's usual view")


def choose_plane(toolpath: Toolpath) -> tuple[Plane, str | None]:
    """The plane to draw when none is asked for, and why when it is not the machine's usual
    one (XZ on a lathe, XY on a mill): a path that makes no move in that plane is drawn in the
    plane it goes furthest in, and on a lathe a path that goes further in XY than in XZ in XY
    (a mill's program run as a lathe's).

    Raises :class:`NothingToPlot` when no move has a place in any plane."""
    order = _PLANES[toolpath.lathe]
    usual = order[0]
    if toolpath.lathe and _extent(toolpath, "XY", any_move=True)[1]:
        # Turning on a lathe with a Y axis goes further in X-Z than its milling in X-Y; a
        # mill's program read as a lathe's goes further in X-Y.
        xz, xy = _extent(toolpath, "XZ")[1], _extent(toolpath, "XY")[1]
        if xy > xz:
            if xz:
                return "XY", tr(
                    "drawn in XY: the path goes further in XY than in XZ, {view}", view=_LATHE_VIEW
                )
            return "XY", tr("drawn in XY: the path makes no move in XZ, {view}", view=_LATHE_VIEW)
        return "XZ", None
    if _extent(toolpath, usual, any_move=True)[1]:
        return usual, None
    extents = {plane: _extent(toolpath, plane) for plane in order}
    moving = [plane for plane in order if extents[plane][1]]
    placed = [plane for plane in order if extents[plane][0]]
    if not placed:
        raise NothingToPlot(
            tr(
                "no move of the trace has a known place in two axes: nothing to plot in XY, XZ"
                " or YZ"
            )
        )
    # max() keeps the first of equals: the machine's order breaks a tie.
    best = max(moving, key=lambda plane: extents[plane][1]) if moving else placed[0]
    if best == usual:
        return usual, None
    view = _LATHE_VIEW if toolpath.lathe else tr("a mill's usual view")
    reason = tr(
        "drawn in {plane}: the path makes no move in {usual}, {view}",
        plane=best,
        usual=usual,
        view=view,
    )
    if len(moving) > 1:
        reason = tr("{reason}; it goes furthest in {plane}", reason=reason, plane=best)
    return best, reason


def _nothing_in(toolpath: Toolpath, view: Plane, across: str, up: str) -> NothingToPlot:
    """The error of a view asked for that has no move, naming the planes that have some."""
    others = [p for p in _PLANES[toolpath.lathe] if p != view and _extent(toolpath, p)[0]]
    if others:
        where = tr(
            "the path has moves in {planes} (--plane {plane})", planes=_and(others), plane=others[0]
        )
    else:
        where = tr("no move has a known place in any plane")
    return NothingToPlot(
        tr(
            "no move of the trace has a known {across} and {up}: nothing to plot in {view};"
            " {where}",
            across=across,
            up=up,
            view=view,
            where=where,
        )
    )


# ---- axes ------------------------------------------------------------------------------------


@dataclass(slots=True)
class _Frame:
    """World (across, up) to SVG pixels: one scale for both axes, up drawn upwards."""

    h_min: float
    v_max: float
    scale: float
    left: float
    top: float

    def x(self, h: float) -> float:
        return self.left + (h - self.h_min) * self.scale

    def y(self, v: float) -> float:
        return self.top + (self.v_max - v) * self.scale


def _decimals(step: float) -> int:
    """The decimals a multiple of ``step`` (1, 2 or 5 times a power of ten) needs."""
    return max(0, -math.floor(math.log10(step) + 1e-9))


def _tick(value: float, step: float = 0.001) -> str:
    """A tick's label: a multiple of ``step`` with the decimals it needs, no trailing zeros."""
    digits = min(_decimals(step), 6)
    text = f"{value:.{digits}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _nice_step(span: float, ticks: int = 8) -> float:
    """1, 2 or 5 times a power of ten, giving about ``ticks`` intervals over ``span``."""
    if span <= 0:
        return 1.0
    raw = span / ticks
    power = 10.0 ** math.floor(math.log10(raw))
    for m in (1.0, 2.0, 5.0, 10.0):
        if raw <= m * power * (1 + 1e-9):
            return m * power
    return 10.0 * power


def _next_step(step: float, up: bool = True) -> float:
    """The next 1, 2 or 5 times a power of ten above (or below) ``step``."""
    power = 10.0 ** math.floor(math.log10(step) + 1e-9)
    m = round(step / power)
    if up:
        return {1: 2.0, 2: 5.0}.get(m, 10.0) * power
    return {5: 2.0, 2: 1.0}.get(m, 0.5) * power


def _tick_values(lo: float, hi: float, step: float) -> list[float]:
    """The multiples of ``step`` from ``lo`` to ``hi``."""
    first, last = math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9)
    return [k * step for k in range(first, last + 1)]


def _fit_step(
    lo: float, hi: float, pixels: float, room: Callable[[float], float], ticks: int
) -> float:
    """The step of an axis from ``lo`` to ``hi`` drawn ``pixels`` a unit: about ``ticks``
    intervals, fewer when their labels would come closer than ``room(step)`` pixels, more
    when fewer than two ticks would show and their labels fit."""
    step = _nice_step(hi - lo, ticks)

    def fits(s: float) -> bool:
        return s * pixels >= room(s)

    for _ in range(60):
        if fits(step):
            break
        step = _next_step(step)
    for _ in range(60):
        if len(_tick_values(lo, hi, step)) >= 2:
            break
        smaller = _next_step(step, up=False)
        if not fits(smaller):
            break
        step = smaller
    return step


def _axis_titles(axis: str, toolpath: Toolpath, units: str) -> list[str]:
    """An axis's title, and shorter ones for a short axis."""
    if toolpath.lathe and axis == "X":
        return [
            _say(tr("X ({units}): a diameter, drawn as a radius", units=units)),
            _say(tr("X ({units}, diameter)", units=units)),
        ]
    return [f"{axis} ({units})"]


def _fitted(titles: list[str], room: float) -> str:
    for title in titles:
        if text_width(title) <= room:
            return title
    return shorten(titles[-1], room)


Box = tuple[float, float, float, float]  # left, top, right, low: the plot's frame in pixels


def _rule(cls: str, across: bool, at: float, box: Box) -> str:
    """A line through the box at ``at``: upright for a place across, level for one up."""
    left, top, right, low = box
    x1, y1, x2, y2 = (at, top, at, low) if across else (left, at, right, at)
    return f'<line class="{cls}" x1="{_num(x1)}" y1="{_num(y1)}" x2="{_num(x2)}" y2="{_num(y2)}"/>'


@dataclass(frozen=True, slots=True)
class _Ticks:
    """The ticks of the two axes of the toolpath's view and what they need room for."""

    h_step: float
    v_step: float
    # What the labels multiply the drawing's values by: 2 for a lathe's X, drawn as a radius
    # and labelled as the diameter the program writes.
    h_factor: float
    v_factor: float
    v_width: float  # the widest label up the left side


def _choose_ticks(
    h_range: tuple[float, float],
    v_range: tuple[float, float],
    scale: float,
    factors: tuple[float, float],
) -> _Ticks:
    h_span, v_span = h_range[1] - h_range[0], v_range[1] - v_range[0]

    h_factor, v_factor = factors

    def across_room(step: float) -> float:
        labels = (_tick(v * h_factor, step * h_factor) for v in _tick_values(*h_range, step))
        return max((text_width(t) for t in labels), default=0.0) + 14.0

    h_step = _fit_step(*h_range, scale, across_room, 8)
    # Each axis gets ticks of its own: a long thin path (a thread along Z) still shows its X.
    v_ticks = max(2, min(8, round(8 * v_span / h_span)))
    v_step = _fit_step(*v_range, scale, lambda _: FONT_SIZE + 6.0, v_ticks)
    labels = [_tick(v * v_factor, v_step * v_factor) for v in _tick_values(*v_range, v_step)]
    widest = max((text_width(t) for t in labels), default=0.0)
    return _Ticks(h_step, v_step, h_factor, v_factor, widest)


def _axes(
    frame: _Frame,
    h_range: tuple[float, float],
    v_range: tuple[float, float],
    ticks: _Ticks,
    titles: tuple[list[str], list[str]],
    units: str,
) -> list[str]:
    """Ticks, grid, titles, the zero lines and a scale bar under the box."""
    out = ['<g class="axes">']
    left, right = frame.x(h_range[0]), frame.x(h_range[1])
    top, low = frame.y(v_range[1]), frame.y(v_range[0])
    out.append(
        f'<rect class="axis" fill="none" x="{_num(left)}" y="{_num(top)}"'
        f' width="{_num(right - left)}" height="{_num(low - top)}"/>'
    )
    box = (left, top, right, low)
    step = ticks.h_step
    for value in _tick_values(*h_range, step):
        at = frame.x(value)
        out.append(_rule("grid", True, at, box))
        label = _tick(value * ticks.h_factor, step * ticks.h_factor)
        # A label at the drawing's right edge moves in, off its tick, rather than out of sight.
        half = text_width(label) / 2
        out.append(_text(min(at, WIDTH - 2 - half), low + 16, label, "middle"))
    factor = ticks.v_factor
    for value in _tick_values(*v_range, ticks.v_step):
        at = frame.y(value)
        out.append(_rule("grid", False, at, box))
        out.append(_text(left - 6, at + 4, _tick(value * factor, ticks.v_step * factor), "end"))
    if h_range[0] < 0 < h_range[1]:
        out.append(_rule("zero", True, frame.x(0.0), box))
    if v_range[0] < 0 < v_range[1]:
        out.append(_rule("zero", False, frame.y(0.0), box))
    across_title = _fitted(titles[0], right - left)
    out.append(_text((left + right) / 2, low + 34, across_title, "middle"))
    # Up the left side, clear of the tick labels: its glyphs reach 0.8 em left of the baseline.
    x = left - 12 - ticks.v_width - 0.2 * FONT_SIZE
    up_title = _fitted(titles[1], low - top)
    out.append(
        f'<text transform="translate({_num(x)} {_num((top + low) / 2)}) rotate(-90)"'
        f' text-anchor="middle">{escape(up_title)}</text>'
    )
    bar = step * frame.scale
    out.append(
        f'<g class="scale" data-length="{_tick(step, step)}">'
        f'<line class="axis" x1="{_num(right - bar)}" y1="{_num(low + 58)}"'
        f' x2="{_num(right)}" y2="{_num(low + 58)}" stroke-width="3"/>'
        f"{_text(right - bar / 2, low + 52, f'{_tick(step, step)} {units}', 'middle')}</g>"
    )
    out.append("</g>")
    return out


def _svg_arc(frame: _Frame, item: _Drawn, toolpath: Toolpath, across: str, up: str) -> str | None:
    """The SVG arc command (``A``, from the current point) of an arc in the view's plane, no
    helix; else None."""
    move, points = item.move, item.points
    if set(_ARC_AXES[move.plane]) != {across, up} or move.centre is None or item.turn is None:
        return None
    start, end = move.start, move.end
    if any(start.get(k) != end.get(k) for k in {*start, *end} - {across, up}):
        return None  # a helix: the polyline shows its projection
    c = geometric(toolpath, move.centre)
    sx, sy = frame.x(points[0][0]), frame.y(points[0][1])
    ex, ey = frame.x(points[-1][0]), frame.y(points[-1][1])
    mid = points[len(points) // 2]
    mx, my = frame.x(mid[0]), frame.y(mid[1])
    cx, cy = frame.x(c[across]), frame.y(c[up])
    r = math.hypot(sx - cx, sy - cy)
    sweep = 1 if (sx - cx) * (my - cy) - (sy - cy) * (mx - cx) > 0 else 0
    turn = abs(item.turn)
    if turn >= math.tau - 1e-9:  # a full circle: two halves, an SVG arc cannot close itself
        ox, oy = 2 * cx - sx, 2 * cy - sy
        return (
            f"A{_num(r)} {_num(r)} 0 0 {sweep} {_num(ox)} {_num(oy)}"
            f"A{_num(r)} {_num(r)} 0 0 {sweep} {_num(sx)} {_num(sy)}"
        )
    large = 1 if turn > math.pi else 0
    return f"A{_num(r)} {_num(r)} 0 {large} {sweep} {_num(ex)} {_num(ey)}"


# ---- the moves -------------------------------------------------------------------------------


class _Drawn(NamedTuple):
    """A move and the points it is drawn through (a tuple: there are 200,000 of them)."""

    move: Move
    points: list[tuple[float, float]]  # (across, up) in the drawing's geometry
    turn: float | None = None  # an arc's angle, radians


def _drawn(toolpath: Toolpath, across: str, up: str) -> tuple[list[_Drawn], list[int]]:
    """Each move with the points it is drawn through, when its place in the view is known;
    the indices of the moves whose place is not."""
    drawn = []
    undrawn = []
    # geometric(), for one axis at a time: a lathe's X diameter as a radius.
    h_scale = 0.5 if toolpath.lathe and across == "X" else 1.0
    v_scale = 0.5 if toolpath.lathe and up == "X" else 1.0
    for i, move in enumerate(toolpath.moves):
        if move.kind == "arc":
            arc = arc_points(toolpath, move)
            if arc is not None:
                if all(across in p and up in p for p in arc[0]):
                    drawn.append(_Drawn(move, [(p[across], p[up]) for p in arc[0]], arc[1]))
                else:
                    undrawn.append(i)
                continue
        start, end = move.start, move.end
        h0, v0, h1, v1 = start.get(across), start.get(up), end.get(across), end.get(up)
        if h0 is None or v0 is None or h1 is None or v1 is None:
            undrawn.append(i)
            continue
        drawn.append(_Drawn(move, [(h0 * h_scale, v0 * v_scale), (h1 * h_scale, v1 * v_scale)]))
    return drawn, undrawn


def _moves(
    drawn: list[_Drawn], frame: _Frame, toolpath: Toolpath, across: str, up: str, main_uri: str
) -> list[str]:
    """The moves' elements: a path for each run of consecutive moves of one kind by one block,
    in a group for each run of one program's moves."""
    out: list[str] = []
    d: list[str] = []  # the path data of the element being made
    element: tuple[str, int, str] | None = None  # its kind, line and document
    group: tuple[str, str] | None = None  # the program and document of the group
    last: tuple[float, float] | None = None  # where the path data ends (world)
    last_command = ""
    cache: tuple[tuple[float, float], str] = ((math.nan, math.nan), "")

    def place(p: tuple[float, float]) -> str:
        nonlocal cache
        if p == cache[0]:
            return cache[1]  # a move's start is the one before's end
        text = f"{_num(frame.x(p[0]))} {_num(frame.y(p[1]))}"
        cache = (p, text)
        return text

    def close() -> None:
        if element is not None and d:
            kind, line, uri = element
            path = f" data-path={quoteattr(uri)}" if uri and uri != main_uri else ""
            out.append(f'<path data-kind="{kind}" data-line="{line + 1}"{path} d="{"".join(d)}"/>')
        d.clear()

    for item in drawn:
        move, points = item.move, item.points
        if (move.program, move.uri) != group:
            close()
            element = None
            if group is not None:
                out.append("</g>")
            group = (move.program, move.uri)
            out.append(f"<g data-program={quoteattr(move.program)}>")
        if (move.kind, move.line, move.uri) != element:
            close()
            element = (move.kind, move.line, move.uri)
            last = None
        if points[0] != last:
            d.append("M" + place(points[0]))
            last_command = "M"
        arc = _svg_arc(frame, item, toolpath, across, up) if item.turn is not None else None
        if arc is not None:
            d.append(arc)
            last_command = "A"
        else:
            rest = " ".join(place(p) for p in points[1:])
            d.append((" " if last_command == "L" else "L") + rest)
            last_command = "L"
        last = points[-1]
    close()
    if group is not None:
        out.append("</g>")
    return out


# ---- marks on the path -----------------------------------------------------------------------


class _Arrow(NamedTuple):
    move: Move
    x: float  # pixels, from the box's top left corner
    y: float
    dx: float  # the direction of travel on the drawing, a unit vector
    dy: float


def _arrows(drawn: list[_Drawn], scale: float) -> list[_Arrow]:
    """Where the direction arrows go: at the middle of moves long enough on the drawing to
    show one, spread over the run (about ``MAX_ARROWS`` places evenly through the moves, the
    first long enough move from each), no two in a square of 28 pixels."""
    count = len(drawn)
    places = MAX_ARROWS * 2
    stride = max(1, count // places)
    arrows: list[_Arrow] = []
    taken: set[tuple[int, int]] = set()
    for first in range(0, count, stride):
        # A bounded search: a posted file's raster is 100,000 moves too short for an arrow.
        for item in drawn[first : first + min(stride, 64)]:
            points = item.points
            # The middle segment: a line's only one, an arc's (as long as each of its others).
            middle = len(points) // 2
            a, b = points[middle - 1], points[middle]
            segment = math.hypot(b[0] - a[0], b[1] - a[1])
            if segment * scale * (len(points) - 1) < ARROW_MIN_LENGTH:
                continue
            x = (a[0] + b[0]) / 2 * scale
            y = -(a[1] + b[1]) / 2 * scale
            cell = (round(x / 28), round(y / 28))
            if cell in taken:  # a pass drawn over another's: one arrow for them
                continue
            taken.add(cell)
            arrows.append(
                _Arrow(item.move, x, y, (b[0] - a[0]) / segment, -(b[1] - a[1]) / segment)
            )
            break
        if len(arrows) >= MAX_ARROWS:
            break
    return arrows


def _link(move: Move, main_uri: str) -> str:
    path = f" data-path={quoteattr(move.uri)}" if move.uri and move.uri != main_uri else ""
    return f' data-line="{move.line + 1}"{path}'


def _marks(
    drawn: list[_Drawn],
    arrows: list[_Arrow],
    frame: _Frame,
    origin: tuple[float, float],
    main_uri: str,
) -> list[str]:
    """The arrows, the start (a ring) and the end (a square) of the drawn path."""
    out = ['<g class="marks">']
    ox, oy = origin
    for arrow in arrows:
        x, y, dx, dy = ox + arrow.x, oy + arrow.y, arrow.dx, arrow.dy
        tip = (x + 5 * dx, y + 5 * dy)
        back = (x - 4 * dx, y - 4 * dy)
        out.append(
            f'<path class="arrow" data-mark="direction"{_link(arrow.move, main_uri)}'
            f' d="M{_num(tip[0])} {_num(tip[1])}L{_num(back[0] - 4 * dy)} {_num(back[1] + 4 * dx)}'
            f' {_num(back[0] + 4 * dy)} {_num(back[1] - 4 * dx)}Z"/>'
        )
    first, last = drawn[0], drawn[-1]
    sx, sy = first.points[0]
    ex, ey = last.points[-1]
    start = escape(_say(tr("start: line {line}", line=first.move.line + 1)))
    end = escape(_say(tr("end: line {line}", line=last.move.line + 1)))
    out.append(
        f'<circle class="start" data-mark="start"{_link(first.move, main_uri)}'
        f' cx="{_num(frame.x(sx))}" cy="{_num(frame.y(sy))}" r="5.5">'
        f"<title>{start}</title></circle>"
    )
    out.append(
        f'<rect class="end" data-mark="end"{_link(last.move, main_uri)}'
        f' x="{_num(frame.x(ex) - 4)}" y="{_num(frame.y(ey) - 4)}" width="8" height="8">'
        f"<title>{end}</title></rect>"
    )
    out.append("</g>")
    return out


def _lost_places(
    toolpath: Toolpath, across: str, up: str
) -> list[tuple[LostTrack, tuple[float, float] | None]]:
    """Where the path lost track of an axis (at the next known position of its block, in the
    drawing's geometry), but for the start of the run, which the start mark shows."""
    lost = [t for t in toolpath.lost if t.reason != UNKNOWN_START]
    if not lost:
        return []
    known: dict[int, tuple[float, float]] = {}
    wanted = {t.line for t in lost}
    for move in toolpath.moves:
        line = move.line
        if line in wanted and line not in known:
            point = geometric(toolpath, move.end)
            if across in point and up in point:
                known[line] = (point[across], point[up])
    return [(t, known.get(t.line)) for t in lost]


def _lost_marks(
    places: list[tuple[LostTrack, tuple[float, float] | None]], frame: _Frame, main_uri: str
) -> list[str]:
    """A ring where the path lost track of an axis, and why (a tooltip)."""
    if not places:
        return []
    out = ['<g class="lost-track">']
    for lost, where in places:
        path = f" data-path={quoteattr(lost.uri)}" if lost.uri and lost.uri != main_uri else ""
        if lost.axes:
            said = tr(
                "line {line}: {axes} unknown: {reason}",
                line=lost.line + 1,
                axes=", ".join(lost.axes),
                reason=lost.reason,
            )
        else:
            said = tr("line {line}: {reason}", line=lost.line + 1, reason=lost.reason)
        reason = escape(_say(said))
        if where is None:
            out.append(f'<desc data-kind="lost" data-line="{lost.line + 1}"{path}>{reason}</desc>')
            continue
        out.append(
            f'<circle class="lost" data-kind="lost" data-line="{lost.line + 1}"{path}'
            f' cx="{_num(frame.x(where[0]))}" cy="{_num(frame.y(where[1]))}" r="5">'
            f"<title>{reason}</title></circle>"
        )
    out.append("</g>")
    return out


# ---- the legend ------------------------------------------------------------------------------

_SAMPLE = 22.0  # the width of a legend entry's sample line or mark
_LEGEND_GAP = 18.0


def _legend_sample(entry: str, x: float, y: float) -> str:
    """The entry's sample, its middle at height ``y``: a line in a move's style, or a mark."""
    mid = x + _SAMPLE / 2
    if entry in KIND_NAMES:
        return (
            f'<line class="{entry}" x1="{_num(x)}" y1="{_num(y)}" x2="{_num(x + _SAMPLE)}"'
            f' y2="{_num(y)}"/>'
        )
    if entry == "start":
        return f'<circle class="start" cx="{_num(mid)}" cy="{_num(y)}" r="5.5"/>'
    if entry == "end":
        return f'<rect class="end" x="{_num(mid - 4)}" y="{_num(y - 4)}" width="8" height="8"/>'
    if entry == "direction":
        return (
            f'<path class="arrow" d="M{_num(mid + 5)} {_num(y)}'
            f'L{_num(mid - 4)} {_num(y - 4)} {_num(mid - 4)} {_num(y + 4)}Z"/>'
        )
    return f'<circle class="lost" cx="{_num(mid)}" cy="{_num(y)}" r="5"/>'


_LEGEND_LABELS: Mapping[str, str] = MappingProxyType(
    {
        **KIND_NAMES,
        "start": tr("start"),
        "end": tr("end"),
        "direction": tr("direction of travel"),
        "lost": tr("lost track (hover: why)"),
    }
)


def _legend(entries: Sequence[str], top: float, timed: str = "") -> tuple[list[str], float]:
    """The legend's rows from ``top`` (the first row's baseline), wrapped to the width, with
    the cycle time ``timed`` last; the baseline of its last row."""
    out = ['<g class="legend">']
    x, y = MARGIN_LEFT, top
    for entry in entries:
        label = _say(_LEGEND_LABELS[entry])
        width = _SAMPLE + 6 + text_width(label)
        if x > MARGIN_LEFT and x + width > WIDTH - MARGIN_RIGHT:
            x, y = MARGIN_LEFT, y + LINE_HEIGHT + 4
        out.append(
            f'<g data-legend="{entry}">{_legend_sample(entry, x, y - 4)}'
            f"{_text(x + _SAMPLE + 6, y, label)}</g>"
        )
        x += width + _LEGEND_GAP
    if timed:
        timed = _say(timed)
        if x > MARGIN_LEFT and x + text_width(timed) > WIDTH - MARGIN_RIGHT:
            x, y = MARGIN_LEFT, y + LINE_HEIGHT + 4
        out.append(f'<g data-legend="cycle-time">{_text(x, y, timed)}</g>')
    out.append("</g>")
    return out, y


# ---- what is left out, and why ---------------------------------------------------------------


def _causes(
    toolpath: Toolpath, undrawn: list[int], across: str, up: str
) -> tuple[int, tuple[str, ...], list[PlotNote]]:
    """Why the moves ``undrawn`` are not drawn: how many start before their run's first
    absolute position of an axis (and which axes), and a note for each other cause (where the
    run lost track of an axis the view needs), with a note for each cycle the path does not
    draw."""
    moves = toolpath.moves
    view = (across, up)
    runs = toolpath.runs
    run_moves = [first for first, _ in runs]
    # Where each axis was lost (and its place in ``lost``), for a search by move index.
    losses: dict[str, list[tuple[int, LostTrack]]] = {axis: [] for axis in view}
    for n, lost in enumerate(toolpath.lost):
        if lost.reason == UNKNOWN_START or lost.at < 0:
            continue
        for axis in lost.axes:
            if axis in losses:
                losses[axis].append((n, lost))
    at = {axis: [t.at for _, t in found] for axis, found in losses.items()}
    hidden: dict[str, int] = {}  # reason -> moves
    sites: dict[str, dict[tuple[str, int], None]] = {}
    order: dict[str, int] = {}  # reason -> its first place in the run
    before_start = 0
    start_axes: dict[str, None] = {}

    def note(lost: LostTrack, rank: int) -> None:
        sites.setdefault(lost.reason, {})[(lost.uri, lost.line)] = None
        order.setdefault(lost.reason, rank)

    for i in undrawn:
        move = moves[i]
        # A loss before the move's run began is not its cause: each run starts unknown.
        k = bisect_right(run_moves, i)
        run_lost = runs[k - 1][1] if k else 0
        missing = [a for a in view if a not in move.start or a not in move.end]
        cause: LostTrack | None = None
        for axis in missing:
            k = bisect_right(at[axis], i)
            if k and losses[axis][k - 1][0] >= run_lost:
                cause = losses[axis][k - 1][1]
                break
        if cause is not None:
            hidden[cause.reason] = hidden.get(cause.reason, 0) + 1
            note(cause, cause.at)
        else:  # not lost since the run began: not placed yet
            before_start += 1
            start_axes.update(dict.fromkeys(missing))
    for lost in toolpath.lost:  # the cycles the path does not draw (no axis lost)
        if not lost.axes and lost.reason != UNKNOWN_START:
            note(lost, lost.at if lost.at >= 0 else len(moves))
    notes = [
        PlotNote(reason, tuple(sites[reason]), hidden.get(reason, 0))
        for reason in sorted(order, key=lambda r: order[r])
    ]
    return before_start, tuple(a for a in "XYZ" if a in start_axes), notes


def _run_notes(toolpath: Toolpath, stop: PlotNote | None) -> list[PlotNote]:
    """What the drawing leaves out of the end of the run."""
    notes = []
    if toolpath.truncated:
        notes.append(
            PlotNote(
                tr(
                    "the run makes more than {moves:,} moves: those after are not drawn",
                    moves=MAX_MOVES,
                ),
                (),
            )
        )
    if stop is not None:
        notes.append(stop)
    return notes


# ---- the drawing -----------------------------------------------------------------------------

_BOX_WIDTH = WIDTH - MARGIN_LEFT - MARGIN_RIGHT
_BOX_HEIGHT = 502.0


def plot_svg(
    toolpath: Toolpath,
    plane: Plane | None = None,
    passes: Sequence[PassMap] = (),
    title: str = "",
    main_uri: str = "",
    locale: str = "en",
) -> str:
    """The SVG document of a toolpath, and of the threads' pass maps after it, its texts in
    ``locale``.

    Raises :class:`NothingToPlot` when no move can be placed in the plane."""
    return backplot(toolpath, plane, passes, title, main_uri, locale=locale).svg


def backplot(
    toolpath: Toolpath,
    plane: Plane | None = None,
    passes: Sequence[PassMap] = (),
    title: str = "",
    main_uri: str = "",
    stop: PlotNote | None = None,
    timed: str = "",
    locale: str = "en",
) -> Backplot:
    """The drawing of a toolpath (in ``plane``, else the one ``choose_plane`` gives), the
    threads' pass maps after it, and what it leaves out; ``stop``: why the run ended early;
    ``timed``: the cycle time, as the legend's last entry says it; the drawing's texts are
    said in ``locale`` (the ``Backplot``'s other texts are :class:`..translation.Text`).

    Raises :class:`NothingToPlot` when no move can be placed in the plane."""
    token = _LOCALE.set(locale)
    try:
        with quiet_gc():  # 200,000 moves' strings and no cycles: the collector would only rescan
            return _backplot(toolpath, plane, passes, title, main_uri, stop, timed)
    finally:
        _LOCALE.reset(token)


def _backplot(
    toolpath: Toolpath,
    plane: Plane | None,
    passes: Sequence[PassMap],
    title: str,
    main_uri: str,
    stop: PlotNote | None,
    timed: str = "",
) -> Backplot:
    plane_reason = None
    if plane is None:
        plane, plane_reason = choose_plane(toolpath)
    view: Plane = plane
    across, up = _VIEW_AXES[(toolpath.lathe, view)]
    drawn, undrawn = _drawn(toolpath, across, up)
    if not drawn:
        raise _nothing_in(toolpath, view, across, up)
    before_start, start_axes, notes = (
        _causes(toolpath, undrawn, across, up) if undrawn else (0, (), [])
    )
    notes += _run_notes(toolpath, stop)
    h_range, v_range = _padded_ranges(drawn)
    # A lathe's X labelled as the diameter the program writes.
    factors = (
        2.0 if toolpath.lathe and across == "X" else 1.0,
        2.0 if toolpath.lathe and up == "X" else 1.0,
    )
    scale, ticks, left = _fitted_scale(h_range, v_range, factors)
    units = "inch" if toolpath.inch else "mm"
    places = _lost_places(toolpath, across, up)
    arrows = _arrows(drawn, scale)
    legend, legend_low = _legend(_legend_entries(drawn, arrows, places), 46.0, timed)
    top = legend_low + 16
    low = top + (v_range[1] - v_range[0]) * scale
    frame = _Frame(h_range[0], v_range[1], scale, left, top)
    note_texts = [_start_text(before_start, start_axes)] if before_start else []
    note_texts = [
        line
        for text in (*note_texts, *(n.text(main_uri) for n in notes))
        for line in wrap(_say(text), _BOX_WIDTH)
    ]
    height = low + MARGIN_BOTTOM + (len(note_texts) * LINE_HEIGHT + 10 if note_texts else 0)
    suffix = _say(
        tr(
            " ({view}, {drawn} of {total} moves drawn)",
            view=view,
            drawn=len(drawn),
            total=len(toolpath.moves),
        )
    )
    name = shorten(
        title or _say(tr("Toolpath")),
        _BOX_WIDTH - text_width(suffix, TITLE_SIZE, bold=True),
        TITLE_SIZE,
        bold=True,
    )
    titles = (_axis_titles(across, toolpath, units), _axis_titles(up, toolpath, units))
    body = [
        f'<g class="view" data-view="toolpath" data-plane="{view}">',
        _text(MARGIN_LEFT, 24, name + suffix, cls="title"),
        *legend,
        *_axes(frame, h_range, v_range, ticks, titles, units),
        '<g class="moves">',
        *_moves(drawn, frame, toolpath, across, up, main_uri),
        "</g>",
        *_lost_marks(places, frame, main_uri),
        *_marks(drawn, arrows, frame, (frame.x(0.0), frame.y(0.0)), main_uri),
    ]
    if note_texts:
        body.append('<g class="notes">')
        body += [
            _text(MARGIN_LEFT, low + 82 + i * LINE_HEIGHT, text, cls="note")
            for i, text in enumerate(note_texts)
        ]
        body.append("</g>")
    body.append("</g>")
    total = len(toolpath.moves)
    drawn_count = len(drawn)
    del drawn  # the pass maps are drawn without the moves' strings kept
    total_height = _add_pass_maps(body, passes, height, units)
    head = (
        '<svg xmlns="http://www.w3.org/2000/svg"'
        f' width="{_num(WIDTH)}" height="{_num(total_height)}"'
        f' viewBox="0 0 {_num(WIDTH)} {_num(total_height)}" data-units="{units}">'
    )
    svg = "\n".join([head, f"<style>{STYLE}</style>", *body, "</svg>"]) + "\n"
    return Backplot(
        svg, view, plane_reason, drawn_count, total, before_start, start_axes, tuple(notes)
    )


def _padded_ranges(
    drawn: Sequence[_Drawn],
) -> tuple[tuple[float, float], tuple[float, float]]:
    """The drawn moves' extent across and up, with a margin around it."""
    h_range = (
        min(h for d in drawn for h, _ in d.points),
        max(h for d in drawn for h, _ in d.points),
    )
    v_range = (
        min(v for d in drawn for _, v in d.points),
        max(v for d in drawn for _, v in d.points),
    )
    # A path that is a line (a drill's plunge seen from above) still gets a square to sit in.
    span = max(h_range[1] - h_range[0], v_range[1] - v_range[0]) or 1.0
    pad = span * 0.04
    # Neither side of the box under a quarter of the other, so that a thin path has room.
    h_pad = pad + max(0.0, span / 4 - (h_range[1] - h_range[0])) / 2
    v_pad = pad + max(0.0, span / 4 - (v_range[1] - v_range[0])) / 2
    return (h_range[0] - h_pad, h_range[1] + h_pad), (v_range[0] - v_pad, v_range[1] + v_pad)


def _fitted_scale(
    h_range: tuple[float, float], v_range: tuple[float, float], factors: tuple[float, float]
) -> tuple[float, _Ticks, float]:
    """The scale, the ticks and the left margin. The margin takes the widest tick label up the
    side and the axis title beside it; a wider margin, a smaller scale, other ticks: settled in
    a round or two."""
    left = MARGIN_LEFT
    for _ in range(3):
        scale = min(
            (WIDTH - left - MARGIN_RIGHT) / (h_range[1] - h_range[0]),
            _BOX_HEIGHT / (v_range[1] - v_range[0]),
        )
        ticks = _choose_ticks(h_range, v_range, scale, factors)
        needed = max(MARGIN_LEFT, math.ceil(ticks.v_width + 12 + FONT_SIZE + 6))
        if needed <= left:
            break
        left = needed
    return scale, ticks, left


def _legend_entries(
    drawn: Sequence[_Drawn],
    arrows: Sequence[_Arrow],
    places: Sequence[tuple[LostTrack, tuple[float, float] | None]],
) -> list[str]:
    """What the legend shows: the kinds of moves drawn, the marks, the lost places."""
    kinds = {d.move.kind for d in drawn}
    entries: list[str] = [kind for kind in KIND_NAMES if kind in kinds]
    entries += ["start", "end", *(["direction"] if arrows else [])]
    if any(where is not None for _, where in places):
        entries.append("lost")
    return entries


def _add_pass_maps(body: list[str], passes: Sequence[PassMap], height: float, units: str) -> float:
    """Adds the threads' pass maps below the toolpath; the drawing's height with them."""
    total_height = height
    for pass_map in passes[:MAX_PASS_MAPS]:
        group, h = _pass_map_view(pass_map, total_height, units)
        body.extend(group)
        total_height += h
    if len(passes) > MAX_PASS_MAPS:
        more = len(passes) - MAX_PASS_MAPS
        body.append(
            f'<g class="view" data-view="more-passes" data-count="{more}">'
            + _text(
                MARGIN_LEFT,
                total_height + 20,
                _say(
                    tr(
                        "{more} more threads: their pass maps are not drawn (the first {first}"
                        " are)",
                        more=more,
                        first=MAX_PASS_MAPS,
                    )
                ),
            )
            + "</g>"
        )
        total_height += 32.0
    return total_height


# ---- the pass maps ---------------------------------------------------------------------------

# The pass map's panels: the infeed diagram (the groove and the tool's tip at each pass) on the
# left, the depth of each pass as bars on the right, each with a depth scale on its left.
_PANEL_TOP = 56.0  # from the view's top to the depth 0 line: the title, the tool's flanks above
_PANEL_HEIGHT = 190.0
_CAPTION_TOP = 24.0  # from the panels' bottom to the first caption line's baseline
_CAPTION_LINE = 15.0


def _passes(n: int) -> str:
    return tr_n("{count} pass", "{count} passes", n)


def _depth_labels(deepest: float, pixels: float) -> tuple[float, list[tuple[float, str]]]:
    """The step of a depth scale from 0 to ``deepest`` drawn ``pixels`` a unit, and its
    labelled values."""
    step = _fit_step(0.0, deepest, pixels, lambda _: FONT_SIZE + 8.0, 5)
    return step, [(v, _tick(v, step)) for v in _tick_values(0.0, deepest, step)]


def _depth_scale(
    x: float,
    y_at: Callable[[float], float],
    labels: tuple[float, list[tuple[float, str]]],
    grid_to: float | None = None,
) -> list[str]:
    """A depth scale left of ``x``: a tick and a label at each value, placed by ``y_at``, with
    grid lines to ``grid_to`` when given."""
    step, values = labels
    out = [f'<g class="ticks" data-axis="depth" data-step="{_tick(step, step)}">']
    for value, label in values:
        y = y_at(value)
        if grid_to is not None and value:
            out.append(
                f'<line class="grid" x1="{_num(x)}" y1="{_num(y)}" x2="{_num(grid_to)}"'
                f' y2="{_num(y)}"/>'
            )
        out.append(
            f'<line class="axis" x1="{_num(x - 4)}" y1="{_num(y)}" x2="{_num(x)}" y2="{_num(y)}"/>'
        )
        out.append(
            f'<text x="{_num(x - 6)}" y="{_num(y + 4)}" text-anchor="end"'
            f' data-value="{label}">{label}</text>'
        )
    out.append("</g>")
    return out


@dataclass(frozen=True)
class _PassPanels:
    """Where one thread's pass map goes: the passes' depths and Z offsets, the infeed panel's
    scale and the depth bars' scale."""

    depths: list[float]  # radial, into the material
    offsets: list[float]  # Z about the middle of the passes
    basic: float | None  # the basic profile's height, 5H/8, when the pitch is known
    deepest: float
    left: float
    panel_w: float
    gap: float
    y0: float  # the depth 0 line
    base: float  # the panels' bottom
    scale: float  # the infeed panel's
    cx: float  # the infeed panel's Z of the middle
    bar_scale: float
    bar_labels: tuple[float, list[tuple[float, str]]]

    def px(self, offset: float) -> float:
        return self.cx + offset * self.scale

    def py(self, depth: float) -> float:
        return self.y0 + depth * self.scale


def _pass_panels(pass_map: PassMap, top: float) -> _PassPanels:
    marks = pass_map.passes
    # Depth is radial, measured into the material from the major diameter when the thread is
    # known, else from the first pass (the tool cannot cut less deep than that).
    reference = pass_map.major if pass_map.major is not None else marks[0].x
    sign = 1.0 if pass_map.internal else -1.0
    depths = [max(0.0, sign * (m.x - reference) / 2.0) for m in marks]
    # ISO 68-1: the basic profile's height between major and minor diameters is 5H/8, with
    # H = 0.866025 P (the fundamental triangle).
    basic = 0.625 * 0.8660254037844386 * pass_map.pitch if pass_map.pitch else None
    deepest = max([*depths, basic or 0.0]) or 1.0
    zs = [m.z for m in marks if m.z is not None]
    # The groove sits in the middle of the passes' Z: a symmetric infeed's left and right.
    z_ref = (min(zs) + max(zs)) / 2.0 if zs else 0.0
    offsets = [(m.z - z_ref) if m.z is not None else 0.0 for m in marks]
    # Wide enough for the groove and for the flanks of the tool at every pass.
    flank = _FLANK
    half_width = max(
        deepest * flank * 1.4,
        *(abs(o) + (d + deepest * 0.08) * flank for o, d in zip(offsets, depths, strict=True)),
    )
    inner_h = _PANEL_HEIGHT
    left = MARGIN_LEFT
    y0 = top + _PANEL_TOP
    # The bars' scale first: the width of its labels sets the gap between the panels.
    bar_top = (max(depths) or 1.0) * 1.1
    bar_scale = inner_h / bar_top
    bar_labels = _depth_labels(bar_top, bar_scale)
    gap = max(40.0, max(text_width(label) for _, label in bar_labels[1]) + 24.0)
    panel_w = (WIDTH - MARGIN_LEFT - MARGIN_RIGHT - gap) / 2.0
    return _PassPanels(
        depths=depths,
        offsets=offsets,
        basic=basic,
        deepest=deepest,
        left=left,
        panel_w=panel_w,
        gap=gap,
        y0=y0,
        base=y0 + inner_h,
        scale=min(panel_w / (2 * half_width), inner_h / (deepest * 1.1)),
        cx=left + panel_w / 2.0,
        bar_scale=bar_scale,
        bar_labels=bar_labels,
    )


# The tool's flank from the thread's axis normal: a 60-degree thread's half angle.
_FLANK = math.tan(math.radians(30.0))


def _pass_map_view(pass_map: PassMap, top: float, units: str = "mm") -> tuple[list[str], float]:
    """The second view for one thread, placed at ``top``; its height."""
    count = len(pass_map.passes)
    panels = _pass_panels(pass_map, top)
    left, y0, base = panels.left, panels.y0, panels.base
    side = tr("internal") if pass_map.internal else tr("external")
    title = _say(
        tr(
            "{program}: {thread}, {side}, {passes}",
            program=pass_map.program,
            thread=pass_map.name,
            side=side,
            passes=_passes(count),
        )
    )
    out = [
        f'<g class="view" data-view="passes" data-program={quoteattr(pass_map.program)}'
        f' data-passes="{count}">',
        _text(left, top + 24, shorten(title, _BOX_WIDTH, TITLE_SIZE, True), cls="title"),
        f'<line class="axis" x1="{_num(left)}" y1="{_num(y0)}" x2="{_num(left + panels.panel_w)}"'
        f' y2="{_num(y0)}"/>',
        f'<line class="axis" x1="{_num(left)}" y1="{_num(y0)}" x2="{_num(left)}"'
        f' y2="{_num(base)}"/>',
        *_depth_scale(left, panels.py, _depth_labels(_PANEL_HEIGHT / panels.scale, panels.scale)),
    ]
    n_places = _infeed_marks(out, pass_map, panels)
    flat, largest = _depth_bars(out, pass_map, panels)
    out.append("</g>")
    captions = _pass_map_captions(pass_map, panels, units, n_places, flat, largest)
    y = base + _CAPTION_TOP
    bars_left = left + panels.panel_w + panels.gap
    for x, lines in ((left, captions[0]), (bars_left, captions[1])):
        out += [_text(x, y + k * _CAPTION_LINE, line, cls="note") for k, line in enumerate(lines)]
    out.append("</g>")
    rows = max(len(c) for c in captions)
    return out, _PANEL_TOP + _PANEL_HEIGHT + _CAPTION_TOP + (rows - 1) * _CAPTION_LINE + 18.0


def _infeed_marks(out: list[str], pass_map: PassMap, panels: _PassPanels) -> int:
    """Draws the basic groove and the tool's tip at each pass; the number of places the tips
    are at."""
    px, py, scale = panels.px, panels.py, panels.scale
    basic, deepest = panels.basic, panels.deepest
    if basic is not None:
        # The basic V groove: 60 degrees, its flanks through the major diameter's line.
        w = basic * _FLANK
        out.append(
            f'<polygon class="profile" data-kind="profile" points="{_num(px(-w))},{_num(py(0))}'
            f' {_num(px(0))},{_num(py(basic))} {_num(px(w))},{_num(py(0))}"/>'
        )
    reference = pass_map.major
    if pass_map.cut and pass_map.cut_pass is not None and reference is not None:
        # The cross-section the passes cut, about the deepest pass's place; the class's
        # pitch diameters as dashed lines across the groove.
        sign = 1.0 if pass_map.internal else -1.0
        centre = panels.offsets[pass_map.cut_pass]
        top = deepest * 1.1

        def depth_of(radius: float) -> float:
            return min(max(sign * (radius - reference / 2.0), 0.0), top)

        points = " ".join(
            f"{_num(px(centre + u))},{_num(py(depth_of(h)))}" for u, h in pass_map.cut
        )
        line = pass_map.passes[pass_map.cut_pass].line + 1  # the deepest pass's block
        out.append(
            f'<polyline class="cut" data-kind="cut-profile" data-line="{line}" points="{points}"/>'
        )
        for diameter in pass_map.band or ():
            y = _num(py(depth_of(diameter / 2.0)))
            out.append(
                f'<line class="band" data-kind="pitch-limit" data-line="{line}" data-diameter="'
                f'{fmt_address(round(diameter, 3))}" x1="{_num(px(centre - pass_map.cut[-1][0]))}"'
                f' y1="{y}" x2="{_num(px(centre + pass_map.cut[-1][0]))}" y2="{y}"/>'
            )
    places: dict[tuple[str, str], None] = {}
    for mark, depth, offset in zip(pass_map.passes, panels.depths, panels.offsets, strict=True):
        # The tool's 60-degree tip at this pass, its point where the pass cuts.
        w = (depth + deepest * 0.08) * _FLANK
        tip_x, tip_y = px(offset), py(depth)
        rise = deepest * 0.08 + depth
        out.append(
            f'<polyline class="tool" data-kind="tool" data-line="{mark.line + 1}"'
            f' points="{_num(tip_x - w * scale)},{_num(tip_y - rise * scale)}'
            f" {_num(tip_x)},{_num(tip_y)} {_num(tip_x + w * scale)},"
            f'{_num(tip_y - rise * scale)}"/>'
        )
        places[(_num(tip_x), _num(tip_y))] = None
        out.append(
            f'<circle class="pass" data-kind="pass" data-line="{mark.line + 1}"'
            f' data-depth="{fmt_address(depth)}" data-x="{fmt_address(mark.x)}"'
            f' cx="{_num(tip_x)}" cy="{_num(tip_y)}" r="2.5"/>'
        )
    return len(places)


def _depth_bars(out: list[str], pass_map: PassMap, panels: _PassPanels) -> tuple[int, float]:
    """Draws a bar for each pass, as high as the pass is deep; darker, what it cuts deeper
    than every pass before it (a pass no deeper cuts nothing new at the root: a bar without).
    The passes at depth 0 and the largest cut."""
    marks = pass_map.passes
    count = len(marks)
    base, y0, panel_w, bar_scale = panels.base, panels.y0, panels.panel_w, panels.bar_scale
    bars_left = panels.left + panel_w + panels.gap
    bar_w = panel_w / count
    out += [
        f'<g class="chart" data-chart="depth" data-bars="{count}">',
        f'<line class="axis" x1="{_num(bars_left)}" y1="{_num(base)}"'
        f' x2="{_num(bars_left + panel_w)}" y2="{_num(base)}"/>',
        f'<line class="axis" x1="{_num(bars_left)}" y1="{_num(y0)}" x2="{_num(bars_left)}"'
        f' y2="{_num(base)}"/>',
        *_depth_scale(
            bars_left, lambda d: base - d * bar_scale, panels.bar_labels, bars_left + panel_w
        ),
    ]
    bar_class = "bar thin" if bar_w < 5 else "bar"  # an outline would hide a narrow bar
    deepest_before = 0.0
    flat = 0
    largest = 0.0
    for i, (mark, depth) in enumerate(zip(marks, panels.depths, strict=True)):
        cut = max(0.0, depth - deepest_before)
        largest = max(largest, cut)
        x = bars_left + i * bar_w + bar_w * 0.1
        h = depth * bar_scale
        if h < 1.5:  # a pass at depth 0: a flat mark on the axis, so that every pass shows
            flat += round(depth, 3) == 0
            h = 1.5
        out.append(
            f'<rect class="{bar_class}" data-kind="cut" data-line="{mark.line + 1}"'
            f' data-cut="{fmt_address(cut)}" data-depth="{fmt_address(depth)}" x="{_num(x)}"'
            f' y="{_num(base - h)}" width="{_num(bar_w * 0.8)}" height="{_num(h)}"/>'
        )
        if cut * bar_scale >= 0.5:
            out.append(
                f'<rect class="cap" x="{_num(x)}" y="{_num(base - depth * bar_scale)}"'
                f' width="{_num(bar_w * 0.8)}" height="{_num(cut * bar_scale)}"/>'
            )
        deepest_before = max(deepest_before, depth)
    return flat, largest


def _pass_map_captions(
    pass_map: PassMap, panels: _PassPanels, units: str, n_places: int, flat: int, largest: float
) -> tuple[list[str], list[str]]:
    """The two panels' captions, wrapped to the panels' width."""
    count = len(pass_map.passes)
    basic = panels.basic
    measured = tr("the major diameter") if pass_map.major is not None else tr("the first pass")
    where = _passes(count)
    if n_places < count:
        where = tr(
            "{passes} at {places} places (passes at one place are one dot)",
            passes=where,
            places=n_places,
        )
    if basic is not None:
        infeed = tr(
            "Infeed: a dot at the tool's tip for each pass ({where}), lines for its 60° flanks,"
            " shaded the basic groove (5H/8 = {basic}); down: depth ({units}, radius, from"
            " {measured}); across: Z about the middle of the passes' starts",
            where=where,
            basic=_tick(basic),
            units=units,
            measured=measured,
        )
    else:
        infeed = tr(
            "Infeed: a dot at the tool's tip for each pass ({where}), lines for its 60° flanks;"
            " down: depth ({units}, radius, from {measured}); across: Z about the middle of the"
            " passes' starts",
            where=where,
            units=units,
            measured=measured,
        )
    if pass_map.cut and pass_map.cut_pass is not None and pass_map.major is not None:
        infeed = tr(
            "{infeed}; blue: the groove the passes cut, over one lead about the deepest pass"
            " (the cross-section), dashed: the class's {which} limits",
            infeed=infeed,
            which="D2" if pass_map.internal else "d2",
        )
    chart = tr(
        "Depth of each pass ({units}, radius, from {measured}): {bars}; darker: how much"
        " deeper it cuts than the passes before (at most {largest})",
        units=units,
        measured=measured,
        bars=tr_n("{count} bar", "{count} bars", count),
        largest=_tick(largest),
    )
    if flat:
        chart = tr("{chart}; {passes} at depth 0: a flat mark", chart=chart, passes=_passes(flat))
    return wrap(_say(infeed), panels.panel_w), wrap(_say(chart), panels.panel_w)


# ---- the run ---------------------------------------------------------------------------------


def run_toolpath(
    uri: str,
    doc: Document,
    index: ProgramIndex,
    others: Sequence[tuple[str, Document, ProgramIndex]] = (),
    config: Config | None = None,
    entry: int | None = None,
) -> Toolpath:
    """Run ``uri``'s programs (or ``entry``) with the toolpath recorded.

    Raises :class:`NothingToPlot` when the run makes no move."""
    return run_plot(uri, doc, index, others, config, entry)[0]


def run_plot(
    uri: str,
    doc: Document,
    index: ProgramIndex,
    others: Sequence[tuple[str, Document, ProgramIndex]] = (),
    config: Config | None = None,
    entry: int | None = None,
) -> tuple[Toolpath, PlotNote | None, str]:
    """``run_toolpath``, why the run stopped early when it did (the drawing ends there), and
    its cycle time as the legend says it (``cycle time 10 min 1.3 s``).

    Raises :class:`NothingToPlot` when the run makes no move."""
    facts = run_with_toolpath(uri, doc, index, others, config, entry)
    toolpath = facts.toolpath
    if toolpath is None or not toolpath.moves:
        raise NothingToPlot(tr("the program makes no move: nothing to plot"))
    timed = cycle_time(facts, machine_config(config or Config(), doc, index))
    text: str = (
        "" if timed is None else tr("cycle time {time}", time=minutes_seconds(timed.total.total))
    )
    stop = None
    if facts.stopped == "budget":
        stop = PlotNote(tr("the run stopped when the analysis's step budget ran out"), ())
    elif facts.stopped == "time":
        stop = PlotNote(
            tr(
                "the run stopped after {seconds:g} s (the analysis's time limit)",
                seconds=facts.time_limit,
            ),
            (),
        )
    return toolpath, stop, text
