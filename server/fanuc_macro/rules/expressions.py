"""MB3xx: expressions and variables: bracket nesting, variable numbers, read-only targets."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import RuleInfo, Severity, register
from ..syntax import Assign, IfThen, ParsedLine
from ..variables import classify
from ..walk import bracket_depth, top_expressions, variables
from .context import LineFinding, line_statements

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
            elif kind.kind == "extended-common":
                yield LineFinding(
                    "MB303",
                    f"#{number} exists only with the extended common variable option (0i-F / 30i)",
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
