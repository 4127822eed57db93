"""MB6xx: address values computed at run time: non-integers and impossible values."""

from __future__ import annotations

from bisect import bisect_left
from collections.abc import Iterator
from typing import cast

from ..diagnostics import (
    Diagnostic,
    Fix,
    FixEdit,
    Related,
    RuleDoc,
    RuleInfo,
    Severity,
    line_list,
    make,
)
from ..evaluator.facts import (
    AddressNotInteger,
    AddressOutOfRange,
    BlockFault,
    CornerRefused,
    FeedUnit,
    FeedZero,
)
from ..program.custom_calls import unset_m_calls
from ..syntax.marks import constant_value
from ..syntax.tree import Assign, Var, Word
from ..translation import tr
from .context import RuleContext

FAMILY = "addresses"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB601 = RuleInfo("MB601", "address-not-integer", Severity.ERROR,
                 "An M, S, T, P, L, H, D or G address gets a value that is not a whole number.",
                 FAMILY)
MB602 = RuleInfo("MB602", "address-out-of-range", Severity.WARNING,
                 "An address gets an impossible value: negative S/T/M/F, S above the machine's "
                 "maximum spindle speed.", FAMILY)
MB603 = RuleInfo("MB603", "feed-not-set", Severity.WARNING,
                 "A G01/G02/G03 cut runs before any F was commanded.", FAMILY)
MB604 = RuleInfo("MB604", "feed-zero", Severity.ERROR,
                 "A cut or a thread runs with F0: the control stops with PS0011 FEED ZERO.",
                 FAMILY)
MB605 = RuleInfo("MB605", "feed-unit", Severity.WARNING,
                 "A cut at a feed whose size belongs to the other feed mode (per minute or per "
                 "revolution).", FAMILY)
MB606 = RuleInfo("MB606", "g30-p", Severity.ERROR,
                 "G30 with a P other than 2, 3 or 4.", FAMILY)
MB607 = RuleInfo("MB607", "t-code-in-block", Severity.ERROR,
                 "A lathe's T code in a G50, G10 or G04 block.", FAMILY)
MB608 = RuleInfo("MB608", "corner-refused", Severity.ERROR,
                 "A chamfer or corner R (,C ,R) on a thread, or on the block that starts or "
                 "cancels radius compensation.", FAMILY)
# fmt: on


MB601_DOC = RuleDoc(
    "MB601",
    reports="""
An `M`, `S`, `T`, `L`, `H` or `D` address, or the `P` of a call, that gets a
value with a fractional part when the program runs (`M#13` with `#13=3.5`), or a `G` with more
than one decimal. The message says where the variable was set.
""",
    why="""
These addresses take whole numbers. A control rejects the
block with an alarm, or rounds the value: `M#13` with 3.5 rounded is `M4`, the spindle in
reverse, and `T#20` with 1.5 selects a tool other than the one meant.
""",
    example="""
```nc
O6001 (SPINDLE FROM A VARIABLE)
#13=3.5
M#13
M30
```
""",
    fix="""
Correct the value (often a variable set for another purpose, `M#1` meant
`M#13`), or round it explicitly with `ROUND`/`FIX`. When the message suggests a variable
(one assigned earlier in the program whose comment names the address), the quick fix in the
editor writes it in the word, offered only when its last assignment before the word is a whole
number written as a constant, so that the word then gets a whole value.
""",
    not_reported="""
Addresses that take a decimal point (`X`, `Y`, `Z`, `F`, `R`...), a
`G` code with one decimal (`G66.1`, `G54.1`), a vacant variable (the word is omitted) and values
the analysis cannot compute. Nor the words of a block that reads as a macro call through an M
code the settings do not set up (MB409: `M165 P9814 D1.415`): they are the macro's arguments
(`D` a diameter, not an offset number). Nor a lathe's `D` in a block of a multiple repetitive
cycle (`G71`-`G76`: the one-block form of the FS10/11 program format, a Haas lathe's
`G71 P Q U W D F`), a depth of cut or a relief, not an offset number: whether FANUC takes a
decimal point there is unverified.
""",
)


