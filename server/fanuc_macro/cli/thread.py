"""``fanuc-macro thread DESIGNATION --length L``: print the symmetric thread module.

The main program (O4009 shape, O4010 internal) enters D, P, L, es/EI and Td2/TD2 from the
ISO 965-1 tables; the sub-program (O3331 / O3330) is the seed paper's, extended as its
"parameter adjustment" paragraph says: flank infeed, taper, multi-start (``M24xPh4P2-6g``)
and left-hand (``M20x2-6g-LH``) threads.  A designation that cannot be read, is not in the
tables, or does not say whether the thread is external or internal (all capitals with a class
both kinds have, ``M50X3-5G6G``, or no class) without ``--external`` / ``--internal``, exits 2
with a one-line message.
"""

from __future__ import annotations

import argparse
import re
import sys

from ..translation import tr
from .language import said, said_error

__all__ = ("add_thread_command", "cmd_thread")

EXIT_OK = 0
EXIT_USAGE = 2
# The generator's INFEEDS, named here so that building the parser does not import it.
INFEED_CHOICES = ("symmetric", "alternate", "left", "right")


def _coefficient(text: str) -> float:
    """``0.2``, ``0.2/3`` (a fraction as the paper writes it), ``steel`` or ``molybdenum``."""
    # The generator is imported by the thread command only: ``check`` starts without it.
    from ..generators import MATERIAL_COEFFICIENTS

    named = MATERIAL_COEFFICIENTS.get(text.strip().lower())
    if named is not None:
        return named
    match = re.fullmatch(r"\s*(\d+(?:\.\d*)?|\.\d+)\s*(?:/\s*(\d+(?:\.\d*)?)\s*)?", text)
    if match is None:
        raise argparse.ArgumentTypeError(
            said(
                tr(
                    "the coefficient is a number, a fraction or a material (e.g. 0.2, 0.2/3, "
                    "steel, molybdenum), not {given}",
                    given=text,
                )
            )
        )
    value = float(match.group(1))
    if match.group(2) is not None:
        divisor = float(match.group(2))
        if divisor == 0:
            raise argparse.ArgumentTypeError(
                said(tr("the coefficient {given} divides by zero", given=text))
            )
        value /= divisor
    if value <= 0:
        raise argparse.ArgumentTypeError(
            said(tr("the coefficient {given} must be positive", given=text))
        )
    return value


def _program(text: str) -> int:
    """``O4009``, ``o4009`` or ``4009``."""
    match = re.fullmatch(r"\s*[Oo]?(\d{1,4})\s*", text)
    if match is None or int(match.group(1)) == 0:
        raise argparse.ArgumentTypeError(
            said(tr("a program number is O0001-O9999, not {given}", given=text))
        )
    return int(match.group(1))


def _taper(text: str) -> float:
    """``1:16`` (a diametral taper as pipe threads give it), ``-1:16`` or ``0.0625``."""
    from ..generators import read_taper  # the generators' reading, the editor's too

    try:
        return read_taper(text)
    except ValueError as err:
        raise argparse.ArgumentTypeError(said_error(err)) from None


def _count(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            said(tr("a whole number is needed, not {given}", given=text))
        ) from None
    if value < 0:
        raise argparse.ArgumentTypeError(
            said(tr("the count {given} must not be negative", given=text))
        )
    return value


def _numbers(args: argparse.Namespace) -> tuple[int | None, int | None, str | None] | str:
    """(main, sub, what moved) for ``--into FILE``: the numbers the file does not have, as
    the editor's command takes them; or the refusal of a number given that the file has."""
    from ..generators import free_numbers, module_numbers, programs_in

    if args.into is None:
        return args.main, args.sub, None
    try:
        with open(args.into, "rb") as file:
            taken = programs_in(file.read())
    except OSError as err:
        why = err.strerror or str(err)
        return said(tr("cannot read {path}: {why}", path=args.into, why=why))
    given = {n for n in (args.main, args.sub) if n is not None}
    for number in sorted(given & taken):
        return said(tr("{path} has O{program:04d} already", path=args.into, program=number))
    paper = module_numbers(args.designation, args.internal, ())
    parts = [
        (part, number)
        for part, number, chosen in zip(
            ("main program", "sub-program"), paper.numbers, (args.main, args.sub), strict=True
        )
        if chosen is None
    ]
    free = free_numbers(parts, taken | given)
    numbers = iter(free.numbers)
    main = args.main if args.main is not None else next(numbers)
    sub = args.sub if args.sub is not None else next(numbers)
    return main, sub, free.note


def cmd_thread(args: argparse.Namespace) -> int:
    from ..generators import SideConflict, SideUndecided, generate_module

    numbers = _numbers(args)
    if isinstance(numbers, str):
        return _refuse(numbers)
    main, sub, note = numbers
    try:
        text = generate_module(
            args.designation,
            args.length,
            args.internal,
            coefficient=args.coefficient,
            spring_passes=args.spring_passes,
            main_number=main,
            sub_number=sub,
            td2_override=args.td2,
            deviation_override=args.deviation,
            infeed=args.infeed,
            taper=args.taper,
        )
    except SideUndecided as err:
        return _refuse(err.question(tr("with --external or --internal")))
    except SideConflict as err:
        given = "--external" if err.designation.internal else "--internal"
        return _refuse(err.refusal(tr("{option} was given", option=given)))
    except ValueError as err:
        return _refuse(said_error(err))
    if note is not None:
        sys.stderr.write(f"fanuc-macro thread: {said(note)}\n")
    sys.stdout.write(text)
    return EXIT_OK


