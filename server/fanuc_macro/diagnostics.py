"""Diagnostics, and what declares the rules that produce them.

Every diagnostic has a code (``MB101``). A rule family's module declares each of its rules as
a ``RuleInfo`` constant named by its code (``MB101``), and each rule's documentation (what it
reports, why it matters on the machine, an example, the fix, what it does not report) as a
``RuleDoc`` constant (``MB101_DOC``) beside the function that finds it. ``analysis.RULES`` and
``analysis.RULE_DOCS`` are built once from them; docs/rules.md is generated from them
(``python3 scripts/rules_doc.py``). Positions are 0-based lines and columns in characters.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace
from enum import Enum


class Severity(str, Enum):
    ERROR = "error"
    WARNING = "warning"
    INFORMATION = "information"
    HINT = "hint"


class Tag(str, Enum):
    """What an editor shows of a diagnostic beside its severity."""

    UNNECESSARY = "unnecessary"  # code that never runs: shown faded
    DEPRECATED = "deprecated"  # a form the control still reads but should not be written


@dataclass(frozen=True, slots=True)
class Related:
    """Another place that explains a diagnostic (the assignment that produced a bad value)."""

    line: int
    column: int
    end_column: int
    message: str
    uri: str | None = None  # None: the same document


@dataclass(frozen=True, slots=True)
class FixEdit:
    """One replacement of a fix: the text from (line, column) to (end_line, end_column)
    becomes ``text`` (an insertion when the two places are the same)."""

    line: int
    column: int
    end_line: int
    end_column: int
    text: str

    @staticmethod
    def insert(line: int, column: int, text: str) -> FixEdit:
        return FixEdit(line, column, line, column, text)


@dataclass(frozen=True, slots=True)
class Fix:
    """A quick fix of a diagnostic, without a protocol: a title saying what it does, and the
    edits of the diagnostic's document that make it. ``preferred``: the one obvious fix."""

    title: str
    edits: tuple[FixEdit, ...]
    preferred: bool = False
    # Whether ``check --fix`` applies it without --unsafe-fixes: it mends only the mistake and
    # changes nothing the control does otherwise (a comment closed). A fix that changes what
    # the program does (a value, a jump, a loop) is the programmer's choice.
    safe: bool = False

    def on_line(self, line: int) -> Fix:
        """The fix of a line rule's finding (its edits on line 0) for the block on ``line``."""
        edits = tuple(
            FixEdit(e.line + line, e.column, e.end_line + line, e.end_column, e.text)
            for e in self.edits
        )
        return Fix(self.title, edits, self.preferred, self.safe)


@dataclass(frozen=True, slots=True)
class Diagnostic:
    code: str
    severity: Severity
    message: str
    line: int
    column: int
    end_line: int
    end_column: int
    related: tuple[Related, ...] = ()
    data: dict[str, object] | None = field(default=None, compare=False, hash=False)
    # The quick fixes a rule works out with the diagnostic; the command line's output leaves
    # them out, the language server offers them as code actions.
    fixes: tuple[Fix, ...] = ()
    tags: frozenset[Tag] = frozenset()  # the rule's (RuleInfo.tags)

    def with_severity(self, severity: Severity) -> Diagnostic:
        return replace(self, severity=severity)


@dataclass(frozen=True, slots=True, eq=False, repr=False)
class RuleInfo:
    """A rule, declared once by its family's module: what each of its diagnostics gets."""

    code: str
    name: str  # kebab-case, e.g. "goto-missing-label"
    severity: Severity
    summary: str
    family: str
    tags: frozenset[Tag] = frozenset()  # on every diagnostic of the rule


@dataclass(frozen=True, slots=True, eq=False, repr=False)
class RuleDoc:
    """The documentation of one rule, in markdown: its section of docs/rules.md.

    Each part is a paragraph or more; the generator (fanuc_macro.rules_doc) strips the blank
    lines around it and writes it after its bold label.
    """

    code: str
    reports: str  # What it reports.
    why: str  # Why it matters on the machine.
    example: str  # Example: a program that triggers the rule, in a ```nc block.
    fix: str  # How to fix.
    not_reported: str  # What it does not report: what the rule's code leaves out.
    severity_note: str = ""  # after the default severity: when the rule gives another


def line_list(lines: Sequence[int], shown: int = 8) -> str:
    """``12, 40, 77, ...``: the first of some 0-based lines, as the user numbers them."""
    text = ", ".join(str(n + 1) for n in lines[:shown])
    return text + (", ..." if len(lines) > shown else "")


def make(
    rule: RuleInfo,
    message: str,
    line: int,
    column: int,
    end_column: int,
    *,
    end_line: int | None = None,
    related: Iterable[Related] = (),
    severity: Severity | None = None,
    data: dict[str, object] | None = None,
    fixes: Iterable[Fix] = (),
) -> Diagnostic:
    return Diagnostic(
        rule.code,
        severity or rule.severity,
        message,
        line,
        column,
        line if end_line is None else end_line,
        max(end_column, column),
        tuple(related),
        data,
        tuple(fixes),
        rule.tags,
    )


# What an internal error (MB000) tells the user to do: it is the analyser's bug, not theirs.
REPORT_INTERNAL_ERROR = (
    "this is a bug in fanuc-macro, not in the program: please report it with the program text "
    "(or this block) and the traceback, which `fanuc-macro check --verbose` prints and the "
    "language server writes to its log (--log-file)"
)


_SUPPRESS = re.compile(
    r"fanuc-macro\s*:\s*ignore(?:-(file|start|end))?(?![\w-])\s*((?:MB\d+[\s,]*)*)", re.I
)
# Where a suppression comment acts: its line, the whole file, or the lines from an
# ``ignore-start`` to the next ``ignore-end`` (both included).
LINE, FILE, START, END = "line", "file", "start", "end"


def suppression_in(comment_text: str) -> tuple[str, frozenset[str]] | None:
    """Where ``(fanuc-macro: ignore MB301)``, ``ignore-file``, ``ignore-start`` or
    ``ignore-end`` acts and the codes it names (none: every code); None for another comment."""
    m = _SUPPRESS.search(comment_text)
    if m is None:
        return None
    codes = frozenset(c.upper() for c in re.findall(r"MB\d+", m.group(2), re.I))
    return (m.group(1) or LINE).lower(), codes


def suppressed_codes(comment_text: str) -> set[str] | None:
    """Codes named by ``(fanuc-macro: ignore MB301 MB302)``; an empty set means every code."""
    found = suppression_in(comment_text)
    if found is None or found[0] != LINE:
        return None
    return set(found[1])
