"""The backplot: a program's toolpath drawn as SVG (``fanuc-macro plot``).

Rapids dashed, feeds solid, threading passes and arcs in colours of their own, with axes in the
program's units and a scale bar. A lathe is drawn in its XZ plane as machinists draw it (Z
across, X up, as a radius: the program's X is a diameter, and its tick labels say so); a mill
in the plane asked for. For a threading program a second view follows: the pass map of each
thread (the depth of every pass, and the infeed diagram: where the tool's tip is in the groove
at each pass), of the first ``MAX_PASS_MAPS`` threads, the others counted.

Every drawn element carries ``data-line`` (the 1-based line of its block) and ``data-kind``, so
that a viewer can link it to the source. A move is a ``<path>``, consecutive moves of one kind
made by one block (a canned cycle's retract and return) one path; the moves of each run of one
program are in a ``<g data-program>``. A 200,000-block posted file is 200,000 small elements.

The drawing is a pure function of the toolpath and the threads: the same program gives the
same bytes (coordinates are written at a fixed precision).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import NamedTuple
from xml.sax.saxutils import escape, quoteattr

from ..config import Config
from ..evaluator.toolpath import Move, Plane, Toolpath
from ..evaluator.values import fmt_address
from ..program.index import ProgramIndex
from ..syntax.parser import quiet_gc
from ..syntax.tree import Document
from ..threads.identify import Thread
from .trace import run_with_toolpath

# The drawing's size in SVG user units (pixels): the path is fitted into this box.
WIDTH = 960.0
PLOT_HEIGHT = 600.0
MARGIN_LEFT = 78.0
MARGIN_RIGHT = 24.0
MARGIN_TOP = 40.0
MARGIN_BOTTOM = 58.0
# An arc drawn out of its own plane is drawn as a polyline of this many segments per turn.
ARC_SEGMENTS_PER_TURN = 72
# The pass maps drawn after the toolpath: a chain of G32 segments (seed 003's drum groove) is
# thousands of one-pass threads to the rules.
MAX_PASS_MAPS = 20

STYLE = (
    "text{font:12px sans-serif;fill:#222}"
    ".title{font-weight:bold;font-size:14px}"
    ".axis{stroke:#444;stroke-width:1}"
    ".grid{stroke:#ddd;stroke-width:0.5}"
    ".zero{stroke:#999;stroke-width:0.8;stroke-dasharray:2 2}"
    ".moves path{fill:none;stroke-width:1.2;stroke-linecap:round}"
    "[data-kind=rapid]{stroke:#888;stroke-dasharray:5 4}"
    "[data-kind=feed]{stroke:#1f5fbf}"
    "[data-kind=arc]{stroke:#1f8f4f}"
    "[data-kind=thread]{stroke:#d2411f;stroke-width:1.6}"
    ".lost{fill:#fff;stroke:#b00;stroke-width:1.5}"
    ".pass{fill:#d2411f;stroke:none}"
    ".tool{fill:none;stroke:#d2411f;stroke-width:0.8;opacity:0.6}"
    ".profile{fill:#f3e9e4;stroke:#555;stroke-width:1}"
    ".bar{fill:#e58a6f;stroke:#a33;stroke-width:0.6}"
)

# Which axes are across and up in each view, as machinists draw them: a lathe's XZ view has Z
# across and X up (the rear-turret convention of FANUC's lathe manuals, unverified for a front
# turret: it is the same picture upside down); a mill's views are seen from +Z, -Y and +X.
_VIEW_AXES: dict[tuple[bool, Plane], tuple[str, str]] = {
    (True, "XZ"): ("Z", "X"),
    (True, "XY"): ("X", "Y"),
    (True, "YZ"): ("Y", "Z"),
    (False, "XY"): ("X", "Y"),
    (False, "XZ"): ("X", "Z"),
    (False, "YZ"): ("Y", "Z"),
}
# The axes of each arc plane in the order in which G02 turns clockwise, seen from the plane's
# positive normal (FANUC: G17 X-Y seen from +Z, G18 Z-X from +Y, G19 Y-Z from +X).
_ARC_AXES: dict[Plane, tuple[str, str]] = {"XY": ("X", "Y"), "XZ": ("Z", "X"), "YZ": ("Y", "Z")}


class NothingToPlot(Exception):
    """The trace has no move whose position in the view's plane is known."""


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


