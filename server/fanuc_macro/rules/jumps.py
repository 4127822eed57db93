"""MB1xx: GOTO targets: missing labels, duplicated labels, jumps into loops."""

from __future__ import annotations

from bisect import bisect_left, bisect_right
from typing import cast

from ..database import Derived
from ..diagnostics import (
    Diagnostic,
    Fix,
    FixEdit,
    Related,
    RuleDoc,
    RuleInfo,
    Severity,
    make,
)
from ..per_line import PerLine
from ..program.index import Jump, Program
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import Assign, IfGoto, IfThen, NcStatement, ParsedLine, Var, While
from ..syntax.walk import cond_exprs, subexpressions
from ..translation import tr
from .context import RuleContext

FAMILY = "jumps"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB101 = RuleInfo("MB101", "goto-missing-label", Severity.ERROR,
                 "GOTO to a sequence number that is not in the program.", FAMILY)
MB102 = RuleInfo("MB102", "duplicate-label", Severity.WARNING,
                 "A sequence number that a GOTO uses stands more than once in the program.", FAMILY)
MB103 = RuleInfo("MB103", "goto-into-loop", Severity.ERROR,
                 "GOTO from outside a WHILE loop to a block inside it.", FAMILY)
MB104 = RuleInfo("MB104", "goto-bad-target", Severity.ERROR,
                 "GOTO target that is not a whole number from 1 to 99999.", FAMILY)
# fmt: on


def _reads(ctx: RuleContext) -> tuple[object, ...]:
    """What the diagnostics are drawn from: the program index and where reading stopped."""
    return ctx.index, ctx.doc.unread_from


def _checked(ctx: RuleContext) -> tuple[list[Diagnostic], bool]:
    found: list[Diagnostic] = []
    return found, _check(ctx, found)


# An edit of lines the index skips (an assignment, a motion) keeps the index, and so the
# diagnostics: the database gives back the last ones.
_diagnostics: Derived[RuleContext, list[Diagnostic]] = Derived("rules.jumps", _reads, _checked)


def check(ctx: RuleContext) -> list[Diagnostic]:
    return list(_diagnostics(ctx.doc.uri, ctx))


MB101_DOC = RuleDoc(
    "MB101",
    reports="""
`GOTO n` or `IF [...] GOTO n` with a constant `n` whose sequence number
`Nn` is not in the same O program. Labels of other programs in the same file do not count:
a `GOTO` only searches its own program.
""",
    why="""
When the jump is taken, the control raises PS0128 ILLEGAL
MACRO SEQUENCE NUMBER and stops. A conditional jump may be taken only on the last pass of a
loop or for one size of part, so the program can run correctly many times and then stop in the
middle of a part.
""",
    example="""
```nc
O3003 (HELICAL HOLE)
#1=#1+#3
IF[#1LT#2]GOTO1
M99
```
""",
    fix="""
Add the missing `Nn` where the jump should land, or correct the number in the
`GOTO`. The quick fix in the editor changes the target to the label of the program nearest in
number (the lower of two as near), naming it and its line; it leaves out labels that stand more
than once (MB102) and labels inside a loop the jump is outside of (MB103). It is a guess, so it
is not offered as the preferred fix. No fix adds the missing `Nn`: where the jump should land is
what the programmer meant, which the text does not say, and a label put on a guessed block would
silence the alarm and send the tool where no one chose.
""",
    not_reported="""
A computed target (`GOTO#1`), which the evaluator checks when it
runs (MB704), an `M99 P` return (MB704), a target that is not a whole number from 1 to 99999
(MB104), and a missing label in a program that goes on past the part of a big file the
analysis reads (MB013): the label may be in the unread part.
""",
)


MB103_DOC = RuleDoc(
    "MB103",
    reports="""
A `GOTO` from outside a `WHILE ... DOm` / `ENDm` range to a block inside
it. Jumping out of a loop, or within one loop, is allowed and not reported.
""",
    why="""
FANUC forbids branching into a loop: the control did not run
the `WHILE` block, so it meets an `ENDm` whose `DOm` it never entered. Depending on the
control this raises a loop alarm or gives a loop that does not behave as written: passes are
skipped or repeated, and the tool position after the loop is not the one the programmer
expected.
""",
    example="""
```nc
O3002 (GROOVE PASSES)
IF[#19GT0]GOTO20
WHILE[#1LT#18]DO1
N20 G01 X[50.-#1*2.] F0.1
#1=#1+1.
END1
M30
```
""",
    fix="""
Jump to a block before the `WHILE`, or restructure with a second loop or a flag
tested in the loop condition.
""",
    not_reported="""
Jumps out of a loop, within one loop, and from an inner loop to its
outer loop; a jump into a `DO` whose `END` is missing (MB201 says so); computed targets. The
block checked is the one the control's search finds (MB102 says when a duplicated N moves it).
""",
)


