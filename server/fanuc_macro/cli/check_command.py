"""``fanuc-macro check PATH...``: the diagnostics of programs on standard output, one summary
line on standard error, and an exit status as ruff's and ESLint's.

Every path given is checked even when another is bad: a path that is not there, a folder
without programs or a file that cannot be read is told on standard error and makes the status
2 (a usage problem) once the others are checked."""

from __future__ import annotations

import argparse
import os
import sys
from collections import Counter
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO

from ..config import Config
from ..config_file import ConfigFileError, files_of
from ..diagnostics import Diagnostic, Severity
from ..ide import Fixed, fix_file, machine_text, unified_diff
from ..program_files import Found, find_programs
from ..workspace import DocumentLinks, Workspace, graph_of_links, related_in_graph

if TYPE_CHECKING:
    from .check_cache import CheckCache
from ..translation import tr, tr_n
from .configuration import ConfigResolver
from .language import current, listed, said, said_error, use
from .reports import github, junit, sarif, statistics, text_line, use_colour
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


def summary_line(checked: int, not_programs: Sequence[str], counts: Counter[Severity]) -> str:
    """``fanuc-macro: 12 files checked, 3 skipped (not programs: a.txt, b.txt, c.txt, +1 more),
    2 errors, 5 warnings``, and ``, N information`` and ``, N hints`` when there are any."""
    skipped = len(not_programs)
    shown = listed(not_programs[:SHOWN_NOT_PROGRAMS])
    more = skipped - SHOWN_NOT_PROGRAMS
    if more > 0:
        skipped_part = tr(
            "{count} skipped (not programs: {names}, +{more} more)",
            count=skipped,
            names=shown,
            more=more,
        )
    elif not_programs:
        skipped_part = tr("{count} skipped (not programs: {names})", count=skipped, names=shown)
    else:
        skipped_part = tr("{count} skipped", count=skipped)
    parts = [
        tr_n("{count} file checked", "{count} files checked", checked),
        skipped_part,
        tr_n("{count} error", "{count} errors", counts[Severity.ERROR]),
        tr_n("{count} warning", "{count} warnings", counts[Severity.WARNING]),
    ]
    if counts[Severity.INFORMATION]:
        parts.append(tr("{count} information", count=counts[Severity.INFORMATION]))
    if counts[Severity.HINT]:
        parts.append(tr_n("{count} hint", "{count} hints", counts[Severity.HINT]))
    return said(tr("fanuc-macro: {summary}", summary=listed(parts)))


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


def _found(paths: Sequence[str], exclude: Sequence[str], resolver: ConfigResolver) -> Found:
    """The programs of the paths given; each folder walked with the ``[files]`` of the
    configuration file nearest it (what it excludes besides --exclude, its own extensions)."""
    found = Found()
    for raw in paths:
        if raw == STDIN:
            continue
        own_exclude, extensions = files_of(resolver.for_path(Path(raw)).settings)
        one = find_programs([raw], [*exclude, *own_exclude], extensions)
        found.programs.extend(one.programs)
        found.not_programs.extend(one.not_programs)
        found.missing.extend(one.missing)
        found.empty.extend(one.empty)
    return found


