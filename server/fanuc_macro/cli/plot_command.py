"""``fanuc-macro plot FILE``: the toolpath a program cuts, drawn as SVG (ide/plot.py)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..translation import tr
from .language import current, listed, said, said_error

EXIT_OK = 0
EXIT_NOTHING_TO_PLOT = 2


def cmd_plot(args: argparse.Namespace) -> int:
    from collections import Counter

    from ..ide import MOVE_NAMES, NothingToPlot, backplot, pass_maps, run_plot
    from . import _traced_workspace

    config, workspace, uri = _traced_workspace(args)
    doc = workspace.document(uri)
    assert doc is not None
    try:
        toolpath, stop, timed = run_plot(
            uri, doc, workspace.index(uri), workspace.others(uri), config, args.entry
        )
        # The pass maps of the threads the rules see in the file.
        threads = (
            workspace.analyse(uri).threads
            if any(m.kind == "thread" for m in toolpath.moves)
            else []
        )
        title = f"O{args.entry:04d}" if args.entry is not None else Path(args.file).name
        drawing = backplot(
            toolpath,
            args.plane,
            pass_maps(threads, workspace.index(uri)),
            title=title,
            main_uri=uri,
            stop=stop,
            timed=timed,
            locale=current(),
        )
    except NothingToPlot as err:
        sys.stderr.write(f"fanuc-macro: {args.file}: {said_error(err)}\n")
        return EXIT_NOTHING_TO_PLOT
    output = args.output or Path(args.file).with_suffix(".svg").name
    if output == "-":
        sys.stdout.write(drawing.svg)
    else:
        Path(output).write_text(drawing.svg, encoding="utf-8")
    stderr = sys.stderr
    if drawing.plane_reason is not None:
        # A mill's program read as a lathe's is the usual way to get here.
        if toolpath.lathe:
            reason = tr(
                "{path}: {why} (a mill's program? --controller 0i-MF); --plane chooses the view",
                path=args.file,
                why=said(drawing.plane_reason),
            )
        else:
            reason = tr(
                "{path}: {why}; --plane chooses the view",
                path=args.file,
                why=said(drawing.plane_reason),
            )
        stderr.write(said(reason) + "\n")
    # One line for each cause of what the drawing leaves out, at the first block it happened.
    for note in drawing.notes:
        if note.sites:
            where, line = note.sites[0]
            stderr.write(f"{where or uri}:{line + 1}: {said(note.text(uri, first_site=False))}\n")
        else:
            stderr.write(f"{args.file}: {said(note.text(uri))}\n")
    kinds = Counter(m.kind for m in toolpath.moves)
    counts = listed(f"{said(MOVE_NAMES.get(kind, kind))} {n}" for kind, n in sorted(kinds.items()))
    shown = said(tr("standard output")) if output == "-" else output
    stderr.write(f"{shown}: {said(drawing.summary(counts))}\n")
    return EXIT_OK


def add_plot_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser], logs: argparse.ArgumentParser
) -> None:
    from . import _add_run_options

    command = sub.add_parser(
        "plot",
        parents=[logs],
        help=said(tr("draw the toolpath a program cuts, as SVG (a backplot)")),
    )
    _add_run_options(command)
    command.add_argument(
        "--plane",
        choices=("XZ", "XY", "YZ"),
        help=said(
            tr(
                "the view (default: XZ on a lathe, Z across and X up; XY on a mill; a path that "
                "makes no move there is drawn in the plane it goes furthest in)"
            )
        ),
    )
    command.add_argument(
        "--output",
        "-o",
        metavar="PATH",
        help=said(
            tr("where the SVG goes (default: FILE's name with .svg, here; - for standard output)")
        ),
    )
    command.set_defaults(func=cmd_plot)
