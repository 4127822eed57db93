"""MB7xx: control flow as the evaluator ran it: constant conditions, dead blocks, endless
loops, jumps and calls that fail at run time."""

from __future__ import annotations

import re
from bisect import bisect_left, bisect_right
from collections.abc import Callable, Iterator, Sequence
from itertools import chain
from operator import itemgetter
from typing import NamedTuple, TypeVar, cast

from ..database import Database, TableKey
from ..database import current as current_database
from ..diagnostics import (
    Diagnostic,
    RuleDoc,
    RuleInfo,
    Severity,
    Tag,
    make,
)
from ..evaluator.facts import (
    DocumentFacts,
    EndlessLoop,
    Finding,
    GotoAlarm,
    LongLoop,
    LoopNoTurn,
    NestingAlarm,
    PollingLoop,
    ProgramNotFound,
    ReturnMissing,
)
from ..evaluator.machine import compiled
from ..line_maps import Kept, LineMap
from ..per_line import PerLine
from ..program.counters import commons_tested, loop_counters, start_values
from ..program.index import Program
from ..syntax.marks import constant_value
from ..syntax.tree import (
    Block,
    Goto,
    IfGoto,
    IfThen,
    Mixed,
    NcStatement,
    ParsedLine,
    While,
)
from ..translation import tr, tr_n
from .context import Changes, RuleContext, Seen

FAMILY = "flow"
# Dead code, shown faded; a restart point (MB709) runs on a search, so it is not.
DEAD_CODE = frozenset({Tag.UNNECESSARY})

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB701 = RuleInfo("MB701", "condition-constant", Severity.INFORMATION,
                 "An IF or WHILE condition that has the same result every time the analysis "
                 "reaches it: the branch is dead or always taken.", FAMILY)
MB702 = RuleInfo("MB702", "never-executed", Severity.INFORMATION,
                 "Blocks of an analysed program that no run reaches.", FAMILY, DEAD_CODE)
MB703 = RuleInfo("MB703", "endless-loop", Severity.ERROR,
                 "A loop that does not end within the analysis budget.", FAMILY)
MB704 = RuleInfo("MB704", "jump-fails", Severity.ERROR,
                 "A computed GOTO or an M99 P whose sequence number is missing when it runs "
                 "(PS0128/PS0078).", FAMILY)
MB705 = RuleInfo("MB705", "call-nesting", Severity.ERROR,
                 "Calls nested deeper than the control allows (PS0077).", FAMILY)
MB706 = RuleInfo("MB706", "call-target-unknown", Severity.WARNING,
                 "A call whose program number, computed at run time, is not in the workspace.",
                 FAMILY)
MB707 = RuleInfo("MB707", "waits-for-outside", Severity.INFORMATION,
                 "A loop that waits for a common or system variable that only something outside "
                 "the program (PMC, FOCAS, another path) changes.", FAMILY)
MB708 = RuleInfo("MB708", "long-loop", Severity.INFORMATION,
                 "A loop still running when the analysis budget ran out, though nearer its end "
                 "every turn: what comes after it is not analysed.", FAMILY)
MB709 = RuleInfo("MB709", "restart-point", Severity.HINT,
                 "Blocks after an unconditional jump or a program end that begin with an N "
                 "number: no run reaches them, a sequence number search (restart at a tool) "
                 "does.", FAMILY)
MB710 = RuleInfo("MB710", "dead-after-end", Severity.INFORMATION,
                 "Blocks after the M30 or M02 of a main program that no jump and no sequence "
                 "number search can reach.", FAMILY, DEAD_CODE)
MB711 = RuleInfo("MB711", "loop-runs-no-turn", Severity.WARNING,
                 "A WHILE loop entered again runs no turn: its counter, a common variable, "
                 "was not set back.", FAMILY)
# fmt: on


# What a dead stretch's blocks are (see _classify_dead), and the state between them.
DEAD, RESTART, LOCAL_CALL, AFTER_STOP = "dead", "restart", "local call", "after stop"
LineRange = tuple[int, int]  # first and last line


MB703_DOC = RuleDoc(
    "MB703",
    reports="""
A loop (`WHILE`/`DO` or a backward `GOTO`) that was still running when the
analysis budget ran out, on the loop's first block, with the variables of its condition that
did not change.

A loop whose test still moves towards its bound when the budget runs out is reported as
MB708 (long loop) instead, and one that waits for a variable only the outside changes as MB707.

A program that reaches a block beginning with `/` runs with the block-delete switch off and
on. A finding of one run only (this one, any alarm the evaluator reports) ends with "(with the
block-delete switch off)" or "(with the block-delete switch on)"; one of both runs is reported
once, as the switch-off run found it.
""",
    why="""
The control repeats the loop until the operator resets it.
With motion in the loop the same pass is cut again and again; without motion the control
looks frozen while it executes macro statements.
""",
    example="""
```nc
O7003 (PECK DRILL)
#1=0
WHILE[#1LT5.]DO1
G01 Z-2. F0.1
#3=#1+1.
END1
M30
```
""",
    fix="""
Change the variable the condition tests inside the loop (here `#1=#1+1.`).
""",
    not_reported="""
A loop whose test moves towards its bound (MB708) or waits for a
common or system variable nothing in it writes (MB707), and a run the 10 s safety net stopped:
how far a run gets in seconds depends on the machine, so nothing is concluded from it.
""",
)


MB704_DOC = RuleDoc(
    "MB704",
    reports="""
A computed `GOTO` (`GOTO#22`, `GOTO[#1+10]`) or an `M99 P` return whose
sequence number does not exist, or is not a whole number from 1 to 99999, when it runs with the
values the analysis computed.
""",
    why="""
The control raises PS0128 ILLEGAL MACRO SEQUENCE NUMBER
(PS0078 SEQUENCE NUMBER NOT FOUND for `M99 P`) and stops at the block.
""",
    example="""
```nc
O7004 (DISPATCH)
#22=41.
GOTO#22
N40 M30
```
""",
    fix="""
Add the missing label or correct the computation of the target.
""",
    not_reported="""
A `GOTO` written with a constant target (MB101 reports a missing
label from the text alone), and a target the analysis cannot compute (the run stops there
without a verdict).
""",
)