MB104_DOC = RuleDoc(
    "MB104",
    reports="""
A constant `GOTO` target that is not a whole number from 1 to 99999:
`GOTO0`, `GOTO100000`, `GOTO1.5`, `GOTO-5`.
""",
    why="""
The control raises PS0128 ILLEGAL MACRO SEQUENCE NUMBER when
the jump is taken, and the program stops there.
""",
    example="""
```nc
O9002 (DISPATCH)
IF[#3EQ2]GOTO1.5
GOTO0
M99
```
""",
    fix="""
Use a whole sequence number from 1 to 99999 that stands in the program.
""",
    not_reported="""
A whole target written with a decimal point (`GOTO10.`): the value
is 10. Computed targets: the evaluator checks their values when it runs (MB704).
""",
)


def _check(ctx: RuleContext, found: list[Diagnostic]) -> bool:
    """The diagnostics into ``found``; whether they follow from the index alone (a jump to a
    duplicated N asks the facts and the lines where it lands)."""
    textual = True
    add = found.append
    for program in ctx.index.programs:
        name = program.display_name
        for jump in program.jumps:
            ts = jump.target_span
            if jump.target is None:
                if jump.constant is not None:
                    add(
                        make(
                            MB104,
                            tr(
                                "GOTO target {target:g} is not a whole number (alarm PS0128)",
                                target=jump.constant,
                            ),
                            jump.line,
                            ts.start,
                            ts.end,
                        )
                    )
                continue
            if not 1 <= jump.target <= 99999:
                add(
                    make(
                        MB104,
                        tr(
                            "GOTO target {target} is outside 1-99999 (alarm PS0128)",
                            target=jump.target,
                        ),
                        jump.line,
                        ts.start,
                        ts.end,
                    )
                )
                continue
            lines = program.labels.get(jump.target)
            if not lines:
                unread = ctx.doc.unread_from
                if unread is not None and program.end_line >= unread:
                    continue  # the label may be in the part of the file left unread (MB013)
                add(
                    make(
                        MB101,
                        tr(
                            "GOTO {target}: no N{target} in {program} (alarm "
                            "PS0128 when the jump is taken)",
                            target=jump.target,
                            program=name,
                        ),
                        jump.line,
                        ts.start,
                        ts.end,
                        fixes=_nearest_label(program, jump),
                    )
                )
                continue
            if len(lines) > 1:
                textual = False
                wrong = _duplicate_lands_wrong(ctx, program, jump, lines)
                if wrong is not None:
                    add(wrong)
            target_line = program.label_line(jump.target, jump.line)
            assert target_line is not None
            target_loops = program.enclosing_loops(target_line)
            source_loops = program.enclosing_loops(jump.line)
            for loop in target_loops:
                if loop not in source_loops:
                    add(
                        make(
                            MB103,
                            tr(
                                "GOTO {target} jumps into the DO{loop_id:g} "
                                "loop of line {line} from outside it; FANUC forbids "
                                "branching into a loop",
                                target=jump.target,
                                loop_id=loop.loop_id,
                                line=loop.do_line + 1,
                            ),
                            jump.line,
                            ts.start,
                            ts.end,
                            related=[Related(loop.do_line, 0, 0, tr("the loop starts here"))],
                        )
                    )
                    break
    return textual


def _nearest_label(program: Program, jump: Jump) -> tuple[Fix, ...]:
    """MB101: the jump retargeted to the program's label nearest in number to the missing one
    (the lower of two as near), among the labels it can take without another error: one that
    stands once (two copies would be MB102's question) and is not inside a loop the jump is
    outside of (MB103). No fix adds the missing ``Nn``: where the jump should land is what the
    programmer meant, which the text does not say, and a label put on a guessed block would
    silence the alarm and send the tool somewhere no one chose."""
    assert jump.target is not None
    source_loops = program.enclosing_loops(jump.line)
    candidates = [
        (abs(number - jump.target), number, lines[0])
        for number, lines in program.labels.items()
        if len(lines) == 1
        and 1 <= number <= 99999
        and all(loop in source_loops for loop in program.enclosing_loops(lines[0]))
    ]
    if not candidates:
        return ()
    _, number, line = min(candidates)
    ts = jump.target_span
    return (
        Fix(
            tr(
                "Change GOTO {target} to GOTO {label} (the nearest label, N{label} at line {line})",
                target=jump.target,
                label=number,
                line=line + 1,
            ),
            (FixEdit(jump.line, ts.start, jump.line, ts.end, str(number)),),
        ),
    )


# ---- MB102: where a jump to a duplicated N lands -----------------------------------------------