def pass_maps(threads: Iterable[Thread]) -> list[PassMap]:
    """A pass map for every thread of an analysis whose passes have a known diameter."""
    maps = []
    for thread in threads:
        job = thread.job
        marks = tuple(PassMark(p.line, p.x, p.start_z) for p in job.passes if p.x is not None)
        if not marks:
            continue
        internal = thread.internal if thread.internal is not None else bool(job.internal)
        maps.append(PassMap(thread.name, job.program, internal, marks, thread.major, thread.pitch))
    return maps


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


def _tick(value: float) -> str:
    """A tick's label: the value to 0.001, without trailing zeros."""
    text = f"{round(value, 3):g}"
    return "0" if text == "-0" else text


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


def _axis_title(axis: str, toolpath: Toolpath, units: str) -> str:
    if toolpath.lathe and axis == "X":
        return f"X ({units}, diameter; drawn as a radius)"
    return f"{axis} ({units})"


Box = tuple[float, float, float, float]  # left, top, right, low: the plot's frame in pixels


def _rule(cls: str, across: bool, at: float, box: Box) -> str:
    """A line through the box at ``at``: upright for a place across, level for one up."""
    left, top, right, low = box
    x1, y1, x2, y2 = (at, top, at, low) if across else (left, at, right, at)
    return f'<line class="{cls}" x1="{_num(x1)}" y1="{_num(y1)}" x2="{_num(x2)}" y2="{_num(y2)}"/>'


def _ticks(
    frame: _Frame,
    across: bool,
    span: tuple[float, float],
    step: float,
    box: Box,
    factor: float = 1.0,
) -> list[str]:
    """The grid line and label of each multiple of ``step`` in ``span``, on the axis across
    (labels below the box) or up (labels left of it); ``factor`` scales the labels."""
    left, _, _, low = box
    out = []
    value = math.ceil(span[0] / step - 1e-9) * step
    while value <= span[1] + 1e-9:
        at = frame.x(value) if across else frame.y(value)
        out.append(_rule("grid", across, at, box))
        x, y, anchor = (at, low + 16, "middle") if across else (left - 6, at + 4, "end")
        out.append(
            f'<text x="{_num(x)}" y="{_num(y)}" text-anchor="{anchor}">'
            f"{_tick(value * factor)}</text>"
        )
        value += step
    return out


def _axes(
    frame: _Frame,
    h_range: tuple[float, float],
    v_range: tuple[float, float],
    across: str,
    up: str,
    toolpath: Toolpath,
    units: str,
    bottom: float,
) -> list[str]:
    """Ticks, grid, titles, the zero lines and a scale bar."""
    out = ['<g class="axes">']
    h_span, v_span = h_range[1] - h_range[0], v_range[1] - v_range[0]
    step = _nice_step(h_span)
    # Each axis gets ticks of its own: a long thin path (a thread along Z) still shows its X.
    v_step = _nice_step(v_span, max(2, min(8, round(8 * v_span / h_span))))
    left, right = frame.x(h_range[0]), frame.x(h_range[1])
    top, low = frame.y(v_range[1]), frame.y(v_range[0])
    out.append(
        f'<rect class="axis" fill="none" x="{_num(left)}" y="{_num(top)}"'
        f' width="{_num(right - left)}" height="{_num(low - top)}"/>'
    )
    box = (left, top, right, low)
    out += _ticks(frame, True, h_range, step, box)
    factor = 2.0 if toolpath.lathe and up == "X" else 1.0  # label a lathe's X as a diameter
    out += _ticks(frame, False, v_range, v_step, box, factor)
    if h_range[0] < 0 < h_range[1]:
        out.append(_rule("zero", True, frame.x(0.0), box))
    if v_range[0] < 0 < v_range[1]:
        out.append(_rule("zero", False, frame.y(0.0), box))
    out.append(
        f'<text x="{_num((left + right) / 2)}" y="{_num(low + 34)}"'
        f' text-anchor="middle">{escape(_axis_title(across, toolpath, units))}</text>'
    )
    out.append(
        f'<text transform="translate({_num(left - 58)} {_num((top + low) / 2)})'
        f' rotate(-90)" text-anchor="middle">{escape(_axis_title(up, toolpath, units))}'
        "</text>"
    )
    bar = step * frame.scale
    out.append(
        f'<g class="scale" data-length="{_tick(step)}">'
        f'<line class="axis" x1="{_num(right - bar)}" y1="{_num(bottom - 8)}"'
        f' x2="{_num(right)}" y2="{_num(bottom - 8)}" stroke-width="3"/>'
        f'<text x="{_num(right - bar / 2)}" y="{_num(bottom - 14)}" text-anchor="middle">'
        f"{_tick(step)} {units}</text></g>"
    )
    out.append("</g>")
    return out


