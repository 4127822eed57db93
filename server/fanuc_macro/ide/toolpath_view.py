"""What the editor's Toolpath view draws: the toolpath as flat arrays of segments.

A view of 200,000 moves needs them in a form a browser reads fast: one array per field, with
arcs already cut into short straight segments, positions in the drawing's geometry (a lathe's X
diameter as a radius, as the SVG backplot draws it). An unknown position is ``null``.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Any

from ..config import Config
from ..evaluator.toolpath import MOVE_KINDS, Toolpath
from ..program.index import ProgramIndex
from ..syntax.parser import quiet_gc
from ..syntax.tree import Document
from .plot import NothingToPlot, arc_points, geometric, run_toolpath

# At most this many segments go to the view (arcs cut into several count each): beyond it
# the toolpath is cut short and the view says so.
MAX_VIEW_SEGMENTS = 1_000_000


# An arc's points are written to this many decimals (0.1 µm, 0.01 of the least increment):
# at full precision they were two thirds of a posted file's payload.
ARC_DECIMALS = 4


def _xyz(point: dict[str, float]) -> tuple[float | None, float | None, float | None]:
    return point.get("X"), point.get("Y"), point.get("Z")


def view_data(toolpath: Toolpath, main_uri: str) -> dict[str, Any]:
    """``{"lathe", "units", "kinds", "paths", "segments": {"kind", "line", "path", "start",
    "end"}, "lost", "truncated"}``: ``kind`` indexes ``kinds``, ``path`` indexes ``paths``
    (the document first), ``line`` is 0-based, ``start``/``end`` hold x, y, z per segment."""
    kinds = {k: i for i, k in enumerate(MOVE_KINDS)}
    paths = {main_uri: 0}
    kind: list[int] = []
    line: list[int] = []
    path: list[int] = []
    start: list[float | None] = []
    end: list[float | None] = []
    truncated = toolpath.truncated
    for move in toolpath.moves:
        arc = arc_points(toolpath, move, ARC_DECIMALS) if move.kind == "arc" else None
        points = arc[0] if arc else [geometric(toolpath, move.start), geometric(toolpath, move.end)]
        if len(kind) + len(points) - 1 > MAX_VIEW_SEGMENTS:
            truncated = True
            break
        where = paths.setdefault(move.uri or main_uri, len(paths))
        placed = [_xyz(p) for p in points]
        k = kinds[move.kind]
        for a, b in itertools.pairwise(placed):
            kind.append(k)
            line.append(move.line)
            path.append(where)
            start.extend(a)
            end.extend(b)
    lost = [
        {
            "line": lost.line,
            "path": paths.setdefault(lost.uri or main_uri, len(paths)),
            "axes": list(lost.axes),
            "reason": lost.reason,
        }
        for lost in toolpath.lost
    ]
    return {
        "lathe": toolpath.lathe,
        "units": "inch" if toolpath.inch else "mm",
        "kinds": list(MOVE_KINDS),
        "paths": list(paths),
        "segments": {"kind": kind, "line": line, "path": path, "start": start, "end": end},
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
) -> dict[str, Any]:
    """The view's data for ``uri``'s programs, or ``{"error": ...}`` when it makes no move."""
    try:
        toolpath = run_toolpath(uri, doc, index, others, config, entry)
    except NothingToPlot as err:
        return {"error": str(err)}
    with quiet_gc():  # a million numbers in lists and no cycles: the collector only rescans
        return view_data(toolpath, uri)
