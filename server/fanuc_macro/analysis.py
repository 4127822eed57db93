"""The pipeline of one document: text → blocks → AST → program index → rules → diagnostics.

The CLI and the language server both call :func:`analyse`; neither holds analysis of its own.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace

from .config import Config
from .diagnostics import Diagnostic, Related, RuleInfo, Severity, make, register, suppressed_codes
from .evaluator import Facts, evaluate
from .index import ProgramIndex, build_index
from .parser import BlockParser, default_parser, parse_text, quiet_gc
from .per_line import PerLine
from .rules import ALL_CHECKS, LINE_CHECKS, LineFinding
from .rules.context import RuleContext
from .syntax import Document, ParsedLine
from .threads.identify import Thread

log = logging.getLogger(__name__)

register(
    RuleInfo("MB000", "internal-error", Severity.ERROR,
             "The analyser failed on this document; the message says where.", "internal"),
)  # fmt: skip

ExtraChecks = Callable[[RuleContext], Iterable[Diagnostic]]


@dataclass
class Analysis:
    doc: Document
    index: ProgramIndex
    diagnostics: list[Diagnostic] = field(default_factory=list)
    facts: Facts | None = None  # the evaluator's, when it ran
    threads: list[Thread] = field(default_factory=list)  # what the threading rules saw


def _apply_settings(diags: Iterable[Diagnostic], doc: Document, config: Config) -> list[Diagnostic]:
    """Drop disabled and suppressed diagnostics; apply configured severities."""
    suppressions: dict[int, set[str]] = {}
    for block in doc.blocks:
        for comment in block.parsed.comments:
            if "ignore" not in comment.text.lower():
                continue
            codes = suppressed_codes(comment.text)
            if codes is not None:
                suppressions.setdefault(block.line, set()).update(codes or {"*"})
    out: list[Diagnostic] = []
    for d in diags:
        if d.code in config.disabled:
            continue
        codes = suppressions.get(d.line)
        if codes is not None and ("*" in codes or d.code in codes):
            continue
        severity = config.severities.get(d.code)
        out.append(d.with_severity(severity) if severity else d)
    out.sort(key=lambda d: (d.line, d.column, d.code))
    return out


def _line_findings(parsed: ParsedLine) -> tuple[LineFinding, ...]:
    """The line rules' findings for one line's text."""
    found: list[LineFinding] = []
    for check in LINE_CHECKS:
        try:
            found.extend(check(parsed))
        except Exception as err:  # a bug in one rule must not hide the others
            log.exception("line rule %s failed", check.__module__)
            found.append(
                LineFinding("MB000", f"internal error in {check.__module__}: {err!r}", 0, 0)
            )
    return tuple(found)


line_findings: PerLine[tuple[LineFinding, ...]] = PerLine(_line_findings)


def run_checks(ctx: RuleContext, checks: Iterable[ExtraChecks]) -> list[Diagnostic]:
    found: list[Diagnostic] = []
    for block in ctx.doc.blocks:
        parsed = block.parsed
        if parsed.statement is None and parsed.problem is None and not parsed.notes:
            continue
        for f in line_findings(parsed):
            found.append(make(f.code, f.message, block.line, f.start, f.end))
    for check in checks:
        try:
            found.extend(check(ctx))
        except Exception as err:  # a bug in one rule must not hide the others
            log.exception("rule %s failed", getattr(check, "__module__", check))
            found.append(make("MB000", f"internal error in {check.__module__}: {err!r}", 0, 0, 0))
    return found


def analyse(
    text: str,
    uri: str = "",
    config: Config | None = None,
    workspace_programs: frozenset[int] | None = None,
    parser: BlockParser | None = None,
    extra_checks: Iterable[ExtraChecks] = (),
    doc: Document | None = None,
    index: ProgramIndex | None = None,
    other_documents: Sequence[tuple[str, Document, ProgramIndex]] = (),
    run_evaluator: bool = True,
    facts: Facts | None = None,
) -> Analysis:
    """Parse (unless ``doc`` is given), index, evaluate and check one document.

    ``other_documents`` are the workspace's other files: the programs this one calls.
    ``facts`` from an earlier run of the same programs spare the evaluator (see
    :meth:`fanuc_macro.workspace.Workspace.analyse`).
    """
    with quiet_gc():  # the run makes many small objects and no cycles
        config = config or Config()
        if doc is None:
            doc = parse_text(text, uri, parser or default_parser())
        if index is None:
            index = build_index(doc)
        failed: list[Diagnostic] = []
        if run_evaluator and facts is None:
            try:
                facts = evaluate([(uri, doc, index), *other_documents], config, only_uri=uri)
            except Exception as err:  # the structural rules still report
                log.exception("evaluation of %s failed", uri)
                failed.append(
                    make(
                        "MB000",
                        f"internal error in the evaluator: {err!r}; its rules did not run",
                        0,
                        0,
                        0,
                    )
                )
        ctx = RuleContext(doc, index, config, workspace_programs, facts)
        found = failed + run_checks(ctx, [*ALL_CHECKS, *extra_checks])
        threads: list[Thread] = []
        if facts is not None:
            try:
                threads = ctx.threads()
            except Exception:  # reported as MB000 by the rules that asked for them
                log.exception("thread identification of %s failed", uri)
        return Analysis(doc, index, _apply_settings(found, doc, config), facts, threads)


def with_uri(diag: Diagnostic, uri: str) -> Diagnostic:
    return replace(diag, related=tuple(replace(r, uri=r.uri or uri) for r in diag.related))


__all__ = ["Analysis", "Related", "analyse", "run_checks", "with_uri"]