class _Drawn(NamedTuple):
    """A move and the points it is drawn through (a tuple: there are 200,000 of them)."""

    move: Move
    points: list[tuple[float, float]]  # (across, up) in the drawing's geometry
    turn: float | None = None  # an arc's angle, radians


def _drawn(toolpath: Toolpath, across: str, up: str) -> list[_Drawn]:
    """Each move with the points it is drawn through, when its place in the view is known."""
    drawn = []
    # geometric(), for one axis at a time: a lathe's X diameter as a radius.
    h_scale = 0.5 if toolpath.lathe and across == "X" else 1.0
    v_scale = 0.5 if toolpath.lathe and up == "X" else 1.0
    for move in toolpath.moves:
        if move.kind == "arc":
            arc = arc_points(toolpath, move)
            if arc is not None:
                if all(across in p and up in p for p in arc[0]):
                    drawn.append(_Drawn(move, [(p[across], p[up]) for p in arc[0]], arc[1]))
                continue
        start, end = move.start, move.end
        h0, v0, h1, v1 = start.get(across), start.get(up), end.get(across), end.get(up)
        if h0 is None or v0 is None or h1 is None or v1 is None:
            continue
        drawn.append(_Drawn(move, [(h0 * h_scale, v0 * v_scale), (h1 * h_scale, v1 * v_scale)]))
    return drawn


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


def plot_svg(
    toolpath: Toolpath,
    plane: Plane | None = None,
    passes: Sequence[PassMap] = (),
    title: str = "",
    main_uri: str = "",
) -> str:
    """The SVG document of a toolpath, and of the threads' pass maps after it.

    Raises :class:`NothingToPlot` when no move can be placed in the plane."""
    with quiet_gc():  # 200,000 moves' strings and no cycles: the collector would only rescan
        return _plot_svg(toolpath, plane, passes, title, main_uri)


