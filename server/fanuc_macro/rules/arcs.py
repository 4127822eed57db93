"""MB62x: arcs the control cannot cut, from where the run has the tool and the arc's words."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import ArcFault
from .context import RuleContext

FAMILY = "arcs"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB621 = RuleInfo("MB621", "arc-radius-short", Severity.ERROR,
                 "A G02/G03 whose R is shorter than half the distance to its end point.",
                 FAMILY)
MB622 = RuleInfo("MB622", "arc-end-off-circle", Severity.ERROR,
                 "A G02/G03 whose end point is not on the circle its I, J, K centre gives.",
                 FAMILY)
MB623 = RuleInfo("MB623", "arc-without-centre", Severity.ERROR,
                 "A G02/G03 to another point with neither R nor I, J, K.", FAMILY)
# fmt: on


MB621_DOC = RuleDoc(
    "MB621",
    reports="""
A circular move (`G02`, `G03`) given by its radius `R` whose end point is farther from its
start than the diameter, 2|R|, by more than 0.02 mm (0.001 inch), in the plane of the arc
(`G17` XY, `G18` ZX, `G19` YZ; a lathe's ZX with X a diameter), where the run knows the start,
the end and R. The message gives R and half the distance.
""",
    why="""
No arc of that radius passes through both points. The control stops at the block with alarm
PS0020 (0i-F alarm list, "OVER TOLERANCE OF RADIUS"; that an R arc raises it rather than
PS0020's I J K case is unverified), after the moves before it: a part half cut, the tool
standing in it. It comes from an R copied from another corner, a diameter written as R, or an
end point computed in the wrong unit or sign.
""",
    example="""
```nc
O4000
G90 G54 G00 X0. Y0.
S1000 M03
G01 Z-2. F150.
G01 X10.
G02 X30. Y0. R5.
M30
```
""",
    fix="""
Give the radius the corner has (here R10.), or the end point it meets; for half a circle or
more, the centre with I, J (or R negative beyond 180°).
""",
    not_reported="""
Arcs whose start, end or R the analysis cannot compute (a call it cannot follow moved the
tool, a coordinate system was set with values it does not know), an R of 0 (no move), arcs
given by I, J, K (MB622), differences within the tolerance (parameter 3410 sets the
control's; 0.02 mm is taken as usual, unverified), and moves after an alarm of the run.
""",
)


def arc_radius_short(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ArcFault):
        if f.fault == "radius":
            yield make(MB621, f.message, f.line, f.column, f.end_column)


MB622_DOC = RuleDoc(
    "MB622",
    reports="""
A circular move (`G02`, `G03`) given by its centre, `I`, `J`, `K` (the centre's distance from
the start point, a lathe's I a radius), whose end point's distance from that centre differs
from the start's by more than 0.02 mm (0.001 inch), where the run knows the start, the end and
the offsets. The message gives both distances and the centre.
""",
    why="""
The control checks that start and end lie on one circle and stops with alarm PS0020 "OVER
TOLERANCE OF RADIUS" past the tolerance of parameter 3410 (0i-MF, 0i-TF "Circular
interpolation"); a control set with a large tolerance cuts a spiral instead. The usual cause is
an I or J with the wrong sign, taken from the end point instead of the start, or given as an
absolute centre.
""",
    example="""
```nc
O4100
G90 G54 G00 X0. Y0.
S1000 M03
G01 Z-2. F150.
G01 X10.
G03 X20. Y10. I0. J-10.
M30
```
""",
    fix="""
Give the centre's distance from the start: here `I0. J10.` (the centre at X10 Y10, not
X10 Y-10), or the end point on the circle.
""",
    not_reported="""
Arcs whose start, end, I, J or K the analysis cannot compute, arcs given by R (MB621), a
full circle (end at the start), differences within the tolerance (0.02 mm or 0.001 inch taken
for parameter 3410, unverified), and the plane's third axis (a helix).
""",
)


def arc_end_off_circle(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ArcFault):
        if f.fault == "centre":
            yield make(MB622, f.message, f.line, f.column, f.end_column)


MB623_DOC = RuleDoc(
    "MB623",
    reports="""
A circular move (`G02`, `G03`, given in the block or in force from an earlier one) to an end
point other than its start in the plane of the arc, with neither `R` nor the centre's words of
that plane (`I J` in G17, `I K` in G18, `J K` in G19). The message names the words it needs.
""",
    why="""
Without a radius or a centre the arc is not defined: the control stops with alarm PS0022 "R
OR I,J,K COMMAND NOT FOUND" (0i-F alarm list). It comes most often from a block meant as a
straight move after an arc, the `G01` left out, so that G02 or G03 is still in force.
""",
    example="""
```nc
O4300
G90 G17 G54 G00 X0. Y0.
S1000 M03
G01 Z-2. F150.
G02 X10. Y10. R10.
X30.
M30
```
""",
    fix="""
Write the motion the block means (`G01 X30.`), or give the arc its R or its centre.
""",
    not_reported="""
A G02/G03 block that moves only out of the plane (a Z move in G17) or not at all, ends the
analysis cannot compute, and the centre's words of another plane (they are not the arc's).
""",
)


def arc_without_centre(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ArcFault):
        if f.fault == "no-centre":
            yield make(MB623, f.message, f.line, f.column, f.end_column)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    yield from arc_radius_short(ctx)
    yield from arc_end_off_circle(ctx)
    yield from arc_without_centre(ctx)
