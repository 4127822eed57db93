"""``fanuc-macro format PATH...``: programs as the editor's formatting writes them
(ide/formatting.py): one file printed, or files and folders (walked as ``check`` walks them)
checked (``--check``) or written back (``--write``) in each file's own encoding."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

from ..config import SPACING, FormatSettings
from ..program_files import find_programs
from ..translation import Text, tr, tr_n
from .language import said, said_error
from .streams import STDIN, read_stdin

EXIT_OK = 0
EXIT_WOULD_CHANGE = 1
EXIT_USAGE = 2
EXIT_STATUS_HELP = tr(
    """\
exit status:
  0  done; with --check, nothing would change
  1  --check: a file would be reformatted
  2  a usage problem: a bad option, several files to print (give --check or --write), a
     path that is not there, a folder without programs, a file that cannot be read or
     formatted (the others are still formatted)
  3  an internal error of fanuc-macro: a bug, please report it"""
)


def _usage_problem(args: argparse.Namespace) -> Text | None:
    """What is wrong with the paths and options together, before anything is read."""
    paths: list[str] = args.paths
    if paths.count(STDIN) > 1:
        return tr("standard input (-) can be formatted once")
    if args.stdin_filename is not None and STDIN not in paths:
        return tr("--stdin-filename names standard input: give - among the paths")
    if args.write and STDIN in paths:
        return tr("standard input cannot be written back: leave out --write (or use --check)")
    if not (args.check or args.write) and (len(paths) > 1 or Path(paths[0]).is_dir()):
        return tr(
            "format prints one file's text: give --check or --write to format several "
            "files or a folder"
        )
    return None


def cmd_format(args: argparse.Namespace) -> int:
    from ..ide import CannotFormat, FormatOptions, format_file

    err = sys.stderr
    problem = _usage_problem(args)
    if problem is not None:
        err.write(f"fanuc-macro: {said(problem)}\n")
        return EXIT_USAGE
    settings = FormatSettings(
        upper_case=not args.keep_case,
        space_between_words=args.space_between_words,
        spaces_around_assignment=args.spaces_around_assignment,
    )
    options = FormatOptions(settings, insert_final_newline=args.final_newline)
    paths: Sequence[str] = args.paths
    found = find_programs([p for p in paths if p != STDIN], args.exclude or ())
    usage_problem = bool(found.missing or found.empty)
    for raw in found.missing:
        err.write(said(tr("fanuc-macro: no such file or directory: {path}", path=raw)) + "\n")
    for folder in found.empty:
        err.write(said(tr("fanuc-macro: no programs found in {path}", path=folder)) + "\n")
    files: list[tuple[str, Path | None]] = []  # the name shown, the file (None: stdin)
    if STDIN in paths:
        files.append((args.stdin_filename or STDIN, None))
    files.extend((str(path), path) for path in found.programs)
    changed = unchanged = 0
    for name, path in files:
        try:
            data = read_stdin() if path is None else path.read_bytes()
        except OSError as error:
            why = error.strerror or str(error)
            err.write(said(tr("fanuc-macro: cannot read {path}: {why}", path=name, why=why)))
            err.write("\n")
            usage_problem = True
            continue
        try:
            formatted = format_file(data, options)
        except CannotFormat as error:
            err.write(f"fanuc-macro: {name}: {said_error(error)}\n")
            usage_problem = True
            continue
        if formatted == data:
            unchanged += 1
        else:
            changed += 1
        if args.check:
            if formatted != data:
                err.write(said(tr("{path}: would be reformatted", path=name)) + "\n")
        elif args.write:
            if formatted != data and path is not None:
                path.write_bytes(formatted)
                err.write(said(tr("{path}: reformatted", path=name)) + "\n")
        else:
            sys.stdout.flush()
            sys.stdout.buffer.write(formatted)  # the file's bytes: its encoding and line ends
            sys.stdout.buffer.flush()
    if args.check:
        line = tr_n(
            "fanuc-macro: {count} file would be reformatted, {unchanged} already formatted",
            "fanuc-macro: {count} files would be reformatted, {unchanged} already formatted",
            changed,
            unchanged=unchanged,
        )
        err.write(said(line) + "\n")
    elif args.write:
        line = tr_n(
            "fanuc-macro: {count} file reformatted, {unchanged} unchanged",
            "fanuc-macro: {count} files reformatted, {unchanged} unchanged",
            changed,
            unchanged=unchanged,
        )
        err.write(said(line) + "\n")
    if usage_problem:
        return EXIT_USAGE
    return EXIT_WOULD_CHANGE if args.check and changed else EXIT_OK


def add_format_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    default = FormatSettings()
    command = sub.add_parser(
        "format",
        help=said(
            tr(
                "print a program formatted (upper case addresses, spaces by the options, no "
                "trailing whitespace; comments, numbers and line ends as they are), or check or "
                "write files and folders; exit status 1 with --check when one would change"
            )
        ),
        epilog=said(EXIT_STATUS_HELP),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    command.add_argument(
        "paths",
        nargs="+",
        metavar="PATH",
        help=said(
            tr(
                "the program file to print (- for standard input); with --check or --write, "
                "program files and folders, walked as check walks them"
            )
        ),
    )
    what = command.add_mutually_exclusive_group()
    what.add_argument(
        "--check",
        action="store_true",
        help=said(
            tr(
                "write nothing but a note for each file formatting would change, and a count; "
                "exit status 1 when it would change one, 0 when not"
            )
        ),
    )
    what.add_argument(
        "--write", action="store_true", help=said(tr("write the formatted text back to each file"))
    )
    command.add_argument(
        "--exclude",
        action="append",
        metavar="GLOB",
        help=said(
            tr("skip what matches in the folders walked, as check --exclude; may be repeated")
        ),
    )
    command.add_argument(
        "--stdin-filename",
        metavar="NAME",
        help=said(tr("the name of the file standard input (-) holds, shown in the notes")),
    )
    command.add_argument(
        "--space-between-words",
        choices=SPACING,
        default=default.space_between_words,
        help=said(
            tr(
                "'G01 X10. Z-5.' (always), 'G01X10.Z-5.' (never) or as written (keep, the "
                "default), as the setting fanuc-macro.format.spaceBetweenWords"
            )
        ),
    )
    command.add_argument(
        "--spaces-around-assignment",
        choices=SPACING,
        default=default.spaces_around_assignment,
        help=said(
            tr(
                "'#1 = 2' (always), '#1=2' (never) or as written (keep, the default), as the "
                "setting fanuc-macro.format.spacesAroundAssignment"
            )
        ),
    )
    command.add_argument(
        "--keep-case",
        action="store_true",
        help=said(
            tr(
                "leave lower case addresses and keywords as they are (fanuc-macro.format."
                "upperCase off)"
            )
        ),
    )
    command.add_argument(
        "--final-newline",
        action="store_true",
        help=said(tr("end the file with a line end when it has none")),
    )
    command.set_defaults(func=cmd_format)


__all__ = ("add_format_command", "cmd_format")