def _plot_svg(
    toolpath: Toolpath, plane: Plane | None, passes: Sequence[PassMap], title: str, main_uri: str
) -> str:
    view: Plane = plane or ("XZ" if toolpath.lathe else "XY")
    across, up = _VIEW_AXES[(toolpath.lathe, view)]
    drawn = _drawn(toolpath, across, up)
    if not drawn:
        raise NothingToPlot(
            f"no move of the trace has a known {across} and {up}: nothing to plot in {view}"
        )
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
    h_range = (h_range[0] - h_pad, h_range[1] + h_pad)
    v_range = (v_range[0] - v_pad, v_range[1] + v_pad)
    inner_w = WIDTH - MARGIN_LEFT - MARGIN_RIGHT
    inner_h = PLOT_HEIGHT - MARGIN_TOP - MARGIN_BOTTOM
    scale = min(inner_w / (h_range[1] - h_range[0]), inner_h / (v_range[1] - v_range[0]))
    height = MARGIN_TOP + (v_range[1] - v_range[0]) * scale + MARGIN_BOTTOM
    frame = _Frame(h_range[0], v_range[1], scale, MARGIN_LEFT, MARGIN_TOP)
    units = "inch" if toolpath.inch else "mm"
    body = [
        f'<g class="view" data-view="toolpath" data-plane="{view}">',
        f'<text class="title" x="{_num(MARGIN_LEFT)}" y="24">'
        f"{escape(title or 'Toolpath')} ({view}, {len(drawn)} of {len(toolpath.moves)} moves)"
        "</text>",
        *_axes(frame, h_range, v_range, across, up, toolpath, units, height),
        '<g class="moves">',
        *_moves(drawn, frame, toolpath, across, up, main_uri),
    ]
    del drawn
    body.append("</g>")
    body.extend(_lost_marks(toolpath, frame, across, up, main_uri))
    body.append("</g>")
    total_height = height
    for pass_map in passes[:MAX_PASS_MAPS]:
        group, h = _pass_map_view(pass_map, total_height)
        body.extend(group)
        total_height += h
    if len(passes) > MAX_PASS_MAPS:
        more = len(passes) - MAX_PASS_MAPS
        body.append(
            f'<g class="view" data-view="more-passes" data-count="{more}">'
            f'<text x="{_num(MARGIN_LEFT)}" y="{_num(total_height + 20)}">{more} more threads:'
            f" their pass maps are not drawn (the first {MAX_PASS_MAPS} are)</text></g>"
        )
        total_height += 32.0
    head = (
        '<svg xmlns="http://www.w3.org/2000/svg"'
        f' width="{_num(WIDTH)}" height="{_num(total_height)}"'
        f' viewBox="0 0 {_num(WIDTH)} {_num(total_height)}" data-units="{units}">'
    )
    return "\n".join([head, f"<style>{STYLE}</style>", *body, "</svg>"]) + "\n"


def _lost_marks(
    toolpath: Toolpath, frame: _Frame, across: str, up: str, main_uri: str
) -> list[str]:
    """A ring where the path lost track of an axis (at the next known position), and why."""
    if not toolpath.lost:
        return []
    known: dict[int, dict[str, float]] = {}
    wanted = {lost.line for lost in toolpath.lost}
    for move in toolpath.moves:
        line = move.line
        if line in wanted and line not in known:
            point = geometric(toolpath, move.end)
            if across in point and up in point:
                known[line] = point
    out = ['<g class="lost-track">']
    for lost in toolpath.lost:
        path = f" data-path={quoteattr(lost.uri)}" if lost.uri and lost.uri != main_uri else ""
        where = known.get(lost.line)
        reason = escape(f"line {lost.line + 1}: {', '.join(lost.axes)} unknown: {lost.reason}")
        if where is None:
            out.append(f'<desc data-kind="lost" data-line="{lost.line + 1}"{path}>{reason}</desc>')
            continue
        out.append(
            f'<circle class="lost" data-kind="lost" data-line="{lost.line + 1}"{path}'
            f' cx="{_num(frame.x(where[across]))}" cy="{_num(frame.y(where[up]))}" r="5">'
            f"<title>{reason}</title></circle>"
        )
    out.append("</g>")
    return out


# The pass map's panels: the infeed diagram (the groove and the tool's tip at each pass) on the
# left, the depth of each pass as bars on the right.
_MAP_HEIGHT = 300.0
_PANEL_TOP = 44.0
_PANEL_BOTTOM = 40.0


