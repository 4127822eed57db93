"""The command line: ``fanuc-macro check``, ``trace``, ``plot``, ``thread``, ``arc-thread``,
``drum-groove``, ``hover``, ``definition`` and ``format``."""

from __future__ import annotations

from ..code_cache import install_code_cache, save_code_cache

# Before the imports below build the package's dataclasses: from cached code (code_cache.py).
install_code_cache("cli")

import argparse
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from .. import __version__
from ..analysis import analyse, log_failure
from ..config import CONTROLLERS, NOT_SET, Config
from ..diagnostics import REPORT_INTERNAL_ERROR, RULES, Diagnostic, Severity
from ..ide.trace import motion_text, trace  # small: what it uses, the check uses too
from ..workspace import PROGRAM_SUFFIXES, Workspace, is_program_file
from .format_command import add_format_command
from .generators import add_generator_commands
from .plot_command import add_plot_command
from .thread import add_thread_command

EXIT_OK = 0
EXIT_ERRORS = 1
EXIT_USAGE = 2


class UsageError(Exception):
    pass


def collect_files(paths: Sequence[str], empty: list[str] | None = None) -> list[Path]:
    """The program files of ``paths``: a file as given, a folder's program files
    (``workspace.is_program_file``) in order. A folder without any is added to ``empty``."""
    files: list[Path] = []
    for raw in paths:
        path = Path(raw)
        if path.is_dir():
            found = [p for p in sorted(path.rglob("*")) if p.is_file() and is_program_file(p)]
            if not found and empty is not None:
                empty.append(raw)
            files.extend(found)
        elif path.is_file():
            files.append(path)
        else:
            raise UsageError(f"fanuc-macro: no such file or directory: {raw}")
    return files


def one_program_file(command: str, raw: str) -> Path:
    """The FILE of ``trace``, ``plot``, ``hover`` and ``definition``: one file, not a folder."""
    path = Path(raw)
    if path.is_dir():
        raise UsageError(f"fanuc-macro: {command} takes one program file; {raw} is a folder")
    if not path.is_file():
        raise UsageError(f"fanuc-macro: no such file: {raw}")
    return path


def _format_text(path: str, d: Diagnostic) -> str:
    return f"{path}:{d.line + 1}:{d.column + 1}: {d.code} {d.severity.value} {d.message}"


def _as_json(path: str, d: Diagnostic) -> dict[str, object]:
    return {
        "path": path,
        "line": d.line + 1,
        "column": d.column + 1,
        "end_line": d.end_line + 1,
        "end_column": d.end_column + 1,
        "severity": d.severity.value,
        "code": d.code,
        "message": d.message,
    }


def _config(args: argparse.Namespace) -> Config:
    return Config(
        controller=args.controller,
        disabled=args.disable or frozenset(),
        max_spindle_speed=args.max_spindle_speed,
        max_threading_feed=args.max_threading_feed,
        extended_commons=args.extended_commons,
        max_line_length=args.max_line_length,
        max_blocks=args.max_blocks,
        max_file_size=args.max_file_size,
        step_budget=args.step_budget,
        time_limit=args.time_limit,
    )


def _rule_codes(text: str) -> frozenset[str]:
    """``--disable``: comma-separated rule codes, in any case; an unknown one is a usage error
    that names the nearest known code."""
    codes = [c.strip().upper() for c in text.split(",") if c.strip()]
    unknown = [c for c in codes if c not in RULES]
    if len(unknown) == 1:
        raise argparse.ArgumentTypeError(
            f"unknown rule code {unknown[0]!r}: the nearest known one is "
            f"{_nearest_rule(unknown[0])}"
        )
    if unknown:
        shown = ", ".join(f"{c!r} (nearest: {_nearest_rule(c)})" for c in unknown)
        raise argparse.ArgumentTypeError(f"unknown rule codes {shown}")
    return frozenset(codes)


def _edit_distance(a: str, b: str) -> int:
    row = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        previous, row[0] = row[0], i
        for j, cb in enumerate(b, 1):
            previous, row[j] = row[j], min(row[j] + 1, row[j - 1] + 1, previous + (ca != cb))
    return row[-1]


