"""``fanuc-macro plot FILE``: the toolpath a program cuts, drawn as SVG (ide/plot.py)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

EXIT_OK = 0
EXIT_NOTHING_TO_PLOT = 2


def cmd_plot(args: argparse.Namespace) -> int:
    from collections import Counter

    from ..ide.plot import NothingToPlot, pass_maps, plot_svg, run_toolpath
    from . import _traced_workspace

    config, workspace, uri = _traced_workspace(args)
    doc = workspace.document(uri)
    assert doc is not None
    try:
        toolpath = run_toolpath(
            uri, doc, workspace.index(uri), workspace.others(uri), config, args.entry
        )
        # The pass maps of the threads the rules see in the file.
        threads = (
            workspace.analyse(uri).threads
            if any(m.kind == "thread" for m in toolpath.moves)
            else []
        )
        title = f"O{args.entry:04d}" if args.entry is not None else Path(args.file).name
        svg = plot_svg(toolpath, args.plane, pass_maps(threads), title=title, main_uri=uri)
    except NothingToPlot as err:
        sys.stderr.write(f"fanuc-macro: {args.file}: {err}\n")
        return EXIT_NOTHING_TO_PLOT
    output = args.output or Path(args.file).with_suffix(".svg").name
    if output == "-":
        sys.stdout.write(svg)
    else:
        Path(output).write_text(svg, encoding="utf-8")
    for lost in toolpath.lost:
        where = lost.uri or uri
        sys.stderr.write(
            f"{where}:{lost.line + 1}: lost track of {', '.join(lost.axes)}: {lost.reason}\n"
        )
    kinds = Counter(m.kind for m in toolpath.moves)
    counts = ", ".join(f"{kind} {n}" for kind, n in sorted(kinds.items()))
    shown = "standard output" if output == "-" else output
    sys.stderr.write(f"{shown}: {len(toolpath.moves)} moves ({counts})\n")
    return EXIT_OK


def add_plot_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser], logs: argparse.ArgumentParser
) -> None:
    from . import _add_run_options

    command = sub.add_parser(
        "plot", parents=[logs], help="draw the toolpath a program cuts, as SVG (a backplot)"
    )
    _add_run_options(command)
    command.add_argument(
        "--plane",
        choices=("XZ", "XY", "YZ"),
        help="the view (default: XZ on a lathe, Z across and X up; XY on a mill)",
    )
    command.add_argument(
        "--output",
        "-o",
        metavar="PATH",
        help="where the SVG goes (default: FILE's name with .svg, here; - for standard output)",
    )
    command.set_defaults(func=cmd_plot)