def _line_io(parsed: ParsedLine) -> tuple[frozenset[int], frozenset[int]]:
    """(variables the line's conditions read, variables the line assigns), direct numbers."""
    tested: set[int] = set()
    written: set[int] = set()
    for statement in statements_of(parsed.statement):
        cond = statement.cond if isinstance(statement, IfGoto | IfThen | While) else None
        if cond is not None:
            for expr in cond_exprs(cond):
                for node in subexpressions(expr):
                    if isinstance(node, Var) and node.number is not None:
                        tested.add(int(node.number))
        assign = statement.then if isinstance(statement, IfThen) else statement
        if isinstance(assign, Assign) and assign.target.number is not None:
            written.add(int(assign.target.number))
    return frozenset(tested), frozenset(written)


_io_of: PerLine[tuple[frozenset[int], frozenset[int]]] = PerLine(_line_io)


def _loop_test(ctx: RuleContext, jump: Jump, copy: int) -> int | None:
    """The variable that makes the jump a loop back to the N at ``copy`` (before it): one the
    jump's condition tests (for a bare GOTO, the test at that N) and the blocks from that N to
    the jump assign: a counter stepped in the loop. -1 for a jump from the N's own block (a
    wait loop, ``N1 IF [#1000 EQ 0] GOTO1``); None when nothing says the jump looks back."""
    if copy == jump.line:
        return -1
    blocks = ctx.doc.blocks
    tested = _io_of(blocks[jump.line].parsed)[0] if jump.conditional else frozenset()
    if not tested:
        tested = _io_of(blocks[copy].parsed)[0]
    if not tested:
        return None
    writes = _writes(ctx)
    # (line, variable) of the first write from the N to the jump: the smallest number of the
    # first line that changes one of them.
    first = (jump.line, -1)
    for number in tested:
        lines = writes.get(number)
        if lines:
            at = bisect_left(lines, copy)
            if at < len(lines) and (lines[at], number) < first:
                first = (lines[at], number)
    return None if first[1] == -1 else first[1]


def _writes(ctx: RuleContext) -> dict[int, list[int]]:
    """The lines that assign each variable (direct numbers), in order: built once per analysis,
    so a jump's question is a bisection, not a walk from its N."""
    found = ctx.memo.get("jumps.writes")
    if found is None:
        writes: dict[int, list[int]] = {}
        for block in ctx.doc.blocks:
            for number in _io_of(block.parsed)[1]:
                writes.setdefault(number, []).append(block.line)
        ctx.memo["jumps.writes"] = found = writes
    return cast("dict[int, list[int]]", found)


def _dead(ctx: RuleContext, program: Program, line: int) -> bool:
    """``line`` is dead code in the evaluator's facts, in MB702's sense: the program ran to its
    end on every path with every branch decided, and no run reached the line."""
    facts = ctx.doc_facts()
    if facts is None or program.first_line not in facts.analysed_programs:
        return False
    if program.first_line in facts.incomplete_programs:
        return False
    if program.first_line in ctx.undecided_programs():
        return False
    return line not in facts.runs


# How many blocks from two copies of an N are compared before they are taken as different.
_SAME_RUN_BLOCKS = 32


def _same_run(ctx: RuleContext, a: int, b: int) -> bool:
    """Whether the blocks from line ``a`` and from line ``b`` are the same text (blanks aside)
    up to one that ends the run (an alarm, ``#3000=``; ``M02``, ``M30``, ``M99``): whichever
    copy of the N the control lands on, the program does the same (two copies of
    ``N906 #3000=6 (...)``)."""
    blocks = ctx.doc.blocks
    for k in range(_SAME_RUN_BLOCKS):
        if a + k >= len(blocks) or b + k >= len(blocks):
            return False
        x, y = blocks[a + k].parsed, blocks[b + k].parsed
        # The control reads no blanks in a block: only what is written counts.
        if "".join(x.text.split()) != "".join(y.text.split()) or x.problem is not None:
            return False
        if _ends_run(x):
            return True
    return False


def _ends_run(parsed: ParsedLine) -> bool:
    for statement in statements_of(parsed.statement):
        target = statement.target.number if isinstance(statement, Assign) else None
        if target is not None and int(target) == 3000:
            return True
        nc = statement if isinstance(statement, NcStatement) else None
        if nc is not None and any(
            w.address == "M" and constant_value(w.value) in (2.0, 30.0, 99.0) for w in nc.words
        ):
            return True
    return False


