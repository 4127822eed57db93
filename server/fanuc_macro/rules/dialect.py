"""MB002: forms of other controls' dialects (Haas, Mitsubishi/Citizen, LinuxCNC, LNC/Syntec)."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import RuleInfo, Severity, register
from ..index import constant_value
from ..syntax import BareCond, BlockIf, IfGoto, IfNc, NcStatement, ParsedLine, Var, While
from ..walk import variables
from .context import LineFinding, line_statements

FAMILY = "dialect"
register(
    RuleInfo("MB002", "not-fanuc", Severity.ERROR,
             "A form another control accepts and a FANUC control rejects.", FAMILY),
)  # fmt: skip


def check_line(parsed: ParsedLine) -> Iterator[LineFinding]:
    problem = parsed.problem
    if problem is not None and problem.dialect is not None:
        yield LineFinding(
            "MB002", f"{problem.dialect}: {problem.message}", problem.span.start, problem.span.end
        )
    for statement in line_statements(parsed):
        span = statement.span
        if isinstance(statement, IfNc):
            form = "IF [...] THEN <NC words>" if statement.has_then else "IF [...] <NC words>"
            yield LineFinding(
                "MB002",
                f"Haas: '{form}' is not FANUC; FANUC's IF takes GOTO n, or THEN "
                "with one macro statement (alarm PS0125)",
                span.start,
                span.end,
            )
        elif isinstance(statement, BlockIf):
            yield LineFinding(
                "MB002",
                f"Haas NGC: block {statement.keyword} (IF ... THEN / ELSE / ENDIF "
                "on their own lines) is not FANUC 0i/16i/30i; use IF [...] GOTO n",
                span.start,
                span.end,
            )
        elif isinstance(statement, NcStatement):
            has_p = statement.find("P") is not None
            for word in statement.words:
                value = constant_value(word.value)
                if word.address == "M" and value == 98.0 and statement.find("H") and not has_p:
                    yield LineFinding(
                        "MB002",
                        "Mitsubishi/Citizen: M98 H<n> (a call to a sequence "
                        "number) is not FANUC; FANUC's M98 takes P<program>",
                        word.span.start,
                        word.span.end,
                    )
                # A bare M97 is an ordinary M code on FANUC; with P it is Haas's local call.
                if word.address == "M" and value == 97.0 and has_p:
                    yield LineFinding(
                        "MB002",
                        "Haas: M97 (local subroutine at an N number) is not FANUC;"
                        " use M98 P<program>",
                        word.span.start,
                        word.span.end,
                    )
        if isinstance(statement, (IfGoto, While)) and isinstance(statement.cond, BareCond):
            c = statement.cond
            yield LineFinding(
                "MB002",
                "Haas NGC: a bare value as a condition is not FANUC; compare it, e.g. [#1 NE 0]",
                c.span.start,
                c.span.end,
            )
        for var in variables(statement):
            if isinstance(var, Var) and var.number is not None and var.number != int(var.number):
                written = parsed.text[var.span.start + 1 : var.span.end].strip()
                yield LineFinding(
                    "MB002",
                    f"Haas NGC: #{written} (a variable number with a decimal part) is not FANUC "
                    "(alarm PS0115)",
                    var.span.start,
                    var.span.end,
                )