def cmd_check(args: argparse.Namespace) -> int:
    err = sys.stderr
    paths: list[str] = args.paths
    stdin_name: str | None = args.stdin_filename
    if paths.count(STDIN) > 1:
        err.write(said(tr("fanuc-macro: standard input (-) can be checked once")) + "\n")
        return EXIT_USAGE
    if stdin_name is not None and STDIN not in paths:
        err.write(
            said(tr("fanuc-macro: --stdin-filename names standard input: give - among the paths"))
            + "\n"
        )
        return EXIT_USAGE
    resolver = ConfigResolver(args)
    try:
        found = _found(paths, args.exclude or (), resolver)
    except ConfigFileError as error:
        err.write(f"fanuc-macro: {said_error(error)}\n")
        return EXIT_USAGE
    for raw in found.missing:
        err.write(said(tr("fanuc-macro: no such file or directory: {path}", path=raw)) + "\n")
    for folder in found.empty:
        err.write(said(tr("fanuc-macro: no programs found in {path}", path=folder)) + "\n")
    usage_problem = bool(found.missing or found.empty)

    datas: list[tuple[str, bytes]] = []
    if STDIN in paths:
        datas.append((stdin_name or STDIN, read_stdin()))
    for path in found.programs:
        key = str(path)
        if any(k == key for k, _ in datas):  # standard input stands for the file of its name
            continue
        try:
            datas.append((key, path.read_bytes()))
        except OSError as error:
            why = error.strerror or str(error)
            err.write(said(tr("fanuc-macro: cannot read {path}: {why}", path=path, why=why)))
            err.write("\n")
            usage_problem = True

    records: list[dict[str, Any]] = []
    counts: Counter[Severity] = Counter()
    internal_error = False
    out = sys.stdout
    # Every form but the text one, and --statistics, needs the findings of every file first.
    as_records = args.format != "text" or args.statistics
    colour = use_colour(args.color, out)
    try:
        groups = _by_configuration(datas, resolver)
    except ConfigFileError as error:
        err.write(f"fanuc-macro: {said_error(error)}\n")
        return EXIT_USAGE
    if args.fix or args.diff:
        if STDIN in paths:
            err.write(said(tr("fanuc-macro: --fix and --diff take files, not standard input")))
            err.write("\n")
            return EXIT_USAGE
        fixed = _fixed(datas, groups, args.unsafe_fixes)
        if args.diff:
            return _show_diff(datas, fixed)
        datas = _write_fixed(datas, fixed, err)
    for checked in _checked_in_order(datas, groups, args):
        if checked.stopped is not None:  # the safety net: not a finding of the program's
            err.write(f"{checked.key}: {checked.stopped}\n")
        if args.verbose and checked.machine is not None:
            err.write(f"{checked.key}: {checked.machine}\n")
        for n, finding in enumerate(checked.findings):
            severity = Severity(finding["severity"])
            counts[severity] += 1
            internal_error |= finding["code"] == INTERNAL_ERROR
            if as_records:
                records.append({"path": checked.key, **finding})
            else:
                out.write(text_line(checked.key, finding, colour, checked.message(n)))
    _write_records(args, records, [key for key, _data in datas], out, colour)
    out.flush()  # the findings before the summary, when both go to one terminal
    if not args.quiet:
        not_programs = [str(p) for p in found.not_programs]
        err.write(summary_line(len(datas), not_programs, counts) + "\n")
    return exit_status(
        counts, Severity(args.fail_on), args.max_warnings, usage_problem, internal_error
    )


def _by_configuration(
    datas: list[tuple[str, bytes]], resolver: ConfigResolver
) -> list[tuple[Config, frozenset[str]]]:
    """The files grouped by the configuration file they are checked with (the one nearest
    each), in the order of their first file. Standard input is where --stdin-filename says."""
    groups: dict[Path | None, list[str]] = {}
    for key, _data in datas:
        path = None if key == STDIN else Path(key)
        groups.setdefault(resolver.file_for(path), []).append(key)
    return [
        (resolver.for_path(None if keys[0] == STDIN else Path(keys[0])).config, frozenset(keys))
        for keys in groups.values()
    ]


def _fixed(
    datas: list[tuple[str, bytes]],
    groups: list[tuple[Config, frozenset[str]]],
    unsafe: bool,
) -> dict[str, Fixed]:
    """Each file's fixes, worked out in a workspace of every file (its called programs decide
    what a rule finds) with its own configuration."""
    found: dict[str, Fixed] = {}
    for config, keys in groups:
        workspace = Workspace(config, keep_runs=False)
        for key, data in datas:
            workspace.add_bytes(key, data)
        for key, data in datas:
            if key in keys:
                found[key] = fix_file(workspace, key, data, unsafe)
    return found