MB705_DOC = RuleDoc(
    "MB705",
    reports="""
Macro calls (`G65`, `G66`) nested more than five levels deep, or calls of
any kind more than ten deep, when the program runs.
""",
    why="""
The control raises PS0077 TOO MANY SUB,MACRO NESTING and stops
at the call. A macro that calls itself without an exit reaches it at once.
""",
    example="""
```nc
O7051 (MAIN)
G65 P7052 A1.
M30
O7052 (CALLS ITSELF)
G65 P7052 A1.
M99
```
""",
    fix="""
Give a recursive macro an exit condition, or flatten the calls into a loop.
""",
    not_reported="""
Nesting through calls of programs outside the analysed files (the
analysis cannot follow them), and nesting that only a different set of values would reach.
""",
)


MB706_DOC = RuleDoc(
    "MB706",
    reports="""
A call whose program number is computed (`M98 P#1`, `G65 P#10`) and, with
the value it has when it runs, names a program that is not in the files analysed. Constant
program numbers are MB403's.
""",
    why="""
If the program is not on the control either, the call raises
PS0076 PROGRAM NOT FOUND and stops there.
""",
    example="""
```nc
O7061 (MAIN)
#1=2000.
M98 P#1
M30
```
""",
    fix="""
Check the computed number, and check the called programs together with the
caller.
""",
    not_reported="""
A computed number the analysis cannot know (the call is then
followed as a call into the unknown), and calls written with a constant number (MB403). A
computed number that comes out as a program kept on the control (the setting
`fanuc-macro.machine.programsOnControl`, `--on-control`) or as a vendor's known cycle (MB408).
""",
)


MB707_DOC = RuleDoc(
    "MB707",
    reports="""
A loop whose exit test reads only common or system variables (#100 and up)
that nothing inside the loop writes: it waits for the PMC, a FOCAS client, a probe or another
path to change them. The evaluator cannot play that part, so it stops the loop at its budget
and says so instead of reporting an endless loop (MB703).
""",
    why="""
Such a loop is intended, but it hangs the program for good if
the outside party never writes the variable: worth a time-out (count the turns, and alarm with
#3000 after too many).
""",
    example="""
```nc
O7071 (WAIT FOR THE CLIENT)
#890=0
N1 IF[#890EQ3]GOTO2
G04 P1000
GOTO1
N2 M99
```
""",
    fix="""
Nothing, if the wait is intended. Otherwise add a time-out: a counter in the loop
and an alarm when it runs out.
""",
    not_reported="""
A loop that writes a variable its test reads (MB703 or MB708 when
it does not end), and a run the 10 s safety net stopped before the step budget.
""",
)


MB708_DOC = RuleDoc(
    "MB708",
    reports="""
A loop still running when the evaluator's step budget (300,000 blocks
per entry program; for documents of more than 150,000 blocks, every block once and 150,000
more) ran out, whose test gets nearer its bound every turn
(`WHILE [#1 LT 1000000]` with `#1` growing): a long loop rather than an endless one (MB703).
Blocks after it are not analysed, and their values are not known.
""",
    why="""
Nothing wrong by itself; the note says why the analysis has
no values past the loop, and a loop of a million turns of macro statements can take the control
minutes, with the machine standing still.
""",
    example="""
```nc
O7081 (COUNT TO TWO MILLION)
#1=0
WHILE[#1LT2000000]DO1
#1=#1+1.
END1
M30
```
""",
    fix="""
Nothing, if the loop is meant to be that long.
""",
    not_reported="""
A loop whose test stays where it was or moves away from its bound
(MB703), and a run the 10 s safety net stopped before the step budget.
""",
)


def check(ctx: RuleContext) -> list[Diagnostic]:
    facts = ctx.doc_facts()
    if facts is None:
        return [d for program in ctx.index.programs for d in _after_end(ctx, program, None)]
    found: list[Diagnostic] = []
    f: Finding  # of each kind in turn
    for f in ctx.findings(EndlessLoop):
        found.append(make(MB703, f.message, f.line, f.column, f.end_column))
    for f in ctx.findings(PollingLoop):
        found.append(make(MB707, f.message, f.line, f.column, f.end_column))
    for f in ctx.findings(LongLoop):
        found.append(make(MB708, f.message, f.line, f.column, f.end_column))
    for f in ctx.findings(GotoAlarm, ReturnMissing):
        statement = ctx.doc.blocks[f.line].statement
        constant = isinstance(statement, IfGoto | Goto) and _is_constant(statement)
        if not constant:  # constant targets are MB101's
            found.append(make(MB704, f.message, f.line, f.column, f.end_column))
    for f in ctx.findings(NestingAlarm):
        found.append(make(MB705, f.message, f.line, f.column, f.end_column))
    found.extend(loop_runs_no_turn(ctx))
    for f in ctx.findings(ProgramNotFound):
        if not _constant_call(ctx, f.line):
            found.append(make(MB706, f.message, f.line, f.column, f.end_column))
    found.extend(_programs(ctx, facts))
    return found


MB711_DOC = RuleDoc(
    "MB711",
    reports="""
A `WHILE` loop that counts its turns in a common variable (`#100`-`#199`, `#500`-`#999`): its
condition reads it and its body adds to it from itself (`#100 = #100 + 1`). Reported at the
WHILE when the loop ran two turns or more earlier in the run and, entered again, runs none
(with the counter's value, on the paths the analysis is sure of); and when no block of the
files checked sets the counter to a start value at all (the loop works only the first time
after power-off, for #500 and up only once).
""",
    why="""
Common variables keep their values from one call to the next (and `#500` and up through power
off). A macro that counts its turns in one and does not set it to its start before the loop
works the first time; the second call finds the counter at its end and cuts nothing: a row of
holes or a pocket missing from the part, with no alarm.
""",
    example="""
```nc
O1000
#100 = 0
G65 P2000
G65 P2000
M30
O2000
WHILE [#100 LT 4] DO1
#100 = #100 + 1
END1
M99
```
""",
    fix="""
Set the counter to its start right before the loop (`#100 = 0`), or count in a local (`#1`),
which each G65 call starts vacant.
""",
    not_reported="""
Loops whose counter is a local, or whose condition reads several variables the body sets, a
loop that ran fewer than two turns before, entries after a condition the analysis could not
decide, a counter some block sets to a start value (wherever it stands), files with an
assignment to an indirect variable (`#[...] =`, it may be the counter), and loops no run
reached.
""",
)


