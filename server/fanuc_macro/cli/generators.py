"""``fanuc-macro arc-thread`` and ``fanuc-macro drum-groove``: print the seed papers' programs
for other parts.

``arc-thread`` is the large-pitch arc thread by the fitting method (seed 002), ``drum-groove``
the drum-shaped spiral groove in chained taper threads (seed 003); both default to the papers'
parts.  The generators run their program with the evaluator before printing it; anything they
refuse exits 2 with one line on standard error.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from ..translation import Text, tr
from .language import said, said_error
from .thread import _count, _program

__all__ = ("add_generator_commands", "cmd_arc_thread", "cmd_drum_groove")

EXIT_OK = 0
EXIT_USAGE = 2

_NUMBER = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)"
_POINT = re.compile(rf"\s*({_NUMBER})\s*[,;\t ]\s*({_NUMBER})\s*[,;\t]?\s*")


class Refused(Exception):
    """An input the command refuses: its message is the one line on standard error."""


def _number(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            said(tr("{given!r} is not a number", given=text))
        ) from None
    if value != value or value in (float("inf"), float("-inf")):
        raise argparse.ArgumentTypeError(said(tr("{given!r} is not a finite number", given=text)))
    return value


def _diameters(text: str) -> tuple[float, ...]:
    """``108,103``: roughing groove-centre diameters, in cutting order."""
    items = [item.strip() for item in text.split(",")]
    if not items or any(not item for item in items):
        raise argparse.ArgumentTypeError(
            said(tr("{given!r} is not a comma list of diameters (108,103)", given=text))
        )
    return tuple(_number(item) for item in items)


def _spindle(text: str) -> int:
    match = re.fullmatch(r"\s*[Mm]?0*([34])\s*", text)
    if match is None:
        raise argparse.ArgumentTypeError(said(tr("{given!r} is not M3 or M4", given=text)))
    return int(match.group(1))


def _speed(text: str) -> int:
    value = _count(text)
    if value == 0:
        raise argparse.ArgumentTypeError(said(tr("{given!r} must be positive", given=text)))
    return value


def _direction(text: str) -> str:
    if text not in ("left", "right"):
        raise argparse.ArgumentTypeError(said(tr("{given!r} is not left or right", given=text)))
    return text


def _refusal(command: str, err: Exception) -> int:
    message = " ".join(said_error(err).split())
    sys.stderr.write(f"fanuc-macro {command}: {message}\n")
    return EXIT_USAGE


def _program_numbers(
    args: argparse.Namespace,
    build: Callable[..., object],
    parts: Sequence[tuple[str, str]],
    options: Sequence[str],
) -> tuple[dict[str, int], str | None]:
    """The program numbers given, and with ``--into FILE`` the others: the paper's, or the first
    free ones after them where the file has them; what moved, for standard error."""
    from ..generators import free_programs, programs_in

    numbers = {
        key: getattr(args, option)
        for (key, _), option in zip(parts, options, strict=True)
        if getattr(args, option) is not None
    }
    if args.into is None:
        return numbers, None
    try:
        with open(args.into, "rb") as file:
            taken = programs_in(file.read())
    except OSError as err:
        why = err.strerror or str(err)
        raise Refused(
            tr("--into {path}: cannot read it ({why})", path=args.into, why=why)
        ) from None
    return numbers, free_programs(numbers, build, parts, taken)


def cmd_arc_thread(args: argparse.Namespace) -> int:
    # Imported here: ``check`` starts without the generators (tests/test_startup.py).
    from ..generators import ARC_PROGRAMS, build_arc_thread

    lead = args.lead if args.lead is not None else args.pitch
    try:
        numbers, note = _program_numbers(
            args, build_arc_thread, ARC_PROGRAMS, ("main", "rough", "finishing")
        )
        program = build_arc_thread(
            outer_diameter=args.outer_diameter,
            groove_radius=args.groove_radius,
            tool_radius=args.tool_radius,
            pitch=lead,
            length=args.length,
            layers=args.layers,
            cuts_per_layer=args.cuts_per_layer,
            finishing_diameter=args.finishing_diameter,
            finishing_cuts=args.finishing_cuts,
            run_in=args.run_in,
            finishing_tool_radius=args.finishing_tool_radius,
            rough_speed=args.rough_speed,
            finishing_speed=args.finishing_speed,
            spindle_m=args.spindle,
            rough_tool=args.rough_tool,
            finishing_tool=args.finishing_tool,
            retract_x=args.retract_x,
            start_x=args.start_x,
            start_z=args.start_z,
            **numbers,
        )
    except (ValueError, RuntimeError) as err:  # RuntimeError: the run of the program failed
        return _refusal("arc-thread", err)
    if note is not None:
        sys.stderr.write(f"fanuc-macro arc-thread: {said(note)}\n")
    sys.stdout.write(program.text)
    return EXIT_OK


def _is_number(text: str) -> bool:
    return re.fullmatch(_NUMBER, text.strip()) is not None


def _parse_points(
    rows: Sequence[str], where: str, kind: Text, header: bool
) -> list[tuple[float, float]]:
    """Profile points (X diameter, Z), one a row: ``X,Z``, ``X;Z`` or tab-separated.  With
    ``header`` a first row of no number at all (``X,Z``) is a header, not a point."""
    points: list[tuple[float, float]] = []
    for n, raw in enumerate(rows, 1):
        row = raw.strip()
        if not row:
            continue
        match = _POINT.fullmatch(row)
        if match is None:
            fields = re.split(r"[,;\t]", row)
            if header and not points and not any(_is_number(f) for f in fields):
                continue
            raise Refused(
                tr(
                    "{where} {kind} {n}: {row!r} is not X diameter, Z (e.g. 298.91,205)",
                    where=where,
                    kind=kind,
                    n=n,
                    row=row,
                )
            )
        points.append((float(match.group(1)), float(match.group(2))))
    if not points:
        raise Refused(tr("{where}: no profile points", where=where))
    return points


def cmd_drum_groove(args: argparse.Namespace) -> int:
    from ..generators import DRUM_PROFILE, DRUM_PROGRAMS, build_drum_groove

    try:
        numbers, note = _program_numbers(args, build_drum_groove, DRUM_PROGRAMS, ("main", "macro"))
        if args.points_file is not None:
            path = Path(args.points_file)
            try:
                rows = path.read_text(encoding="utf-8-sig").splitlines()
            except (OSError, UnicodeDecodeError) as err:
                raise Refused(
                    tr(
                        "--points-file {path}: cannot read it ({why})",
                        path=args.points_file,
                        why=str(err),
                    )
                ) from None
            where = f"--points-file {args.points_file}"
            points = _parse_points(rows, where, tr("row"), True)
        elif args.points is not None:
            points = _parse_points(args.points.split(";"), "--points", tr("point"), False)
        else:
            points = list(DRUM_PROFILE)
        program = build_drum_groove(
            points,
            args.pitch,
            args.layers,
            args.radial_step,
            args.axial_step,
            cuts_per_layer=args.cuts_per_layer,
            direction=-1 if args.direction == "left" else 1,
            run_in=args.run_in,
            clearance=args.clearance,
            spindle_speed=args.speed,
            tool=args.tool,
            **numbers,
        )
    except (Refused, ValueError, RuntimeError) as err:
        return _refusal("drum-groove", err)
    if note is not None:
        sys.stderr.write(f"fanuc-macro drum-groove: {said(note)}\n")
    sys.stdout.write(program.text)
    _write_drum_summary(program, len(points))
    return EXIT_OK


def _write_drum_summary(program: Any, points: int) -> None:
    """The crown fitted and the blocks the macro saves, on standard error."""
    crown = program.crown
    if crown is not None:
        line = tr(
            "crown: R{radius:.1f} mm, the best-fit circle of the {points} points (all within "
            "{deviation:.2g} mm of it)",
            radius=crown.radius,
            points=points,
            deviation=crown.max_deviation,
        )
    else:
        line = tr("crown: none fitted (fewer than 3 points, or points on a line)")
    cuts = tr(
        "cuts: {cuts} G32 blocks in {passes} passes of {segments} taper segments",
        cuts=program.g32_cuts,
        passes=program.passes,
        segments=program.segments_per_pass,
    )
    blocks = tr(
        "blocks: this program {program}; the same cut written out without a macro {plain} "
        "({motions} motions + {setup} set-up): {saved} saved",
        program=program.program_blocks,
        plain=program.plain_blocks,
        motions=program.motion_blocks,
        setup=program.setup_blocks,
        saved=program.plain_blocks - program.program_blocks,
    )
    for text in (line, cuts, blocks):
        sys.stderr.write(said(text) + "\n")


def _shown(value: object) -> str:
    return f"{value:g}" if isinstance(value, float) else str(value)


def _option(
    parser: argparse.ArgumentParser,
    name: str,
    kind: Callable[[str], object],
    default: object,
    metavar: str,
    text: Text,
    shown: str | None = None,
) -> None:
    """An option whose help ends with its default, as the paper's value."""
    value = _shown(default) if shown is None else shown
    parser.add_argument(
        name,
        type=kind,
        default=default,
        metavar=metavar,
        help=said(tr("{what} (default {value})", what=text, value=value)),
    )


