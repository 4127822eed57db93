"""The command line: ``fanuc-macro check``, ``trace``, ``plot``, ``thread``, ``arc-thread``,
``drum-groove``, ``hover``, ``definition`` and ``format``."""

from __future__ import annotations

from ..code_cache import install_code_cache, save_code_cache

# Before the imports below build the package's dataclasses: from cached code (code_cache.py).
install_code_cache("cli")

import argparse
import sys
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any, TextIO

from .. import __version__
from ..analysis import RULES, analyse, log_failure
from ..config import (
    CONTROLLERS,
    G_CODE_SYSTEMS,
    NOT_SET,
    Config,
    read_program_ranges,
)
from ..diagnostics import REPORT_INTERNAL_ERROR, Severity
from ..ide import motion_text, trace  # small: what it uses, the check uses too
from ..program_files import (
    PROGRAM_SUFFIXES,
    SKIPPED_FOLDERS,
    SNIFFED_SUFFIXES,
    TOOL_FOLDER_SUFFIXES,
    TOOL_MARKERS,
    find_programs,
)
from ..translation import tr
from ..workspace import Workspace
from .format_command import add_format_command
from .generators import add_generator_commands
from .language import (
    AUTO,
    OPTION,
    argparse_in,
    chosen_locale,
    current,
    listed,
    said,
    use,
    wide_help,
    wrapped,
)
from .plot_command import add_plot_command
from .streams import STDIN, read_stdin, tolerate_unencodable
from .thread import add_thread_command

EXIT_OK = 0
EXIT_ERRORS = 1  # check: findings; hover, definition: nothing there; format --check: changes
EXIT_USAGE = 2
EXIT_INTERNAL = 3  # the analyser's own failure


class UsageError(Exception):
    pass


def collect_files(paths: Sequence[str]) -> list[Path]:
    """The program files of ``paths`` (the ``--with`` files): a file as given, a folder's
    programs as ``check`` walks it (``program_files.find_programs``). A path that is not there
    is a usage error."""
    found = find_programs(paths)
    if found.missing:
        raise UsageError(
            said(tr("fanuc-macro: no such file or directory: {path}", path=found.missing[0]))
        )
    return found.programs


def one_program_file(command: str, raw: str) -> Path:
    """The FILE of ``trace``, ``plot``, ``hover`` and ``definition``: one file, not a folder."""
    path = Path(raw)
    if path.is_dir():
        raise UsageError(
            said(
                tr(
                    "fanuc-macro: {command} takes one program file; {path} is a folder",
                    command=command,
                    path=raw,
                )
            )
        )
    if not path.is_file():
        raise UsageError(said(tr("fanuc-macro: no such file: {path}", path=raw)))
    return path


def _config(args: argparse.Namespace, path: str | None) -> Config:
    """The settings of the program at ``path`` (a file or folder; - or None: standard input,
    named by --stdin-filename, else the current folder): the configuration file nearest it
    under the options given here."""
    from .configuration import ConfigResolver, config_or_exit

    resolver = getattr(args, "resolver", None)
    if resolver is None:
        resolver = args.resolver = ConfigResolver(args)
    return config_or_exit(resolver, _anchor(args, path))


def _anchor(args: argparse.Namespace, path: str | None) -> Path | None:
    if path is None or path == STDIN:
        name = getattr(args, "stdin_filename", None)
        return Path(name) if name else None
    return Path(path)


def _custom_call_option(text: str) -> tuple[str, str]:
    code, sep, program = text.partition("=")
    if not sep or not code.strip() or not program.strip():
        raise argparse.ArgumentTypeError(
            said(tr("not CODE=PROGRAM (M165=9022): {given!r}", given=text))
        )
    return code.strip(), program.strip()


def _on_control_option(text: str) -> tuple[tuple[int, int], ...]:
    ranges, problems = read_program_ranges(text)
    if problems:
        raise argparse.ArgumentTypeError(problems[0].removeprefix("machine.programsOnControl: "))
    return ranges


def _rule_code(text: str) -> str:
    """The code of a rule given by its code or its name, in any case (``mb009``,
    ``Tape-Mark-Not-Alone``, ``tape_mark_not_alone``); the text in upper case when it is
    neither."""
    from ..config_file import rule_code

    return rule_code(text) or text.strip().upper()


