"""What the editor's Toolpath view draws: the toolpath as packed arrays of segments.

A view of 200,000 moves needs them in a form a browser reads fast and the server builds without
a Python object per number: one typed array per field, little-endian, in base64 (the client lays
a ``Uint8Array``/``Int32Array``/``Float64Array`` over the decoded bytes). Arcs are already cut
into short straight segments, positions are in the drawing's geometry (a lathe's X diameter as a
radius, as the SVG backplot draws it), and an unknown coordinate is NaN.

Segments that meet share their point: segment ``i`` goes from point ``point[i]`` to point
``point[i] + 1``, and a move that starts elsewhere than the last one ended adds its start point.
Positions are float64: float32's 24 bits would not keep 0.0001 inch (nor 0.001 mm beyond 8 m).

Beside the path, what a backplot shows about it: per segment the motion record it belongs to,
and per record its code, feed F and spindle speed S (the tooltip of a segment); whether the
program states its unit (G20/G21) or the view assumes one; the stock where the program gives
it (a lathe's bar: the blank a thread is cut in, or the start of a stock removal cycle); the
tool's radius where the program gives it (a threading tool's nose radius); and for a threading
program each thread's simulated cross-section (threads/cross_section.py, as the SVG backplot's
pass maps draw it).
"""

from __future__ import annotations

import base64
import math
import re
import sys
from array import array
from collections.abc import Sequence
from typing import Any, TypedDict

from ..config import Config
from ..evaluator.facts import Facts, Motion
from ..evaluator.toolpath import MOVE_KINDS, Toolpath
from ..program.index import ProgramIndex
from ..syntax.parser import quiet_gc
from ..syntax.tree import Document
from ..threads.cross_section import blank_diameter
from ..threads.identify import Thread, identify
from ..translation import tr
from .plot import PassMap, arc_points, pass_maps
from .trace import run_with_toolpath

# The payload's layout; the client refuses another.
VIEW_FORMAT = 3

# At most this many segments go to the view (arcs cut into several count each): beyond it
# the toolpath is cut short and the view says so.
MAX_VIEW_SEGMENTS = 1_000_000

# A segment's file is a Uint16: a program calling more files than that is cut short there.
MAX_VIEW_PATHS = 0xFFFF + 1

# An arc's points are rounded to this many decimals (0.1 µm, 0.01 of the least increment), as
# the SVG backplot writes them.
ARC_DECIMALS = 4


# The threads whose cross-section the view is given: the first ones the run cuts. Their chains
# (threads/cross_section.thread_chains) are worked out among these alone: the 11,988 one-pass
# jobs of seed 003's drum groove took minutes to chain.
MAX_VIEW_THREADS = 8

# The longest a path may be across, with no unit stated, before the view says its sizes look like
# inches: a part of 12 mm is a small one, of 12 inches an ordinary one.
INCH_LOOKING_SPAN = 12.0

# A unit word of the program, outside its comments: G20 (inch) or G21 (mm), G020 too.
_UNIT_WORD = re.compile(r"(?<![A-Z#])G0*2[01](?![0-9.])")
_COMMENT = re.compile(r"\([^)]*\)")

# The stock removal cycles whose start point is the stock's outside (0i-TF "Multiple
# repetitive cycle": the tool starts the cycle from the point A, outside the blank).
STOCK_CYCLES = frozenset({"G71", "G72", "G73"})


# The payload goes to the editor as it is: TypedDicts, their keys in the order they are sent.


class ViewSegments(TypedDict):
    """Per segment, one packed array each (base64 of little-endian items)."""

    kind: str  # uint8, an index in ``kinds``
    line: str  # int32, the block's 0-based line
    path: str  # uint16, an index in ``paths``
    point: str  # int32, the index of its start point
    motion: str  # int32, the index of its motion record in ``blocks`` (-1: none)


class ViewBlocks(TypedDict):
    """Per motion record (a block's execution), packed: what a segment's tooltip says."""

    code: str  # uint16, an index in ``codes``
    feed: str  # float64, the feed F in force (NaN: not known)
    speed: str  # float64, the spindle speed S: rpm, or G96's surface speed (NaN: not known)
    surface: str  # uint8, 1 when ``speed`` is G96's surface speed