def _nearest_rule(text: str) -> str:
    """The known rule nearest to ``text``, by its code (``MB1O1``) or by its name
    (``lowercse``): the fewest characters to change, of the code's or the name's length."""

    def distance(code: str) -> float:
        by_code = _edit_distance(text, code) / max(len(text), len(code))
        name = RULES[code].name
        by_name = _edit_distance(text.lower(), name) / max(len(text), len(name))
        return min(by_code, by_name)

    best = min(sorted(RULES), key=distance)
    return f"{best} {RULES[best].name}"


def _whole(text: str) -> int:
    try:
        value = int(text.replace("_", ""))
    except ValueError:
        value = 0
    if value <= 0:
        raise argparse.ArgumentTypeError(f"not a positive whole number: {text!r}")
    return value


def _add_analysis_options(parser: argparse.ArgumentParser) -> None:
    """How much the analysis reads and runs, as the editor's fanuc-macro.analysis.* settings."""
    default = Config()
    parser.add_argument(
        "--max-line-length",
        type=_whole,
        default=default.max_line_length,
        metavar="CHARS",
        help=f"a longer block is not analysed (MB011; default {default.max_line_length})",
    )
    parser.add_argument(
        "--max-blocks",
        type=_whole,
        default=default.max_blocks,
        metavar="N",
        help=f"blocks of a file the analysis reads (MB013; default {default.max_blocks:,})",
    )
    parser.add_argument(
        "--max-file-size",
        type=_whole,
        default=default.max_file_size,
        metavar="CHARS",
        help=f"characters of a file the analysis reads (MB013; default {default.max_file_size:,})",
    )
    parser.add_argument(
        "--step-budget",
        type=_whole,
        default=default.step_budget,
        metavar="BLOCKS",
        help=f"blocks one run of a program may execute (default {default.step_budget:,})",
    )
    parser.add_argument(
        "--time-limit",
        type=_positive,
        default=default.time_limit,
        metavar="SECONDS",
        help=f"the safety net of a slow or busy machine (default {default.time_limit:g} s)",
    )


