"""MB9xx: how variables are used at run time: vacant reads, indirect writes and indexes."""

from __future__ import annotations

from bisect import bisect_left
from collections.abc import Iterable, Iterator

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import DocumentFacts, Finding, NoSuchVariable, ReadOnlyWrite
from ..evaluator.machine import compiled
from ..line_maps import Kept, LineMap
from ..program.arguments import ARGUMENT_LETTER, local_name
from ..program.index import Program
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import Assign, Compare, Cond, IfGoto, IfThen, Logic, Num, ParsedLine, Var
from ..syntax.walk import subexpressions, top_expressions
from ..translation import tr, tr_n
from .context import RuleContext, Seen

FAMILY = "variable-use"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB901 = RuleInfo("MB901", "vacant-local-read", Severity.WARNING,
                 "A local variable read while vacant: never assigned in the program and not an "
                 "argument it receives.", FAMILY)
MB902 = RuleInfo("MB902", "indirect-write-read-only", Severity.ERROR,
                 "#[...] = ... writes #0 or a read-only system variable at run time (PS0116).",
                 FAMILY)
MB903 = RuleInfo("MB903", "indirect-no-such-variable", Severity.ERROR,
                 "#[...] refers to a variable number that does not exist (PS0115).", FAMILY)
MB904 = RuleInfo("MB904", "arguments-assumed", Severity.HINT,
                 "A program ending with M30 or M02 reads locals before setting them: it is "
                 "analysed as a macro with unknown arguments.", FAMILY)
MB905 = RuleInfo("MB905", "vacant-compared-with-zero", Severity.WARNING,
                 "An argument check [#n EQ 0] or [#n NE 0] before an alarm: a vacant #n is "
                 "not equal to 0, so a missing argument passes it.", FAMILY)
# fmt: on


MB901_DOC = RuleDoc(
    "MB901",
    reports="""
A local variable (`#1`–`#33`) read while vacant when another program calls
this one: the program never assigns it, its `G65` caller does not pass it as an argument (or,
with `M98`, the caller never sets it), and the program does not test it against `#0` first. It
is reported once per variable and program, at the first read.
""",
    why="""
A vacant variable counts as 0 in arithmetic and removes the
word from an NC block: `G00 X#1 Z#2` with `#2` vacant moves X only, and `Z[#2-5.]` goes to
Z-5. The tool goes somewhere the programmer did not compute.
""",
    example="""
```nc
O9011 (MAIN)
G65 P9012 X10.
M30
O9012 (MOVE)
G00 X#24 Z#26
M99
```
""",
    fix="""
Assign the variable, pass it as an argument (here `Z`), or check it with
`IF [#26 EQ #0] GOTO ...` and raise a `#3000` alarm.
""",
    not_reported="""
A local the program assigns anywhere (even in a block that does
not parse), one a caller passes as an argument (any caller in the analysed files), one tested
against `#0` before it is read, and the locals of a program that nothing in the analysed files
calls: it runs with unknown arguments, not vacant ones. That includes a program ending with
`M30` that reads locals before setting them (MB904 says it is taken for a macro). A vacant
local passed on as a `G65` argument is no read: the argument is simply not given.
""",
)


MB902_DOC = RuleDoc(
    "MB902",
    reports="""
An indirect assignment `#[...] = ...` whose index, when the program runs,
is `#0` or a read-only system variable. Direct assignments are MB304's.
""",
    why="""
The control raises PS0116 WRITE PROTECTED VARIABLE and stops
at the block, often part-way through a table being filled.
""",
    example="""
```nc
O9021 (CLEAR A TABLE)
#1=5021.
#[#1]=0
M30
```
""",
    fix="""
Check the index range of the table (the first and last values of the index).
""",
    not_reported="""
Direct assignments (`#5021=0`, MB304), and indexes the analysis
cannot compute (a common variable set elsewhere): only values it knows are judged.
""",
)