def loop_runs_no_turn(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(LoopNoTurn):
        yield make(MB711, f.message, f.line, f.column, f.end_column)
    yield from _counters_never_started(ctx)


def _counters_never_started(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB711 from the text: a loop the run reached whose counter no block of the files
    checked sets to a start value."""
    facts = ctx.doc_facts()
    if facts is None:
        return
    tests = dict(_while_commons(ctx.doc))
    if not tests:
        return  # most documents: no WHILE tests a common variable
    docs = [ctx.doc, *(doc for _uri, doc, _index in ctx.other_documents)]
    for program in ctx.index.programs:
        for loop in program.loops:
            tested = tests.get(loop.do_line)
            if tested is None or not facts.runs.get(loop.do_line) or loop.end_line is None:
                continue
            for n, update in sorted(loop_counters(ctx.doc, loop, tested).items()):
                if next(start_values(docs, n), None) is not None:
                    continue
                span = ctx.doc.blocks[loop.do_line].text.rstrip()
                yield make(
                    MB711,
                    tr(
                        "the loop counts its turns in #{variable} (line {line} adds to it), and "
                        "no block sets #{variable} to a start value: a common variable keeps its "
                        "value from the last run or call, so the loop goes on from there, and "
                        "runs no turn once it is past its end",
                        variable=n,
                        line=update + 1,
                    ),
                    loop.do_line,
                    0,
                    len(span),
                )


# The WHILE blocks that test common variables, kept from one analysis of a document to the next.
_while_commons: LineMap[frozenset[int]] = LineMap(commons_tested)


# ---- What the programs' runs say, kept from one analysis to the next -------------------------
#
# A document of thousands of loops has thousands of constant conditions (MB701) and of
# stretches no run reached (MB702): built again on every keystroke, they would cost far more
# than the edit. Each program whose runs were whole keeps its verdicts and their diagnostics
# with the lines they were drawn from. After an edit the facts of a line differ only where
# the text changed or where the evaluation ran again (the stretches of the run it did not take
# from the earlier one, :func:`~fanuc_macro.evaluator.checkpoints.lines_with_other_facts`), so
# only the conditions on those lines (and those that read a variable whose first write moved)
# and the stretches between the blocks that ran around them are looked at again; the rest is
# kept, or moved by the lines the edit added or removed. ``tests/test_flow_reuse.py`` compares
# the result with fresh analyses after random edits.


class _Segment(NamedTuple):
    """A part of a dead stretch that gets a diagnostic: DEAD (MB702) or RESTART (MB709)."""

    kind: str
    first: int
    end: int  # its last block
    size: int  # the blocks in it
    width: int  # the length of its last line
    stop_line: int  # the jump or end before it
    labels: str  # RESTART: the N numbers a search may start at
    stop: str  # RESTART: what ``stop_line`` is ("GOTO", "M30"...)


class _Stretch(NamedTuple):
    """A stretch of blocks no run reached (first and last line), what it gives."""

    start: int
    last: int
    segments: tuple[_Segment, ...]
    diagnostics: tuple[Diagnostic, ...]


class _Flow:
    """The conditions and dead stretches of one program whose runs were whole and whose
    blocks all parse, each with its diagnostics, in the order of the lines."""

    __slots__ = (
        "condition_lines",
        "conditions",
        "dead",
        "dead_starts",
        "end_line",
        "first_writes",
        "gates",
    )

    def __init__(
        self,
        end_line: int,
        gates: tuple[object, ...],
        first_writes: dict[int, int],
        conditions: tuple[list[int], list[Diagnostic]],
        dead: tuple[list[int], list[_Stretch]],
    ) -> None:
        self.end_line = end_line
        self.gates = gates  # what the whole program's verdicts depend on
        self.first_writes = first_writes  # variable -> its first write in the program
        self.condition_lines, self.conditions = conditions  # MB701
        self.dead_starts, self.dead = dead  # MB702, MB709, by the first line of the stretch


class _State:
    """What the flow rules found in one version of a document, and from what."""

    __slots__ = ("programs", "seen")

    def __init__(self, seen: Seen, programs: dict[int, _Flow]) -> None:
        self.seen = seen
        self.programs = programs  # by first line


_kept: Kept[_State] = Kept()


# The work done, for the tests of what an edit costs: "conditions", the evaluated conditions
# looked at; "stretches", the dead stretches worked out.
WORK_DONE: TableKey[str, int] = TableKey("rules.flow.work_done")


def work_done(kind: str, db: Database | None = None) -> int:
    """How much work of ``kind`` ("conditions", "stretches") the flow rules did in ``db`` (by
    default the current database)."""
    return (db or current_database()).table(WORK_DONE).get(kind, 0)


def _add_work(kind: str, amount: int) -> None:
    work = current_database().table(WORK_DONE)
    work[kind] = work.get(kind, 0) + amount


def _programs(ctx: RuleContext, facts: DocumentFacts) -> list[Diagnostic]:
    """MB701, MB702, MB709 and MB710 of every program."""
    uri = ctx.doc.uri
    last = _kept.get(uri)
    change = None if last is None else last.seen.changes(ctx)
    kept: dict[int, _Flow] = {}
    found: list[Diagnostic] = []
    previous_end = 0
    for program in ctx.index.programs:
        first = program.first_line
        analysed = first in facts.analysed_programs
        # A run cut short (budget, alarm) proves nothing about its branches.
        whole = analysed and first not in facts.incomplete_programs
        undecided = first in ctx.undecided_programs()
        if whole and not _unreadable_flow(ctx, program):
            before = None
            if last is not None and change is not None:
                at = change.diff.before(first)
                before = None if at is None else last.programs.get(at)
                if change.text_start < first and change.text_end > previous_end:
                    before = None  # a label search may look at the lines before the program
            flow = _program_flow(ctx, program, facts, undecided, before, change)
            kept[first] = flow
            found.extend(flow.conditions)
            if not undecided:
                found.extend(chain.from_iterable(map(_diagnostics_of, flow.dead)))
            else:  # what the text alone says is dead still is
                found.extend(_after_end(ctx, program, facts))
        elif not whole or undecided:
            found.extend(_after_end(ctx, program, facts))
        previous_end = program.end_line
    _kept.put(uri, _State(Seen(ctx), kept))
    return found


def _program_flow(
    ctx: RuleContext,
    program: Program,
    facts: DocumentFacts,
    undecided: bool,
    before: _Flow | None,
    change: Changes | None,
) -> _Flow:
    """One program's verdicts: those of ``before`` (the last analysis's) where nothing they
    were drawn from changed, the others looked at again."""
    local_calls = _local_calls(program)
    gates = (undecided, program.display_name, local_calls)
    if (
        before is None
        or change is None
        or before.gates != gates
        or change.moved_end(before.end_line) != program.end_line
    ):
        return _fresh_flow(ctx, program, facts, gates, local_calls)
    dirty = change.within(program.first_line, program.end_line)
    if not dirty and (change.diff.shift == 0 or program.end_line <= change.diff.start):
        return before  # nothing moved, nothing changed
    first_writes, redo = _first_writes_now(ctx, program, facts, before.first_writes, change, dirty)
    spans = _intervals(dirty)
    conditions = _spliced(
        before.condition_lines,
        before.conditions,
        change,
        spans if redo is dirty else _intervals(redo),
        _conditions_at(ctx, facts, first_writes, redo),
        _moved_diagnostic,
    )
    if undecided:
        return _Flow(program.end_line, gates, first_writes, conditions, ([], []))
    windows = _windows(ctx, program, facts.runs, spans)
    fresh = [
        (start, _stretch(ctx, program, start, last, local_calls))
        for a, b in windows
        for start, last in _stretches_between(ctx, facts.runs, a + 1, b)
    ]
    _add_work("stretches", len(fresh))
    name = program.display_name
    dead = _spliced(
        before.dead_starts,
        before.dead,
        change,
        windows,
        fresh,
        lambda stretch, shift: _moved_stretch(stretch, shift, name),
    )
    if not _apart(*dead, windows):
        return _fresh_flow(ctx, program, facts, gates, local_calls)
    return _Flow(program.end_line, gates, first_writes, conditions, dead)


def _fresh_flow(
    ctx: RuleContext,
    program: Program,
    facts: DocumentFacts,
    gates: tuple[object, ...],
    local_calls: frozenset[int],
) -> _Flow:
    """One program's verdicts, each looked at."""
    first_writes = dict(_first_writes(ctx, facts).get(program.first_line, {}))
    jump_lines = _sorted_jump_lines(ctx, facts)
    lines = jump_lines[
        bisect_left(jump_lines, program.first_line) : bisect_left(jump_lines, program.end_line)
    ]
    conditions = _conditions_at(ctx, facts, first_writes, lines)
    condition_lines = [line for line, _ in conditions]
    dead: list[_Stretch] = []
    if not gates[0]:  # decided: which blocks no run reached is known
        for start, last in _dead_stretches(ctx, program.first_line, program.end_line, facts.runs):
            dead.append(_stretch(ctx, program, start, last, local_calls))
        _add_work("stretches", len(dead))
    return _Flow(
        program.end_line,
        gates,
        first_writes,
        (condition_lines, [d for _, d in conditions]),
        ([stretch.start for stretch in dead], dead),
    )


def _local_calls(program: Program) -> frozenset[int]:
    """The N numbers the program enters other than by a run's path: a Haas M97 calls them, or a
    conditional GOTO jumps to them (for other values than this run's: MB701 says the
    condition was decided)."""
    calls = {c.program for c in program.calls if c.kind == "M97" and c.program is not None}
    jumps = {j.target for j in program.jumps if j.conditional and j.target is not None}
    return frozenset(calls | jumps)


def _first_writes_now(
    ctx: RuleContext,
    program: Program,
    facts: DocumentFacts,
    before: dict[int, int],
    change: Changes,
    dirty: list[int],
) -> tuple[dict[int, int], list[int]]:
    """The program's first write of each variable, and the lines (ascending) whose condition
    is to be looked at again: the changed lines, and those that read a variable whose first
    write moved (a condition is the program's own when its variables were set before it).

    The first writes come from the last analysis's and the changed lines' writes, unless a
    first write is on a changed line (the next one may be anywhere)."""
    moved: dict[int, int] = {}
    for number, line in before.items():
        at = change.diff.moved(line)
        if at is None:  # the edit removed it: which conditions it decided is not known
            found = dict(_first_writes(ctx, facts).get(program.first_line, {}))
            jump_lines = _sorted_jump_lines(ctx, facts)
            return found, jump_lines[
                bisect_left(jump_lines, program.first_line) : bisect_left(
                    jump_lines, program.end_line
                )
            ]
        moved[number] = at
    if change.lines.isdisjoint(moved.values()):
        found = dict(moved)
        writes = facts.writes
        for line in dirty:
            write = writes.get(line)
            if write is not None and line < found.get(write[0], line + 1):
                found[write[0]] = line
    else:
        found = dict(_first_writes(ctx, facts).get(program.first_line, {}))
    if found == moved:
        return found, dirty
    redo = set(dirty)
    jumps, blocks = facts.jumps, ctx.doc.blocks
    for number in moved.keys() | found.keys():
        a, b = moved.get(number), found.get(number)
        if a == b:
            continue
        # Conditions after the earlier of the two and up to the later one read it otherwise.
        lo = min(x for x in (a, b) if x is not None) + 1
        hi = program.end_line if a is None or b is None else max(a, b) + 1
        redo.update(
            line
            for line in range(lo, hi)
            if line in jumps and number in compiled(blocks[line].parsed).reads
        )
    return found, sorted(redo)


MB701_DOC = RuleDoc(
    "MB701",
    reports="""
An `IF` or `WHILE` condition with the same result every time the analysis
reached it, decided by the program's own values: every variable it reads was set earlier in
the same program and had one value each time. The branch is never or always taken, the loop
body never runs or always repeats.
""",
    why="""
Nothing stops, but a branch that is never taken is code that
never runs, often a sign of a wrong variable or comparison: a safety check that never fires, a
finishing pass that is always skipped.
""",
    example="""
```nc
O7001 (ROUGHING)
#1=5.
IF[#1GT3.]GOTO10
G00 X100.
N10 M30
```
""",
    fix="""
If the condition tests values that change on the machine (arguments, probe
results), nothing to do. Otherwise remove the dead branch or correct the condition.
""",
    not_reported="""
Conditions on values the analysis does not know: arguments of a
macro analysed on its own, common and system variables set by another program, and anything a
call of a program outside the analysed files (`G65 P9814`) may have changed. Conditions on
values that come from outside the program even when known (a macro's arguments from its one
caller, the caller's locals, a common set by the main program, a probing macro's result): the
outcome is the caller's choice, and another call may change it. Guards whose inputs change
from one time to the next but that never fire (a clamp on the last step of a loop). Outcomes
reached on a path that went through an undecided condition, conditions in a program with a
rejected block that may hold a jump, and conditions in a run that stopped early (an alarm, the
step budget). A condition whose result depends on the block-delete switch (a `/` block sets
what it reads): both runs, switch off and on, count, so it is reported only when it has the
same result with either.
""",
)


def _conditions_at(
    ctx: RuleContext, facts: DocumentFacts, first_writes: dict[int, int], lines: list[int]
) -> list[tuple[int, Diagnostic]]:
    """MB701 on those of ``lines`` (ascending) that hold an evaluated condition."""
    found: list[tuple[int, Diagnostic]] = []
    jumps = facts.jumps
    looked_at = 0
    for line in lines:
        jc = jumps.get(line)
        if jc is None:
            continue
        looked_at += 1
        if jc.undecided or jc.guessed:
            continue  # an outcome on a guessed path proves nothing
        statement = ctx.doc.blocks[line].statement
        if not isinstance(statement, IfGoto | IfThen | While) or statement.cond is None:
            continue
        total = jc.taken + jc.not_taken
        if total == 0 or (jc.taken and jc.not_taken):
            continue
        if not _decided_by_the_program(ctx, facts, first_writes, line):
            continue
        effect = _effect(statement, jc.taken > 0)
        c = statement.cond.span
        found.append(
            (
                line,
                make(
                    MB701,
                    (
                        tr_n(
                            "condition is always true for the values that reach it "
                            "({count} time): {effect}",
                            "condition is always true for the values that reach it "
                            "({count} times): {effect}",
                            total,
                            effect=effect,
                        )
                        if jc.taken
                        else tr_n(
                            "condition is always false for the values that reach it "
                            "({count} time): {effect}",
                            "condition is always false for the values that reach it "
                            "({count} times): {effect}",
                            total,
                            effect=effect,
                        )
                    ),
                    line,
                    c.start,
                    c.end,
                ),
            )
        )
    _add_work("conditions", looked_at)
    return found


def _intervals(lines: list[int]) -> list[LineRange]:
    """Ascending lines as runs of consecutive lines (first, last)."""
    found: list[LineRange] = []
    for line in lines:
        if found and found[-1][1] == line - 1:
            found[-1] = (found[-1][0], line)
        else:
            found.append((line, line))
    return found


def _windows(
    ctx: RuleContext, program: Program, runs: dict[int, int], changed: list[LineRange]
) -> list[LineRange]:
    """The stretches of lines whose dead blocks may have changed, (a, b): from the block that
    ran before a run of ``changed`` lines to the one that ran after it (the program's edges
    when none did). A dead stretch ends at a block that ran, and what it gives depends on its lines
    and the block before it alone, so the stretches outside are the ones found before."""
    blocks = ctx.doc.blocks
    first, end = program.first_line, program.end_line
    windows: list[LineRange] = []
    for lo, hi in changed:
        a = lo - 1
        while a >= first and not (a in runs and blocks[a].statement is not None):
            a -= 1
        b = hi + 1
        while b < end and not (b in runs and blocks[b].statement is not None):
            b += 1
        if windows and a <= windows[-1][1]:
            windows[-1] = (windows[-1][0], b)
        else:
            windows.append((a, b))
    return windows


def _stretches_between(ctx: RuleContext, runs: dict[int, int], a: int, b: int) -> list[LineRange]:
    """The dead stretches (first, last) of the lines ``a`` to before ``b``: the blocks no run
    reached, those with no block that ran between them in one stretch."""
    blocks = ctx.doc.blocks
    dead = [ln for ln in range(a, b) if ln not in runs and blocks[ln].statement is not None]
    found: list[LineRange] = []
    for line in dead:
        if found and not _ran_between(blocks, runs, found[-1][1], line):
            found[-1] = (found[-1][0], line)
        else:
            found.append((line, line))
    return found


def _ran_between(blocks: Sequence[Block], runs: dict[int, int], a: int, b: int) -> bool:
    """Whether a block between lines ``a`` and ``b`` (exclusive) ran."""
    return any(ln in runs and blocks[ln].statement is not None for ln in range(a + 1, b))


T = TypeVar("T")


def _spliced(
    lines: list[int],
    items: list[T],
    change: Changes,
    drops: list[LineRange],
    fresh: list[tuple[int, T]],
    move: Callable[[T, int], T],
) -> tuple[list[int], list[T]]:
    """The last analysis's ``items`` at ``lines`` (ascending) in new line numbers, less those
    at the lines of ``drops`` (new numbers, ascending, apart) and with ``fresh`` (found
    within them) in their place."""
    diff = change.diff
    i, j = bisect_left(lines, diff.start), bisect_left(lines, diff.old_end)
    if diff.shift and j < len(lines):
        shift = diff.shift
        lines = [*lines[:i], *[line + shift for line in lines[j:]]]
        items = [*items[:i], *[move(item, shift) for item in items[j:]]]
    elif i < j:
        lines, items = [*lines[:i], *lines[j:]], [*items[:i], *items[j:]]
    out_lines: list[int] = []
    out_items: list[T] = []
    at = 0
    k = 0
    for a, b in drops:
        lo = bisect_left(lines, a, at)
        out_lines += lines[at:lo]
        out_items += items[at:lo]
        at = bisect_right(lines, b, lo)
        while k < len(fresh) and fresh[k][0] <= b:
            out_lines.append(fresh[k][0])
            out_items.append(fresh[k][1])
            k += 1
    out_lines += lines[at:]
    out_items += items[at:]
    return out_lines, out_items


def _apart(starts: list[int], dead: list[_Stretch], windows: list[LineRange]) -> bool:
    """Whether no stretch kept reaches into a window (which the way windows are drawn rules
    out: the check guards the reuse)."""
    for a, _b in windows:
        at = bisect_left(starts, a)
        if at > 0 and dead[at - 1].last >= a:
            return False
    return True


def _moved_diagnostic(d: Diagnostic, shift: int) -> Diagnostic:
    return Diagnostic(
        d.code,
        d.severity,
        d.message,
        d.line + shift,
        d.column,
        d.end_line + shift,
        d.end_column,
        d.related,
        d.data,
        d.fixes,
        d.tags,
    )


def _moved_stretch(stretch: _Stretch, shift: int, program_name: str) -> _Stretch:
    """A stretch in new line numbers, its diagnostics made again (their messages name them)."""
    segments = tuple(
        s._replace(first=s.first + shift, end=s.end + shift, stop_line=s.stop_line + shift)
        for s in stretch.segments
    )
    return _Stretch(
        stretch.start + shift,
        stretch.last + shift,
        segments,
        tuple(_segment_diagnostic(s, program_name) for s in segments),
    )


def _stretch(
    ctx: RuleContext, program: Program, start: int, last: int, local_calls: frozenset[int]
) -> _Stretch:
    """What a stretch of blocks no run reached gives: MB702 and MB709 segments."""
    blocks = ctx.doc.blocks
    before = _statement_before(ctx, program, start)
    stop = _stops(blocks[before]) if before is not None else None
    after = start - 1 if before is None else before
    segments: list[_Segment] = []
    for kind, first, end, stop_line in _classify_dead(
        ctx, program, after, last, stop is not None, local_calls
    ):
        if kind == DEAD:
            count = _count(ctx, first, end)
            segments.append(
                _Segment(DEAD, first, end, count, len(blocks[end].text), stop_line, "", "")
            )
        elif kind == RESTART:
            count = _count(ctx, first, end)
            segments.append(
                _Segment(
                    RESTART,
                    first,
                    end,
                    count,
                    len(blocks[end].text),
                    stop_line,
                    _labels(ctx, first, end),
                    str(_stops(blocks[stop_line])),
                )
            )
    name = program.display_name
    return _Stretch(
        start, last, tuple(segments), tuple(_segment_diagnostic(s, name) for s in segments)
    )


_diagnostics_of = itemgetter(3)  # a _Stretch's diagnostics, read in C


MB702_DOC = RuleDoc(
    "MB702",
    reports="""
A stretch of blocks of an analysed program that no run reached, reported
on its first block with the number of blocks and the line range. It is not reported when a run
stopped early or took a branch the analysis could not decide. A program that reaches a block
beginning with `/` (block delete, `/1`-`/9` too) runs twice, with the operator's block-delete
switch off (those blocks run) and on (they are skipped): a block is never executed only when
neither run reaches it.
""",
    why="""
Blocks that never run are harmless by themselves, but they
often show a jump to the wrong label or an old pass left in place, and they are not what the
reader of the program thinks the machine does.
""",
    example="""
```nc
O7002 (FINISH PASS)
GOTO10
G00 X100. Z100.
N10 M30
```
""",
    fix="""
Delete the dead blocks or correct the jump that skips them.
""",
    not_reported="""
Blocks after an unconditional jump, `M30`, `M02` or `M99` that
begin with an N number, and what follows them up to the next jump or end: a sequence number
search reaches them (MB709). Blocks an N number called by a Haas `M97` starts. Nothing in a
program whose run stopped early (an alarm, the step budget) or took a branch the analysis could
not decide: which blocks are reached is not known then (MB710 still reports what no jump can
reach after the end). Nor in a program with a block that does not parse and may change which
blocks run: one in another control's language (Syntec `IF (...) THEN`, a Citizen `$2` path) or
one that holds a `GOTO`, `IF`, `WHILE`, `END` or a call. Blocks that only one position of the
block-delete switch passes over (`/GOTO10` skips them when the switch is off, runs them when it
is on): the operator decides. The second run has every switch on (`/1`-`/9` together), so a
block that only a mix of switches passes over may still be reported.
""",
)


MB709_DOC = RuleDoc(
    "MB709",
    reports="""
Blocks that no run of the program reaches but that begin with an N number
right after an unconditional `GOTO`, an `M30`, `M02` or `M99`, and the blocks that follow them
up to the next jump or end. The message gives the range, the N numbers and the jump or end
before them. Reported when MB702 would be: runs that were whole and decided every branch.
""",
    why="""
Nothing is wrong: shops restart a program at a tool by a
sequence number search (the operator searches `N2` and presses cycle start), and blocks kept
behind a jump or after the end are run that way. The hint says that no normal run reaches them,
so that a jump put there by mistake is still seen.
""",
    example="""
```nc
O7091 (TWO TOOLS)
N1 T0101
G01 Z-20. F0.2
GOTO3
N2 T0202
G01 Z-20. F0.1
N3 M30
```
""",
    fix="""
Nothing, if the blocks are a restart point. If the program should run them,
correct the jump before them.
""",
    not_reported="""
Blocks without an N number of their own before them (MB702, or
MB710 after the end), blocks skipped by a conditional jump whose condition is always true
(MB701 and MB702), an N number a Haas `M97` calls or a conditional `GOTO` of the program jumps
to (it runs for other values than the run's: MB701 says the condition was decided), and the
programs MB702 leaves out (runs
stopped early or undecided, blocks that do not parse and may change which blocks run).
""",
)


def _segment_diagnostic(s: _Segment, program_name: str) -> Diagnostic:
    if s.kind == DEAD:
        return make(
            MB702,
            tr(
                "{block_count} never executed ({lines}): no path of the analysed runs reaches them",
                block_count=_blocks(s.size),
                lines=_lines(s.first, s.end),
            ),
            s.first,
            0,
            s.width,
            end_line=s.end,
        )
    return make(
        MB709,
        tr(
            "{block_count} reached only by a sequence number search "
            "({lines}, from {labels}): no run of "
            "{program} comes here past the {stop} "
            "of line {line}; an operator restarting at "
            "{label} runs them",
            block_count=_blocks(s.size),
            lines=_lines(s.first, s.end),
            labels=s.labels,
            program=program_name,
            stop=s.stop,
            line=s.stop_line + 1,
            label=s.labels.split(", ")[0],
        ),
        s.first,
        0,
        s.width,
        end_line=s.end,
    )


def _sorted_jump_lines(ctx: RuleContext, facts: DocumentFacts) -> list[int]:
    """The lines of the evaluated jumps in order, sorted once for every program's question."""
    found = ctx.memo.get("flow.jump_lines")
    if found is None:
        found = ctx.memo["flow.jump_lines"] = sorted(facts.jumps)
    return cast("list[int]", found)


def _first_writes(ctx: RuleContext, facts: DocumentFacts) -> dict[int, dict[int, int]]:
    """Program's first line -> variable -> the first line of the program that set it when the
    run came by: one pass over the writes for every program."""
    found = ctx.memo.get("flow.first_writes")
    if found is None:
        by_program: dict[int, dict[int, int]] = {}
        for line, (number, _summary) in facts.writes.items():
            program = ctx.index.program_at(line)
            if program is None:
                continue
            first = by_program.setdefault(program.first_line, {})
            if line < first.get(number, line + 1):
                first[number] = line
        found = ctx.memo["flow.first_writes"] = by_program
    return cast("dict[int, dict[int, int]]", found)


def _decided_by_the_program(
    ctx: RuleContext, facts: DocumentFacts, first_writes: dict[int, int], line: int
) -> bool:
    """Whether a condition's outcome follows from the program's own values: each variable it
    reads had one value every time and was set earlier in the program. A value from outside (a
    macro's argument, the caller's locals or commons, a probe result) is the caller's choice,
    and a guard whose inputs vary but that never fires (a clamp on the last step) is a guard."""
    for n in compiled(ctx.doc.blocks[line].parsed).reads:
        summary = facts.reads.get((line, n))
        if summary is None or not summary.constant:
            return False
        if first_writes.get(n, line) >= line:
            return False
    return True


def _effect(statement: IfGoto | IfThen | While, taken: bool) -> str:
    if isinstance(statement, IfGoto):
        return tr("the GOTO is always taken") if taken else tr("the GOTO is never taken")
    if isinstance(statement, IfThen):
        return tr("the assignment always runs") if taken else tr("the assignment never runs")
    return tr("the loop body never runs") if not taken else tr("the loop always repeats")


def _is_constant(statement: IfGoto | Goto) -> bool:
    goto = statement.goto if isinstance(statement, IfGoto) else statement
    return constant_value(goto.target) is not None


def _constant_call(ctx: RuleContext, line: int) -> bool:
    program = ctx.index.program_at(line)
    return program is not None and any(
        c.line == line and c.program is not None for c in program.calls
    )


def _dead_stretches(
    ctx: RuleContext, first: int, end: int, runs: dict[int, int]
) -> list[LineRange]:
    """(first, last) line of each stretch of blocks no run reached; comments and blank lines
    inside a stretch belong to it, those around it do not."""
    blocks = ctx.doc.blocks
    found: list[LineRange] = []
    start: int | None = None
    last = first
    done = first  # the lines before it are looked at
    for a, b in _not_run(_run_lines(ctx, runs), first, end):
        # Between two stretches of lines not run: lines that ran. A block among them ends a
        # dead stretch (comments and blank lines do not, whether counted as run or not).
        if start is not None and any(blocks[ln].statement is not None for ln in range(done, a)):
            found.append((start, last))
            start = None
        for line in range(a, b):
            if blocks[line].statement is not None:
                if start is None:
                    start = line
                last = line
        done = b
    if start is not None:
        found.append((start, last))
    return found


def _run_lines(ctx: RuleContext, runs: dict[int, int]) -> list[int]:
    """The lines that ran, in order: sorted once for every program's question (the run goes
    through most blocks in the order of the text, which the sort takes in one pass)."""
    found = ctx.memo.get("flow.run_lines")
    if found is None:
        found = ctx.memo["flow.run_lines"] = sorted(runs)
    return cast("list[int]", found)


def _not_run(ran: list[int], first: int, end: int) -> list[LineRange]:
    """The stretches [a, b) of the lines from ``first`` to before ``end`` that are not in
    ``ran`` (distinct lines in order): a slice of it without a gap spans as many lines as it
    holds, so only the slices with one are cut in two, and a program that ran through costs a
    comparison."""
    lo, hi = bisect_left(ran, first), bisect_left(ran, end)
    if lo == hi:
        return [(first, end)] if first < end else []
    found: list[LineRange] = []
    if ran[lo] > first:
        found.append((first, ran[lo]))
    stack = [(lo, hi - 1)]  # index ranges of ``ran`` that may hold a gap, the earliest last
    while stack:
        i, j = stack.pop()
        if ran[j] - ran[i] == j - i:
            continue  # no gap
        if j == i + 1:
            found.append((ran[i] + 1, ran[j]))
            continue
        middle = (i + j) // 2
        stack.append((middle, j))
        stack.append((i, middle))
    if ran[hi - 1] + 1 < end:
        found.append((ran[hi - 1] + 1, end))
    return found


def _line_stop(parsed: ParsedLine) -> str | None:
    """What ends the fall-through at a block: 'GOTO', 'M30', 'M02' or 'M99' when the next block
    runs only if something jumps to it; None otherwise (a block skip '/' makes it optional)."""
    statement = parsed.statement
    if statement is None or parsed.skip is not None:
        return None
    parts = (statement.nc, statement.macro) if isinstance(statement, Mixed) else (statement,)
    for part in parts:
        if isinstance(part, Goto):
            return "GOTO"
        if isinstance(part, NcStatement):
            for word in part.words:
                if word.address == "M" and (code := constant_value(word.value)) in _ENDS:
                    return f"M{int(code):02d}"
    return None


# Worked out once per distinct line: the rules read every line of a program on each analysis.
_line_stops: PerLine[str | None] = PerLine(_line_stop)


def _stops(block: Block) -> str | None:
    return _line_stops(block.parsed)


_ENDS = (2.0, 30.0, 99.0)


def _classify_dead(
    ctx: RuleContext,
    program: Program,
    after: int,
    last: int,
    stopped: bool,
    local_calls: frozenset[int] | None = None,
) -> list[tuple[str, int, int, int]]:
    """The blocks from the line after ``after`` to ``last``, which no run reached, in segments
    (kind, first, last): DEAD; RESTART, a block with an N number right after an unconditional
    jump or an end, and what falls through from it to the next jump or end, which an operator's
    sequence number search reaches (macro-b.md §9: restart at a tool); LOCAL_CALL, the same
    from an N number a Haas M97 calls, which the analysis does not run. ``stopped``: the block
    at ``after`` ends the fall-through. Each segment comes with the line of the jump or end
    before it."""
    if local_calls is None:
        local_calls = _local_calls(program)
    blocks = ctx.doc.blocks
    state = AFTER_STOP if stopped else DEAD
    segments: list[tuple[str, int, int, int]] = []
    stop_line = after
    for line in range(after + 1, last + 1):
        block = blocks[line]
        seq = block.parsed.seq
        if seq is not None and state == AFTER_STOP:
            state = LOCAL_CALL if seq in local_calls else RESTART
        if block.statement is None:
            continue
        kind = DEAD if state == AFTER_STOP else state
        if segments and segments[-1][0] == kind:
            segments[-1] = (kind, segments[-1][1], line, segments[-1][3])
        else:
            segments.append((kind, line, line, stop_line))
        if _stops(block) is not None:
            state = AFTER_STOP
            stop_line = line
    return segments


def _statement_before(ctx: RuleContext, program: Program, line: int) -> int | None:
    for before in range(line - 1, program.first_line - 1, -1):
        if ctx.doc.blocks[before].statement is not None:
            return before
    return None


def _unreadable_flow(ctx: RuleContext, program: Program) -> bool:
    """Whether a block the parser rejected may change which blocks run: one in another control's
    language (its paths, calls and jumps are not FANUC's), or one that holds a jump, a
    condition, a loop or a call. The run went past it as if it were empty, so which blocks are
    reached is not known."""
    return bool(_unreadable_lines(ctx.doc).between(program.first_line, program.end_line))


def _rejected_flow(parsed: ParsedLine) -> bool:
    problem = parsed.problem
    if problem is None or parsed.statement is not None:
        return False
    if problem.dialect is not None:
        return True
    code = parsed.text
    for comment in reversed(parsed.comments):
        code = code[: comment.span.start] + code[comment.span.end :]
    return _FLOW_WORDS.search(code.upper()) is not None


# The rejected blocks that may change the flow, kept from one analysis of a document to the next.
_unreadable_lines: LineMap[bool] = LineMap(_rejected_flow)
_FLOW_WORDS = re.compile(r"GOTO|IF|WHILE|DO|END|M0*9[6-9](?!\d)|G0*6[56](?!\d)")


def _count(ctx: RuleContext, first: int, last: int) -> int:
    return sum(1 for ln in range(first, last + 1) if ctx.doc.blocks[ln].statement is not None)


def _blocks(n: int) -> str:
    return tr_n("{count} block", "{count} blocks", n)


def _lines(first: int, last: int) -> str:
    if first == last:
        return tr("line {line}", line=first + 1)
    return tr("lines {first}-{last}", first=first + 1, last=last + 1)


def _labels(ctx: RuleContext, first: int, last: int) -> str:
    """The N numbers a search may start at in a restart segment (and one just before it)."""
    lines = range(_label_line(ctx, first), last + 1)
    seqs = [f"N{seq}" for ln in lines if (seq := ctx.doc.blocks[ln].parsed.seq) is not None]
    if len(seqs) > 4:
        return tr("{labels} and {more} more", labels=", ".join(seqs[:4]), more=len(seqs) - 4)
    return ", ".join(seqs)


def _label_line(ctx: RuleContext, first: int) -> int:
    """The line of the N number that starts a restart segment: its first block, or a line of
    its own just before it ('N5' alone)."""
    line = first
    while line > 0 and ctx.doc.blocks[line].parsed.seq is None:
        previous = ctx.doc.blocks[line - 1]
        if previous.statement is not None:
            break
        line -= 1
    return line


MB710_DOC = RuleDoc(
    "MB710",
    reports="""
Blocks after the first `M30` or `M02` of a program that no N number starts:
a `GOTO` can only reach an N number, and so can a sequence number search, so nothing ever runs
them. Typically a second copy of the program pasted below the first without an O number, or
an old version kept after the end. Reported once per run of blocks, at its first block, with
the count and the line range.
""",
    why="""
The control never runs these blocks: a correction made
there does nothing, and the reader of the program sees cuts the machine does not make.
""",
    example="""
```nc
O7101 (FACE)
IF[#500EQ1]GOTO20
G01 X0. F0.2
N20 G00 X100. Z100.
M30
G00 X50. Z2.
G01 X0. F0.2
M30
```
""",
    fix="""
Delete the blocks, or give them an O number of their own if they are another
program.
""",
    not_reported="""
Blocks MB702 reports already (a program whose runs were whole and
decided: MB702 names every block they did not reach), blocks that begin with an N number after
the end and what follows them up to the next jump or end (a jump or a search can reach them;
MB709), blocks after an `M30` with a block skip (`/M30`), which the control may pass, and
programs with a block that does not parse and may change which blocks run (see MB702).
""",
)


def _after_end(
    ctx: RuleContext, program: Program, facts: DocumentFacts | None
) -> Iterator[Diagnostic]:
    """MB710: blocks after the first M30/M02 of a program that nothing can reach, from the text
    alone (a block without an N number is no jump's target and no search's start)."""
    blocks = ctx.doc.blocks
    # The evaluator found the first M30/M02 as it compiled the program; a block skip can make
    # that one optional, so the search goes on from there.
    start = program.first_line if facts is None else facts.program_ends.get(program.first_line)
    if start is None:
        return
    end_line = next(
        (ln for ln in range(start, program.end_line) if _stops(blocks[ln]) in ("M30", "M02")),
        None,
    )
    if end_line is None:
        return
    last = _statement_before(ctx, program, program.end_line)
    if last is None or last <= end_line or _unreadable_flow(ctx, program):
        return
    end_code = _stops(blocks[end_line])
    for kind, first, end, _stop_line in _classify_dead(ctx, program, end_line, last, True):
        if kind != DEAD:
            continue
        count = _count(ctx, first, end)
        yield make(
            MB710,
            tr(
                "{block_count} after the {end_code} of {program} (line "
                "{line}) can never run ({lines}): no N number starts "
                "them, so neither a jump nor a sequence number search reaches them",
                block_count=_blocks(count),
                end_code=end_code,
                program=program.display_name,
                line=end_line + 1,
                lines=_lines(first, end),
            ),
            first,
            0,
            len(blocks[end].text),
            end_line=end,
        )
