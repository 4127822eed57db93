"""MB9xx: how variables are used at run time: vacant reads, indirect writes and indexes."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleInfo, Severity, make, register
from ..evaluator.facts import DocumentFacts
from ..evaluator.machine import compiled
from ..line_maps import LineMap
from ..program.variables import ARGUMENT_VARIABLES
from ..syntax.tree import Assign, IfThen, ParsedLine, Var
from ..syntax.walk import subexpressions, top_expressions
from .context import RuleContext

FAMILY = "variable-use"
register(
    RuleInfo("MB901", "vacant-local-read", Severity.WARNING,
             "A local variable read while vacant: never assigned in the program and not an "
             "argument it receives.", FAMILY),
    RuleInfo("MB902", "indirect-write-read-only", Severity.ERROR,
             "#[...] = ... writes #0 or a read-only system variable at run time (PS0116).",
             FAMILY),
    RuleInfo("MB903", "indirect-no-such-variable", Severity.ERROR,
             "#[...] refers to a variable number that does not exist (PS0115).", FAMILY),
    RuleInfo("MB904", "arguments-assumed", Severity.HINT,
             "A program ending with M30 or M02 reads locals before setting them: it is "
             "analysed as a macro with unknown arguments.", FAMILY),
)  # fmt: skip

ARGUMENT_LETTER = {n: letter for letter, n in ARGUMENT_VARIABLES.items()}


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    facts = ctx.doc_facts()
    if facts is None:
        return
    for f in ctx.findings("alarm:write-read-only"):
        yield make("MB902", f.message, f.line, f.column, f.end_column)
    for f in ctx.findings("alarm:no-such-variable"):
        yield make("MB903", f.message, f.line, f.column, f.end_column)
    yield from _assumed_arguments(ctx, facts)
    # Locals that were vacant every time a block read them: few or none in most programs. The
    # run records the reads of the variables a block names (CompiledLine.reads), so only the
    # lines that name a local are asked, not every read of the run.
    scanned = _local_reads(ctx.doc)
    reads = facts.reads
    vacant_reads = sorted(
        (line, n)
        for line, numbers in zip(scanned.lines, scanned.values, strict=True)
        for n in numbers
        if (summary := reads.get((line, n))) is not None
        and summary.vacant
        and summary.vacant == summary.count
    )
    if not vacant_reads:
        return
    by_program: dict[int, list[tuple[int, int]]] = {}  # one pass, not one per program
    for line, n in vacant_reads:
        holder = ctx.index.program_at(line)
        if holder is not None:
            by_program.setdefault(holder.first_line, []).append((line, n))
    for program in ctx.index.programs:
        candidates = by_program.get(program.first_line)
        if not candidates:
            continue
        assigned: set[int] = set()
        checked: set[int] = set()
        for line in range(program.first_line, program.end_line):
            parsed = ctx.doc.blocks[line].parsed
            statement = parsed.statement
            if statement is None:
                if parsed.failed_assignment is not None:  # '#5=#4*2:' sets #5 all the same
                    assigned.add(parsed.failed_assignment)
                continue
            target = statement.then if isinstance(statement, IfThen) else statement
            if isinstance(target, Assign) and target.target.number is not None:
                assigned.add(int(target.target.number))
            _vacancy_checks(statement, checked)
        reported: set[int] = set()
        for line, n in candidates:
            if n in reported or n in assigned or n in checked:
                continue
            reported.add(n)
            span = _var_span(ctx, line, n)
            yield make(
                "MB901",
                f"#{n} is read while vacant: {program.display_name} never "
                f"sets it and no caller passes it (a vacant local counts as 0 in "
                "arithmetic, and omits the word in an address)",
                line,
                span[0],
                span[1],
            )


def _read_locals(parsed: ParsedLine) -> tuple[int, ...]:
    """The locals #1-#33 a line's block reads by number, as the run records them."""
    if parsed.statement is None or "#" not in parsed.text:  # no variable
        return ()
    return tuple(n for n in compiled(parsed).reads if 1 <= n <= 33)


# The lines that read a local, kept from one analysis of a document to the next.
_local_reads: LineMap[tuple[int, ...]] = LineMap(_read_locals)


def _vacancy_checks(statement: object, checked: set[int]) -> None:
    """Locals compared with #0 (argument checks): vacancy there is expected."""
    from ..syntax.tree import IfGoto, While
    from ..syntax.walk import cond_exprs

    cond = getattr(statement, "cond", None)
    if not isinstance(statement, IfGoto | IfThen | While) or cond is None:
        return
    for expr in cond_exprs(cond):
        for node in subexpressions(expr):
            if isinstance(node, Var) and node.number is not None:
                checked.add(int(node.number))


def _var_span(ctx: RuleContext, line: int, number: int) -> tuple[int, int]:
    statement = ctx.doc.blocks[line].statement
    if statement is not None:
        for top in top_expressions(statement):
            for node in subexpressions(top):
                if isinstance(node, Var) and node.number == number:
                    return node.span.start, node.span.end
    return 0, len(ctx.doc.blocks[line].text)


def _assumed_arguments(ctx: RuleContext, facts: DocumentFacts) -> Iterator[Diagnostic]:
    """MB904, at the first read of the first local a main-looking program reads unset."""
    for program in ctx.index.programs:
        read_first = facts.assumed_arguments.get(program.first_line)
        if not read_first:
            continue
        names = [
            f"#{n} ({ARGUMENT_LETTER[n]})" if n in ARGUMENT_LETTER else f"#{n}"
            for n, _line in read_first
        ]
        shown = ", ".join(names[:8]) + (f" and {len(names) - 8} more" if len(names) > 8 else "")
        one = len(names) == 1
        number, line = read_first[0]
        start, end = _var_span(ctx, line, number)
        yield make(
            "MB904",
            f"{program.display_name} ends with M30 or M02 but reads {shown} before setting "
            f"{'it' if one else 'them'}: it is analysed as a macro called with "
            f"{'an argument' if one else 'arguments'} of unknown value; run from cycle start "
            f"as a main program, {'it is' if one else 'they are'} vacant (0 in arithmetic, "
            "the word left out of an address)",
            line,
            start,
            end,
        )