def _show_diff(datas: list[tuple[str, bytes]], fixed: dict[str, Fixed]) -> int:
    """--diff: each change as ``diff -u`` shows it; exit status 1 when there is one."""
    changed = 0
    for key, data in datas:
        after = fixed[key].data
        if after is not None:
            sys.stdout.write(unified_diff(key, data, after))
            changed += 1
    sys.stderr.write(
        said(
            tr_n(
                "fanuc-macro: {count} file would be changed",
                "fanuc-macro: {count} files would be changed",
                changed,
            )
        )
        + "\n"
    )
    return 1 if changed else 0


def _write_fixed(
    datas: list[tuple[str, bytes]], fixed: dict[str, Fixed], err: TextIO
) -> list[tuple[str, bytes]]:
    """--fix: the changed files written; the texts to check, as fixed."""
    out: list[tuple[str, bytes]] = []
    applied = files = 0
    for key, data in datas:
        result = fixed[key]
        if result.refused:
            refused = said(result.refused)
            err.write(said(tr("fanuc-macro: {path}: not fixed: {why}", path=key, why=refused)))
            err.write("\n")
        if result.data is not None:
            Path(key).write_bytes(result.data)
            applied += result.applied
            files += 1
            data = result.data
        out.append((key, data))
    in_files = tr_n("{count} file", "{count} files", files)
    err.write(
        said(
            tr_n(
                "fanuc-macro: {count} fix applied in {files}",
                "fanuc-macro: {count} fixes applied in {files}",
                applied,
                files=in_files,
            )
        )
        + "\n"
    )
    return out


def _checked_in_order(
    datas: list[tuple[str, bytes]],
    groups: list[tuple[Config, frozenset[str]]],
    args: argparse.Namespace,
) -> Iterator[_Checked]:
    """Each file's check in the order of ``datas``: one group at a time when the files have
    several configurations (every file read by each, as a called program; checked by its
    own), so that a file's findings do not depend on the others' settings."""
    if len(groups) == 1:
        yield from _check_files(datas, groups[0][0], args)
        return
    found: dict[str, _Checked] = {}
    for config, keys in groups:
        for checked in _check_files(datas, config, args, keys):
            found[checked.key] = checked
    for key, _data in datas:
        yield found[key]


def _write_records(
    args: argparse.Namespace,
    records: list[dict[str, Any]],
    checked: list[str],
    out: TextIO,
    colour: bool,
) -> None:
    """The findings in the form --format asks for, then the --statistics table."""
    import json

    form = args.format
    if form == "json":
        json.dump(records, out, ensure_ascii=not writes_unicode(out), indent=1)
        out.write("\n")
    elif form == "sarif":
        json.dump(sarif(records), out, ensure_ascii=not writes_unicode(out), indent=1)
        out.write("\n")
    elif form == "github":
        github(records, out)
    elif form == "junit":
        out.write(junit(checked, records))
    elif not args.statistics:
        for record in records:
            out.write(text_line(record["path"], record, colour))
    if args.statistics:
        statistics(records, out if form == "text" else sys.stderr)


@dataclass(frozen=True, slots=True)
class _Checked:
    """One file's check: the safety net's stop, the machine it was read as, and its findings
    as :func:`as_json` gives them but for the path (the form they are kept in between runs);
    the first two and the findings' messages (``messages``; None: English, the findings'
    own) said in the run's language, as the text form shows them. The JSON forms keep the
    findings' English."""

    key: str
    stopped: str | None
    machine: str | None
    findings: list[dict[str, Any]]
    messages: list[str] | None = None

    def message(self, n: int) -> str:
        """The message of the ``n``th finding in the run's language."""
        return str(self.findings[n]["message"] if self.messages is None else self.messages[n])

    @property
    def keepable(self) -> bool:
        """Whether another run would find the same: not stopped by the clock, not failed."""
        return self.stopped is None and all(f["code"] != INTERNAL_ERROR for f in self.findings)

    def kept(self) -> list[object]:
        """What the cache keeps, under a key of the run's language (check_cache.py)."""
        return [self.stopped, self.machine, self.findings, self.messages]

    @classmethod
    def from_kept(cls, key: str, value: list[Any]) -> _Checked:
        stopped, machine, findings, messages = value
        return cls(key, stopped, machine, findings, messages)