class ViewLostTrack(TypedDict):
    line: int  # 0-based
    path: int  # an index in ``paths``
    axes: list[str]
    reason: str


class ViewStock(TypedDict):
    """A lathe's bar, as the settings or the program give it: its diameter from ``front`` to
    ``back`` (Z)."""

    diameter: float
    front: float
    back: float
    source: str  # where the program gives it, for the status line
    line: int  # 0-based, of the main document (-1: none)


class ViewTool(TypedDict):
    """The tool as the program gives it: a nose radius (a lathe's insert) or a cutter's."""

    radius: float
    angle: float  # a lathe insert's included angle, degrees (0: not known)
    source: str
    line: int  # 0-based (-1: none)


class ViewThread(TypedDict):
    """A thread's simulated cross-section (threads/cross_section.py) over one lead: (offset
    along the lead from the deepest pass, radius) pairs, the class's pitch diameters."""

    name: str
    line: int  # 0-based, the first pass's block
    internal: bool
    pitch: float | None
    major: float | None
    passes: int
    profile: list[list[float]]
    band: list[float] | None  # the pitch diameter's least and greatest (the class)


class ToolpathViewData(TypedDict):
    """What the Toolpath view draws (see :func:`view_data`)."""

    format: int
    lathe: bool
    units: str  # "mm" or "inch"
    units_stated: bool  # the program has a G20 or a G21
    units_note: str  # why the unit is assumed ("" when stated)
    kinds: list[str]
    paths: list[str]
    count: int
    points: str  # float64 x, y, z per point, packed
    segments: ViewSegments
    codes: list[str]
    blocks: ViewBlocks
    lost: list[ViewLostTrack]
    truncated: bool
    stopped: str  # why the run stopped early ("" when it did not)
    stock: ViewStock | None
    tool: ViewTool | None
    threads: list[ViewThread]


class NoToolpathView(TypedDict):
    """The program makes no move: the view shows why."""

    error: str
    empty: bool  # True: the program was read and makes no move (not a failure)


def packed(values: array[Any]) -> str:
    """The array's items as little-endian bytes, in base64."""
    if sys.byteorder == "big":
        values = array(values.typecode, values)
        values.byteswap()
    return base64.b64encode(values).decode("ascii")


class _Packed:
    """The segments' arrays as they are filled."""

    def __init__(self) -> None:
        self.kind = array("B")
        self.line = array("i")
        self.path = array("H")
        self.point = array("i")
        self.motion = array("i")
        self.points = array("d")
        assert self.line.itemsize == 4 and self.point.itemsize == 4 and self.path.itemsize == 2

    def segment(self, kind: int, line: int, path: int, point: int, motion: int) -> None:
        self.kind.append(kind)
        self.line.append(line)
        self.path.append(path)
        self.point.append(point)
        self.motion.append(motion)

    def segments(self) -> ViewSegments:
        return {
            "kind": packed(self.kind),
            "line": packed(self.line),
            "path": packed(self.path),
            "point": packed(self.point),
            "motion": packed(self.motion),
        }


def _pack(toolpath: Toolpath, main_uri: str) -> tuple[_Packed, dict[str, int], int, bool]:
    """The moves as segments: the arrays, the files' indexes, the count, cut short or not."""
    kinds = {k: i for i, k in enumerate(MOVE_KINDS)}
    paths = {main_uri: 0}
    out = _Packed()
    points = out.points
    nan = math.nan
    # A lathe's X is a diameter, drawn as a radius (arc_points gives its points so already).
    xs = 0.5 if toolpath.lathe else 1.0
    # The last point written, to join a move that starts there.
    lx = ly = lz = nan
    last = -1
    count = 0
    truncated = toolpath.truncated
    for move in toolpath.moves:
        arc = arc_points(toolpath, move, ARC_DECIMALS) if move.kind == "arc" else None
        n = len(arc[0]) - 1 if arc else 1
        if count + n > MAX_VIEW_SEGMENTS:
            truncated = True
            break
        uri = move.uri or main_uri
        where = paths.get(uri)
        if where is None:
            if len(paths) >= MAX_VIEW_PATHS:
                truncated = True
                break
            where = paths[uri] = len(paths)
        k = kinds[move.kind]
        if arc:
            first, *rest = arc[0]
            x, y, z = first.get("X", nan), first.get("Y", nan), first.get("Z", nan)
        else:
            s = move.start
            x, y, z = s.get("X", nan) * xs, s.get("Y", nan), s.get("Z", nan)
        # The same point, an unknown coordinate (NaN) matching an unknown one (a lathe's Y).
        if not (
            last >= 0
            and (x == lx or (x != x and lx != lx))
            and (y == ly or (y != y and ly != ly))
            and (z == lz or (z != z and lz != lz))
        ):
            points.extend((x, y, z))
            last += 1
        if arc:
            for p in rest:
                out.segment(k, move.line, where, last, move.motion)
                lx, ly, lz = p.get("X", nan), p.get("Y", nan), p.get("Z", nan)
                points.extend((lx, ly, lz))
                last += 1
        else:
            out.segment(k, move.line, where, last, move.motion)
            e = move.end
            lx, ly, lz = e.get("X", nan) * xs, e.get("Y", nan), e.get("Z", nan)
            points.extend((lx, ly, lz))
            last += 1
        count += n
    return out, paths, count, truncated