MB903_DOC = RuleDoc(
    "MB903",
    reports="""
An indirect variable `#[...]` (read or written) whose index, when the
program runs, is a variable number that does not exist (for example `#34`–`#99`).
""",
    why="""
The control raises PS0115 VARIABLE NO. OUT OF RANGE and stops
at the block.
""",
    example="""
```nc
O9031 (PROBE TABLE)
#1=50.
#2=#[#1]
M30
```
""",
    fix="""
Correct the base of the index (`#[#1+100]`) or the range of the loop that
computes it.
""",
    not_reported="""
Direct variable numbers (`#50`, MB302) and indexes the analysis
cannot compute.
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    facts = ctx.doc_facts()
    if facts is None:
        return
    f: Finding  # of each kind in turn
    for f in ctx.findings(ReadOnlyWrite):
        yield make(MB902, f.message, f.line, f.column, f.end_column)
    for f in ctx.findings(NoSuchVariable):
        yield make(MB903, f.message, f.line, f.column, f.end_column)
    yield from _assumed_arguments(ctx, facts)
    yield from _zero_tests_of_arguments(ctx)
    # Locals that were vacant every time a block read them: few or none in most programs. The
    # run records the reads of the variables a block names (CompiledLine.reads), so only the
    # lines that name a local are asked, not every read of the run.
    vacant_reads = _vacant_reads(ctx, facts)
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
                MB901,
                tr(
                    "#{number} is read while vacant: {program} never sets it and no caller "
                    "passes it (a vacant local counts as 0 in arithmetic, and omits the word in "
                    "an address)",
                    number=n,
                    program=program.display_name,
                ),
                line,
                span[0],
                span[1],
            )


def _vacant_reads(ctx: RuleContext, facts: DocumentFacts) -> list[tuple[int, int]]:
    """(line, local) of the reads of a local that found it vacant every time, ascending: those
    of the last analysis of the document where neither the line nor its facts changed, the
    others looked up."""
    scanned = _local_reads(ctx.doc)
    last = _kept.get(ctx.doc.uri)
    changes = None if last is None else last[0].changes(ctx)
    if last is None or changes is None:
        found = _vacant_at(facts, zip(scanned.lines, scanned.values, strict=True))
    else:
        moved = changes.diff.moved
        found = [
            (at, n)
            for line, n in last[1]
            if (at := moved(line)) is not None and at not in changes.lines
        ]
        lines, values = scanned.lines, scanned.values
        looked = []
        for line in changes.sorted:
            i = bisect_left(lines, line)
            if i < len(lines) and lines[i] == line:
                looked.append((line, values[i]))
        found = sorted(found + _vacant_at(facts, looked))
    _kept.put(ctx.doc.uri, (Seen(ctx), found))
    return found


def _vacant_at(
    facts: DocumentFacts, lines: Iterable[tuple[int, tuple[int, ...]]]
) -> list[tuple[int, int]]:
    reads = facts.reads
    return sorted(
        (line, n)
        for line, numbers in lines
        for n in numbers
        if (summary := reads.get((line, n))) is not None
        and summary.vacant
        and summary.vacant == summary.count
    )


# The vacant reads of the last analyses of a few documents, and what they were drawn from.
_kept: Kept[tuple[Seen, list[tuple[int, int]]]] = Kept()


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


MB904_DOC = RuleDoc(
    "MB904",
    reports="""
A program that ends as a main program does (`M30`, `M02`) but reads local
variables before any block of it sets them, when nothing in the analysed files calls it. It is
analysed as a macro called by `G65` from a program elsewhere: its locals are unknown arguments,
not vacant, and the caller's feed is unknown. Reported once per program, at the first such
read; the message lists the locals with their argument letters.
""",
    why="""
Probe and cycle macros are often saved with `M30` and called
with `G65`; then their `IF [#26 EQ #0]` argument checks pass or fail with the caller's values,
and the analysis must not pretend they fail. But if the program is run from cycle start as a
main program, those locals are vacant: `G00 X#24` moves no X, `Z[#26-5.]` goes to Z-5.
""",
    example="""
```nc
O9041 (BORE)
IF[#26EQ#0]GOTO90
G01 Z#26 F#9
M30
N90 #3000=1(Z IS NEEDED)
M30
```
""",
    fix="""
Nothing, if the program is a macro. If it is a main program, set the locals
before reading them (`#26=-5.`); if it is a macro, end it with `M99`.
""",
    not_reported="""
Programs ending with `M99` (they are analysed as macros anyway),
programs another analysed program calls (their caller's arguments are used), and locals the
program sets before it reads them.
""",
)


def _assumed_arguments(ctx: RuleContext, facts: DocumentFacts) -> Iterator[Diagnostic]:
    """MB904, at the first read of the first local a main-looking program reads unset."""
    for program in ctx.index.programs:
        read_first = facts.assumed_arguments.get(program.first_line)
        if not read_first:
            continue
        names = [local_name(n) for n, _line in read_first]
        shown = (
            tr("{names} and {more} more", names=", ".join(names[:8]), more=len(names) - 8)
            if len(names) > 8
            else ", ".join(names)
        )
        number, line = read_first[0]
        start, end = _var_span(ctx, line, number)
        yield make(
            MB904,
            tr_n(
                "{program} ends with M30 or M02 but reads {variables} before setting it: it is "
                "analysed as a macro called with an argument of unknown value; run from cycle "
                "start as a main program, it is vacant (0 in arithmetic, the word left out of "
                "an address)",
                "{program} ends with M30 or M02 but reads {variables} before setting them: it is "
                "analysed as a macro called with arguments of unknown value; run from cycle "
                "start as a main program, they are vacant (0 in arithmetic, the word left out "
                "of an address)",
                len(names),
                program=program.display_name,
                variables=shown,
            ),
            line,
            start,
            end,
        )


MB905_DOC = RuleDoc(
    "MB905",
    reports="""
A condition `[#n EQ 0]` or `[#n NE 0]` on a local the program takes from its call (it reads
the local before any block of it sets it) that decides whether an alarm (`#3000=`) is
raised: `IF [#7 EQ 0] GOTO 90` with `N90 #3000=1 (D MISSING)`, `IF [#7 EQ 0] THEN #3000=1`,
or `IF [#7 NE 0] GOTO 10` with the alarm in the next block. The program never compares that
local with `#0`.
""",
    why="""
On FANUC a vacant variable differs from 0 in `EQ` and `NE` (and only there): with `D` not
given, `#7` is vacant, `[#7 EQ 0]` is false and `[#7 NE 0]` true, so the check meant to
stop a call without `D` lets it through, and the macro runs with #7 as 0 in arithmetic and
its word left out of NC blocks. FANUC Custom Macro B's table of vacant variables in
conditions (the shared reference macro-b.md §2.3).
""",
    example="""
```nc
O9050 (POCKET: D TOOL DIAMETER)
IF [#7 EQ 0] GOTO 90
G41 D#7 X#24 Y#25 F#9
M99
N90 #3000=1 (D MISSING)
```
""",
    fix="""
Test for a missing argument with `#0`: `IF [#7 EQ #0] GOTO 90`; keep `[#7 EQ 0]` too if a
zero `D` is also a mistake (`IF [#7 EQ #0] GOTO 90` then `IF [#7 EQ 0] GOTO 90`).
""",
    not_reported="""
A local the program also compares with `#0` anywhere (it checks vacancy), one it sets before
reading it, a comparison with 0 that no alarm depends on (a zero value may be meant), other
comparisons (`GT`, `LT`, `GE`, `LE` treat a vacant variable as 0), and programs that name a
local indirectly.
""",
)


def _zero_tests_of_arguments(ctx: RuleContext) -> Iterator[Diagnostic]:
    blocks = ctx.doc.blocks
    found = _conditions_on_locals(ctx.doc)
    for program in ctx.index.programs:
        on_lines = found.within(program.first_line, program.end_line)
        if not any(tests for _, (tests, _checked) in on_lines):
            continue  # most programs: no comparison of a local with 0, nothing to read
        use = ctx.locals_named(ctx.doc, program, with_subprograms=False)
        if use is None or not use.read_first:
            continue
        checked = {n for _, (_tests, numbers) in on_lines for n in numbers}
        for line, (tests, _checked) in on_lines:
            for n, op, start, end in tests:
                if n in checked or n not in use.read_first:
                    continue
                statement = next(
                    s
                    for s in statements_of(blocks[line].statement)
                    if isinstance(s, IfGoto | IfThen)
                )
                alarm = _alarm_line(ctx, program, line, op, statement)
                if alarm is None:
                    continue
                letter = ARGUMENT_LETTER.get(n)
                missing = (
                    tr("with no {letter} in the call", letter=letter)
                    if letter is not None
                    else tr("not given")
                )
                which = (
                    tr("its alarm")
                    if alarm == line
                    else tr("the alarm on line {line}", line=alarm + 1)
                )
                yield make(
                    MB905,
                    tr(
                        "[#{number} {op} 0] is false for a vacant #{number}: {missing}, the "
                        "check passes and {which} is not raised (a vacant variable differs from "
                        "0 in EQ and NE); [#{number} EQ #0] tests for a missing argument",
                        number=n,
                        op=op,
                        missing=missing,
                        which=which,
                    )
                    if op == "EQ"
                    else tr(
                        "[#{number} {op} 0] is true for a vacant #{number}: {missing}, the "
                        "check passes and {which} is not raised (a vacant variable differs from "
                        "0 in EQ and NE); [#{number} EQ #0] tests for a missing argument",
                        number=n,
                        op=op,
                        missing=missing,
                        which=which,
                    ),
                    line,
                    start,
                    end,
                )


# A condition's comparisons of a local: with 0 by EQ or NE (local, op, span), and with #0.
_LocalConditions = tuple[tuple[tuple[int, str, int, int], ...], frozenset[int]]


def _local_conditions(parsed: ParsedLine) -> _LocalConditions | None:
    """What an IF block compares its locals with: 0 (EQ, NE), or #0 (a vacancy check)."""
    if parsed.statement is None or "#" not in parsed.text:
        return None
    tests: list[tuple[int, str, int, int]] = []
    checked: set[int] = set()
    for statement in statements_of(parsed.statement):
        if not isinstance(statement, IfGoto | IfThen):
            continue
        for test in _comparisons(statement.cond):
            for side, other in ((test.left, test.right), (test.right, test.left)):
                n = _local_number(side)
                if n is None:
                    continue
                if isinstance(other, Var) and other.number == 0:
                    checked.add(n)
                elif test.op in ("EQ", "NE") and isinstance(other, Num) and other.value == 0.0:
                    tests.append((n, test.op, test.span.start, test.span.end))
    return (tuple(tests), frozenset(checked)) if tests or checked else None


# The IF blocks that compare locals, kept from one analysis of a document to the next.
_conditions_on_locals: LineMap[_LocalConditions] = LineMap(_local_conditions)


def _comparisons(cond: Cond) -> Iterator[Compare]:
    stack: list[Cond] = [cond]
    while stack:
        node = stack.pop()
        if isinstance(node, Logic):
            stack.append(node.first)
            stack.extend(c for _, c in node.rest)
        elif isinstance(node, Compare):
            yield node


def _local_number(expr: object) -> int | None:
    if isinstance(expr, Var) and expr.number is not None and 1 <= expr.number <= 33:
        return int(expr.number)
    return None


def _alarm_line(
    ctx: RuleContext, program: Program, line: int, op: str, statement: IfGoto | IfThen
) -> int | None:
    """The line of the #3000 alarm the test decides: the THEN's, the block the GOTO reaches
    (EQ: the test true means "not given"), or the next block (NE: true goes on); None when no
    alarm depends on it."""
    blocks = ctx.doc.blocks
    if isinstance(statement, IfThen):
        return line if _raises_alarm(statement.then) else None
    at: int | None
    if op == "EQ":
        target = constant_value(statement.goto.target)
        if target is None or target != int(target):
            return None
        at = program.label_line(int(target), line)
    else:
        at = line + 1
        while at < program.end_line and blocks[at].statement is None:
            at += 1
    if at is None or at >= program.end_line:
        return None
    return at if any(_raises_alarm(s) for s in statements_of(blocks[at].statement)) else None


def _raises_alarm(statement: object) -> bool:
    """``#3000=...``: the macro alarm (0i-F: alarm 3000 + the value, the comment shown)."""
    return isinstance(statement, Assign) and statement.target.number == 3000