# Fewer files than this are checked in one process and without the cache: starting other
# processes, or reading and writing the cache, costs more than it saves.
PARALLEL_FROM = 8
TASKS_PER_PROCESS = 1  # chunks of files a forked process checks before a new one takes over
# Files a process of a parallel check keeps read between its files: past it, those the next
# file does not need are dropped (a shop's archive does not fit in each process).
FILES_KEPT = 64


def _jobs(args: argparse.Namespace, files: int) -> int:
    """Processes for a check of ``files`` files: 1 unless there are enough files to share and
    the platform forks (each process inherits what the first read)."""
    jobs = min(args.jobs or os.cpu_count() or 1, files)
    if jobs < 2 or files < PARALLEL_FROM:
        return 1
    import multiprocessing as mp  # a check of a few files starts without it

    return jobs if "fork" in mp.get_all_start_methods() else 1


def _check_files(
    datas: list[tuple[str, bytes]],
    config: Config,
    args: argparse.Namespace,
    only: frozenset[str] | None = None,
) -> Iterator[_Checked]:
    """Each file's check (of those in ``only``, when given), in the order of ``datas``: from
    the cache of earlier runs (:mod:`.check_cache`) where nothing it depends on changed, else
    analysed."""
    workspace = Workspace(config, keep_runs=False)
    jobs = _jobs(args, len(datas))
    cache = None
    if len(datas) >= PARALLEL_FROM and not args.no_cache:
        from .check_cache import CheckCache

        cache = CheckCache.open(config, current())
    if cache is None and jobs < 2:
        for key, data in datas:
            workspace.add_bytes(key, data)
        programs = workspace.program_numbers()
        for key, _data in datas:
            if only is None or key in only:
                yield _check_one(workspace, key, programs)
        return
    try:
        yield from _check_archive(workspace, datas, config, jobs, cache, only)
    finally:
        if cache is not None:
            cache.close()


@dataclass(frozen=True)
class _Archive:
    """What a check of many files knows before it analyses one: their bytes, their order, how
    they are tied (the program graph of their links) and the program numbers they define."""

    datas: dict[str, bytes]
    order: dict[str, int]
    related: dict[str, list[str] | None]  # each file's related files (None: every file)
    programs: frozenset[int]

    def needed(self, key: str) -> list[str]:
        """The files an analysis of ``key`` reads: itself and its related files."""
        related = self.related[key]
        return list(self.datas) if related is None else [key, *related]


def _check_archive(
    workspace: Workspace,
    datas: list[tuple[str, bytes]],
    config: Config,
    jobs: int,
    cache: CheckCache | None,
    only: frozenset[str] | None = None,
) -> Iterator[_Checked]:
    """:func:`_check_files` of many files: the files tied together from their links (kept in
    ``cache`` between runs, else read and dropped), then each file analysed with the files it
    needs (the kept result where nothing it depends on changed)."""
    digests: dict[str, str] = {}
    if cache is not None:
        from .check_cache import digest

        digests = {key: digest(data) for key, data in datas}
    links: dict[str, DocumentLinks] = {}
    for key, data in datas:
        found = cache.links(digests[key]) if cache is not None else None
        if found is None:
            found = workspace.links_of(key, data)
            if cache is not None:
                cache.keep_links(digests[key], found)
        links[key] = found
    graph = graph_of_links(links)
    custom = frozenset(c.program for c in config.custom_calls)
    archive = _Archive(
        dict(datas),
        {key: n for n, (key, _data) in enumerate(datas)},
        {key: related_in_graph(key, graph, custom) for key, _data in datas},
        frozenset(n for link in links.values() for n in link.defines),
    )
    done: dict[str, _Checked] = {}
    todo: dict[str, str] = {}  # key -> the key of its result in the cache
    checked_keys = [key for key, _data in datas if only is None or key in only]
    if cache is None:
        todo = {key: key for key in checked_keys}
    else:
        from .check_cache import all_digest, numbers_digest

        programs_digest, every = numbers_digest(archive.programs), all_digest(digests)
        for key in checked_keys:
            related = archive.related[key]
            pairs = None if related is None else [(r, digests[r]) for r in related]
            result_key = cache.result_key(key, digests[key], pairs, every, programs_digest)
            kept = cache.result(result_key)
            if kept is not None:
                done[key] = _Checked.from_kept(key, kept)
            else:
                todo[key] = result_key
    for checked in _analysed(workspace, archive, list(todo), jobs):
        done[checked.key] = checked
        if cache is not None and checked.keepable:
            cache.keep_result(todo[checked.key], checked.kept())
    if cache is not None:
        cache.save()
    for key in checked_keys:
        yield done[key]


