"""MB2xx: WHILE/DO/END structure: pairs, loop numbers, nesting, crossed ranges."""

from __future__ import annotations

import re
from collections.abc import Iterator

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
from ..program.index import Program
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import Block, NcStatement
from ..translation import tr
from .context import RuleContext

FAMILY = "loops"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB201 = RuleInfo("MB201", "do-without-end", Severity.ERROR,
                 "A DO m with no END m after it in the program (alarm PS0124).", FAMILY)
MB202 = RuleInfo("MB202", "end-without-do", Severity.ERROR,
                 "An END m with no open DO m before it (alarm PS0126).", FAMILY)
MB203 = RuleInfo("MB203", "loop-number", Severity.ERROR,
                 "A DO/END identification number other than 1, 2 or 3 (alarm PS0126).", FAMILY)
MB204 = RuleInfo("MB204", "loop-too-deep", Severity.ERROR,
                 "WHILE loops nested more than three deep.", FAMILY)
MB205 = RuleInfo("MB205", "loops-crossed", Severity.ERROR,
                 "Loop ranges that cross (DO1 ... DO2 ... END1 ... END2).", FAMILY)
# fmt: on


def _rejected_do_lines(ctx: RuleContext, start: int, end: int) -> dict[float, list[int]]:
    """Lines from ``start`` to ``end`` that FANUC rejects (MB001/MB002) and that hold 'DOm':
    the loop they open is not seen, and its END is no second mistake."""
    found: dict[float, list[int]] = {}
    for block in ctx.doc.blocks[start:end]:
        parsed = block.parsed
        if parsed.problem is None:
            continue
        for m in _DO_WORD.finditer(parsed.text):
            found.setdefault(float(m.group(1)), []).append(block.line)
    return found


_DO_WORD = re.compile(r"\bDO\s*(\d)\b", re.I)


def _insert_end(ctx: RuleContext, program: Program, line: int, n: str) -> Fix:
    """MB201's fix: close the DO with END<n> before the program's M99/M30 (or after its last
    block). A line end in the text is "\n": the editor writes the document's own."""
    blocks = ctx.doc.blocks
    end = min(program.end_line, len(blocks))
    target = next((ln for ln in range(line + 1, end) if _ends_program(blocks[ln])), None)
    if target is not None:
        edit = FixEdit.insert(target, 0, f"END{n}\n")
    else:
        last = max(
            (ln for ln in range(line, end) if blocks[ln].statement is not None), default=line
        )
        edit = FixEdit.insert(last, len(blocks[last].text), f"\nEND{n}")
    return Fix(tr("Insert END{loop_id} to close DO{loop_id}", loop_id=n), (edit,), preferred=True)


def _ends_program(block: Block) -> bool:
    for statement in statements_of(block.statement):
        nc = statement if isinstance(statement, NcStatement) else None
        if nc is not None and any(
            w.address == "M" and constant_value(w.value) in (2.0, 30.0, 99.0) for w in nc.words
        ):
            return True
    return False


MB201_DOC = RuleDoc(
    "MB201",
    reports="""
A `DOm` (with or without `WHILE`) with no `ENDm` after it in the same O
program.
""",
    why="""
The control raises PS0124 MISSING END STATEMENT. When the
loop condition becomes false it has nowhere to go; a `DOm` without `WHILE` would loop for ever.
""",
    example="""
```nc
O2002 (WAIT FOR SPINDLE)
WHILE[#1000EQ0]DO1
G04 P100
M99
```
""",
    fix="""
Add `ENDm` after the last block of the loop body, with the same number `m`.
""",
    not_reported="""
A `DO` in a block FANUC rejects for another reason (a
`WHILE [#1<3] DO1`): that block's own diagnostic comes first, and its `END` is not reported
either (MB202). A `DO` of a program that goes on past the part of a big file the analysis
reads (MB013): its `END` may be in the unread part.
""",
)


MB202_DOC = RuleDoc(
    "MB202",
    reports="""
An `ENDm` with no open `DOm` before it in the same program.
""",
    why="""
The control raises PS0126 ILLEGAL LOOP NUMBER when it reaches
the block, and the program stops there.
""",
    example="""
```nc
O2004 (FINISH PASSES)
WHILE[#1LT3]DO1
#1=#1+1
END1
END2
M30
```
""",
    fix="""
Delete the extra `END`, or add the missing `WHILE [...] DOm` and check that the
numbers pair up.
""",
    not_reported="""
An `END` whose `DO` stands in a block FANUC rejects: that block is
reported, and the `END` is no second mistake.
""",
)