MB102_DOC = RuleDoc(
    "MB102",
    reports="""
A `GOTO` to a sequence number that stands more than once in the program,
when the copy the control jumps to is not the one the text suggests. The control searches
forward from the block after the `GOTO` to the end of the program, then from its head, and
takes the first `Nn` it meets. The text suggests the first copy after a jump that looks
forward, and the nearest copy before a loop back. A jump looks back when a copy stands before
it and either no copy stands after it, or the jump is on the copy's own block (a wait loop,
`N1 IF [#1000 EQ 0] GOTO1`), or a variable the jump tests (for a bare `GOTO`, the test on the
copy's block) is assigned between that copy and the jump: a counter stepped in the loop. It is
reported too when the copy the control finds is dead code: the evaluator ran the program to
its end with every branch decided, and no run reached that copy (an old block left after
`M30`). The message says where the jump lands, which copy was likely meant, and why.
""",
    why="""
The jump goes to another block than the programmer meant. A
block copied with its N number can turn a retract into another cutting pass, or a loop into a
jump past the retract: wrong part, or a tool driven into the work.
""",
    example="""
```nc
O2001 (ROUGH TURN)
N10 G00 X#1 Z2.
#1=#1-4.
IF[#1GT40.]GOTO10
N10 G00 X100. Z100.
M30
```
""",
    fix="""
Give every jump target a sequence number that stands once in the program.
""",
    not_reported="""
A duplicated N that lands as the text suggests: a forward jump to
the next copy after it (sections that each end at their own `N20`, a `GOTO77` just before its
`N77`), whatever other copies stand elsewhere. Sequence numbers that no `GOTO` uses (a `G70 P Q`
range, an operator's restart point), which may repeat freely. Computed targets (`GOTO#1`),
whose copy is known only at run time. Without the evaluator's facts, or when a branch was
undecided, nothing is called dead code. Copies that run the same blocks (blanks aside) up to
an alarm (`#3000=`), `M02`, `M30` or `M99`, such as two `N906 #3000=6 (TOOL NOT SET)`: the
program does the same wherever it lands.
""",
)


def _duplicate_lands_wrong(
    ctx: RuleContext, program: Program, jump: Jump, lines: list[int]
) -> Diagnostic | None:
    """MB102. The control searches for the N from the block after the GOTO to the end of the
    program, then from its head (macro-b.md 4.1: "The search runs forward from the current
    block and then wraps to the program head" [K; S FI], unverified against a FANUC manual).
    A duplicate matters only when it moves the landing away from the copy the text suggests:
    the first one after a jump that looks forward, the nearest one before a loop back. Or when
    the copy the control finds is dead code in the evaluator's runs."""
    seq = jump.target
    assert seq is not None
    # The copies up to the GOTO's own block (searched last) and after it; lines are in order.
    split = bisect_right(lines, jump.line)
    before, after = split > 0, split < len(lines)
    last_before = lines[split - 1] if before else -1
    lands = lines[split] if after else lines[0]
    loop_var = _loop_test(ctx, jump, last_before) if before else None
    looks_back = before and (not after or loop_var is not None)
    meant = last_before if looks_back else lines[split]
    name = program.display_name
    ts = jump.target_span
    if lands != meant and _same_run(ctx, lands, meant):
        return None  # either copy runs the same blocks to the same end
    if lands != meant:
        if after:
            why = tr(
                "the control searches forward from the GOTO first and takes the first "
                "N{label} it meets",
                label=seq,
            )
            if loop_var == -1:
                back = tr("the N{label} of this block, which the jump loops on", label=seq)
            else:
                back = tr(
                    "the N{label} of line {line}, which this loop goes back to (#{variable}, "
                    "which it tests, changes from line {line} to the jump)",
                    label=seq,
                    line=meant + 1,
                    variable=loop_var,
                )
        else:
            why = tr(
                "with no N{label} after the GOTO, the control searches from the head of "
                "{program} and takes the first",
                label=seq,
                program=name,
            )
            back = tr("the nearest N{label} before it, line {line}", label=seq, line=meant + 1)
        all_lines = ", ".join(str(ln + 1) for ln in lines)  # only for a message: it is long
        message = tr(
            "GOTO {label} lands on the N{label} of line {line}, not on {meant}: {why} "
            "(N{label} stands {count} times in {program}: lines {lines})",
            label=seq,
            line=lands + 1,
            meant=back,
            why=why,
            count=len(lines),
            program=name,
            lines=all_lines,
        )
    elif _dead(ctx, program, lands) and not _dead(ctx, program, jump.line):
        others = ", ".join(str(ln + 1) for ln in lines if ln != lands)
        message = tr(
            "GOTO {label} lands on the N{label} of line {line}, in blocks that no run of the "
            "analysis executes, while N{label} also stands at line {others}: an old copy left "
            "in {program} catches the jump, which the control sends to the first N{label} "
            "after it",
            label=seq,
            line=lands + 1,
            others=others,
            program=name,
        )
    else:
        return None
    related = [Related(lands, 0, 0, tr("the control lands here"))]
    if meant != lands:
        related.append(Related(meant, 0, 0, tr("the N{label} the text suggests", label=seq)))
    return make(MB102, message, jump.line, ts.start, ts.end, related=related)
