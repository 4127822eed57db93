"""MB7xx: control flow as the evaluator ran it: constant conditions, dead blocks, endless
loops, jumps and calls that fail at run time."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleInfo, Severity, make, register
from ..index import constant_value
from ..syntax import Goto, IfGoto, IfThen, While
from .context import RuleContext

FAMILY = "flow"
register(
    RuleInfo("MB701", "condition-constant", Severity.INFORMATION,
             "An IF or WHILE condition that has the same result every time the analysis "
             "reaches it: the branch is dead or always taken.", FAMILY),
    RuleInfo("MB702", "never-executed", Severity.INFORMATION,
             "Blocks of an analysed program that no run reaches.", FAMILY),
    RuleInfo("MB703", "endless-loop", Severity.ERROR,
             "A loop that does not end within the analysis budget.", FAMILY),
    RuleInfo("MB704", "jump-fails", Severity.ERROR,
             "A computed GOTO or an M99 P whose sequence number is missing when it runs "
             "(PS0128/PS0078).", FAMILY),
    RuleInfo("MB705", "call-nesting", Severity.ERROR,
             "Calls nested deeper than the control allows (PS0077).", FAMILY),
    RuleInfo("MB706", "call-target-unknown", Severity.WARNING,
             "A call whose program number, computed at run time, is not in the workspace.",
             FAMILY),
    RuleInfo("MB707", "waits-for-outside", Severity.INFORMATION,
             "A loop that waits for a common or system variable that only something outside "
             "the program (PMC, FOCAS, another path) changes.", FAMILY),
    RuleInfo("MB708", "long-loop", Severity.INFORMATION,
             "A loop still running when the analysis budget ran out, though nearer its end "
             "every turn: what comes after it is not analysed.", FAMILY),
)  # fmt: skip


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    facts = ctx.doc_facts()
    if facts is None:
        return
    for f in ctx.findings("endless-loop"):
        yield make("MB703", f.message, f.line, f.column, f.end_column)
    for f in ctx.findings("polling-loop"):
        yield make("MB707", f.message, f.line, f.column, f.end_column)
    for f in ctx.findings("long-loop"):
        yield make("MB708", f.message, f.line, f.column, f.end_column)
    for f in ctx.findings("alarm:goto-", "alarm:return-missing"):
        statement = ctx.doc.blocks[f.line].statement
        constant = isinstance(statement, IfGoto | Goto) and _is_constant(statement)
        if not constant:  # constant targets are MB101's
            yield make("MB704", f.message, f.line, f.column, f.end_column)
    for f in ctx.findings("alarm:nesting"):
        yield make("MB705", f.message, f.line, f.column, f.end_column)
    for f in ctx.findings("program-not-found"):
        if not _constant_call(ctx, f.line):
            yield make("MB706", f.message, f.line, f.column, f.end_column)
    for program in ctx.index.programs:
        if program.first_line not in facts.analysed_programs:
            continue
        undecided = any(jc.undecided for ln, jc in facts.jumps.items() if program.contains(ln))
        if program.first_line in facts.incomplete_programs:
            continue  # a run cut short (budget, alarm) proves nothing about its branches
        for line, jc in sorted(facts.jumps.items()):
            if not program.contains(line) or jc.undecided:
                continue
            statement = ctx.doc.blocks[line].statement
            if not isinstance(statement, IfGoto | IfThen | While) or statement.cond is None:
                continue
            total = jc.taken + jc.not_taken
            if total == 0 or (jc.taken and jc.not_taken):
                continue
            outcome = "true" if jc.taken else "false"
            effect = _effect(statement, jc.taken > 0)
            c = statement.cond.span
            yield make(
                "MB701",
                f"condition is always {outcome} for the values that reach it "
                f"({total} time{'s' if total > 1 else ''}): {effect}",
                line,
                c.start,
                c.end,
            )
        if undecided:
            continue
        yield from _dead_blocks(ctx, program.first_line, program.end_line, facts.runs)


def _effect(statement: IfGoto | IfThen | While, taken: bool) -> str:
    if isinstance(statement, IfGoto):
        return "the GOTO is always taken" if taken else "the GOTO is never taken"
    if isinstance(statement, IfThen):
        return "the assignment always runs" if taken else "the assignment never runs"
    return "the loop body never runs" if not taken else "the loop always repeats"


def _is_constant(statement: IfGoto | Goto) -> bool:
    goto = statement.goto if isinstance(statement, IfGoto) else statement
    return constant_value(goto.target) is not None


def _constant_call(ctx: RuleContext, line: int) -> bool:
    program = ctx.index.program_at(line)
    return program is not None and any(
        c.line == line and c.program is not None for c in program.calls
    )


def _dead_blocks(
    ctx: RuleContext, first: int, end: int, runs: dict[int, int]
) -> Iterator[Diagnostic]:
    start: int | None = None
    last = first
    for line in range(first, end + 1):
        block = ctx.doc.blocks[line] if line < end else None
        live = block is None or block.statement is None or line in runs
        if block is not None and block.statement is None and start is not None:
            continue  # comments and blank lines inside a dead stretch
        if not live:
            if start is None:
                start = line
            last = line
        elif start is not None:
            count = sum(1 for ln in range(start, last + 1) if ctx.doc.blocks[ln].statement)
            text = ctx.doc.blocks[last].text
            yield make(
                "MB702",
                f"{count} block{'s' if count > 1 else ''} never executed "
                f"(lines {start + 1}-{last + 1}): no path of the analysed runs reaches "
                "them",
                start,
                0,
                len(text),
                end_line=last,
            )
            start = None