MB203_DOC = RuleDoc(
    "MB203",
    reports="""
A `DO` or `END` identification number other than 1, 2 or 3 (`DO4`, `DO0`,
`END 5`). It is reported on both the `DO` and the `END`.
""",
    why="""
FANUC accepts only 1, 2 and 3. Another number raises PS0126
ILLEGAL LOOP NUMBER and stops the program at that block.
""",
    example="""
```nc
O2005 (PECK LOOP)
WHILE[#1LT5]DO4
#1=#1+1
END4
M30
```
""",
    fix="""
Number loops 1, 2 and 3. Numbers may be reused for loops that do not overlap,
so three numbers are always enough.
""",
    not_reported="""
The numbers 1 to 3 reused for loops that follow one another, or
nest in another order (`DO2` outside `DO1`; the reference gives no rule on the order,
unverified).
""",
)


MB204_DOC = RuleDoc(
    "MB204",
    reports="""
A `WHILE ... DOm` opened while three loops are already open in the same
program.
""",
    why="""
FANUC nests `DO` loops at most three deep. A fourth level
raises a loop alarm when the control reads it, in the middle of the pattern being machined.
""",
    example="""
```nc
O2006 (GRID OF HOLES)
WHILE[#1LT3]DO1
WHILE[#2LT3]DO2
WHILE[#3LT3]DO3
WHILE[#4LT2]DO1
END1
END3
END2
END1
M99
```
""",
    fix="""
Move the innermost levels into a macro called with `G65` inside the loop (the
called program may nest three loops again), or replace a level with an `IF [...] GOTO` loop.
""",
    not_reported="""
Loops of a macro called inside a loop (a `G65` call starts a new
level: its three count again), and loops made with `IF [...] GOTO`, which have no nesting limit.
""",
)


MB205_DOC = RuleDoc(
    "MB205",
    reports="""
Loop ranges that cross: `DO1 ... DO2 ... END1 ... END2`. It is reported on
the `END` that closes the outer loop while the inner one is still open.
""",
    why="""
FANUC requires loops to nest. Crossed ranges raise a loop
alarm, or pass control to the wrong `WHILE`: rows and columns of a pattern are machined in the
wrong order or the wrong number of times.
""",
    example="""
```nc
O2007 (ROWS AND COLUMNS)
WHILE[#1LT3]DO1
WHILE[#2LT4]DO2
#2=#2+1
END1
END2
M30
```
""",
    fix="""
Close the inner loop first: `DO1 ... DO2 ... END2 ... END1`.
""",
    not_reported="""
Loops that nest properly whatever their numbers, and loops made
with `IF [...] GOTO`, whose ranges the control does not pair.
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    unread = ctx.doc.unread_from
    for program in ctx.index.programs:
        name = program.display_name
        rejected_dos: dict[float, list[int]] | None = None
        # A program that goes on past the part of the file the analysis reads (MB013) may
        # have its END there.
        cut = unread is not None and program.end_line >= unread
        for p in program.loop_problems:
            if cut and p.kind == "no-end":
                continue
            if p.kind == "no-do":
                if rejected_dos is None:
                    rejected_dos = _rejected_do_lines(ctx, program.first_line, program.end_line)
                if any(line < p.line for line in rejected_dos.get(p.loop_id, ())):
                    continue  # its DO is in a block already reported as rejected
            n = f"{p.loop_id:g}"
            if p.kind == "no-end":
                yield make(
                    MB201,
                    tr(
                        "DO{loop_id} has no END{loop_id} in {program} (alarm PS0124)",
                        loop_id=n,
                        program=name,
                    ),
                    p.line,
                    p.span.start,
                    p.span.end,
                    data={"loop_id": n},
                    fixes=(_insert_end(ctx, program, p.line, n),),
                )
            elif p.kind == "no-do":
                yield make(
                    MB202,
                    tr(
                        "END{loop_id} closes no open DO{loop_id} in {program} (alarm PS0126)",
                        loop_id=n,
                        program=name,
                    ),
                    p.line,
                    p.span.start,
                    p.span.end,
                )
            elif p.kind == "bad-id":
                yield make(
                    MB203,
                    tr("loop number {loop_id} is outside 1-3 (alarm PS0126)", loop_id=n),
                    p.line,
                    p.span.start,
                    p.span.end,
                )
            elif p.kind == "too-deep":
                related = (
                    []
                    if p.other_line is None
                    else [Related(p.other_line, 0, 0, tr("outermost loop starts here"))]
                )
                yield make(
                    MB204,
                    tr("DO{loop_id} is a fourth nested loop; FANUC nests at most three", loop_id=n),
                    p.line,
                    p.span.start,
                    p.span.end,
                    related=related,
                )
            elif p.kind == "crossed":
                related = (
                    []
                    if p.other_line is None
                    else [Related(p.other_line, 0, 0, tr("inner loop opened here is still open"))]
                )
                yield make(
                    MB205,
                    tr(
                        "END{loop_id} closes DO{loop_id} while a loop opened inside it (line "
                        "{line}) is still open: loop ranges cross",
                        loop_id=n,
                        line=(p.other_line or 0) + 1,
                    ),
                    p.line,
                    p.span.start,
                    p.span.end,
                    related=related,
                )
