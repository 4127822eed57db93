"""``fanuc-macro format FILE``: the file as the editor's formatting writes it (ide/formatting.py),
printed, checked (``--check``) or written back (``--write``) in the file's own encoding."""

from __future__ import annotations

import argparse
import sys

from ..config import SPACING, FormatSettings

EXIT_OK = 0
EXIT_WOULD_CHANGE = 1
EXIT_USAGE = 2


def cmd_format(args: argparse.Namespace) -> int:
    from ..ide.formatting import CannotFormat, FormatOptions, format_file
    from . import one_program_file

    path = one_program_file("format", args.file)
    data = path.read_bytes()
    settings = FormatSettings(
        upper_case=not args.keep_case,
        space_between_words=args.space_between_words,
        spaces_around_assignment=args.spaces_around_assignment,
    )
    options = FormatOptions(settings, insert_final_newline=args.final_newline)
    try:
        formatted = format_file(data, options)
    except CannotFormat as err:
        sys.stderr.write(f"fanuc-macro: {args.file}: {err}\n")
        return EXIT_USAGE
    changed = formatted != data
    if args.check:
        if changed:
            sys.stderr.write(f"{args.file}: would be reformatted\n")
        return EXIT_WOULD_CHANGE if changed else EXIT_OK
    if args.write:
        if changed:
            path.write_bytes(formatted)
            sys.stderr.write(f"{args.file}: reformatted\n")
        return EXIT_OK
    sys.stdout.flush()
    sys.stdout.buffer.write(formatted)  # the file's bytes: its encoding and line ends
    sys.stdout.buffer.flush()
    return EXIT_OK


def add_format_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    default = FormatSettings()
    command = sub.add_parser(
        "format",
        help="print FILE formatted (upper case addresses, spaces by the options, no trailing "
        "whitespace; comments, numbers and line ends as they are); exit status 1 with "
        "--check when it would change",
    )
    command.add_argument("file", metavar="FILE", help="the program file")
    what = command.add_mutually_exclusive_group()
    what.add_argument(
        "--check",
        action="store_true",
        help="write nothing but a note; exit status 1 when formatting would change the file, "
        "0 when not",
    )
    what.add_argument("--write", action="store_true", help="write the formatted text back to FILE")
    command.add_argument(
        "--space-between-words",
        choices=SPACING,
        default=default.space_between_words,
        help="'G01 X10. Z-5.' (always), 'G01X10.Z-5.' (never) or as written (keep, the "
        "default), as the setting fanuc-macro.format.spaceBetweenWords",
    )
    command.add_argument(
        "--spaces-around-assignment",
        choices=SPACING,
        default=default.spaces_around_assignment,
        help="'#1 = 2' (always), '#1=2' (never) or as written (keep, the default), as the "
        "setting fanuc-macro.format.spacesAroundAssignment",
    )
    command.add_argument(
        "--keep-case",
        action="store_true",
        help="leave lower case addresses and keywords as they are (fanuc-macro.format."
        "upperCase off)",
    )
    command.add_argument(
        "--final-newline",
        action="store_true",
        help="end the file with a line end when it has none",
    )
    command.set_defaults(func=cmd_format)


__all__ = ["add_format_command", "cmd_format"]
