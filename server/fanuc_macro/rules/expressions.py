"""MB3xx: expressions and variables: bracket nesting, variable numbers, read-only targets."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, Related, RuleInfo, Severity, make, register
from ..per_line import PerLine
from ..syntax import Assign, IfThen, ParsedLine
from ..variables import classify
from ..walk import bracket_depth, top_expressions, variables
from .context import LineFinding, RuleContext, line_statements

FAMILY = "expressions"
MAX_BRACKET_NESTING = 5
register(
    RuleInfo("MB301", "bracket-nesting", Severity.ERROR,
             "Brackets nested more than five deep, function brackets included (PS0118).", FAMILY),
    RuleInfo("MB302", "no-such-variable", Severity.ERROR,
             "A variable number that does not exist on a FANUC control (PS0115).", FAMILY),
    RuleInfo("MB303", "extended-common", Severity.INFORMATION,
             "A common variable of #200-#499, which exists only with an option.", FAMILY),
    RuleInfo("MB304", "write-read-only", Severity.ERROR,
             "An assignment to #0 or to a read-only system variable (PS0116).", FAMILY),
)  # fmt: skip


def check_line(parsed: ParsedLine) -> Iterator[LineFinding]:
    for statement in line_statements(parsed):
        for expr in top_expressions(statement):
            depth = bracket_depth(expr)
            if depth > MAX_BRACKET_NESTING:
                yield LineFinding(
                    "MB301",
                    f"brackets nested {depth} deep; FANUC allows "
                    f"{MAX_BRACKET_NESTING} (alarm PS0118)",
                    expr.span.start,
                    expr.span.end,
                )
        for var in variables(statement):
            if var.number is None or var.number != int(var.number):
                continue
            number = int(var.number)
            kind = classify(number)
            if kind.kind == "none":
                yield LineFinding(
                    "MB302",
                    f"#{number} does not exist on a FANUC control (alarm "
                    "PS0115): locals are #1-#33, commons #100-#199 and #500-#999",
                    var.span.start,
                    var.span.end,
                )
        targets = [statement] if isinstance(statement, Assign) else []
        if isinstance(statement, IfThen):
            targets.append(statement.then)
        for assign in targets:
            target = assign.target
            if target.number is None or target.number != int(target.number):
                continue
            kind = classify(int(target.number))
            if kind.read_only:
                what = "#0 is always vacant" if target.number == 0 else kind.meaning
                yield LineFinding(
                    "MB304",
                    f"#{int(target.number)} is read-only ({what}); writing it raises alarm PS0116",
                    target.span.start,
                    target.span.end,
                )


def _extended_commons(parsed: ParsedLine) -> tuple[tuple[int, int, int], ...]:
    """(number, start, end) of each #200-#499 the line names, in source order."""
    found: list[tuple[int, int, int]] = []
    for statement in line_statements(parsed):
        for var in variables(statement):
            number = var.number
            if number is not None and number == int(number) and 200 <= number <= 499:
                found.append((int(number), var.span.start, var.span.end))
    return tuple(sorted(found, key=lambda f: f[1]))


_extended_of: PerLine[tuple[tuple[int, int, int], ...]] = PerLine(_extended_commons)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB303, once per file at the first use: whether the option is there is one fact about
    the machine, not about each block. The range #200-#499 is the reference's (macro-b.md 2.1:
    "Extended ranges ... are options" [K], unverified against B-64604EN)."""
    if ctx.config.extended_commons:
        return
    uses: list[tuple[int, int, int, int]] = []  # (line, number, start, end)
    for block in ctx.doc.blocks:
        if block.parsed.statement is None:
            continue
        for number, start, end in _extended_of(block.parsed):
            uses.append((block.line, number, start, end))
    if not uses:
        return
    line, number, start, end = uses[0]
    last = uses[-1][0]
    numbers = sorted({u[1] for u in uses})
    shown = ", ".join(f"#{n}" for n in numbers[:6]) + (", ..." if len(numbers) > 6 else "")
    if len(uses) == 1:
        where = "its only use in this file"
    else:
        where = (
            f"the first of {len(uses)} uses of #200-#499 in this file, lines {line + 1}-"
            f"{last + 1} ({shown})"
        )
    yield make(
        "MB303",
        f"#{number} is {where}: these common variables exist only with the extended common "
        "variable option (0i-F / 30i); without it each use stops with alarm PS0115. If the "
        "machine has the option, say so (setting fanuc-macro.machine.extendedCommons, "
        "--extended-commons)",
        line,
        start,
        end,
        related=[Related(last, uses[-1][2], uses[-1][3], "the last use")] if last != line else [],
    )