def _rule_codes(text: str) -> frozenset[str]:
    """``--disable``: comma-separated rule codes or names, in any case; an unknown one is a
    usage error that names the nearest known rule."""
    codes = [_rule_code(c.strip()) for c in text.split(",") if c.strip()]
    unknown = [c for c in codes if c not in RULES]
    if len(unknown) == 1:
        raise argparse.ArgumentTypeError(
            said(
                tr(
                    "unknown rule code {code!r}: the nearest known one is {nearest}",
                    code=unknown[0],
                    nearest=_nearest_rule(unknown[0]),
                )
            )
        )
    if unknown:
        shown = listed(
            tr("{code!r} (nearest: {nearest})", code=c, nearest=_nearest_rule(c)) for c in unknown
        )
        raise argparse.ArgumentTypeError(said(tr("unknown rule codes {codes}", codes=shown)))
    return frozenset(codes)


def _rule_selectors(text: str) -> tuple[str, ...]:
    """``--select``, ``--extend-select``: comma-separated rule codes, names, prefixes of codes
    (MB6) or ALL."""
    from ..config_file import rule_selector

    found: list[str] = []
    for item in (c.strip() for c in text.split(",") if c.strip()):
        selector = rule_selector(item)
        if selector is None:
            raise argparse.ArgumentTypeError(
                said(
                    tr(
                        "{given!r} is not a rule's code or name, a prefix of codes or ALL: the "
                        "nearest known rule is {nearest}",
                        given=item,
                        nearest=_nearest_rule(item.upper()),
                    )
                )
            )
        found.append(selector)
    return tuple(found)


def _severity_option(text: str) -> tuple[str, str]:
    """``--severity CODE=LEVEL``: a rule by code or name and its severity."""
    code, sep, level = text.partition("=")
    levels = [s.value for s in Severity]
    if not sep or level.strip().lower() not in levels:
        raise argparse.ArgumentTypeError(
            said(
                tr(
                    "not RULE=LEVEL with LEVEL one of {levels}: {given!r}",
                    levels=levels,
                    given=text,
                )
            )
        )
    rules = _rule_codes(code)
    if len(rules) != 1:
        raise argparse.ArgumentTypeError(said(tr("one rule before '=': {given!r}", given=text)))
    return next(iter(rules)), level.strip().lower()


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


def _controller(text: str) -> str:
    """``--controller`` in any case, as config.CONTROLLERS spells it (0i-mf is 0i-MF)."""
    for controller in CONTROLLERS:
        if controller.lower() == text.strip().lower():
            return controller
    raise argparse.ArgumentTypeError(
        said(
            tr(
                "unknown controller {given!r} (choose from {controllers})",
                given=text,
                controllers=", ".join(CONTROLLERS),
            )
        )
    )


def _count(text: str) -> int:
    try:
        value = int(text.replace("_", ""))
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(
            said(tr("not a whole number from 0: {given!r}", given=text))
        )
    return value


def _whole(text: str) -> int:
    try:
        value = int(text.replace("_", ""))
    except ValueError:
        value = 0
    if value <= 0:
        raise argparse.ArgumentTypeError(
            said(tr("not a positive whole number: {given!r}", given=text))
        )
    return value


def _add_analysis_options(parser: argparse.ArgumentParser) -> None:
    """How much the analysis reads and runs, as the editor's fanuc-macro.analysis.* settings."""
    default = Config()
    parser.add_argument(
        "--max-line-length",
        type=_whole,
        metavar="CHARS",
        help=said(
            tr(
                "a longer block is not analysed (MB011; default {chars})",
                chars=default.max_line_length,
            )
        ),
    )
    parser.add_argument(
        "--max-blocks",
        type=_whole,
        metavar="N",
        help=said(
            tr(
                "blocks of a file the analysis reads (MB013; default {blocks:,})",
                blocks=default.max_blocks,
            )
        ),
    )
    parser.add_argument(
        "--max-file-size",
        type=_whole,
        metavar="CHARS",
        help=said(
            tr(
                "characters of a file the analysis reads (MB013; default {chars:,})",
                chars=default.max_file_size,
            )
        ),
    )
    parser.add_argument(
        "--step-budget",
        type=_whole,
        metavar="BLOCKS",
        help=said(
            tr(
                "blocks one run of a program may execute (default {blocks:,})",
                blocks=default.step_budget,
            )
        ),
    )
    parser.add_argument(
        "--time-limit",
        type=_positive,
        metavar="SECONDS",
        help=said(
            tr(
                "the safety net of a slow or busy machine (default {seconds:g} s)",
                seconds=default.time_limit,
            )
        ),
    )


