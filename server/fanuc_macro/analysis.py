"""The pipeline of one document: text → blocks → AST → program index → rules → diagnostics.

The CLI and the language server both call :func:`analyse`; neither holds analysis of its own.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from operator import attrgetter

from .cancel import RULE_CHECKS, CancelToken, raise_if_cancelled
from .config import Config, ignored_in
from .database import current
from .diagnostics import (
    REPORT_INTERNAL_ERROR,
    Diagnostic,
    Related,
    RuleDoc,
    RuleInfo,
    Severity,
    make,
)
from .evaluator import Facts, evaluate
from .line_maps import LineMap
from .program.index import ProgramIndex, build_index
from .program.machine_kind import machine_config, mill_reading, readings_differ
from .rules import ALL_CHECKS, FAMILIES, LINE_CHECKS, LineFinding, declared, plain_line_quiet
from .rules.context import RuleContext
from .rules.dialect import (
    FANUC_RECORD_CODES,
    FOLDED_CODES,
    dialect_of_blocks,
    fold_foreign_file,
    foreign_dialect,
    past_the_stop,
    unrecognised_dialect,
)
from .rules.expressions import fold_missing_variables
from .rules.reading import (
    fold_elisions,
    fold_long_numbers,
    fold_lowercase,
    fold_runaway_comments,
)
from .rules.suppression import Hidden, Marks, marks_of
from .syntax.parser import BlockParser, default_parser, parse_text, quiet_gc
from .syntax.tree import Document, ParsedLine, PlainNc
from .threads.identify import Thread
from .translation import tr


def log_failure(logger: str, message: str, *args: object) -> None:
    """Logs the exception being handled, with its traceback, to ``logger``. ``logging`` is
    imported here, when something failed: a start does not load it (4 ms of a check). The
    package's logger gets a NullHandler when it has none, as a library's should: a traceback
    goes where a front end sends the log (``--verbose``, ``--log-file``, the server's log), not
    to the terminal by default."""
    import logging

    package = logging.getLogger("fanuc_macro")
    if not package.handlers:
        package.addHandler(logging.NullHandler())
    logging.getLogger(logger).exception(message, *args)


# The analysis's own code: a rule or the evaluator failed (internal_error gives the message).
MB000 = RuleInfo(
    "MB000",
    "internal-error",
    Severity.ERROR,
    "The analyser failed on this document; the message says where.",
    "internal",
)
MB000_DOC = RuleDoc(
    "MB000",
    reports="""
One of the rules (or the evaluator) failed with an exception on this
document. The message names the rule function and the codes it gives, the exception, and how
to report it. The other rules still ran, so the other diagnostics are valid. The traceback is
not printed by default: `fanuc-macro check --verbose` prints it, `--log-file PATH` writes it to
a file, and the language server writes it to its log.
""",
    why="""
It does not come from the program: nothing will happen on
the control because of it. But the failed rule checked nothing, so a problem that rule looks
for may be in the program unreported.
""",
    example="""
No correct program should produce it; a report looks like this:

```text
prog.nc:1:1: MB000 error internal error in rule rules.expressions.check_line (MB301-MB304):
OverflowError(...); this is a bug in fanuc-macro, not in the program: please report it with
the program text (or this block) and the traceback, which `fanuc-macro check --verbose` prints
and the language server writes to its log (--log-file)
```
""",
    fix="""
Report it with the block that causes it (the smallest program that reproduces
it) and the traceback. Until it is fixed, check by hand what the failed rule family covers.
""",
    not_reported="""
Anything about the program: it says only that a rule failed. A rule
that fails on one document does not stop the others, nor the analysis of other documents.
""",
)


# Every rule and its documentation, by code: built once from the declarations.
RULES = declared(RuleInfo, FAMILIES, MB000)
RULE_DOCS = declared(RuleDoc, FAMILIES, MB000_DOC)


def rule_name(check: Callable[..., object]) -> str:
    """``rules.jumps.check (MB101-MB104)``: the function that failed and the codes it gives."""
    module = getattr(check, "__module__", None) or "?"
    family = getattr(sys.modules.get(module), "FAMILY", None)
    codes = sorted(c for c, info in RULES.items() if family is not None and info.family == family)
    name = f"{module.removeprefix('fanuc_macro.')}.{getattr(check, '__name__', '?')}"
    if not codes:
        return name
    return f"{name} ({codes[0] if len(codes) == 1 else codes[0] + '-' + codes[-1]})"


def internal_error(what: str, err: BaseException) -> str:
    """The message of an MB000: ``what`` failed (:func:`failed_rule`, or the evaluator)."""
    return tr(
        "internal error in {what}: {error_text}; {report}",
        what=what,
        error_text=repr(err),
        report=REPORT_INTERNAL_ERROR,
    )


def failed_rule(check: Callable[..., object]) -> str:
    """``rule rules.jumps.check (MB101-MB104)``, as an MB000 names a rule that failed."""
    return tr("rule {rule_text}", rule_text=rule_name(check))


ExtraChecks = Callable[[RuleContext], Iterable[Diagnostic]]


@dataclass(eq=False, repr=False)
class Analysis:
    doc: Document
    index: ProgramIndex
    diagnostics: list[Diagnostic] = field(default_factory=list)
    facts: Facts | None = None  # the evaluator's, when it ran
    threads: list[Thread] = field(default_factory=list)  # what the threading rules saw
    # The settings the document was analysed with: its machine resolved (machine_kind).
    config: Config | None = None
    # The mill's reading's facts when the machine is not known (kept for the next analysis).
    mill_facts: Facts | None = None


# The lines whose comments suppress diagnostics: few, and kept from edit to edit.
suppressions: LineMap[Marks] = LineMap(marks_of)


def _apply_settings(
    diags: Iterable[Diagnostic], doc: Document, config: Config, whole: bool = False
) -> list[Diagnostic]:
    """Drop disabled and suppressed diagnostics; apply configured severities. ``whole``: every
    rule ran on a whole run, so a suppression comment that hid nothing is told (MB015)."""
    marks = dict(suppressions(doc))
    hidden = Hidden(marks) if marks else None
    disabled = config.disabled | ignored_in(config, doc.uri)
    selected = config.selected
    out: list[Diagnostic]
    if hidden is None and not disabled and not config.severities and selected is None:
        out = list(diags)  # nothing to drop or change: tens of thousands in a dense program
    else:
        found = list(diags)
        if hidden is not None:
            visible = [d for d in found if not hidden.hides(d.line, d.code)]
            if whole:
                judged = frozenset(c for c in RULES if _reported(c, disabled, selected))
                visible += hidden.unused(judged)
            found = visible
        out = []
        for d in found:
            if not _reported(d.code, disabled, selected):
                continue
            severity = config.severities.get(d.code)
            out.append(d.with_severity(severity) if severity else d)
    out.sort(key=_position)
    return out


def _reported(code: str, disabled: frozenset[str], selected: tuple[str, ...] | None) -> bool:
    """Whether the settings report ``code`` (MB000, the analyser's own failure, always)."""
    if code in disabled:
        return False
    return selected is None or code == MB000.code or code.startswith(selected)


_position = attrgetter("line", "column", "code")  # a diagnostic's place in the list, in C


def _line_findings(parsed: ParsedLine) -> tuple[LineFinding, ...]:
    """The line rules' findings for one line's text."""
    found: list[LineFinding] = []
    for check in LINE_CHECKS:
        try:
            found.extend(check(parsed))
        except Exception as err:  # a bug in one rule must not hide the others
            log_failure(__name__, "line rule %s failed on %r", rule_name(check), parsed.text[:200])
            found.append(LineFinding("MB000", internal_error(failed_rule(check), err), 0, 0))
    return tuple(found)


def _findings_of_line(parsed: ParsedLine) -> tuple[LineFinding, ...] | None:
    if parsed.statement is None and parsed.problem is None and not parsed.notes:
        return None  # a comment or an empty line: no line rule has anything to say
    if type(parsed.statement) is PlainNc and plain_line_quiet(parsed):
        return None  # words of numbers: nothing, by its flags and its G and M codes
    # Not through a per-line cache: the map keeps the findings and looks at a line again only
    # when it changed, so an entry per line would only hold memory.
    return _line_findings(parsed) or None


# The lines with a line rule's finding: after an edit only the edited lines are looked at again.
lines_with_findings: LineMap[tuple[LineFinding, ...]] = LineMap(_findings_of_line)


def run_checks(
    ctx: RuleContext, checks: Iterable[ExtraChecks], cancel: CancelToken | None = None
) -> list[Diagnostic]:
    found: list[Diagnostic] = []
    blocks = ctx.doc.blocks
    stop_line: int | None = None  # a foreign file's first block FANUC rejects
    per_block = [(line, blocks[line].parsed, f) for line, f in lines_with_findings(ctx.doc, cancel)]
    foreign = foreign_dialect(ctx.doc) or dialect_of_blocks(per_block)
    if foreign is None:
        rejected = [line for line, _, f in per_block if any(x.code in FOLDED_CODES for x in f)]
        foreign = unrecognised_dialect(ctx.doc, rejected)
    if foreign is None:
        per_block = fold_lowercase(fold_elisions(fold_runaway_comments(per_block)))
        per_block = fold_long_numbers(per_block)
        per_block = fold_missing_variables(per_block)
    elif blocks:  # another control's file: one MB002 for the blocks FANUC rejects
        first = next((b for b in blocks if b.text.strip() not in ("", "%")), blocks[0])
        per_block, whole_file = fold_foreign_file(per_block, foreign, first.line, first.text)
        if whole_file is not None:
            found.append(whole_file)
            stop_line = min(r.line for r in whole_file.related)
    for line, _, findings in per_block:
        for f in findings:
            fixes = [fix.on_line(line) for fix in f.fixes] if f.fixes else ()
            found.append(make(RULES[f.code], f.message, line, f.start, f.end, fixes=fixes))
    rules = list(checks)
    for done, rule in enumerate(rules):
        if cancel is not None:
            cancel.reached(RULE_CHECKS, done, len(rules))
        try:
            found.extend(
                d
                for d in rule(ctx)
                if not past_the_stop(d, stop_line)
                and (foreign is None or d.code not in FANUC_RECORD_CODES)
            )
        except Exception as err:  # a bug in one rule must not hide the others
            log_failure(__name__, "rule %s failed on %s", rule_name(rule), ctx.doc.uri)
            message = internal_error(failed_rule(rule), err)
            found.append(make(MB000, message, 0, 0, 0))
    return found


# What the caches of a database (its cache tables and its parser's lines) may hold, in bytes
# as :func:`cache_bytes` estimates them. Past it they are dropped before the next analysis or
# edit, and built again from the lines read after: a server's memory levels off, whatever it
# has read in a day.
CACHE_BUDGET = 64 * 1024 * 1024
# The estimate's weights, measured with tracemalloc on the corpus and on 5,000 typed lines
# (tests/test_cache_budget.py checks the estimate against the bytes traced): a cached parsed
# line with its tree, a character of its text, and an entry of another cache (an interned
# span, a compiled expression, a per-line rule value). An entry took 320 bytes while a
# closure held its values in cells; with them as defaults, about 150-250 (thirty programs of
# 120 distinct lines: 11.2 MB held, 12.0 MB before): the weight keeps to the high side.
BYTES_PER_LINE = 800
BYTES_PER_CHAR = 24
BYTES_PER_ENTRY = 240


def cache_bytes(parser: BlockParser) -> int:
    """The bytes the current database's caches and ``parser``'s cached lines hold, estimated
    from their entries (deterministic: no measure of the process)."""
    lines, chars = parser.cached()
    entries = current().cache_entries()
    return lines * BYTES_PER_LINE + chars * BYTES_PER_CHAR + entries * BYTES_PER_ENTRY


def keep_caches_within_budget(parser: BlockParser, budget: int | None = None) -> bool:
    """Drop the current database's caches and ``parser``'s lines if they pass ``budget``
    (:data:`CACHE_BUDGET` by default; True then). Called where no analysis runs in this
    database: before one starts."""
    if cache_bytes(parser) <= (CACHE_BUDGET if budget is None else budget):
        return False
    current().drop_caches()
    parser.clear_cache()
    return True


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
    previous_facts: Facts | None = None,
    cancel: CancelToken | None = None,
    mill_facts: Facts | None = None,
    mill_previous: Facts | None = None,
) -> Analysis:
    """Parse (unless ``doc`` is given), index, evaluate and check one document.

    ``other_documents`` are the workspace's other files: the programs this one calls.
    ``facts`` from an earlier run of the same programs spare the evaluator (see
    :meth:`fanuc_macro.workspace.Workspace.analyse`); ``previous_facts``, from a run of an
    earlier version of the same documents, let it resume where the edit begins to matter. A
    set ``cancel`` token stops the analysis at its next block boundary with
    :class:`~fanuc_macro.cancel.Cancelled` (none is given by the command line); nothing is
    returned then, and the caches hold only whole lines' results.
    """
    raise_if_cancelled(cancel)
    keep_caches_within_budget(parser or default_parser())
    with quiet_gc():  # the run makes many small objects and no cycles
        config = config or Config()
        if doc is None:
            doc = parse_text(
                text, uri, parser or default_parser(), limits=config.read_limits, cancel=cancel
            )
        if index is None:
            index = build_index(doc)
        config = machine_config(config, doc, index)
        failed: list[Diagnostic] = []
        if run_evaluator and facts is None:
            try:
                facts = evaluate(
                    [(uri, doc, index), *other_documents],
                    config,
                    only_uri=uri,
                    previous=previous_facts,
                    cancel=cancel,
                )
            except Exception as err:  # the structural rules still report
                log_failure(__name__, "evaluation of %s failed", uri)
                message = internal_error(
                    tr("the evaluator (its rules MB501-MB903 did not run)"), err
                )
                failed.append(make(MB000, message, 0, 0, 0))
        ctx = RuleContext(doc, index, config, workspace_programs, facts, other_documents)
        found = failed + run_checks(ctx, [*ALL_CHECKS, *extra_checks], cancel)
        threads: list[Thread] = []
        if facts is not None:
            try:
                threads = ctx.threads()
            except Exception:  # reported as MB000 by the rules that asked for them
                log_failure(__name__, "thread identification of %s failed", uri)
        # A suppression is judged on a whole run where every rule ran: not when the safety net
        # stopped the run, nor when a rule or the evaluator failed (MB000).
        whole = (
            facts is not None
            and facts.stopped is None
            and not any(d.code == MB000.code for d in found)
        )
        diagnostics = _apply_settings(found, doc, config, whole)
        kept_mill: Facts | None = None
        if not config.machine_known and readings_differ(doc):
            # Neither machine shown: only what a lathe's and a mill's reading both find.
            mill = analyse(
                text,
                uri,
                mill_reading(config),
                workspace_programs,
                parser,
                extra_checks,
                doc,
                index,
                other_documents,
                run_evaluator,
                mill_facts,
                mill_previous,
                cancel,
            )
            both = {_verdict(d) for d in mill.diagnostics}
            diagnostics = [d for d in diagnostics if _verdict(d) in both]
            kept_mill = mill.facts
        return Analysis(doc, index, diagnostics, facts, threads, config, kept_mill)


def _verdict(diag: Diagnostic) -> tuple[str, str, int, int, int, int]:
    """What a diagnostic says, where: the same in two readings of a document."""
    return diag.code, diag.message, diag.line, diag.column, diag.end_line, diag.end_column


def with_uri(diag: Diagnostic, uri: str) -> Diagnostic:
    return replace(diag, related=tuple(replace(r, uri=r.uri or uri) for r in diag.related))


__all__ = ("RULES", "RULE_DOCS", "Analysis", "Related", "analyse", "run_checks", "with_uri")