def _into(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--into",
        metavar="FILE",
        help=said(
            tr(
                "the program file the program goes into: a program number it has is not taken (the "
                "first free one after it is, and standard error says which); a number given that "
                "it has is refused"
            )
        ),
    )


def _add_arc_thread(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    arc = subparsers.add_parser(
        "arc-thread",
        help=said(tr("print the large-pitch arc thread program (fitting method, G32 cuts)")),
        description=said(
            tr(
                "Print the large-pitch arc thread of Ren Guozhu's paper by the fitting "
                "method: a main program, a G65 roughing macro called once per layer and a G65 "
                "finishing macro, each cut a G32 at a tool-centre angle on the groove's arc.  The "
                "defaults are the paper's part (OD 93.82, R10, r1.2, pitch 25, layers 108 and 103 "
                "of 7 cuts, finishing on 100 in 19 cuts: 33 G32 cuts).  Diameters are on X."
            )
        ),
    )
    _option(arc, "--outer-diameter", _number, 93.82, "D", tr("thread outer diameter (A, #1)"))
    _option(arc, "--groove-radius", _number, 10.0, "R", tr("groove (profile) radius R (I, #4)"))
    _option(arc, "--tool-radius", _number, 1.2, "r", tr("roughing tool nose radius r (R, #18)"))
    _option(
        arc,
        "--finishing-tool-radius",
        _number,
        None,
        "r",
        tr("finishing tool nose radius"),
        shown="--tool-radius",
    )
    feed = arc.add_mutually_exclusive_group()
    feed.add_argument(
        "--pitch",
        type=_number,
        default=25.0,
        metavar="P",
        help=said(tr("pitch of the single-start thread, the G32 F (C, #3) (default 25)")),
    )
    feed.add_argument(
        "--lead",
        type=_number,
        default=None,
        metavar="L",
        help=said(
            tr(
                "the lead as the G32 F instead of --pitch (a multi-start thread's other starts "
                "are not generated)"
            )
        ),
    )
    _option(arc, "--length", _number, 113.0, "MM", tr("cut end distance: G32 to Z-MM (B, #2)"))
    _option(arc, "--run-in", _number, 50.0, "Z", tr("Z of the groove centre at the start (K, #6)"))
    _option(
        arc,
        "--layers",
        _diameters,
        (108.0, 103.0),
        "J,J,...",
        tr("roughing groove-centre diameters, one layer each, deepest last (J, #5)"),
        shown="108,103",
    )
    _option(arc, "--cuts-per-layer", _count, 7, "N", tr("G32 cuts of each roughing layer (D, #7)"))
    _option(
        arc, "--finishing-diameter", _number, 100.0, "J", tr("finishing groove-centre diameter")
    )
    _option(arc, "--finishing-cuts", _count, 19, "N", tr("G32 cuts of the finishing"))
    _option(arc, "--rough-tool", _count, 1, "T", tr("roughing tool and offset number"))
    _option(arc, "--finishing-tool", _count, 2, "T", tr("finishing tool and offset number"))
    _option(arc, "--rough-speed", _speed, 300, "S", tr("roughing spindle speed, rpm"))
    _option(arc, "--finishing-speed", _speed, 400, "S", tr("finishing spindle speed, rpm"))
    _option(arc, "--spindle", _spindle, 3, "M3|M4", tr("spindle direction"), shown="M3")
    _option(arc, "--retract-x", _number, 140.0, "X", tr("X the tool retracts to after each cut"))
    _option(arc, "--start-x", _number, 150.0, "X", tr("start point X, where each macro begins"))
    _option(arc, "--start-z", _number, 100.0, "Z", tr("start point Z"))
    _option(arc, "--main", _program, None, "O0002", tr("main program number"), shown="O0002")
    _option(arc, "--rough", _program, None, "O0003", tr("roughing macro number"), shown="O0003")
    _option(
        arc, "--finishing", _program, None, "O0005", tr("finishing macro number"), shown="O0005"
    )
    _into(arc)
    arc.set_defaults(func=cmd_arc_thread)


def _add_drum_groove(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    drum = subparsers.add_parser(
        "drum-groove",
        help=said(tr("print the drum-shaped spiral groove program (chained G32 taper threads)")),
        description=said(
            tr(
                "Print the drum-shaped spiral groove of Pu Yanmin's paper: a main program "
                "that enters the profile points in common variables and one G65 macro that cuts "
                "the groove layer by layer, each pass a G32 run-in and a chain of G32 taper "
                "threads through the points.  The default profile is the paper's table 1 (12 "
                "points).  Standard error gets the crown radius fitted to the points and how many "
                "blocks the macro saves against the same cut written out."
            )
        ),
    )
    points = drum.add_mutually_exclusive_group()
    points.add_argument(
        "--points",
        metavar="X,Z;X,Z;...",
        help=said(
            tr("profile points, X diameter and Z, in cutting order (default: the paper's 12)")
        ),
    )
    points.add_argument(
        "--points-file",
        metavar="FILE.csv",
        help=said(
            tr(
                "profile points, one X diameter, Z a row (',', ';' or tab between; a header row "
                "is skipped)"
            )
        ),
    )
    drum.add_argument(
        "--pitch",
        type=_number,
        required=True,
        metavar="P",
        help=said(
            tr(
                "the groove's lead, the G32 F; required: the paper's figure 2, which gives it, "
                "is lost"
            )
        ),
    )
    _option(drum, "--layers", _count, 9, "N", tr("layers, each a radial step deeper"))
    _option(drum, "--radial-step", _number, 0.8, "MM", tr("depth of each layer, on the radius"))
    _option(drum, "--axial-step", _number, 0.5, "MM", tr("Z shift between the cuts of a layer"))
    _option(drum, "--cuts-per-layer", _count, 1, "N", tr("cuts of each layer, an axial step apart"))
    _option(
        drum,
        "--direction",
        _direction,
        "left",
        "left|right",
        tr("where the cuts of a layer step: left, toward -Z (the paper's T1), or right (T2)"),
    )
    _option(drum, "--run-in", _number, 10.0, "MM", tr("straight G32 run-in before the first point"))
    _option(drum, "--clearance", _number, 10.0, "MM", tr("retract above the largest diameter"))
    _option(drum, "--speed", _speed, 80, "S", tr("spindle speed, rpm"))
    _option(drum, "--tool", _count, 1, "T", tr("tool and offset number"))
    _option(drum, "--main", _program, None, "O0010", tr("main program number"), shown="O0010")
    _option(drum, "--macro", _program, None, "O0001", tr("macro number"), shown="O0001")
    _into(drum)
    drum.set_defaults(func=cmd_drum_groove)


def add_generator_commands(
    subparsers: argparse._SubParsersAction[argparse.ArgumentParser],
) -> None:
    """Register ``arc-thread`` and ``drum-groove`` on the ``fanuc-macro`` sub-command parsers."""
    _add_arc_thread(subparsers)
    _add_drum_groove(subparsers)