def _positive(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = 0.0
    if not value > 0 or value == NOT_SET:
        raise argparse.ArgumentTypeError(said(tr("not a positive number: {given!r}", given=text)))
    return value


def _add_machine_options(parser: argparse.ArgumentParser) -> None:
    """The machine's limits and options, as the editor's fanuc-macro.machine.* settings: a
    limit not given is not checked."""
    parser.add_argument(
        "--max-spindle-speed",
        type=_positive,
        metavar="RPM",
        help=said(tr("the machine's maximum spindle speed (MB602); not checked when not given")),
    )
    parser.add_argument(
        "--max-threading-feed",
        type=_positive,
        metavar="MM_PER_MIN",
        help=said(
            tr(
                "the machine's largest feed while threading, S x lead (MB807); not checked when "
                "not given"
            )
        ),
    )
    parser.add_argument(
        "--extended-commons",
        action="store_true",
        default=None,
        help=said(tr("the machine has the extended common variables #200-#499 (no MB303)")),
    )
    parser.add_argument(
        "--custom-call",
        action="append",
        type=_custom_call_option,
        metavar="CODE=PROGRAM",
        help=said(
            tr(
                "a code the control's parameters make call a program, e.g. M165=9022, G100=9010, "
                "T=9000 (repeatable)"
            )
        ),
    )
    parser.add_argument(
        "--g-code-system",
        type=str.upper,
        choices=G_CODE_SYSTEMS,
        metavar="{A,B,C}",
        help=said(
            tr(
                "the lathe's G code system (parameters GSB, GSC): in B and C, G90/G91 are absolute "
                "and incremental, G77/G78/G79 (C: G20/G21/G24) the turning, threading and facing "
                "cycles, G92 the coordinate system setting; default A"
            )
        ),
    )
    parser.add_argument(
        "--on-control",
        action="append",
        type=_on_control_option,
        metavar="PROGRAMS",
        help=said(
            tr(
                "programs kept on the control, not beside the files: numbers or ranges, e.g. "
                "O9000-O9999 (repeatable, or a comma list); their calls are not reported missing"
            )
        ),
    )


def cmd_check(args: argparse.Namespace) -> int:
    from .check_command import cmd_check as check

    return check(args)


def read_one(command: str, workspace: Workspace, raw: str, stdin_name: str | None = None) -> str:
    """Read the FILE of ``trace``, ``plot``, ``hover`` or ``definition`` into ``workspace``;
    its key. It is one file, not a folder, and a program text (``check`` reports a file that
    is not as MB007 and goes on; a command that runs or looks into the file stops). ``-`` is
    standard input, known by ``stdin_name`` (--stdin-filename) when given."""
    if raw == STDIN:
        key = stdin_name or STDIN
        workspace.add_bytes(key, read_stdin())
    else:
        if stdin_name is not None:
            raise UsageError(
                said(
                    tr(
                        "fanuc-macro: --stdin-filename names standard input: give - as FILE, "
                        "not {path}",
                        path=raw,
                    )
                )
            )
        path = one_program_file(command, raw)
        key = str(path)
        workspace.add_bytes(key, path.read_bytes())
    reason = workspace.not_text(key)
    if reason is not None:
        raise UsageError(f"fanuc-macro: {raw}: {said(reason)}")
    return key


def _program_number(text: str) -> int:
    digits = text.upper().lstrip("O")
    if not digits.isdigit():
        raise argparse.ArgumentTypeError(
            said(tr("not a program number: {given!r} (write O4009 or 4009)", given=text))
        )
    return int(digits)


def read_with_files(workspace: Workspace, paths: Sequence[str] | None, key: str) -> None:
    """Read the ``--with`` files into ``workspace`` beside the FILE of ``key`` (which stands
    for a file of its name, as the text of standard input does)."""
    for extra in collect_files(paths or []):
        if str(extra) != key:
            workspace.add_bytes(str(extra), extra.read_bytes())


def _traced_workspace(args: argparse.Namespace) -> tuple[Config, Workspace, str]:
    """The file of ``trace`` or ``plot`` and the ``--with`` files it calls, read; its URI."""
    if args.command == "plot" and args.file == STDIN and not getattr(args, "output", None):
        raise UsageError(
            said(tr("fanuc-macro: plot of standard input: say where the SVG goes (-o)"))
        )
    config = _config(args, args.file)
    workspace = Workspace(config)
    uri = read_one(args.command, workspace, args.file, args.stdin_filename)
    read_with_files(workspace, args.with_files, uri)
    if args.entry is not None and workspace.find_program(args.entry) is None:
        raise UsageError(
            said(
                tr(
                    "fanuc-macro: no program O{program:04d} in {path}",
                    program=args.entry,
                    path=args.file,
                )
            )
        )
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
        out.write(said(motion_text(m)) + "\n")
    _write_trace_summary(result, out)
    return EXIT_OK


def _write_trace_summary(result: Mapping[str, Any], out: TextIO) -> None:
    """The lines after the motions of ``trace``'s text form."""
    summary = result["summary"]
    by_code = listed(f"{k} {v}" for k, v in summary["by_code"].items())
    out.write(
        said(
            tr(
                "{motions} motions ({by_code}); {blocks} blocks executed",
                motions=summary["motions"],
                by_code=by_code,
                blocks=summary["blocks_executed"],
            )
        )
        + "\n"
    )
    from ..ide import cycle_time_text

    out.write(said(cycle_time_text(summary)) + "\n")
    if summary["stopped"]:
        why = said(summary.get("stop_message") or summary["stopped"])
        out.write(said(tr("stopped early: {why}", why=why)) + "\n")
    for part in summary["read_in_part"]:
        last, message = part["last_line_read"], said(part["message"])
        if "path" in part:
            line = tr(
                "{path}: read only up to line {line}: {why}",
                path=part["path"],
                line=last,
                why=message,
            )
        else:
            line = tr("read only up to line {line}: {why}", line=last, why=message)
        out.write(said(line) + "\n")
    if result["toolpath"]["truncated"]:
        moves = result["toolpath"]["moves"]
        out.write(said(tr("the toolpath keeps the first {moves:,} moves only", moves=moves)) + "\n")
    for f in summary["findings"]:
        out.write(said(tr("line {line}: {message}", line=f["line"], message=said(f["message"]))))
        out.write("\n")


def cmd_hover(args: argparse.Namespace) -> int:
    from .ide_commands import cmd_hover as hover

    return hover(args, _config(args, args.file))


def cmd_definition(args: argparse.Namespace) -> int:
    from .ide_commands import cmd_definition as definition

    return definition(args, _config(args, args.file))


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
        help=said(
            tr(
                "print {what} at LINE COLUMN of FILE (1-based, as editors show them; "
                "exit status 1 when there is none)",
                what=what,
            )
        ),
    )
    command.add_argument(
        "file", metavar="FILE", help=said(tr("the program file; - for standard input"))
    )
    command.add_argument("line", type=_whole, metavar="LINE", help=said(tr("the line, from 1")))
    command.add_argument(
        "column", type=_whole, metavar="COLUMN", help=said(tr("the column in characters, from 1"))
    )
    _add_with_option(command)
    _add_stdin_filename_option(command)
    _add_format_option(command, tr("the answer as text (default) or as JSON"))
    _add_rule_options(command)
    _add_machine_options(command)
    _add_analysis_options(command)
    return command


