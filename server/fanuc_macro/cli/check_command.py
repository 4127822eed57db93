"""``fanuc-macro check PATH...``: the diagnostics of programs on standard output, one summary
line on standard error, and an exit status as ruff's and ESLint's.

Every path given is checked even when another is bad: a path that is not there, a folder
without programs or a file that cannot be read is told on standard error and makes the status
2 (a usage problem) once the others are checked."""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from collections.abc import Sequence

from ..config import Config
from ..diagnostics import Diagnostic, Severity
from ..ide import machine_text
from ..program_files import Found, find_programs
from ..workspace import Workspace
from .streams import STDIN, read_stdin, writes_unicode

EXIT_OK = 0
EXIT_FINDINGS = 1
EXIT_USAGE = 2
EXIT_INTERNAL = 3
INTERNAL_ERROR = "MB000"  # the analyser's own failure, reported as a diagnostic
SEVERITIES = tuple(Severity)  # the most severe first
SHOWN_NOT_PROGRAMS = 3  # names in the summary line; the rest are counted


def format_text(path: str, d: Diagnostic) -> str:
    return f"{path}:{d.line + 1}:{d.column + 1}: {d.code} {d.severity.value} {d.message}"


def as_json(path: str, d: Diagnostic) -> dict[str, object]:
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


def _plural(count: int, word: str, plural: str | None = None) -> str:
    return f"{count} {word if count == 1 else plural or word + 's'}"


def summary_line(checked: int, not_programs: Sequence[str], counts: Counter[Severity]) -> str:
    """``fanuc-macro: 12 files checked, 3 skipped (not programs: a.txt, b.txt, c.txt, +1 more),
    2 errors, 5 warnings``, and ``, N information`` and ``, N hints`` when there are any."""
    skipped = f"{len(not_programs)} skipped"
    if not_programs:
        shown = ", ".join(not_programs[:SHOWN_NOT_PROGRAMS])
        more = len(not_programs) - SHOWN_NOT_PROGRAMS
        skipped += f" (not programs: {shown}{f', +{more} more' if more > 0 else ''})"
    parts = [
        f"{_plural(checked, 'file')} checked",
        skipped,
        _plural(counts[Severity.ERROR], "error"),
        _plural(counts[Severity.WARNING], "warning"),
    ]
    if counts[Severity.INFORMATION]:
        parts.append(f"{counts[Severity.INFORMATION]} information")
    if counts[Severity.HINT]:
        parts.append(_plural(counts[Severity.HINT], "hint"))
    return "fanuc-macro: " + ", ".join(parts)


def exit_status(
    counts: Counter[Severity],
    fail_on: Severity,
    max_warnings: int | None,
    usage_problem: bool,
    internal_error: bool,
) -> int:
    """3 for the analyser's own failure, 2 for a usage problem, 1 for a finding at or above
    ``fail_on`` or more warnings than ``max_warnings``, else 0."""
    if internal_error:
        return EXIT_INTERNAL
    if usage_problem:
        return EXIT_USAGE
    failing = SEVERITIES[: SEVERITIES.index(fail_on) + 1]
    if any(counts[s] for s in failing):
        return EXIT_FINDINGS
    if max_warnings is not None and counts[Severity.WARNING] > max_warnings:
        return EXIT_FINDINGS
    return EXIT_OK


def _found(paths: Sequence[str], exclude: Sequence[str]) -> Found:
    return find_programs([p for p in paths if p != STDIN], exclude)


def cmd_check(args: argparse.Namespace, config: Config) -> int:
    err = sys.stderr
    paths: list[str] = args.paths
    stdin_name: str | None = args.stdin_filename
    if paths.count(STDIN) > 1:
        err.write("fanuc-macro: standard input (-) can be checked once\n")
        return EXIT_USAGE
    if stdin_name is not None and STDIN not in paths:
        err.write("fanuc-macro: --stdin-filename names standard input: give - among the paths\n")
        return EXIT_USAGE
    found = _found(paths, args.exclude or ())
    for raw in found.missing:
        err.write(f"fanuc-macro: no such file or directory: {raw}\n")
    for folder in found.empty:
        err.write(f"fanuc-macro: no programs found in {folder}\n")
    usage_problem = bool(found.missing or found.empty)

    workspace = Workspace(config)
    keys: list[str] = []
    if STDIN in paths:
        key = stdin_name or STDIN
        workspace.add_bytes(key, read_stdin())
        keys.append(key)
    for path in found.programs:
        key = str(path)
        if key in keys:  # the text on standard input stands for the file of its name
            continue
        try:
            data = path.read_bytes()
        except OSError as error:
            err.write(f"fanuc-macro: cannot read {path}: {error.strerror or error}\n")
            usage_problem = True
            continue
        workspace.add_bytes(key, data)
        keys.append(key)

    programs = workspace.program_numbers()
    records: list[dict[str, object]] = []
    counts: Counter[Severity] = Counter()
    internal_error = False
    out = sys.stdout
    for key in keys:
        analysis = workspace.analyse(key, workspace_programs=programs)
        stopped = analysis.facts.stop_message() if analysis.facts is not None else None
        if stopped is not None:  # the safety net: not a finding of the program's
            err.write(f"{key}: {stopped}\n")
        if args.verbose and analysis.config is not None:
            err.write(f"{key}: {machine_text(analysis.config)}\n")
        for d in analysis.diagnostics:
            counts[d.severity] += 1
            internal_error |= d.code == INTERNAL_ERROR
            if args.format == "json":
                records.append(as_json(key, d))
            else:
                out.write(format_text(key, d) + "\n")
    if args.format == "json":
        import json

        json.dump(records, out, ensure_ascii=not writes_unicode(out), indent=1)
        out.write("\n")
    out.flush()  # the findings before the summary, when both go to one terminal
    if not args.quiet:
        not_programs = [str(p) for p in found.not_programs]
        err.write(summary_line(len(keys), not_programs, counts) + "\n")
    return exit_status(
        counts, Severity(args.fail_on), args.max_warnings, usage_problem, internal_error
    )


__all__ = ("as_json", "cmd_check", "exit_status", "format_text", "summary_line")