def _blocks(motions: Sequence[Motion]) -> tuple[list[str], ViewBlocks]:
    """Each motion record's code (as the program writes it), feed and spindle speed."""
    codes: dict[str, int] = {}
    code = array("H")
    feed = array("d")
    speed = array("d")
    surface = array("B")
    nan = math.nan
    for m in motions:
        shown = m.written or m.code
        c = codes.get(shown)
        if c is None:
            c = codes[shown] = min(len(codes), 0xFFFF)
        code.append(c)
        f = m.words.get("F")
        feed.append(nan if f is None else f)
        css = m.surface_speed
        rpm = m.rpm
        speed.append(css if css is not None else rpm if rpm is not None else nan)
        surface.append(1 if css is not None else 0)
    blocks: ViewBlocks = {
        "code": packed(code),
        "feed": packed(feed),
        "speed": packed(speed),
        "surface": packed(surface),
    }
    return list(codes), blocks


def units_stated(documents: Sequence[Document]) -> bool:
    """Whether a block of the documents has G20 or G21 (outside its comments)."""
    for doc in documents:
        for block in doc.blocks:
            text = block.parsed.text
            if "2" not in text or ("G" not in text and "g" not in text):
                continue
            if _UNIT_WORD.search(_COMMENT.sub("", text.upper())):
                return True
    return False


def _largest_span(points: array[float]) -> float:
    """The path's greatest extent along one axis (0 when no point is known)."""
    span = 0.0
    for axis in range(3):
        known = [v for v in points[axis::3] if v == v]
        if known:
            span = max(span, max(known) - min(known))
    return span


def units_note(stated: bool, inch: bool, span: float, lathe: bool) -> str:
    """Why the unit is the one the view says: "" when the program states it."""
    if stated:
        return ""
    unit = "inch" if inch else "mm"
    note = tr(
        "assumed {unit}: the program states neither G20 nor G21 (the control keeps the unit it "
        "was in, or its setting's at power-on)",
        unit=unit,
    )
    # A lathe's X is drawn as a radius: its span is half the diameters'.
    if not inch and 0.0 < span * (2.0 if lathe else 1.0) <= INCH_LOOKING_SPAN:
        return tr(
            "{note}; the path is only {span:.4g} across, as a part in inches would be",
            note=note,
            span=span,
        )
    return note