def _refuse(message: str) -> int:
    sys.stderr.write(f"fanuc-macro thread: {' '.join(said(message).split())}\n")
    return EXIT_USAGE


def add_thread_command(
    subparsers: argparse._SubParsersAction[argparse.ArgumentParser],
) -> argparse.ArgumentParser:
    """Register ``thread`` on the ``fanuc-macro`` sub-command parsers."""
    thread = subparsers.add_parser(
        "thread",
        help=said(
            tr("print the symmetric thread module (main + sub-program) for an ISO metric thread")
        ),
        description=said(
            tr(
                "Print the symmetric thread module of Deng Ronggang's paper (main program "
                "O4009 external / O4010 internal, sub-program O3331 / O3330) for an ISO metric "
                "thread, with es/EI and Td2/TD2 from ISO 965-1 and the computed values in "
                "comments.  The tolerance class says the kind of thread in the case ISO 965-1 "
                "writes it: lower case external (5g6g), upper case internal (4H5H).  A designation "
                "without a lower-case letter (M50X3-5G6G, M10-6H) may have lost its case: a class "
                "only one kind has in ISO 965-1 decides (6E external, 4H5H internal); "
                "a class both kinds have (5G6G, 6H), or no class, is refused unless --external or "
                "--internal says which.  A flag that contradicts the class is refused."
            )
        ),
    )
    thread.add_argument(
        "designation",
        metavar="DESIGNATION",
        help=said(
            tr(
                "e.g. M50x3-5g6g (external), M20x1.5-6H (internal), M24xPh4P2-6g (two starts), "
                "M20x2-6g-LH (left hand); M50X3-5G6G needs --external or --internal"
            )
        ),
    )
    thread.add_argument(
        "--length", type=float, required=True, metavar="L", help=said(tr("thread length L (mm)"))
    )
    side = thread.add_mutually_exclusive_group()
    side.add_argument(
        "--internal",
        dest="internal",
        action="store_const",
        const=True,
        default=None,
        help=said(
            tr(
                "an internal thread: needed when the designation does not say (all capitals with "
                "a class both kinds have, M50X3-5G6G, or no class); refused when its class is "
                "external"
            )
        ),
    )
    side.add_argument(
        "--external",
        dest="internal",
        action="store_const",
        const=False,
        help=said(
            tr(
                "an external thread: needed when the designation does not say; refused when its "
                "class is internal"
            )
        ),
    )
    thread.add_argument(
        "--coefficient",
        type=_coefficient,
        default="molybdenum",  # a string default goes through ``type`` when the command runs
        metavar="C",
        help=said(tr("depth coefficient: 0.2 (steel) or 0.2/3 (molybdenum, the paper's; default)")),
    )
    thread.add_argument(
        "--spring-passes",
        type=_count,
        default=8,
        metavar="N",
        help=said(tr("spring passes (default 8)")),
    )
    _add_thread_numbers(thread)
    thread.set_defaults(func=cmd_thread)
    return thread


def _add_thread_numbers(thread: argparse.ArgumentParser) -> None:
    """The module's program numbers, its file, and what replaces the tables and the paper's
    way of cutting."""
    thread.add_argument(
        "--main",
        type=_program,
        default=None,
        metavar="O4009",
        help=said(tr("number of the main program (default O4009 external, O4010 internal)")),
    )
    thread.add_argument(
        "--sub",
        type=_program,
        default=None,
        metavar="O3331",
        help=said(tr("number of the sub-program (default O3331 external, O3330 internal)")),
    )
    thread.add_argument(
        "--into",
        default=None,
        metavar="FILE",
        help=said(
            tr(
                "the program file the module goes into: where it has the paper's numbers (O4009 "
                "and O3331, internal O4010 and O3330), the module takes the first free ones after "
                "them, and standard error says which; a --main or --sub it has is refused"
            )
        ),
    )
    thread.add_argument(
        "--td2",
        type=float,
        default=None,
        metavar="MM",
        help=said(tr("Td2/TD2 instead of the table's")),
    )
    thread.add_argument(
        "--deviation",
        type=float,
        default=None,
        metavar="MM",
        help=said(tr("es/EI magnitude instead of the table's")),
    )
    thread.add_argument(
        "--infeed",
        choices=INFEED_CHOICES,
        default="symmetric",
        help=said(
            tr(
                "how the rough passes go down: symmetric, both flanks each pass (the paper's; "
                "default); alternate, the left flank one pass and the right the next (the "
                "left-right method); left or right, one flank only (as G76)"
            )
        ),
    )
    thread.add_argument(
        "--taper",
        type=_taper,
        default=0.0,
        metavar="1:16",
        help=said(
            tr(
                "a taper thread: the diameter change per length (1:16, or 0.0625); the nominal "
                "diameter is the one at Z0, an external thread growing toward -Z, an internal one "
                "shrinking (a negative taper the other way)"
            )
        ),
    )