def _add_format_option(parser: argparse.ArgumentParser, what: str) -> None:
    parser.add_argument("--format", choices=("text", "json"), default="text", help=said(what))


def _add_rule_options(parser: argparse.ArgumentParser) -> None:
    """The controller and the rules, as the editor's fanuc-macro.controller and
    fanuc-macro.rules.disabled settings."""
    parser.add_argument(
        "--controller",
        type=_controller,
        choices=CONTROLLERS,
        help=said(
            tr(
                "the control the programs are for, in any case; the default, 0i-F, reads each "
                "file as a lathe (0i-TF) or a mill (0i-MF) as its codes show"
            )
        ),
    )
    parser.add_argument(
        "--ignore",
        "--disable",
        dest="disable",
        type=_rule_codes,
        action="append",
        metavar="RULES",
        help=said(
            tr(
                "comma-separated rules to skip, by code or name in any case, e.g. "
                "MB006,tape-mark-not-alone (docs/rules.md lists them); may be repeated"
            )
        ),
    )
    parser.add_argument(
        "--select",
        type=_rule_selectors,
        action="append",
        metavar="RULES",
        help=said(
            tr(
                "report only these rules: codes, names, prefixes of codes (MB6) or ALL, "
                "comma-separated; replaces the configuration file's select"
            )
        ),
    )
    parser.add_argument(
        "--extend-select",
        type=_rule_selectors,
        action="append",
        metavar="RULES",
        help=said(tr("report these rules too, besides those selected")),
    )
    parser.add_argument(
        "--severity",
        type=_severity_option,
        action="append",
        metavar="RULE=LEVEL",
        help=said(
            tr(
                "report a rule at another severity: error, warning, information or hint, e.g. "
                "MB403=information (repeatable)"
            )
        ),
    )
    _add_config_options(parser)