def view_data(
    toolpath: Toolpath,
    main_uri: str,
    facts: Facts | None = None,
    stated: bool = True,
    threads: Sequence[Thread] = (),
    maps: Sequence[PassMap] = (),
    stock_diameter: float = math.inf,
    main_doc: Document | None = None,
) -> ToolpathViewData:
    """``{"format", "lathe", "units", "units_stated", "units_note", "kinds", "paths", "count",
    "points", "segments": {"kind", "line", "path", "point", "motion"}, "codes", "blocks":
    {"code", "feed", "speed", "surface"}, "lost", "truncated", "stopped", "stock", "tool",
    "threads"}``: ``points`` holds x, y, z per point (float64); per segment, ``kind`` (uint8)
    indexes ``kinds``, ``line`` (int32) is 0-based, ``path`` (uint16) indexes ``paths`` (the
    document first), ``point`` (int32) is its start, ``motion`` (int32) its record in
    ``blocks``. ``facts``: the run's (its motion records); ``stated``: whether the program
    has G20/G21; ``threads`` and ``maps``: the threads it cuts and their pass maps;
    ``stock_diameter``: the bar's diameter the settings give (inf: the program's);
    ``main_doc``: the document, whose comments may give a mill's cutter."""
    out, paths, count, truncated = _pack(toolpath, main_uri)
    lost: list[ViewLostTrack] = [
        {
            "line": lost.line,
            "path": paths.setdefault(lost.uri or main_uri, len(paths)),
            "axes": list(lost.axes),
            "reason": lost.reason,
        }
        for lost in toolpath.lost
    ]
    codes, blocks = _blocks(facts.motions if facts is not None else ())
    stopped = ""
    if facts is not None and facts.stopped == "budget":
        stopped = tr("the run stopped when the analysis's step budget ran out")
    elif facts is not None and facts.stopped == "time":
        stopped = tr(
            "the run stopped after {seconds:g} s (the analysis's time limit)",
            seconds=facts.time_limit,
        )
    return {
        "format": VIEW_FORMAT,
        "lathe": toolpath.lathe,
        "units": "inch" if toolpath.inch else "mm",
        "units_stated": stated,
        "units_note": units_note(stated, toolpath.inch, _largest_span(out.points), toolpath.lathe),
        "kinds": list(MOVE_KINDS),
        "paths": list(paths),
        "count": count,
        "points": packed(out.points),
        "segments": out.segments(),
        "codes": codes,
        "blocks": blocks,
        "lost": lost,
        "truncated": truncated,
        "stopped": stopped,
        "stock": stock_of(
            toolpath, facts.motions if facts is not None else (), threads, stock_diameter
        ),
        "tool": tool_of(threads) if toolpath.lathe else cutter_of(main_doc),
        "threads": [_thread(m, t) for m, t in zip(maps, _mapped(threads), strict=False)],
    }


def _mapped(threads: Sequence[Thread]) -> list[Thread]:
    """The threads ``pass_maps`` makes a map of, in its order: those with a pass of known X."""
    return [t for t in threads if any(p.x is not None for p in t.job.passes)]


def _thread(m: PassMap, thread: Thread) -> ViewThread:
    return {
        "name": m.name,
        "line": thread.job.passes[0].line,
        "internal": m.internal,
        "pitch": m.pitch,
        "major": m.major,
        "passes": len(m.passes),
        "profile": [[u, h] for u, h in m.cut],
        "band": None if m.band is None else [m.band[0], m.band[1]],
    }


def stock_of(
    toolpath: Toolpath,
    motions: Sequence[Motion],
    threads: Sequence[Thread],
    setting: float = math.inf,
) -> ViewStock | None:
    """A lathe's bar: the diameter ``setting`` gives (the setting view.stockDiameter, when
    finite), else where the program gives it: the start point of its first stock removal
    cycle (G71-G73 start outside the blank), else the blank its first external thread is cut
    in (the diameter turned before it, or its designation's major diameter); along Z, from
    Z0 (the front of the cuts when they stay in front of it) to the cuts' end. None on a mill,
    or when none is."""
    if not toolpath.lathe:
        return None
    cuts = [m for m in toolpath.moves if m.kind != "rapid"]
    zs = [p["Z"] for m in cuts for p in (m.start, m.end) if "Z" in p]
    if not zs:
        return None
    # The work's zero is its front face where the cuts go behind it (the run-in of a thread
    # starts in the air before it).
    back = min(zs)
    front = 0.0 if back < 0.0 else max(zs)
    if back >= front:
        return None
    if 0.0 < setting < math.inf:
        return {
            "diameter": setting,
            "front": front,
            "back": back,
            "source": tr("the setting fanuc-macro.view.stockDiameter"),
            "line": -1,
        }
    for m in motions:
        if m.code in STOCK_CYCLES and m.start_x is not None and m.start_x > 0.0:
            return {
                "diameter": m.start_x,
                "front": front,
                "back": back,
                "source": tr(
                    "the start point of {code} at line {line}", code=m.code, line=m.line + 1
                ),
                "line": m.line,
            }
    for thread in threads:
        if thread.internal:
            continue
        surface = thread.surface
        if surface is not None:
            diameter: float | None = surface.blank
            source = tr("the diameter turned at line {line}", line=surface.line + 1)
        else:
            diameter = blank_diameter(thread)
            source = tr("the major diameter of {thread}", thread=thread.name)
        if diameter is not None and diameter > 0.0:
            line = thread.job.passes[0].line
            return {
                "diameter": diameter,
                "front": front,
                "back": back,
                "source": source,
                "line": line,
            }
    return None


