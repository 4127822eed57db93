"""The backplot: a program's toolpath drawn as SVG (``fanuc-macro plot``).

Rapids dashed, feeds solid, threading passes and arcs in colours of their own, with axes in the
program's units and a scale bar. Every drawn element carries ``data-line`` (the 1-based line of
its block) and ``data-kind``, so that a viewer can link it to the source. A lathe is drawn in
its XZ plane as machinists draw it (Z across, X up, as a radius: the program's X is a
diameter, and its tick labels say so); a mill in the plane asked for. For a threading program a
second view follows: the pass map of each thread (the depth of every pass, and the infeed
diagram: where the tool's tip is in the groove at each pass).

The drawing is a pure function of the toolpath and the threads: the same program gives the
same bytes (coordinates are written at a fixed precision).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from xml.sax.saxutils import escape, quoteattr

from ..config import Config
from ..evaluator.toolpath import Move, Plane, Toolpath
from ..evaluator.values import fmt_address
from ..program.index import ProgramIndex
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

STYLE = (
    "text{font:12px sans-serif;fill:#222}"
    ".title{font-weight:bold;font-size:14px}"
    ".axis{stroke:#444;stroke-width:1}"
    ".grid{stroke:#ddd;stroke-width:0.5}"
    ".zero{stroke:#999;stroke-width:0.8;stroke-dasharray:2 2}"
    ".move{fill:none;stroke-width:1.2;stroke-linecap:round}"
    ".rapid{stroke:#888;stroke-dasharray:5 4}"
    ".feed{stroke:#1f5fbf}"
    ".arc{stroke:#1f8f4f}"
    ".thread{stroke:#d2411f;stroke-width:1.6}"
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


def arc_points(toolpath: Toolpath, move: Move) -> tuple[list[dict[str, float]], float] | None:
    """Points along an arc (a helix when the third axis moves), start and end included, and
    the angle it turns through (radians, negative clockwise)."""
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
    third = [k for k in (*start, *end) if k not in (a, b)]
    points = []
    for i in range(steps + 1):
        f = i / steps
        t = t0 + span * f
        p = {a: c[a] + radius * math.cos(t), b: c[b] + radius * math.sin(t)}
        for k in third:
            if k in start and k in end:
                p[k] = start[k] + (end[k] - start[k]) * f
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


def _attrs(move: Move, main_uri: str) -> str:
    path = f" data-path={quoteattr(move.uri)}" if move.uri and move.uri != main_uri else ""
    return (
        f' class="move {move.kind}" data-kind="{move.kind}" data-line="{move.line + 1}"'
        f' data-program="{escape(move.program)}"{path}'
    )


def _svg_arc(frame: _Frame, across: str, up: str, item: _Drawn, toolpath: Toolpath) -> str | None:
    """An SVG arc command for an arc in the view's plane (no helix), else None."""
    move, points = item.move, item.points
    if set(_ARC_AXES[move.plane]) != {across, up} or move.centre is None or item.turn is None:
        return None
    start, end = move.start, move.end
    if any(start.get(k) != end.get(k) for k in {*start, *end} - {across, up}):
        return None  # a helix: the polyline shows its projection
    c = geometric(toolpath, move.centre)
    sx, sy = frame.x(points[0][across]), frame.y(points[0][up])
    ex, ey = frame.x(points[-1][across]), frame.y(points[-1][up])
    mid = points[len(points) // 2]
    mx, my = frame.x(mid[across]), frame.y(mid[up])
    cx, cy = frame.x(c[across]), frame.y(c[up])
    r = math.hypot(sx - cx, sy - cy)
    sweep = 1 if (sx - cx) * (my - cy) - (sy - cy) * (mx - cx) > 0 else 0
    turn = abs(item.turn)
    if turn >= math.tau - 1e-9:  # a full circle: two halves, an SVG arc cannot close itself
        ox, oy = 2 * cx - sx, 2 * cy - sy
        return (
            f"M{_num(sx)} {_num(sy)}A{_num(r)} {_num(r)} 0 0 {sweep} {_num(ox)} {_num(oy)}"
            f"A{_num(r)} {_num(r)} 0 0 {sweep} {_num(sx)} {_num(sy)}"
        )
    large = 1 if turn > math.pi else 0
    return f"M{_num(sx)} {_num(sy)}A{_num(r)} {_num(r)} 0 {large} {sweep} {_num(ex)} {_num(ey)}"


def _axis_title(axis: str, toolpath: Toolpath, units: str) -> str:
    if toolpath.lathe and axis == "X":
        return f"X ({units}, diameter; drawn as a radius)"
    return f"{axis} ({units})"


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
    value = math.ceil(h_range[0] / step - 1e-9) * step
    while value <= h_range[1] + 1e-9:
        px = frame.x(value)
        out.append(
            f'<line class="grid" x1="{_num(px)}" y1="{_num(top)}" x2="{_num(px)}"'
            f' y2="{_num(low)}"/>'
        )
        out.append(
            f'<text x="{_num(px)}" y="{_num(low + 16)}" text-anchor="middle">{_tick(value)}</text>'
        )
        value += step
    factor = 2.0 if toolpath.lathe and up == "X" else 1.0  # label a lathe's X as a diameter
    value = math.ceil(v_range[0] / v_step - 1e-9) * v_step
    while value <= v_range[1] + 1e-9:
        py = frame.y(value)
        out.append(
            f'<line class="grid" x1="{_num(left)}" y1="{_num(py)}" x2="{_num(right)}"'
            f' y2="{_num(py)}"/>'
        )
        out.append(
            f'<text x="{_num(left - 6)}" y="{_num(py + 4)}" text-anchor="end">'
            f"{_tick(value * factor)}</text>"
        )
        value += v_step
    if h_range[0] < 0 < h_range[1]:
        px = frame.x(0.0)
        out.append(
            f'<line class="zero" x1="{_num(px)}" y1="{_num(top)}" x2="{_num(px)}"'
            f' y2="{_num(low)}"/>'
        )
    if v_range[0] < 0 < v_range[1]:
        py = frame.y(0.0)
        out.append(
            f'<line class="zero" x1="{_num(left)}" y1="{_num(py)}" x2="{_num(right)}"'
            f' y2="{_num(py)}"/>'
        )
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


@dataclass(frozen=True, slots=True)
class _Drawn:
    """A move and the points it is drawn through."""

    move: Move
    points: list[dict[str, float]]  # in the drawing's geometry
    turn: float | None = None  # an arc's angle, radians


def _drawn(toolpath: Toolpath, across: str, up: str) -> list[_Drawn]:
    """Each move with the points it is drawn through, when its place in the view is known."""
    drawn = []
    for move in toolpath.moves:
        arc = arc_points(toolpath, move) if move.kind == "arc" else None
        if arc is not None:
            item = _Drawn(move, arc[0], arc[1])
        else:
            item = _Drawn(move, [geometric(toolpath, move.start), geometric(toolpath, move.end)])
        if all(across in p and up in p for p in item.points):
            drawn.append(item)
    return drawn


def plot_svg(
    toolpath: Toolpath,
    plane: Plane | None = None,
    passes: Sequence[PassMap] = (),
    title: str = "",
    main_uri: str = "",
) -> str:
    """The SVG document of a toolpath, and of the threads' pass maps after it.

    Raises :class:`NothingToPlot` when no move can be placed in the plane."""
    view: Plane = plane or ("XZ" if toolpath.lathe else "XY")
    across, up = _VIEW_AXES[(toolpath.lathe, view)]
    drawn = _drawn(toolpath, across, up)
    if not drawn:
        raise NothingToPlot(
            f"no move of the trace has a known {across} and {up}: nothing to plot in {view}"
        )
    hs = [p[across] for d in drawn for p in d.points]
    vs = [p[up] for d in drawn for p in d.points]
    h_range = (min(hs), max(hs))
    v_range = (min(vs), max(vs))
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
    ]
    for item in drawn:
        move, points = item.move, item.points
        attrs = _attrs(move, main_uri)
        arc = _svg_arc(frame, across, up, item, toolpath) if item.turn is not None else None
        if arc is not None:
            body.append(f'<path{attrs} d="{arc}"/>')
        elif len(points) == 2:
            a, b = points
            body.append(
                f'<line{attrs} x1="{_num(frame.x(a[across]))}" y1="{_num(frame.y(a[up]))}"'
                f' x2="{_num(frame.x(b[across]))}" y2="{_num(frame.y(b[up]))}"/>'
            )
        else:
            coords = " ".join(f"{_num(frame.x(p[across]))},{_num(frame.y(p[up]))}" for p in points)
            body.append(f'<polyline{attrs} points="{coords}"/>')
    body.append("</g>")
    body.extend(_lost_marks(toolpath, frame, across, up, main_uri))
    body.append("</g>")
    total_height = height
    for pass_map in passes:
        group, h = _pass_map_view(pass_map, total_height)
        body.extend(group)
        total_height += h
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
    for move in toolpath.moves:
        point = geometric(toolpath, move.end)
        if across in point and up in point:
            known.setdefault(move.line, point)
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