MB602_DOC = RuleDoc(
    "MB602",
    reports="""
An address that gets an impossible value when the program runs: a negative
`S`, `T`, `M`, `H`, `D` or `F`, or an `S` above the machine's maximum spindle speed when that
limit is set (setting `fanuc-macro.machine.maxSpindleSpeed`, command line
`--max-spindle-speed`). The limit has no default: it is the machine builder's, and a guessed one
reports good programs.
""",
    why="""
A negative feed or speed raises an alarm. A speed above the
maximum is clamped by the control (or stopped with an alarm), so the surface speed the program
computed is not the one cutting: poor finish, broken inserts, and on a lathe a chuck turning
faster than its rating.
""",
    example="""
```nc
O6002 (SURFACE SPEED TO RPM)
#19=FIX[1000.*300./[3.1416*20.]]
S#19 M03
M30
```

The example assumes `"fanuc-macro.machine.maxSpindleSpeed": 4000`.
""",
    fix="""
Clamp the computed speed (`G50 S` on a lathe, or `IF [#19 GT ...]`), or correct
the formula or the setting of the machine's maximum speed.
""",
    not_reported="""
A spindle speed of any size while the machine's maximum is not
set; values the analysis cannot compute (an argument of a macro nobody calls); the speed a
`G96` constant surface speed turns into at a diameter (the control clamps it with `G50 S`), and
the words of a block that reads as a macro call through an M code (MB409): its arguments.
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    yield from _feed_not_set(ctx)
    yield from _feed_zero(ctx)
    yield from feed_unit(ctx)
    yield from g30_p(ctx)
    yield from t_code_in_block(ctx)
    yield from corner_refused(ctx)
    # A block that reads as a macro call through an M code not set up (MB409): its words are
    # the macro's arguments (D a diameter, not an offset number), which no NC rule applies to.
    arguments = {
        line: (start, end)
        for line, _, start, end in unset_m_calls(ctx.doc, ctx.config.custom_calls)
    }
    for f in ctx.findings(AddressNotInteger, AddressOutOfRange):
        code_at = arguments.get(f.line)
        if code_at is not None and f.column != code_at[0]:
            continue
        rule = MB601 if isinstance(f, AddressNotInteger) else MB602
        message = f.message
        related: list[Related] = []
        fixes: tuple[Fix, ...] = ()
        word = _word_at(ctx, f.line, f.column)
        if word is not None and isinstance(word.value, Var) and word.value.number is not None:
            n = int(word.value.number)
            origin = _last_assignment(ctx, f.line, n)
            if origin is not None:
                line, text = origin
                message = tr(
                    "{finding} (#{variable} set at line {line}: {assignment_text})",
                    finding=message,
                    variable=n,
                    line=line + 1,
                    assignment_text=text,
                )
                related.append(
                    Related(
                        line,
                        0,
                        len(ctx.doc.blocks[line].text),
                        tr("#{variable} is set here", variable=n),
                    )
                )
                hint = _likely_meant(ctx, f.line, word.address)
                if hint:
                    message = tr(
                        "{finding}; did you mean {address}{variable}?",
                        finding=message,
                        address=word.address,
                        variable=hint,
                    )
                    fixes = _use_meant(ctx, f.line, word, hint)
        yield make(rule, message, f.line, f.column, f.end_column, related=related, fixes=fixes)


MB603_DOC = RuleDoc(
    "MB603",
    reports="""
A cutting move (`G01`, `G02`, `G03`; on a mill a hole of a drilling, boring or tapping cycle)
that the evaluator runs before any `F` has been commanded since the main program started:
once per program, at the first such cut, with the number of cuts after it that run without F
too (and their lines). A macro analysed on its own gets its caller's feed, so it is not
reported there.
""",
    why="""
F is modal. With none given, the move runs at the feed an
earlier program left, which no one chose for this cut, or, after power-on, with F zero, which
stops the program with PS0011 FEED ZERO (COMMAND) at that block. (The power-on feed of
parameter 1411 on some controls is not checked here.)
""",
    example="""
```nc
O0001 (FACE)
G54 G90 G00 X0 Y0
S1000 M03
G01 Z-2.
X100.
M30
```
""",
    fix="""
Give F in the first cutting block (`G01 Z-2. F100.`), or before it.
""",
    not_reported="""
Rapid moves (`G00`), a lathe's threading and canned cycles, whose F is the lead or is given
in the cycle block, cutting moves after a call of a program outside the
analysed files, which may have commanded F, and each later cut without F as a warning of its
own.
""",
)


def _feed_not_set(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB603. F is modal: a cut with none commanded since the program started runs at what an
    earlier program left, or stops with PS0011 FEED ZERO (COMMAND) after power-on, when F is 0
    (FANUC 0i-D alarm list; the power-on F of parameter 1411 is unverified here).

    Once per program, at the first such cut the run reached: the cuts after it lack the same F
    (a CAM file without F would otherwise get one warning per block)."""
    facts = ctx.doc_facts()
    if facts is None:
        return
    for program in facts.feedless().values():
        cuts = program.lines
        line = cuts[0]
        text = ctx.doc.blocks[line].text
        if program.count > 1:
            message = tr(
                "{cut}: the feed is what an earlier program left, or 0 after power-on (alarm "
                "PS0011 FEED ZERO); give F in this block or before it; {count} more cuts run "
                "without F after it (lines {lines})",
                cut=program.message,
                count=program.count - 1,
                lines=line_list(cuts[1:]),  # the first few: SHOWN_CUTS is more than it shows
            )
        else:
            message = tr(
                "{cut}: the feed is what an earlier program left, or 0 after power-on (alarm "
                "PS0011 FEED ZERO); give F in this block or before it",
                cut=program.message,
            )
        related = tr("a cut without F")
        yield make(
            MB603,
            message,
            line,
            len(text) - len(text.lstrip()),
            len(text.rstrip()),
            related=[Related(n, 0, 0, related) for n in cuts[1:20]],
        )


MB604_DOC = RuleDoc(
    "MB604",
    reports="""
A cutting move (`G01`, `G02`, `G03`), a thread (`G32`, `G92`, `G76`) or a
lathe turning or facing cycle (`G90`, `G94`) that the evaluator runs with F exactly 0: written
`F0`, a variable that holds 0 (the message says where it was set), or the modal F left at 0
by an earlier block. The evaluator stops the run there, as the control does (so does the
debugger, on its alarm filter).
""",
    why="""
The control stops at that block with alarm PS0011 FEED ZERO
(COMMAND) (FANUC 0i-TF/0i-MF alarm lists; for a threading lead of 0 the alarm number is not
verified here). A feed or lead computed into a variable that comes out 0 is usually a formula
or an argument gone wrong, found on the machine in the middle of a job.
""",
    example="""
```nc
O1010 (PITCH FROM A VARIABLE)
G97 S500 M03
G00 X22. Z5.
#9=0
G32 Z-30. F#9
G00 X40.
M30
```
""",
    fix="""
Give the feed (the lead for a thread): correct the formula or the argument
that gives 0, or the `F` word.
""",
    not_reported="""
Rapid moves, which do not use F; `G70`–`G73` and the drilling cycles;
a feed the analysis cannot compute (a macro's argument nobody passes); a feed that is tiny
but not 0 (MB602 reports a negative one).
""",
)


def _feed_zero(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB604: the evaluator's PS0011 FEED ZERO, a cut or thread run with F exactly 0, where it
    stopped the run; the message says where the 0 comes from."""
    for f in ctx.findings(FeedZero):
        text = ctx.doc.blocks[f.line].text
        word = _word_in_block(ctx, f.line, "F")
        if word is None:
            where: str = tr("the modal F, commanded 0 before this block")
            start, end = len(text) - len(text.lstrip()), len(text.rstrip())
        else:
            where = _zero_word(ctx, f.line, word)
            start, end = word.span.start, word.span.end
        message = (
            tr(
                "{finding}, {where}: the control stops at this block; give the lead",
                finding=f.message,
                where=where,
            )
            if f.lead
            else tr(
                "{finding}, {where}: the control stops at this block; give the feed",
                finding=f.message,
                where=where,
            )
        )
        yield make(MB604, message, f.line, start, end)


def _zero_word(ctx: RuleContext, line: int, word: Word) -> str:
    """MB604: where the 0 of the block's F word comes from."""
    word_text = ctx.doc.blocks[line].text[word.span.start : word.span.end]
    if constant_value(word.value) is not None:
        return tr("{word_text} in this block", word_text=word_text)
    value = word.value
    if isinstance(value, Var) and value.number is not None:
        assigned = _last_assignment(ctx, line, int(value.number))
        if assigned is not None:
            return tr(
                "{word_text} in this block gives 0 (#{variable:g} set at line {line}: "
                "{assignment_text})",
                word_text=word_text,
                variable=value.number,
                line=assigned[0] + 1,
                assignment_text=assigned[1],
            )
    return tr("{word_text} in this block gives 0", word_text=word_text)


def _block_words(ctx: RuleContext, line: int) -> Iterator[Word]:
    """The NC words of the block at ``line``, an IF's included."""
    from ..syntax.parser import statements_of
    from ..syntax.tree import IfNc, NcStatement

    for statement in statements_of(ctx.doc.blocks[line].statement):
        nc = statement.words if isinstance(statement, IfNc) else statement
        if isinstance(nc, NcStatement):
            yield from nc.words


def _word_in_block(ctx: RuleContext, line: int, address: str) -> Word | None:
    return next((w for w in _block_words(ctx, line) if w.address == address), None)


def _word_at(ctx: RuleContext, line: int, column: int) -> Word | None:
    return next((w for w in _block_words(ctx, line) if w.span.start == column), None)


def _last_assignment(ctx: RuleContext, before: int, number: int) -> tuple[int, str] | None:
    program = ctx.index.program_at(before)
    first = program.first_line if program else 0
    lines = _assignments(ctx).get(number, [])
    at = bisect_left(lines, before) - 1  # the last assignment before the line
    if at >= 0 and lines[at] >= first:
        line = lines[at]
        return line, ctx.doc.blocks[line].text.strip()
    return None


def _assignments(ctx: RuleContext) -> dict[float, list[int]]:
    """The lines that assign each variable, in order: gathered once for every finding."""
    found = ctx.memo.get("addresses.assignments")
    if found is None:
        by_number: dict[float, list[int]] = {}
        for block in ctx.doc.blocks:
            statement = block.statement
            if isinstance(statement, Assign) and statement.target.number is not None:
                by_number.setdefault(statement.target.number, []).append(block.line)
        found = ctx.memo["addresses.assignments"] = by_number
    return cast("dict[float, list[int]]", found)


def _use_meant(ctx: RuleContext, line: int, word: Word, hint: str) -> tuple[Fix, ...]:
    """MB601: the word's variable replaced by the one the message suggests (``M#1`` becomes
    ``M#13``), offered when the last assignment of that variable before the word, in its
    program, is a whole number written as a constant: then the word gets a whole value."""
    now = word.value
    if isinstance(now, Var) and now.number is not None and f"#{int(now.number)}" == hint:
        return ()  # the word has that variable already
    origin = _last_assignment(ctx, line, int(hint[1:]))
    if origin is None:
        return ()
    statement = ctx.doc.blocks[origin[0]].statement
    assert isinstance(statement, Assign)
    value = constant_value(statement.value)
    if value is None or value != int(value):
        return ()
    span = word.value.span
    return (
        Fix(
            tr(
                "Use {address}{variable} (#{number} is set to {value:g} at line {line})",
                address=word.address,
                variable=hint,
                number=hint[1:],
                value=value,
                line=origin[0] + 1,
            ),
            (FixEdit(line, span.start, line, span.end, hint),),
            preferred=True,
        ),
    )


def _likely_meant(ctx: RuleContext, line: int, address: str) -> str | None:
    """A local assigned in the same program whose comment names this address (M#13 for M#1)."""
    program = ctx.index.program_at(line)
    if program is None:
        return None
    lines = _named_assignments(ctx, address)
    at = bisect_left(lines, program.first_line)  # the first one in the program, before the line
    if at < len(lines) and lines[at] < line:
        statement = ctx.doc.blocks[lines[at]].statement
        assert isinstance(statement, Assign) and statement.target.number is not None
        return f"#{int(statement.target.number)}"
    return None


def _named_assignments(ctx: RuleContext, address: str) -> list[int]:
    """The lines of assignments whose comment names ``address``, in order: one pass over the
    document per address, not one per finding."""
    key = f"addresses.named.{address}"
    found = ctx.memo.get(key)
    if found is None:
        lines: list[int] = []
        for block in ctx.doc.blocks:
            statement = block.statement
            if not isinstance(statement, Assign) or statement.target.number is None:
                continue
            comment = " ".join(c.text for c in block.parsed.comments).upper()
            if f" {address} " in f" {comment} " or f"{address}代码" in comment.replace(" ", ""):
                lines.append(block.line)
        found = ctx.memo[key] = lines
    return cast("list[int]", found)


MB605_DOC = RuleDoc(
    "MB605",
    reports="""
A cutting move (`G01`-`G03`; a lathe's turning, facing and roughing cycles, G90, G94 and
G71-G73; a mill's drilling cycles)
whose F, in the feed mode the run set (a lathe's `G98` per minute and `G99` per revolution, a
mill's `G94` and `G95`), has the other mode's size: per minute below 1 mm/min (0.04 inch/min),
per revolution above 5 mm (0.2 inch). Once per mode set; the message names the block that set
it.
""",
    why="""
The control takes F in the mode in force. F0.25 in G98 is a quarter of a millimetre a minute:
the tool stands in the cut, rubbing, and the cycle never ends; F150 in G99 is 150 mm a
revolution, a crash at the first turn. It comes from a safety block copied from another
machine's program, or a feed written for the other mode.
""",
    example="""
```nc
O8000 (TURN)
G21 G40 G98
T0101
G97 S800 M03
G00 X42. Z2.
G01 Z-30. F0.25
M30
```
""",
    fix="""
Set the mode the feeds are written for (`G99` for F0.25 per revolution), or write the feed in
the mode set (`F200.` per minute).
""",
    not_reported="""
Feeds in a mode the run did not set (the control's power-on mode is a parameter's), threading
(its F is the lead) and the moves after it that run at the lead, rapid moves, feeds between
the two limits, and each later cut until the mode is set again.
""",
)


def feed_unit(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(FeedUnit):
        yield make(MB605, f.message, f.line, f.column, f.end_column)


MB606_DOC = RuleDoc(
    "MB606",
    reports="""
A `G30` block (a return to the second, third or fourth reference position) whose `P` is not 2,
3 or 4, as the run computes it. The message gives P.
""",
    why="""
P says which reference position G30 goes to (P2, the second, when it is left out); the control
stops with alarm PS0046 "ILLEGAL REFERENCE RETURN COMMAND" (0i-F alarm list) for any other.
`G30 P1` for the first reference position, which is G28's, is the usual slip.
""",
    example="""
```nc
O3400
G91 G30 P1 Z0.
M30
```
""",
    fix="""
Return to the first reference position with `G28`, or give the position meant: `G30 P2 Z0.`.
""",
    not_reported="""
A G30 without P (the second position), P3 and P4 on a machine without the option (the
builder's), and a P the analysis cannot compute.
""",
)


def g30_p(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(BlockFault):
        if f.fault == "g30-p":
            yield make(MB606, f.message, f.line, f.column, f.end_column)


MB607_DOC = RuleDoc(
    "MB607",
    reports="""
On a lathe, a `T` word in a block with `G50` (the coordinate system or the spindle speed clamp),
`G10` (data setting) or `G04` (dwell).
""",
    why="""
The tool change and its offset cannot run with these: the control stops with alarm PS0245
"T-CODE NOT ALLOWED IN THIS BLOCK" (0i-F alarm list). A clamp and the next tool written on one
line (`G50 S2000 T0202`) gives it.
""",
    example="""
```nc
O2100
G50 S2000 T0101
G96 S180 M03
M30
```
""",
    fix="""
Give the tool in a block of its own: `T0101`, then `G50 S2000`.
""",
    not_reported="""
Mills (their T selects the tool for the next M06). A lathe in G code system B or C writes G50
as G92: its blocks are read as system A's, and reported alike.
""",
)


def t_code_in_block(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(BlockFault):
        if f.fault == "t-code":
            yield make(MB607, f.message, f.line, f.column, f.end_column)


MB608_DOC = RuleDoc(
    "MB608",
    reports="""
A chamfer (`,C`) or a corner R (`,R`) written on a lathe's threading block (`G32`, `G92`,
`G76`, ...), or on the block that starts radius compensation (the first move in the plane after
`G41`/`G42`) or cancels it (`G40` while it was on). The message says which.
""",
    why="""
The control rounds or bevels the corner between two moves it knows; it cannot do it on a
thread, nor where the offset path begins or ends. It stops with alarm PS0050 "CHF/CNR NOT
ALLOWED IN THRD BLK" or PS0039 "CHF/CNR NOT ALLOWED IN G41,G42" (0i-F alarm list; 0i-MF
"Optional chamfering and corner R").
""",
    example="""
```nc
O5400
G90 G17 G54 G00 X-20. Y0.
S1000 M03
G01 Z-2. F200.
G41 D1 G01 X0. Y0. ,R5.
Y40.
G40 G01 X-20.
M30
```
""",
    fix="""
Move the corner to a block after the start-up (`Y40. ,R5.`), or write it as its own move.
""",
    not_reported="""
A lathe's chamfer and corner R without the comma (`C`, `R`, `I`, `K` of G01 in the older
format), corners on blocks in the middle of compensation, and compensation whose state a call
the analysis cannot follow may have changed.
""",
)


def corner_refused(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(CornerRefused):
        yield make(MB608, f.message, f.line, f.column, f.end_column)
