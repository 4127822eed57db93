"""MB63x: radius compensation (cutter compensation on a mill, tool nose radius compensation on
a lathe) as the run starts, carries and cancels it."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import CompensationFault
from .context import RuleContext

FAMILY = "compensation"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB631 = RuleInfo("MB631", "compensation-on-arc", Severity.ERROR,
                 "Radius compensation started or cancelled on a G02/G03 move.", FAMILY)
MB632 = RuleInfo("MB632", "compensation-plane-change", Severity.ERROR,
                 "G17, G18 or G19 changes the plane while radius compensation is on.", FAMILY)
MB633 = RuleInfo("MB633", "compensation-left-on", Severity.WARNING,
                 "Radius compensation still on at the end of the program or at a reference "
                 "return.", FAMILY)
MB634 = RuleInfo("MB634", "skip-in-compensation", Severity.ERROR,
                 "A G31 skip move while radius compensation is on.", FAMILY)
# fmt: on


MB631_DOC = RuleDoc(
    "MB631",
    reports="""
The start-up of radius compensation, the first move in the plane after `G41` or `G42`, when it
is a `G02` or `G03`; and a `G40` in a `G02`/`G03` block that moves in the plane while
compensation was on. The message names the G41/G42 block.
""",
    why="""
The control builds the offset path from the start-up and cancel moves, which must be straight:
on an arc it stops with alarm PS0034 "NO CIRC ALLOWED IN ST-UP/EXT BLK" (0i-F alarm list;
0i-MF "Cutter compensation C": the move of the start-up is G00 or G01).
""",
    example="""
```nc
O5000
G90 G54 G00 X-20. Y0.
S1000 M03
G01 Z-2. F150.
G41 D1 G03 X0. Y20. R20.
G01 X30.
G40 G00 X50.
M30
```
""",
    fix="""
Start (and cancel) compensation on a straight lead-in (`G41 D1 G01 X-20. Y10.`) before the arc,
or after it.
""",
    not_reported="""
Compensation whose state a call the analysis cannot follow, or the caller of a subprogram
analysed alone, may have changed, moves out of the
plane (a Z move starts nothing), a G40 block with no move in the plane, and arcs after the
start-up.
""",
)


def compensation_on_arc(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(CompensationFault):
        if f.fault == "arc":
            yield make(MB631, f.message, f.line, f.column, f.end_column)


MB632_DOC = RuleDoc(
    "MB632",
    reports="""
On a mill, `G17`, `G18` or `G19` that selects another plane while `G41` or `G42` is in force.
The message names the G41/G42 block.
""",
    why="""
Compensation offsets the path in its plane; the control cannot carry it into another and stops
with alarm PS0037 "CAN NOT CHANGE PLANE IN G41/G42" (0i-F alarm list).
""",
    example="""
```nc
O5100
G17 G90 G54 G00 X-10. Y-10.
G41 D1 G01 X0. F200.
G18
G40 G00 X-10.
M30
```
""",
    fix="""
Cancel compensation (`G40` on a straight move) before changing the plane, and start it again in
the new one.
""",
    not_reported="""
Lathes (their compensation is in the ZX plane), a plane code that selects the plane already
in force, and compensation whose state a call the analysis cannot follow may have changed.
""",
)


def compensation_plane_change(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(CompensationFault):
        if f.fault == "plane":
            yield make(MB632, f.message, f.line, f.column, f.end_column)


MB633_DOC = RuleDoc(
    "MB633",
    reports="""
`G41` or `G42` still in force at `M02`/`M30`, or at a reference return (`G28`, `G30`), with no
`G40` since. Once until the next G40; the message names the G41/G42 block.
""",
    why="""
The retract and the moves to the reference point are offset by the radius, and a tool change
or the next program starts with the offset vector in place (whether reset clears it is
parameter 5003's, the builder's): the first moves of the next tool swing by its radius where
the program does not say. Leaving the profile without G40 is also the usual sign that the
lead-out was forgotten.
""",
    example="""
```nc
O5200
G90 G54 G00 X-10. Y-10.
S1000 M03
G41 D1 G01 X0. F200.
Y50.
G00 Z50.
G91 G28 Z0.
M30
```
""",
    fix="""
Cancel compensation on the lead-out move, `G40 G01 X-10.`, before the retract.
""",
    not_reported="""
Compensation whose state a call the analysis cannot follow, or the caller of a subprogram
analysed alone, may have changed, a G41/G42 after
the last reference return that the program ends without (the end is reported), and each later
return until a G40.
""",
)


def compensation_left_on(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(CompensationFault):
        if f.fault == "left-on":
            yield make(MB633, f.message, f.line, f.column, f.end_column)


MB634_DOC = RuleDoc(
    "MB634",
    reports="""
A skip move, `G31`, while `G41` or `G42` is in force (started or asked for, with no `G40`
since). The message names the compensation.
""",
    why="""
The skip stops the axes where a probe's signal comes on, which an offset path cannot follow:
the control refuses G31 in radius compensation with alarm PS0035 (0i-F alarm list, "CAN NOT
COMMANDED G31"; the condition is the 16i manual's, unverified for the 0i-F). It comes from a
probing macro called after a contour whose G40 was left out.
""",
    example="""
```nc
O5300
G90 G17 G54 G00 X-10. Y0.
S1000 M03
G41 D1 G01 X0. F200.
Y30.
G00 Z50.
G31 X40. F100.
G40 G00 X-10.
M30
```
""",
    fix="""
Cancel compensation (`G40` on a straight move) before the probing move.
""",
    not_reported="""
Compensation whose state a call the analysis cannot follow, or the caller of a subprogram
analysed alone, may have changed.
""",
)


def skip_in_compensation(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(CompensationFault):
        if f.fault == "skip":
            yield make(MB634, f.message, f.line, f.column, f.end_column)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    yield from compensation_on_arc(ctx)
    yield from compensation_plane_change(ctx)
    yield from compensation_left_on(ctx)
    yield from skip_in_compensation(ctx)
