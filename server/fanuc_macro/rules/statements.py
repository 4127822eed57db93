"""MB4xx: statements and calls: mixed blocks, G65 arguments, call targets, repeat counts."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleInfo, Severity, make, register
from ..parser import statements_of
from ..syntax import IfNc, Mixed, NcStatement, Num, ParsedLine, Word
from ..variables import FORBIDDEN_ARGUMENTS
from .context import LineFinding, RuleContext

FAMILY = "statements"
register(
    RuleInfo("MB401", "nc-and-macro", Severity.ERROR,
             "An NC statement and a macro statement in one block (alarm PS0127).", FAMILY),
    RuleInfo("MB402", "g65-argument-letter", Severity.ERROR,
             "G, L, N, O or P used as a G65/G66 argument (alarm PS0129 for G).", FAMILY),
    RuleInfo("MB403", "call-target-missing", Severity.WARNING,
             "M98/G65/G66 calls a program that is in neither the file nor the workspace.",
             FAMILY),
    RuleInfo("MB404", "argument-without-decimal-point", Severity.INFORMATION,
             "A G65 argument written without a decimal point: its value depends on the "
             "machine's least input increment.", FAMILY),
    RuleInfo("MB405", "repeat-count", Severity.ERROR,
             "An L repeat count outside 1-9999, or a call with no P.", FAMILY),
)  # fmt: skip


def check_line(parsed: ParsedLine) -> Iterator[LineFinding]:
    statement = parsed.statement
    if isinstance(statement, Mixed):
        m = statement.macro.span
        n = statement.nc.span
        yield LineFinding(
            "MB401",
            f"macro statement {parsed.text[m.start : m.end]!r} in the same block as NC "
            f"words {parsed.text[n.start : n.end]!r}: FANUC raises PS0127; put "
            "them in separate blocks",
            m.start,
            m.end,
        )


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    local_programs = {p.number for p in ctx.index.programs if p.number is not None}
    known = local_programs | set(ctx.workspace_programs or ())
    for program in ctx.index.programs:
        for call in program.calls:
            line = call.line
            span = call.span
            if call.kind == "M97":
                continue  # Haas local subroutine: MB002 says so
            words = _words(ctx, line)
            if call.program_span is None:
                if call.kind == "M98" and any(w.address == "H" for w in words):
                    continue  # Citizen's M98 H<n>: MB002 says so
                yield make(
                    "MB405",
                    f"{call.kind} without P: no program to call",
                    line,
                    span.start,
                    span.end,
                )
                continue
            if call.program is not None and call.program not in known:
                where = "this file" if ctx.workspace_programs is None else "the workspace"
                ps = call.program_span
                yield make(
                    "MB403",
                    f"{call.kind} calls O{call.program:04d}, which is not in "
                    f"{where} (alarm PS0076 if it is not in the control's memory)",
                    line,
                    ps.start,
                    ps.end,
                    data={"program": call.program},
                )
            if call.repeat is not None and not 1 <= call.repeat <= 9999:
                l_word = next((w for w in words if w.address == "L"), None)
                at = l_word.span if l_word is not None else span
                yield make(
                    "MB405",
                    f"{call.kind} repeat count {call.repeat} is outside 1-9999",
                    line,
                    at.start,
                    at.end,
                )
            for word in call.arguments:
                if word.address in FORBIDDEN_ARGUMENTS and not (
                    call.kind == "G66.1" and word.address == "G"
                ):
                    yield make(
                        "MB402",
                        f"{word.address} cannot be a {call.kind} argument; "
                        "arguments are A-Z except G, L, N, O, P",
                        line,
                        word.span.start,
                        word.span.end,
                    )
                elif (
                    word.address != "G"  # a G code in a G66.1 block, not an argument
                    and isinstance(word.value, Num)
                    and not word.value.has_decimal_point
                ):
                    value = word.value.value
                    yield make(
                        "MB404",
                        f"argument {word.address}{word.value.text} has no decimal "
                        f"point: the macro receives {value:g} x the least input "
                        f"increment (e.g. {value / 1000:g} on IS-B), not {value:g}; write "
                        f"{word.address}{word.value.text}.",
                        line,
                        word.span.start,
                        word.span.end,
                    )


def _words(ctx: RuleContext, line: int) -> tuple[Word, ...]:
    for statement in statements_of(ctx.doc.blocks[line].statement):
        nc = statement.words if isinstance(statement, IfNc) else statement
        if isinstance(nc, NcStatement):
            return nc.words
    return ()
