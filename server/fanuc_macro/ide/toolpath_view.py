"""What the editor's Toolpath view draws: the toolpath as packed arrays of segments.

A view of 200,000 moves needs them in a form a browser reads fast and the server builds without
a Python object per number: one typed array per field, little-endian, in base64 (the client lays
a ``Uint8Array``/``Int32Array``/``Float64Array`` over the decoded bytes). Arcs are already cut
into short straight segments, positions are in the drawing's geometry (a lathe's X diameter as a
radius, as the SVG backplot draws it), and an unknown coordinate is NaN.

Segments that meet share their point: segment ``i`` goes from point ``point[i]`` to point
``point[i] + 1``, and a move that starts elsewhere than the last one ended adds its start point.
Positions are float64: float32's 24 bits would not keep 0.0001 inch (nor 0.001 mm beyond 8 m).
"""

from __future__ import annotations

import base64
import math
import sys
from array import array
from collections.abc import Sequence
from typing import Any, TypedDict

from ..config import Config
from ..evaluator.toolpath import MOVE_KINDS, Toolpath
from ..program.index import ProgramIndex
from ..syntax.parser import quiet_gc
from ..syntax.tree import Document
from .plot import NothingToPlot, arc_points, run_toolpath

# The payload's layout; the client refuses another.
VIEW_FORMAT = 2

# At most this many segments go to the view (arcs cut into several count each): beyond it
# the toolpath is cut short and the view says so.
MAX_VIEW_SEGMENTS = 1_000_000

# A segment's file is a Uint16: a program calling more files than that is cut short there.
MAX_VIEW_PATHS = 0xFFFF + 1

# An arc's points are rounded to this many decimals (0.1 µm, 0.01 of the least increment), as
# the SVG backplot writes them.
ARC_DECIMALS = 4


# The payload goes to the editor as it is: TypedDicts, their keys in the order they are sent.


class ViewSegments(TypedDict):
    """Per segment, one packed array each (base64 of little-endian items)."""

    kind: str  # uint8, an index in ``kinds``
    line: str  # int32, the block's 0-based line
    path: str  # uint16, an index in ``paths``
    point: str  # int32, the index of its start point


class ViewLostTrack(TypedDict):
    line: int  # 0-based
    path: int  # an index in ``paths``
    axes: list[str]
    reason: str


class ToolpathViewData(TypedDict):
    """What the Toolpath view draws (see :func:`view_data`)."""

    format: int
    lathe: bool
    units: str  # "mm" or "inch"
    kinds: list[str]
    paths: list[str]
    count: int
    points: str  # float64 x, y, z per point, packed
    segments: ViewSegments
    lost: list[ViewLostTrack]
    truncated: bool


class NoToolpathView(TypedDict):
    """The program makes no move: the view shows why."""

    error: str


def packed(values: array[Any]) -> str:
    """The array's items as little-endian bytes, in base64."""
    if sys.byteorder == "big":
        values = array(values.typecode, values)
        values.byteswap()
    return base64.b64encode(values).decode("ascii")


def view_data(toolpath: Toolpath, main_uri: str) -> ToolpathViewData:
    """``{"format", "lathe", "units", "kinds", "paths", "count", "points", "segments": {"kind",
    "line", "path", "point"}, "lost", "truncated"}``: ``points`` holds x, y, z per point
    (float64); per segment, ``kind`` (uint8) indexes ``kinds``, ``line`` (int32) is 0-based,
    ``path`` (uint16) indexes ``paths`` (the document first), ``point`` (int32) is its start."""
    kinds = {k: i for i, k in enumerate(MOVE_KINDS)}
    paths = {main_uri: 0}
    kind = array("B")
    line = array("i")
    path = array("H")
    point = array("i")
    points = array("d")
    assert line.itemsize == 4 and point.itemsize == 4 and path.itemsize == 2
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
                kind.append(k)
                line.append(move.line)
                path.append(where)
                point.append(last)
                lx, ly, lz = p.get("X", nan), p.get("Y", nan), p.get("Z", nan)
                points.extend((lx, ly, lz))
                last += 1
        else:
            kind.append(k)
            line.append(move.line)
            path.append(where)
            point.append(last)
            e = move.end
            lx, ly, lz = e.get("X", nan) * xs, e.get("Y", nan), e.get("Z", nan)
            points.extend((lx, ly, lz))
            last += 1
        count += n
    lost: list[ViewLostTrack] = [
        {
            "line": lost.line,
            "path": paths.setdefault(lost.uri or main_uri, len(paths)),
            "axes": list(lost.axes),
            "reason": lost.reason,
        }
        for lost in toolpath.lost
    ]
    return {
        "format": VIEW_FORMAT,
        "lathe": toolpath.lathe,
        "units": "inch" if toolpath.inch else "mm",
        "kinds": list(MOVE_KINDS),
        "paths": list(paths),
        "count": count,
        "points": packed(points),
        "segments": {
            "kind": packed(kind),
            "line": packed(line),
            "path": packed(path),
            "point": packed(point),
        },
        "lost": lost,
        "truncated": truncated,
    }


def toolpath_view(
    uri: str,
    doc: Document,
    index: ProgramIndex,
    others: Sequence[tuple[str, Document, ProgramIndex]] = (),
    config: Config | None = None,
    entry: int | None = None,
) -> ToolpathViewData | NoToolpathView:
    """The view's data for ``uri``'s programs, or ``{"error": ...}`` when it makes no move."""
    try:
        toolpath = run_toolpath(uri, doc, index, others, config, entry)
    except NothingToPlot as err:
        return {"error": str(err)}
    with quiet_gc():  # the arcs' points in lists and no cycles: the collector only rescans
        return view_data(toolpath, uri)