def _add_config_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--config",
        metavar="PATH",
        help=said(
            tr(
                "the configuration file to use (default: the fanuc-macro.toml, or pyproject.toml "
                "with {table}, nearest each file, looking up from its folder); the "
                "options given here win over it",
                table="[tool.fanuc-macro]",  # a name, not the glossary's tool
            )
        ),
    )
    parser.add_argument(
        "--isolated",
        action="store_true",
        help=said(tr("read no configuration file: the options given here and the defaults only")),
    )


def cmd_rule(args: argparse.Namespace) -> int:
    """``fanuc-macro rule MB601``: the rule's documentation, as docs/rules.md has it."""
    from ..analysis import RULE_DOCS
    from ..rules_doc import rule_url, section

    code = _rule_code(args.rule)
    if code not in RULES:
        raise UsageError(
            said(
                tr(
                    "fanuc-macro: unknown rule {given!r}: the nearest known one is {nearest}",
                    given=args.rule,
                    nearest=_nearest_rule(code),
                )
            )
        )
    out = sys.stdout
    text = section(RULES[code], RULE_DOCS[code]) if current() == "en" else _said_section(code)
    out.write(text.rstrip("\n") + "\n")
    out.write(f"\n{rule_url(code)}\n")
    return EXIT_OK


def _said_section(code: str) -> str:
    """``rules_doc.section`` in the command line's language, from the catalogue of the
    documentation (domain ``rules_doc``; a text without a translation stays English)."""
    from ..analysis import RULE_DOCS
    from ..rules_doc import PARTS, part_texts
    from ..translation import translate
    from .reports import SEVERITY_WORDS

    info, doc, locale = RULES[code], RULE_DOCS[code], current()
    severity = said(SEVERITY_WORDS[info.severity.value])
    if doc.severity_note:
        severity += f"; {translate(doc.severity_note, locale, 'rules_doc')}"
    label = translate("Severity:", locale, "rules_doc")
    lines = [f"## {info.code} {info.name}", "", f"**{label}** {severity}", ""]
    texts = part_texts(doc)
    for name, english_label in PARTS:
        text = translate(texts[name], locale, "rules_doc")
        heading = translate(english_label, locale, "rules_doc")
        lines.append(f"**{heading}**" + ("\n\n" if text.startswith("```") else " ") + text)
        lines.append("")
    return "\n".join(lines)


def cmd_config(args: argparse.Namespace) -> int:
    from .configuration import print_config

    return print_config(args, _anchor(args, args.path))


def _add_with_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--with",
        dest="with_files",
        action="append",
        metavar="PATH",
        help=said(
            tr(
                "a file or folder with programs it calls; repeat it for more (--with lib "
                "--with subs.nc), or give several after FILE (--with lib subs.nc); anywhere among "
                "the arguments"
            )
        ),
    )


def _add_stdin_filename_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--stdin-filename",
        metavar="NAME",
        help=said(
            tr(
                "the name of the file standard input (-) holds: shown in messages, and its "
                "program number when it has no O line (O1234.nc)"
            )
        ),
    )


def _add_run_options(parser: argparse.ArgumentParser) -> None:
    """What ``trace`` and ``plot`` run: a file, where to start, the files it calls, the
    machine."""
    parser.add_argument(
        "file", metavar="FILE", help=said(tr("the program file to run; - for standard input"))
    )
    parser.add_argument(
        "--entry", type=_program_number, help=said(tr("program to start from, e.g. O4009"))
    )
    _add_with_option(parser)
    _add_stdin_filename_option(parser)
    _add_rule_options(parser)
    _add_machine_options(parser)
    _add_analysis_options(parser)


EXIT_STATUS_HELP = tr(
    """\
exit status:
  0  done: no finding at or above --fail-on (check), nothing to reformat (format --check)
  1  check: a finding at or above --fail-on (default: an error), or more warnings than
     --max-warnings; format --check: a file would be reformatted; hover, definition:
     nothing there
  2  a usage problem: a bad option or argument, a path that is not there, a folder
     without programs, a file that cannot be read or is not a program text (check
     still checks the other paths)
  3  an internal error of fanuc-macro: a bug, please report it"""
)