def _positive(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = 0.0
    if not value > 0 or value == NOT_SET:
        raise argparse.ArgumentTypeError(f"not a positive number: {text!r}")
    return value


def _add_machine_options(parser: argparse.ArgumentParser) -> None:
    """The machine's limits and options, as the editor's fanuc-macro.machine.* settings: a
    limit not given is not checked."""
    parser.add_argument(
        "--max-spindle-speed",
        type=_positive,
        default=NOT_SET,
        metavar="RPM",
        help="the machine's maximum spindle speed (MB602); not checked when not given",
    )
    parser.add_argument(
        "--max-threading-feed",
        type=_positive,
        default=NOT_SET,
        metavar="MM_PER_MIN",
        help="the machine's largest feed while threading, S x lead (MB807); not checked when "
        "not given",
    )
    parser.add_argument(
        "--extended-commons",
        action="store_true",
        help="the machine has the extended common variables #200-#499 (no MB303)",
    )


def cmd_check(args: argparse.Namespace) -> int:
    empty: list[str] = []
    files = collect_files(args.paths, empty)
    for folder in empty:
        sys.stderr.write(f"fanuc-macro: no programs found in {folder}\n")
    if not files:  # every PATH is a folder without programs
        return EXIT_USAGE
    config = _config(args)
    workspace = Workspace(config)
    for path in files:
        workspace.add_bytes(str(path), path.read_bytes())
    programs = workspace.program_numbers()
    records: list[dict[str, object]] = []
    any_error = False
    out = sys.stdout
    for path in files:
        analysis = workspace.analyse(str(path), workspace_programs=programs)
        stopped = analysis.facts.stop_message() if analysis.facts is not None else None
        if stopped is not None:  # the safety net: not a finding of the program's
            sys.stderr.write(f"{path}: {stopped}\n")
        for d in analysis.diagnostics:
            any_error |= d.severity is Severity.ERROR
            if args.format == "json":
                records.append(_as_json(str(path), d))
            else:
                out.write(_format_text(str(path), d) + "\n")
    if args.format == "json":
        import json

        json.dump(records, out, ensure_ascii=False, indent=1)
        out.write("\n")
    return EXIT_ERRORS if any_error else EXIT_OK


def read_one(command: str, workspace: Workspace, raw: str) -> str:
    """Read the FILE of ``trace``, ``plot``, ``hover`` or ``definition`` into ``workspace``;
    its key. It is one file, not a folder, and a program text (``check`` reports a file that
    is not as MB007 and goes on; a command that runs or looks into the file stops)."""
    path = one_program_file(command, raw)
    key = str(path)
    workspace.add_bytes(key, path.read_bytes())
    reason = workspace.not_text(key)
    if reason is not None:
        raise UsageError(f"fanuc-macro: {raw}: {reason}")
    return key


def _program_number(text: str) -> int:
    digits = text.upper().lstrip("O")
    if not digits.isdigit():
        raise argparse.ArgumentTypeError(f"not a program number: {text!r} (write O4009 or 4009)")
    return int(digits)


def _traced_workspace(args: argparse.Namespace) -> tuple[Config, Workspace, str]:
    """The file of ``trace`` or ``plot`` and the ``--with`` files it calls, read; its URI."""
    config = _config(args)
    workspace = Workspace(config)
    uri = read_one(args.command, workspace, args.file)
    for extra in collect_files(args.with_files or []):
        if str(extra) != uri:
            workspace.add_bytes(str(extra), extra.read_bytes())
    if args.entry is not None and workspace.find_program(args.entry) is None:
        raise UsageError(f"fanuc-macro: no program O{args.entry:04d} in {args.file}")
    return config, workspace, uri


def cmd_trace(args: argparse.Namespace) -> int:
    import json

    config, workspace, uri = _traced_workspace(args)
    doc = workspace.document(uri)
    assert doc is not None
    result = trace(uri, doc, workspace.index(uri), workspace.others(uri), config, args.entry)
    out = sys.stdout
    if args.format == "json":
        json.dump(result, out, ensure_ascii=False, indent=1)
        out.write("\n")
        return EXIT_OK
    for m in result["motions"]:
        out.write(motion_text(m) + "\n")
    summary = result["summary"]
    by_code = ", ".join(f"{k} {v}" for k, v in summary["by_code"].items())
    out.write(
        f"{summary['motions']} motions ({by_code}); {summary['blocks_executed']} blocks executed\n"
    )
    if summary["stopped"]:
        out.write(f"stopped early: {summary.get('stop_message') or summary['stopped']}\n")
    for f in summary["findings"]:
        out.write(f"line {f['line']}: {f['message']}\n")
    return EXIT_OK


def cmd_hover(args: argparse.Namespace) -> int:
    from .ide_commands import cmd_hover as hover

    return hover(args, _config(args))


def cmd_definition(args: argparse.Namespace) -> int:
    from .ide_commands import cmd_definition as definition

    return definition(args, _config(args))


def _add_place_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
    logs: argparse.ArgumentParser,
    name: str,
    what: str,
) -> argparse.ArgumentParser:
    """A command about the place LINE COLUMN of FILE, as the editor's request of that name."""
    command = sub.add_parser(
        name,
        parents=[logs],
        help=f"print {what} at LINE COLUMN of FILE (1-based, as editors show them; "
        "exit status 1 when there is none)",
    )
    command.add_argument("file", metavar="FILE", help="the program file")
    command.add_argument("line", type=_whole, metavar="LINE", help="the line, from 1")
    command.add_argument(
        "column", type=_whole, metavar="COLUMN", help="the column in characters, from 1"
    )
    command.add_argument(
        "--with",
        dest="with_files",
        nargs="*",
        metavar="PATH",
        help="more files or folders with the programs it calls",
    )
    _add_format_option(command, "the answer as text (default) or as JSON")
    _add_rule_options(command)
    _add_machine_options(command)
    _add_analysis_options(command)
    return command


def _add_format_option(parser: argparse.ArgumentParser, what: str) -> None:
    parser.add_argument("--format", choices=("text", "json"), default="text", help=what)


def _add_rule_options(parser: argparse.ArgumentParser) -> None:
    """The controller and the rules, as the editor's fanuc-macro.controller and
    fanuc-macro.rules.disabled settings."""
    parser.add_argument(
        "--controller",
        choices=CONTROLLERS,
        default="0i-TF",
        help="the control the programs are for (default 0i-TF)",
    )
    parser.add_argument(
        "--disable",
        type=_rule_codes,
        metavar="CODES",
        help="comma-separated rule codes to skip, e.g. MB006,MB403 (docs/rules.md lists them)",
    )