def tool_of(threads: Sequence[Thread]) -> ViewTool | None:
    """The tool's radius where the program gives it: a threading tool's nose radius."""
    for thread in threads:
        r = thread.nose_radius
        if r is not None and r > 0.0:
            line = thread.nose_line if thread.nose_line is not None else -1
            source = (
                tr("the threading tool's nose radius at line {line}", line=line + 1)
                if line >= 0
                else tr("the threading tool's nose radius")
            )
            return {
                "radius": r,
                "angle": 60.0 if thread.pipe is None else 55.0,
                "source": source,
                "line": line,
            }
    return None


# A cutter's diameter as CAM posts write it in the tool list at a program's head: Fusion 360
# and HSM "(T1 D=10. CR=0. - ZMIN=-5. - FLAT END MILL)", Mastercam "(TOOL - 1 DIA. OFF. - 1
# LEN. - 1 DIA. - 10.)", or a diameter sign "(T2 Ø8 DRILL)". For the drawing only: no verdict
# reads it.
_CUTTER_DIAMETER = re.compile(
    r"(?:\bD\s*=\s*|\bDIA\.\s*-\s*|[Ø⌀]\s*)(\d+(?:\.\d*)?|\.\d+)", re.IGNORECASE
)


def cutter_of(doc: Document | None) -> ViewTool | None:
    """A mill's cutter where the program's comments give its diameter (the first tool of its
    tool list); None when none does."""
    if doc is None:
        return None
    for block in doc.blocks:
        for comment in block.parsed.comments:
            found = _CUTTER_DIAMETER.search(comment.text)
            if found is not None and float(found[1]) > 0.0:
                return {
                    "radius": float(found[1]) / 2.0,
                    "angle": 0.0,
                    "source": tr("the diameter in the comment at line {line}", line=block.line + 1),
                    "line": block.line,
                }
    return None


def empty_reason(doc: Document, facts: Facts) -> str:
    """Why a run draws nothing, in the words the view shows."""
    if not any(b.parsed.statement is not None for b in doc.blocks):
        return tr("the document holds no blocks: nothing to draw")
    if not facts.motions:
        return tr(
            "the program makes no move: no block of it that runs moves an axis (G00-G03, a "
            "canned cycle)"
        )
    return tr(
        "the program makes no move whose place is known: its moves are incremental from a "
        "place the program never states"
    )


def toolpath_view(
    uri: str,
    doc: Document,
    index: ProgramIndex,
    others: Sequence[tuple[str, Document, ProgramIndex]] = (),
    config: Config | None = None,
    entry: int | None = None,
) -> ToolpathViewData | NoToolpathView:
    """The view's data for ``uri``'s programs, or ``{"error": ..., "empty": true}`` when it
    makes no move."""
    facts = run_with_toolpath(uri, doc, index, others, config, entry)
    toolpath = facts.toolpath
    if toolpath is None or not toolpath.moves:
        return {"error": empty_reason(doc, facts), "empty": True}
    threads: list[Thread] = []
    doc_facts = facts.by_uri.get(uri)
    if doc_facts is not None and any(m.kind == "thread" for m in toolpath.moves):
        found = identify(doc, index, doc_facts, facts.motions, facts.run_values)
        threads = found[:MAX_VIEW_THREADS]
    stated = units_stated([doc, *(d for _u, d, _i in others)])
    with quiet_gc():  # the arcs' points in lists and no cycles: the collector only rescans
        stock = config.stock_diameter if config is not None else math.inf
        maps = pass_maps(threads, index)
        return view_data(toolpath, uri, facts, stated, threads, maps, stock, doc)