def _walk_help() -> str:
    """What ``check --help`` says of the folder walk, the summary and the exit status, from
    program_files' own lists."""
    import textwrap

    def item(text: str) -> str:
        if current() != "en":  # Chinese and Japanese characters take two columns each
            lines = wrapped(said(text), 83)
            return "\n".join(["  " + lines[0], *("     " + line for line in lines[1:])])
        return textwrap.fill(
            text, 88, initial_indent="  ", subsequent_indent="     ", break_on_hyphens=False
        )

    skipped = [*sorted(SKIPPED_FOLDERS), *(f"*{s}" for s in TOOL_FOLDER_SUFFIXES)]
    markers = said(tr(" or ")).join(TOOL_MARKERS)
    walk = [
        item(
            tr(
                "by extension, in any case: {suffixes}",
                suffixes=" ".join(sorted(PROGRAM_SUFFIXES)),
            )
        ),
        item(
            tr(
                "by content, for {suffixes} and files with no extension: a first line that is "
                "%, O1234, O<NAME>, :1234 or an NC block, and most of the first lines NC blocks "
                "(a file with no extension named O1234 is a program too); the other text files "
                "are skipped and counted in the summary",
                suffixes=" ".join(sorted(SNIFFED_SUFFIXES)),
            )
        ),
        item(
            tr(
                "skipped: hidden files and folders, {folders}, any folder holding {markers}, "
                "and what --exclude matches",
                folders=listed(skipped),
                markers=markers,
            )
        ),
    ]
    return "\n".join(
        [
            said(tr("a folder is walked for programs:")),
            *walk,
            said(tr("a file named on the command line is checked whatever it is.")),
            "",
            said(
                tr(
                    "a summary goes to standard error, after the findings (-q: none):\n"
                    "  fanuc-macro: 12 files checked, 2 skipped (not programs: notes.txt, "
                    "a/b.txt),\n"
                    "  1 error, 5 warnings"
                )
            ),
            "",
            said(EXIT_STATUS_HELP),
        ]
    )


