"""MB6xx: address values computed at run time: non-integers and impossible values."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, Related, RuleInfo, Severity, make, register
from ..syntax import Assign, Var, Word
from .context import RuleContext

FAMILY = "addresses"
register(
    RuleInfo("MB601", "address-not-integer", Severity.ERROR,
             "An M, S, T, P, L, H, D or G address gets a value that is not a whole number.",
             FAMILY),
    RuleInfo("MB602", "address-out-of-range", Severity.WARNING,
             "An address gets an impossible value: negative S/T/M/F, S above the machine's "
             "maximum spindle speed.", FAMILY),
    RuleInfo("MB603", "feed-not-set", Severity.WARNING,
             "A G01/G02/G03 cut runs before any F was commanded.", FAMILY),
)  # fmt: skip


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    yield from _feed_not_set(ctx)
    for f in ctx.findings("address-"):
        code = "MB601" if f.kind == "address-non-integer" else "MB602"
        message = f.message
        related: list[Related] = []
        word = _word_at(ctx, f.line, f.column)
        if word is not None and isinstance(word.value, Var) and word.value.number is not None:
            n = int(word.value.number)
            origin = _last_assignment(ctx, f.line, n)
            if origin is not None:
                line, text = origin
                message += f" (#{n} set at line {line + 1}: {text})"
                related.append(
                    Related(line, 0, len(ctx.doc.blocks[line].text), f"#{n} is set here")
                )
                hint = _likely_meant(ctx, f.line, word.address)
                if hint:
                    message += f"; did you mean {word.address}{hint}?"
        yield make(code, message, f.line, f.column, f.end_column, related=related)


def _feed_not_set(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB603. F is modal: a cut with none commanded since the program started runs at what an
    earlier program left, or stops with PS0011 FEED ZERO (COMMAND) after power-on, when F is 0
    (FANUC 0i-D alarm list; the power-on F of parameter 1411 is unverified here)."""
    for f in ctx.findings("feed-not-set"):
        text = ctx.doc.blocks[f.line].text
        yield make(
            "MB603",
            f"{f.message}: the feed is what an earlier program left, or 0 after power-on "
            "(alarm PS0011 FEED ZERO); give F in this block or before it",
            f.line,
            len(text) - len(text.lstrip()),
            len(text.rstrip()),
        )


def _word_at(ctx: RuleContext, line: int, column: int) -> Word | None:
    from ..parser import statements_of
    from ..syntax import IfNc, NcStatement

    for statement in statements_of(ctx.doc.blocks[line].statement):
        nc = statement.words if isinstance(statement, IfNc) else statement
        if isinstance(nc, NcStatement):
            for w in nc.words:
                if w.span.start == column:
                    return w
    return None


def _last_assignment(ctx: RuleContext, before: int, number: int) -> tuple[int, str] | None:
    program = ctx.index.program_at(before)
    first = program.first_line if program else 0
    for line in range(before - 1, first - 1, -1):
        statement = ctx.doc.blocks[line].statement
        if isinstance(statement, Assign) and statement.target.number == number:
            return line, ctx.doc.blocks[line].text.strip()
    return None


def _likely_meant(ctx: RuleContext, line: int, address: str) -> str | None:
    """A local assigned in the same program whose comment names this address (M#13 for M#1)."""
    program = ctx.index.program_at(line)
    if program is None:
        return None
    for ln in range(program.first_line, line):
        block = ctx.doc.blocks[ln]
        statement = block.statement
        if not isinstance(statement, Assign) or statement.target.number is None:
            continue
        comment = " ".join(c.text for c in block.parsed.comments).upper()
        if f" {address} " in f" {comment} " or f"{address}代码" in comment.replace(" ", ""):
            return f"#{int(statement.target.number)}"
    return None