# What the processes of a parallel check work from: set before they are forked, so that each
# inherits it (the files' bytes, the caches of the lines read for the links).
_FORKED: tuple[Workspace, _Archive, str] | None = None


def _analysed(
    workspace: Workspace, archive: _Archive, keys: list[str], jobs: int
) -> Iterator[_Checked]:
    """Each of ``keys`` checked with the files it needs: in ``jobs`` processes forked from this
    one (each analysis is the same in any process, so the output is too)."""
    global _FORKED
    # A file with a call whose program is not known before the run needs every file: those
    # are checked last, here, once the processes have ended (one process holding the whole
    # archive, not each).
    whole = [key for key in keys if archive.related[key] is None]
    keys = [key for key in keys if archive.related[key] is not None]
    if jobs < 2 or len(keys) < PARALLEL_FROM:
        for key in [*keys, *whole]:
            yield _check_in(workspace, archive, key)
        return
    import multiprocessing as mp

    # The language too: a process the pool starts in place of another is forked from its
    # thread, whose context does not hold the run's language (language.py).
    _FORKED = (workspace, archive, current())
    try:
        # Each process is replaced after a few chunks: what it copied of the parent's pages
        # (an object read is an object written, its reference count) and its own caches go
        # with it.
        context = mp.get_context("fork")
        with context.Pool(min(jobs, len(keys)), maxtasksperchild=TASKS_PER_PROCESS) as pool:
            # Small chunks: the files' analyses differ a hundredfold in time.
            chunk = max(1, len(keys) // (jobs * 16))
            yield from pool.imap(_check_forked, keys, chunksize=chunk)
    finally:
        _FORKED = None
    for key in whole:
        yield _check_in(workspace, archive, key)


def _check_forked(key: str) -> _Checked:
    assert _FORKED is not None
    workspace, archive, locale = _FORKED
    use(locale)
    return _check_in(workspace, archive, key)


def _check_in(workspace: Workspace, archive: _Archive, key: str) -> _Checked:
    """``key`` checked in ``workspace`` once it holds the files the analysis reads, in the
    archive's order (which decides the first definition of a number); the files it held
    for earlier ones stay while they are few (a called program is often called again)."""
    needed = archive.needed(key)
    held = workspace.uris()
    if len(held) + len(needed) > FILES_KEPT:
        keep = set(needed)
        workspace.remove_all(uri for uri in held if uri not in keep)
    added = False
    for uri in needed:
        if not workspace.has(uri):
            workspace.add_bytes(uri, archive.datas[uri])
            added = True
    if added:
        workspace.order_as(sorted(workspace.uris(), key=archive.order.__getitem__))
    return _check_one(workspace, key, archive.programs)


def _check_one(workspace: Workspace, key: str, programs: frozenset[int]) -> _Checked:
    analysis = workspace.analyse(key, workspace_programs=programs)
    stopped = analysis.facts.stop_message() if analysis.facts is not None else None
    machine = machine_text(analysis.config) if analysis.config is not None else None
    findings: list[dict[str, Any]] = []
    for d in analysis.diagnostics:
        record = as_json(key, d)
        del record["path"]
        record["message"] = str(record["message"])  # English, as a cached one is
        findings.append(record)
    messages = None
    if current() != "en":
        messages = [said(d.message) for d in analysis.diagnostics]
    return _Checked(
        key,
        None if stopped is None else said(stopped),
        None if machine is None else said(machine),
        findings,
        messages,
    )


__all__ = ("as_json", "cmd_check", "exit_status", "format_text", "summary_line")
