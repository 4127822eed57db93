"""MB0xx: reading the text. Syntax errors, comments, end of block, case, encoding."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleInfo, Severity, make, register
from ..syntax import ParsedLine
from .context import LineFinding, RuleContext

FAMILY = "reading"
register(
    RuleInfo("MB001", "syntax-error", Severity.ERROR,
             "The block does not follow FANUC Macro B syntax.", FAMILY),
    RuleInfo("MB003", "nested-comment", Severity.WARNING,
             "Parentheses nested in a comment: FANUC ends the comment at the first ')'.", FAMILY),
    RuleInfo("MB004", "unclosed-comment", Severity.WARNING,
             "A comment is opened with '(' and not closed on its line.", FAMILY),
    RuleInfo("MB005", "text-after-eob", Severity.ERROR,
             "Program text after the end-of-block ';' on the same line.", FAMILY),
    RuleInfo("MB006", "lowercase", Severity.WARNING,
             "Lowercase letters outside comments; FANUC program text is uppercase.", FAMILY),
    RuleInfo("MB007", "encoding", Severity.INFORMATION,
             "The file is not UTF-8; it was read in another encoding.", FAMILY),
    RuleInfo("MB008", "unknown-function", Severity.ERROR,
             "A name used as a function that FANUC does not have.", FAMILY),
)  # fmt: skip

_NOTE_CODES = {"nested-comment": "MB003", "unclosed-comment": "MB004", "text-after-eob": "MB005"}


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    if ctx.doc.decode_note:
        yield make("MB007", ctx.doc.decode_note, 0, 0, 0)


def check_line(parsed: ParsedLine) -> Iterator[LineFinding]:
    problem = parsed.problem
    if problem is not None and problem.dialect is None:
        code = "MB008" if problem.unknown_function else "MB001"
        yield LineFinding(code, problem.message, problem.span.start, problem.span.end)
    for note in parsed.notes:
        yield LineFinding(_NOTE_CODES[note.kind], note.message, note.span.start, note.span.end)
    if parsed.has_lowercase and problem is None:
        col = next(
            (i for i, ch in enumerate(parsed.text) if ch.islower() and _outside(parsed, i)),
            None,
        )
        if col is not None:
            yield LineFinding(
                "MB006",
                f"lowercase {parsed.text[col]!r} at column {col + 1}: FANUC program text is "
                "uppercase; the control may reject it",
                col,
                col + 1,
            )


def _outside(parsed: ParsedLine, col: int) -> bool:
    return all(not (c.span.start <= col < c.span.end) for c in parsed.comments)