def _pass_map_view(pass_map: PassMap, top: float) -> tuple[list[str], float]:
    """The second view for one thread, placed at ``top``; its height."""
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
    half_width = max(deepest * math.tan(math.radians(30.0)) * 1.4, *(abs(o) for o in offsets))
    half_width = half_width or 1.0
    inner_h = _MAP_HEIGHT - _PANEL_TOP - _PANEL_BOTTOM
    panel_w = (WIDTH - MARGIN_LEFT - MARGIN_RIGHT - 40.0) / 2.0
    scale = min(panel_w / (2 * half_width), inner_h / (deepest * 1.1))
    left = MARGIN_LEFT
    y0 = top + _PANEL_TOP
    cx = left + panel_w / 2.0

    def px(offset: float) -> float:
        return cx + offset * scale

    def py(depth: float) -> float:
        return y0 + depth * scale

    side = "internal" if pass_map.internal else "external"
    measured = "the major diameter" if pass_map.major is not None else "the first pass"
    out = [
        f'<g class="view" data-view="passes" data-program="{escape(pass_map.program)}">',
        f'<text class="title" x="{_num(left)}" y="{_num(top + 24)}">'
        f"{escape(pass_map.program)}: {escape(pass_map.name)}, {side}, {len(marks)} passes"
        f" (depth from {measured})</text>",
        f'<line class="axis" x1="{_num(left)}" y1="{_num(y0)}" x2="{_num(left + panel_w)}"'
        f' y2="{_num(y0)}"/>',
    ]
    if basic is not None:
        # The basic V groove: 60 degrees, its flanks through the major diameter's line.
        w = basic * math.tan(math.radians(30.0))
        out.append(
            f'<polygon class="profile" data-kind="profile" points="{_num(px(-w))},{_num(py(0))}'
            f' {_num(px(0))},{_num(py(basic))} {_num(px(w))},{_num(py(0))}"/>'
        )
        out.append(
            f'<text x="{_num(px(0))}" y="{_num(py(basic) + 16)}" text-anchor="middle">'
            f"basic height 5H/8 = {fmt_address(basic)}</text>"
        )
    for mark, depth, offset in zip(marks, depths, offsets, strict=True):
        # The tool's 60-degree tip at this pass, its point where the pass cuts.
        w = (depth + deepest * 0.08) * math.tan(math.radians(30.0))
        tip_x, tip_y = px(offset), py(depth)
        rise = deepest * 0.08 + depth
        out.append(
            f'<polyline class="tool" data-kind="tool" data-line="{mark.line + 1}"'
            f' points="{_num(tip_x - w * scale)},{_num(tip_y - rise * scale)}'
            f" {_num(tip_x)},{_num(tip_y)} {_num(tip_x + w * scale)},"
            f'{_num(tip_y - rise * scale)}"/>'
        )
        out.append(
            f'<circle class="pass" data-kind="pass" data-line="{mark.line + 1}"'
            f' data-depth="{fmt_address(depth)}" data-x="{fmt_address(mark.x)}"'
            f' cx="{_num(tip_x)}" cy="{_num(tip_y)}" r="2.5"/>'
        )
    out.append(
        f'<text x="{_num(cx)}" y="{_num(top + _MAP_HEIGHT - 12)}" text-anchor="middle">'
        "infeed: the tool's tip at each pass (across: Z about the middle of the passes'"
        " starts)</text>"
    )
    # The depth of cut of each pass, as bars.
    bars_left = left + panel_w + 40.0
    count = len(marks)
    bar_w = panel_w / count
    cuts = [d - (depths[i - 1] if i else 0.0) for i, d in enumerate(depths)]
    most = max(max(cuts), 1e-9)
    bar_scale = inner_h / (most * 1.1)
    base = y0 + inner_h
    out.append(
        f'<line class="axis" x1="{_num(bars_left)}" y1="{_num(base)}"'
        f' x2="{_num(bars_left + panel_w)}" y2="{_num(base)}"/>'
    )
    for i, (mark, cut) in enumerate(zip(marks, cuts, strict=True)):
        h = max(cut, 0.0) * bar_scale
        out.append(
            f'<rect class="bar" data-kind="cut" data-line="{mark.line + 1}"'
            f' data-cut="{fmt_address(cut)}" x="{_num(bars_left + i * bar_w + bar_w * 0.1)}"'
            f' y="{_num(base - h)}" width="{_num(bar_w * 0.8)}" height="{_num(h)}"/>'
        )
    out.append(
        f'<text x="{_num(bars_left + panel_w / 2)}" y="{_num(top + _MAP_HEIGHT - 12)}"'
        f' text-anchor="middle">depth of cut of each pass (largest {fmt_address(most)},'
        " radius)</text>"
    )
    out.append("</g>")
    return out, _MAP_HEIGHT


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
    facts = run_with_toolpath(uri, doc, index, others, config, entry)
    toolpath = facts.toolpath
    if toolpath is None or not toolpath.moves:
        raise NothingToPlot("the program makes no move: nothing to plot")
    return toolpath