def _add_run_options(parser: argparse.ArgumentParser) -> None:
    """What ``trace`` and ``plot`` run: a file, where to start, the files it calls, the
    machine."""
    parser.add_argument("file", metavar="FILE", help="the program file to run")
    parser.add_argument("--entry", type=_program_number, help="program to start from, e.g. O4009")
    parser.add_argument(
        "--with",
        dest="with_files",
        nargs="*",
        metavar="PATH",
        help="more files or folders with the programs it calls",
    )
    _add_rule_options(parser)
    _add_machine_options(parser)
    _add_analysis_options(parser)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="fanuc-macro", description="Check FANUC Custom Macro B programs."
    )
    parser.add_argument("--version", action="version", version=f"fanuc-macro {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    # How the analyser's own failures (MB000) are told: by default one line in the output.
    logs = argparse.ArgumentParser(add_help=False)
    logs.add_argument(
        "--verbose", action="store_true", help="print the traceback of an internal error"
    )
    logs.add_argument("--log-file", metavar="PATH", help="write the analyser's log to this file")

    check = sub.add_parser(
        "check", parents=[logs], help="report problems in programs (files or folders)"
    )
    check.add_argument(
        "paths",
        nargs="+",
        metavar="PATH",
        help="program files, or folders whose program files are checked together (by "
        f"extension: {', '.join(sorted(PROGRAM_SUFFIXES))}; without one, a name such as "
        "O1234 or a first line '%%' or 'O<number>')",
    )
    _add_format_option(
        check, "one line PATH:LINE:COLUMN: CODE severity message each (default), or a JSON list"
    )
    _add_rule_options(check)
    _add_machine_options(check)
    _add_analysis_options(check)
    check.set_defaults(func=cmd_check)

    tr = sub.add_parser("trace", parents=[logs], help="print the motion blocks a program executes")
    _add_run_options(tr)
    _add_format_option(tr, "one line a motion and a summary (default), or JSON")
    tr.set_defaults(func=cmd_trace)

    add_plot_command(sub, logs)

    _add_place_command(sub, logs, "hover", "the hover text (markdown)").set_defaults(func=cmd_hover)
    _add_place_command(
        sub, logs, "definition", "where what is there is defined (PATH:LINE:COLUMN)"
    ).set_defaults(func=cmd_definition)

    add_thread_command(sub)
    add_generator_commands(sub)
    add_format_command(sub)
    return parser


def _log_to(verbose: bool, log_file: str | None) -> Callable[[], None] | None:
    """Where the package's log goes: tracebacks only to a file or with --verbose, never to the
    user's terminal by default (``analysis.log_failure`` gives the package's logger a
    NullHandler when it has none). Returns what undoes it; None when neither is asked for:
    then ``logging`` is not even imported, unless something fails."""
    if not (verbose or log_file):
        return None
    import logging

    handlers: list[logging.Handler] = []
    if log_file:
        handlers.append(logging.FileHandler(log_file, encoding="utf-8"))
    if verbose:
        handlers.append(logging.StreamHandler(sys.stderr))
    package = logging.getLogger("fanuc_macro")
    level = package.level
    for handler in handlers:
        handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
        package.addHandler(handler)
    package.setLevel(logging.INFO)

    def undo() -> None:  # main() may run again in the same process (tests do)
        for handler in handlers:
            package.removeHandler(handler)
            handler.close()
        package.setLevel(level)

    return undo


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # argparse exits 2 on a usage problem, 0 for --help
        return int(exc.code or 0)
    stop_logging = _log_to(getattr(args, "verbose", False), getattr(args, "log_file", None))
    try:
        result: int = args.func(args)
        return result
    except UsageError as err:
        sys.stderr.write(f"{err}\n")
        return EXIT_USAGE
    except BrokenPipeError:
        return EXIT_OK
    except Exception as err:  # the analyser's bug: one line here, the traceback in the log
        log_failure(__name__, "fanuc-macro %s failed", args.command)
        message = f"internal error: {err!r}; {REPORT_INTERNAL_ERROR}"
        if getattr(args, "format", "text") == "json":
            import json

            json.dump({"error": message}, sys.stdout, ensure_ascii=False, indent=1)
            sys.stdout.write("\n")
        sys.stderr.write(f"fanuc-macro: {message}\n")
        return EXIT_ERRORS
    finally:
        save_code_cache()
        if stop_logging is not None:
            stop_logging()


if __name__ == "__main__":
    sys.exit(main())


__all__ = ["analyse", "main"]
