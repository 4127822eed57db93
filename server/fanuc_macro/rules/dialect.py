"""MB002: forms of other controls' dialects (Haas, Mitsubishi/Citizen, LinuxCNC, LNC/Syntec,
Okuma, wire EDM registers): those the block reader names in rejected blocks, and Haas-only codes
in blocks FANUC's grammar reads."""

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
                haas = _haas_code(word.address, value, has_p)
                if haas is not None:
                    yield LineFinding("MB002", haas, word.span.start, word.span.end)
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
            elif isinstance(var, Var) and var.number is not None and 20000 <= var.number <= 29999:
                n = int(var.number)
                yield LineFinding(
                    "MB002",
                    f"Haas NGC: #{n} reads Haas setting {n - 20000} (#20000-#29999 are the "
                    "settings); FANUC has no settings variables (alarm PS0115 on most controls)",
                    var.span.start,
                    var.span.end,
                )


def _haas_code(address: str, value: float | None, has_p: bool) -> str | None:
    """Haas-only G and M codes (Haas mill operator's manual 96-8000 and the reference's 7:
    G103 look-ahead, G154 P work offsets, M109 user input; [S HAAS], [C jpaullee]). FANUC has
    none of them as standard: an unknown G code raises PS0010 IMPROPER G-CODE, unless a
    parameter (6050-6059) makes it a custom macro call; buffering is suppressed by the M codes
    of parameters 3411-3432 (macro-b.md 7, [M FANUC-16iTB-buf]). #20000-#29999 as Haas NGC
    settings: macro-b.md 2.1 [C], unverified against Haas's manual."""
    if address == "G" and value == 103.0:
        return (
            "Haas: G103 (block look-ahead limit) is not FANUC: FANUC raises PS0010 IMPROPER "
            "G-CODE (unless a parameter makes G103 a macro call); FANUC stops look-ahead with "
            "an M code that suppresses buffering (parameters 3411-3432)"
        )
    if address == "G" and value == 154.0 and has_p:
        return (
            "Haas: G154 P<n> (additional work offsets) is not FANUC (PS0010 IMPROPER G-CODE); "
            "FANUC selects them with G54.1 P<n>"
        )
    if address == "M" and value == 109.0 and has_p:
        return (
            "Haas: M109 P<n> (interactive input of a character into #n) is not FANUC; on FANUC "
            "M109 is whatever the machine builder made it"
        )
    return None