def _add_check_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser], logs: argparse.ArgumentParser
) -> None:
    check = sub.add_parser(
        "check",
        parents=[logs],
        help=said(tr("report problems in programs (files or folders)")),
        epilog=_walk_help(),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    check.add_argument(
        "paths",
        nargs="+",
        metavar="PATH",
        help=said(
            tr(
                "program files (- for standard input), or folders whose programs are checked "
                "together (which files: below)"
            )
        ),
    )
    check.add_argument(
        "--format",
        choices=("text", "json", "sarif", "github", "junit"),
        default="text",
        help=said(
            tr(
                "text: one line PATH:LINE:COLUMN: CODE severity message each (default); json: a "
                "list; sarif: SARIF 2.1.0 for code scanning; github: GitHub Actions annotations; "
                "junit: JUnit XML, a test case per file"
            )
        ),
    )
    check.add_argument(
        "--fix",
        action="store_true",
        help=said(
            tr(
                "apply the fixes the rules mark safe (they mend only the mistake, e.g. close a "
                "comment) to the files, then check them as fixed"
            )
        ),
    )
    check.add_argument(
        "--unsafe-fixes",
        action="store_true",
        help=said(
            tr(
                "with --fix or --diff, the other fixes too (they change what the program does, "
                "as the message suggests)"
            )
        ),
    )
    check.add_argument(
        "--diff",
        action="store_true",
        help=said(
            tr(
                "print the changes --fix would make, as diff -u, and write nothing; exit status "
                "1 when there is one"
            )
        ),
    )
    check.add_argument(
        "--statistics",
        action="store_true",
        help=said(
            tr(
                "a count of the findings of each rule, the most first, instead of the findings "
                "(beside the other forms, on standard error)"
            )
        ),
    )
    check.add_argument(
        "--color",
        choices=("auto", "always", "never"),
        default="auto",
        help=said(tr("colour the text form: auto (default) on a terminal unless NO_COLOR is set")),
    )
    _add_check_run_options(check)
    _add_stdin_filename_option(check)
    _add_rule_options(check)
    _add_machine_options(check)
    _add_analysis_options(check)
    check.set_defaults(func=cmd_check)


def _add_check_run_options(check: argparse.ArgumentParser) -> None:
    """What a check reads, when it fails, what it says on standard error, how it runs."""
    check.add_argument(
        "--exclude",
        action="append",
        metavar="GLOB",
        help=said(
            tr(
                "skip what matches in the folders walked: a name anywhere (*.bak, old) or, "
                "with a /, a path from the folder walked (old/*.nc); may be repeated; a file named "
                "on the command line is checked all the same"
            )
        ),
    )
    check.add_argument(
        "--fail-on",
        choices=[s.value for s in Severity],
        default=Severity.ERROR.value,
        help=said(tr("the least severe finding that makes the exit status 1 (default error)")),
    )
    check.add_argument(
        "--max-warnings",
        type=_count,
        metavar="N",
        help=said(tr("exit status 1 also when there are more than N warnings")),
    )
    check.add_argument(
        "--quiet", "-q", action="store_true", help=said(tr("no summary line on standard error"))
    )
    check.add_argument(
        "--jobs",
        "-j",
        type=_count,
        metavar="N",
        help=said(
            tr(
                "check the files in N processes (default: one per core; 1: in this one); the "
                "output is the same in any case"
            )
        ),
    )
    check.add_argument(
        "--no-cache",
        action="store_true",
        help=said(
            tr(
                "analyse every file again: by default the findings of a file whose text, "
                "settings and related files did not change are taken from the last run's (kept "
                "under the user's cache directory; FANUC_MACRO_CHECK_CACHE=0 turns it off, another "
                "value names the directory)"
            )
        ),
    )


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="fanuc-macro",
        description=said(tr("Check FANUC Custom Macro B programs.")),
        epilog=said(EXIT_STATUS_HELP),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument(
        "--version",
        action="version",
        version=f"fanuc-macro {__version__}",
        help=said(tr("show program's version number and exit")),
    )
    _add_language_option(parser, AUTO)
    sub = parser.add_subparsers(dest="command", required=True)
    # How the analyser's own failures (MB000) are told: by default one line in the output.
    logs = argparse.ArgumentParser(add_help=False)
    logs.add_argument(
        "--verbose",
        action="store_true",
        help=said(
            tr(
                "print the traceback of an internal error; check also says which machine, lathe "
                "or mill, each file is read as and why"
            )
        ),
    )
    logs.add_argument(
        "--log-file", metavar="PATH", help=said(tr("write the analyser's log to this file"))
    )

    _add_check_command(sub, logs)

    trace_command = sub.add_parser(
        "trace", parents=[logs], help=said(tr("print the motion blocks a program executes"))
    )
    _add_run_options(trace_command)
    _add_format_option(trace_command, tr("one line a motion and a summary (default), or JSON"))
    trace_command.set_defaults(func=cmd_trace)

    add_plot_command(sub, logs)

    _add_place_command(sub, logs, "hover", tr("the hover text (markdown)")).set_defaults(
        func=cmd_hover
    )
    _add_place_command(
        sub, logs, "definition", tr("where what is there is defined (PATH:LINE:COLUMN)")
    ).set_defaults(func=cmd_definition)

    rule = sub.add_parser(
        "rule", help=said(tr("print a rule's documentation (what, why, example, fix)"))
    )
    rule.add_argument("rule", metavar="RULE", help=said(tr("its code or name, e.g. MB601")))
    rule.set_defaults(func=cmd_rule)

    config = sub.add_parser(
        "config",
        help=said(
            tr("print the settings a program is checked with, and where each value comes from")
        ),
    )
    config.add_argument(
        "path",
        nargs="?",
        metavar="PATH",
        help=said(tr("a program file or folder (default: the current folder)")),
    )
    config.add_argument(
        "--format",
        choices=("text", "json", "schema"),
        default="text",
        help=said(tr("text (default), JSON, or the configuration file's JSON Schema")),
    )
    _add_rule_options(config)
    _add_machine_options(config)
    _add_analysis_options(config)
    config.set_defaults(func=cmd_config)

    add_thread_command(sub)
    add_generator_commands(sub)
    add_format_command(sub)
    for command in sub.choices.values():  # --lang after the command's name too
        _add_language_option(command, argparse.SUPPRESS)
    return parser


def _add_language_option(parser: argparse.ArgumentParser, default: str) -> None:
    """``--lang``: read by ``main`` before the parser is built (its help is in the language
    chosen); here so that argparse takes it, before or after the command's name."""
    parser.add_argument(
        OPTION,
        metavar="LOCALE",
        default=default,
        help=said(
            tr(
                "the language of the messages and help: zh-cn (Chinese), en, or auto (the "
                "default): the first of LC_ALL, LC_MESSAGES and LANG that is set, e.g. "
                "zh_CN.UTF-8; C and POSIX are English. The JSON, SARIF, GitHub and JUnit "
                "forms of check stay in English"
            )
        ),
    )


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


WITH = "--with"


def _command_parser(
    parser: argparse.ArgumentParser, argv: Sequence[str]
) -> tuple[int, argparse.ArgumentParser] | None:
    """Where the command's name is in ``argv``, and its parser."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            after_option = False
            for i, token in enumerate(argv):
                if token in action.choices:
                    return i, action.choices[token]
                if not token.startswith("-") and not after_option:
                    return None
                after_option = token == OPTION  # --lang LOCALE before the command
    return None


def spread_with_paths(parser: argparse.ArgumentParser, argv: Sequence[str]) -> list[str]:
    """``--with A B`` as ``--with A --with B``, short of the positional arguments the command
    needs: in ``hover --with lib prog.nc 3 5`` the last three are FILE LINE COLUMN, in
    ``hover prog.nc 3 5 --with lib subs.nc`` both paths are ``--with``'s. (argparse alone
    would give every word after ``--with`` to it, or take one.)"""
    argv = list(argv)
    found = _command_parser(parser, argv) if WITH in argv else None
    if found is None:
        return argv
    start, command = found
    options = {o: a.nargs != 0 for a in command._actions for o in a.option_strings}
    if WITH not in options:
        return argv
    needed = sum(1 for a in command._actions if not a.option_strings)

    def takes_value(token: str) -> bool:
        if "=" in token or (not token.startswith("--") and len(token) > 2):
            return False  # --format=json, -oplot.svg
        if token in options:
            return options[token]
        prefixed = [value for option, value in options.items() if option.startswith(token)]
        return len(prefixed) == 1 and prefixed[0]  # argparse's abbreviations

    # Each word: [kind, token], kind "as is", "positional", "path" (a --with's) or WITH.
    words: list[list[str]] = []
    groups: list[tuple[int, list[int]]] = []  # a --with: its word, the words after it
    group: list[int] | None = None
    tokens = iter(argv[start + 1 :])
    for token in tokens:
        if token == "--":
            group = None
            words.append(["as is", token])
            words.extend(["positional", rest] for rest in tokens)
        elif token == STDIN or not token.startswith("-"):
            if group is not None:
                group.append(len(words))
            words.append(["path" if group is not None else "positional", token])
        elif token == WITH:
            group = []
            groups.append((len(words), group))
            words.append([WITH, token])
        else:
            group = None
            words.append(["as is", token])
            if takes_value(token):
                words.extend(["as is", v] for v in [next(tokens, None)] if v is not None)
    missing = needed - sum(1 for kind, _ in words if kind == "positional")
    for _, paths in reversed(groups):  # what the command lacks: the last words given
        taken = paths[max(len(paths) - missing, 0) :] if missing > 0 else []
        missing -= len(taken)
        for i in taken:
            words[i][0] = "positional"
    spread = argv[: start + 1]
    for kind, token in words:
        if kind == "path":
            spread.extend([WITH, token])
        elif kind != WITH:
            spread.append(token)
    if any(all(words[i][0] == "positional" for i in paths) for _, paths in groups):
        # A --with left without a path: last, where argparse says it wants one.
        end = spread.index("--") if "--" in spread[start + 1 :] else len(spread)
        spread.insert(end, WITH)
    return spread


def main(argv: Sequence[str] | None = None) -> int:
    words = list(sys.argv[1:] if argv is None else argv)
    locale = chosen_locale(words)
    use(locale)  # before the parser is built: its help is said in the language
    try:
        return _run(words, locale)
    finally:
        use("en")  # main() may run again in the same process (tests do), as may other callers


def _run(words: list[str], locale: str) -> int:
    tolerate_unencodable()
    with argparse_in(locale):
        parser = build_parser()
        if locale != "en":
            wide_help(parser)
        try:
            args = parser.parse_args(spread_with_paths(parser, words))
        except SystemExit as exc:  # argparse exits 2 on a usage problem, 0 for --help
            return int(exc.code or 0)
    tolerate_unencodable(args.command)
    stop_logging = _log_to(getattr(args, "verbose", False), getattr(args, "log_file", None))
    try:
        result: int = args.func(args)
        return result
    except UsageError as err:
        sys.stderr.write(f"{err}\n")  # said where it was raised
        return EXIT_USAGE
    except BrokenPipeError:
        return EXIT_OK
    except Exception as err:  # the analyser's bug: one line here, the traceback in the log
        log_failure(__name__, "fanuc-macro %s failed", args.command)
        message = tr("internal error: {error!r}; {report}", error=err, report=REPORT_INTERNAL_ERROR)
        if getattr(args, "format", "text") == "json":
            import json

            json.dump({"error": str(message)}, sys.stdout, ensure_ascii=False, indent=1)
            sys.stdout.write("\n")
        sys.stderr.write(f"fanuc-macro: {said(message)}\n")
        return EXIT_INTERNAL
    finally:
        save_code_cache()
        if stop_logging is not None:
            stop_logging()


if __name__ == "__main__":
    sys.exit(main())


__all__ = ("analyse", "main")
