"""MB65x: the profile a lathe's G70-G73 names by P and Q, as the run reads it."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import ProfileFault
from .context import RuleContext

FAMILY = "profiles"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB651 = RuleInfo("MB651", "profile-label-missing", Severity.ERROR,
                 "A G70-G73 whose P or Q names no block of the program (Q: none after P).",
                 FAMILY)
MB652 = RuleInfo("MB652", "profile-not-monotone", Severity.ERROR,
                 "A G71 or G72 profile that does not keep going one way.", FAMILY)
MB653 = RuleInfo("MB653", "profile-p-q-missing", Severity.ERROR,
                 "A G70-G73 that gives P without Q or Q without P (a G70 neither).", FAMILY)
MB654 = RuleInfo("MB654", "profile-first-move", Severity.ERROR,
                 "A G71-G73 profile whose first block moves by G02 or G03.", FAMILY)
MB655 = RuleInfo("MB655", "roughing-cycle-data", Severity.ERROR,
                 "A G71/G72 with a depth of cut of 0, or a G73 with fewer than one division.",
                 FAMILY)
MB656 = RuleInfo("MB656", "profile-past-start", Severity.WARNING,
                 "A G71/G72 profile that goes past the cycle's start point on the stock's side.",
                 FAMILY)
MB657 = RuleInfo("MB657", "profile-last-corner", Severity.ERROR,
                 "A G71-G73 profile whose last block ends in a chamfer or corner R.", FAMILY)
# fmt: on


MB651_DOC = RuleDoc(
    "MB651",
    reports="""
A lathe's `G70`, `G71`, `G72` or `G73` with `P` and `Q` where the program holds no block
`N` with P's number, or none with Q's number after it. The message names the number.
""",
    why="""
P and Q name the first and the last block of the finishing profile. Without them the control
stops at the cycle with alarm PS0063 "THE BLOCK OF A SPECIFIED SEQUENCE NUMBER IS NOT FOUND"
(0i-F alarm list): usually a G70 copied from another program, or a profile renumbered after the
cycle was written.
""",
    example="""
```nc
O7000
T0101
G00 X62. Z2.
G71 U2. R0.5
G71 P100 Q200 U0.4 W0.1 F0.25
N100 G00 X20.
G01 Z-30. F0.1
N200 X62.
G70 P100 Q210
M30
```
""",
    fix="""
Give P and Q the N numbers of the profile's first and last blocks (`G70 P100 Q200`).
""",
    not_reported="""
A P or Q the analysis cannot compute, cycles in a program run through a call it cannot
follow, mills (their G73 is a drilling cycle), and a `G71`/`G72` first block with no P (it
sets the depth of cut and the escape).
""",
)


def profile_label_missing(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ProfileFault):
        if f.fault == "label":
            yield make(MB651, f.message, f.line, f.column, f.end_column)


MB652_DOC = RuleDoc(
    "MB652",
    reports="""
A `G71` whose profile's end points go back in Z, or in type I (its first block moves in X
only) go back in X; a `G72` likewise with X and Z exchanged. The message names the axis and
where the profile turns back. Judged on the end points of the profile's first block and of its
cutting blocks (G01-G03), from the cycle's start point.
""",
    why="""
The roughing cycle cuts in layers along one axis and can only follow a profile that keeps
going one way (type II allows pockets in the other axis). Otherwise the control stops at the
cycle with alarm PS0064 or PS0329 "THE FINISHING SHAPE IS NOT A MONOTONOUS CHANGE" (0i-TF
"Stock removal in turning (G71)"; which number for which axis is unverified): a groove or an
undercut in the profile, or a diameter typed wrong.
""",
    example="""
```nc
O7100
T0101
G00 X62. Z2.
G71 U2. R0.5
G71 P100 Q200 U0.4 W0.1 F0.25
N100 G00 X20.
G01 Z-10. F0.1
X30. Z-15.
X26. Z-25.
N200 X62.
G70 P100 Q200
M30
```
""",
    fix="""
Rough the profile without the groove and cut the groove with its own tool, or write the
profile as type II (the first block `G00 X20. Z2.` names Z too) where it goes back in X.
""",
    not_reported="""
An arc that bulges past its end points (only the ends are judged), a rapid block after the
first (a retract at the profile's end, which a Haas lathe takes), profiles with a value the
analysis cannot compute, G73 (it follows any shape), G70, and profiles the analysis does not
follow (a call, a jump or an assignment in them).
""",
)


def profile_not_monotone(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ProfileFault):
        if f.fault == "monotone":
            yield make(MB652, f.message, f.line, f.column, f.end_column)


MB653_DOC = RuleDoc(
    "MB653",
    reports="""
A lathe's `G70`, `G71`, `G72` or `G73` block with `P` but no `Q`, or `Q` but no `P`; a `G70`
with neither. (The first block of G71-G73, which sets the depth of cut and the escape, has
neither.)
""",
    why="""
The cycle needs both ends of its profile: without one the control stops with alarm PS0061
"P OR Q COMMAND IS NOT IN THE MULTIPLE REPETITIVE CYCLES BLOCK" (0i-F alarm list).
""",
    example="""
```nc
O7200
T0101
G00 X62. Z2.
G71 U2. R0.5
G71 P100 Q200 U0.4 W0.1 F0.25
N100 G00 X20.
G01 Z-30. F0.1
N200 X62.
G70 P100
M30
```
""",
    fix="""
Give both: `G70 P100 Q200`.
""",
    not_reported="""
Mills (their G73 is a drilling cycle), the one-block G71/G72 of the Series 10/11 format when
it gives both, and a P or Q given by a variable the analysis cannot compute (still given).
""",
)


def profile_p_q_missing(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ProfileFault):
        if f.fault == "p-q":
            yield make(MB653, f.message, f.line, f.column, f.end_column)


MB654_DOC = RuleDoc(
    "MB654",
    reports="""
A `G71`, `G72` or `G73` whose profile's first block (N with P's number) commands `G02` or
`G03`, or commands no motion while G02 or G03 is in force.
""",
    why="""
The first block of the profile is the approach from the cycle's start point, which the control
takes at G00 or G01: with an arc there it stops with alarm PS0065 "G00/G01 IS NOT IN THE FIRST
BLOCK OF SHAPE PROGRAM" (0i-F alarm list). A profile that begins with a radius needs a straight
approach block before it.
""",
    example="""
```nc
O7300
T0101
G00 X62. Z2.
G71 U2. R0.5
G71 P100 Q200 U0.4 W0.1 F0.25
N100 G03 X20. Z-10. R10.
G01 Z-30. F0.1
N200 X62.
M30
```
""",
    fix="""
Begin the profile with its approach, `N100 G00 X0.`, and cut the radius in the next block.
""",
    not_reported="""
A first block with no motion code while G00 or G01 is in force (taken as that motion; whether
the control wants it written is unverified), G70 (it runs the profile, checked at the roughing
cycle), and profiles the analysis does not follow.
""",
)


def profile_first_move(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ProfileFault):
        if f.fault == "first":
            yield make(MB654, f.message, f.line, f.column, f.end_column)


MB655_DOC = RuleDoc(
    "MB655",
    reports="""
The first block of a lathe's `G71` (`U`, the depth of cut) or `G72` (`W`) that gives 0, the
one-block form's `D` of 0, and the first block of `G73` whose number of divisions `R` is below
1. The message gives the value.
""",
    why="""
A roughing cycle with no depth of cut makes no pass, and a pattern with no division none
either: the control stops with alarm PS0062 "THE CUTTING AMOUNT IS ILLEGAL IN THE ROUGH CUTTING
CYCLE" or PS0321 "ILLEGAL REPEATED TIME IS IN THE PATTERN REPEATING CYCLE" (0i-F alarm list).
A depth computed from a variable that is vacant or 0 gives the first.
""",
    example="""
```nc
O7400
T0101
G00 X62. Z2.
G71 U0 R0.5
G71 P100 Q200 U0.4 W0.1 F0.25
N100 G00 X20.
G01 Z-30. F0.1
N200 X62.
M30
```
""",
    fix="""
Give the depth of each pass (`G71 U2. R0.5`), or the number of passes of G73 (`R3`).
""",
    not_reported="""
A negative depth (whether the control takes its size or stops is unverified), a depth left to
parameter 5132 (no U in the block), values the analysis cannot compute, and mills.
""",
)


def roughing_cycle_data(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ProfileFault):
        if f.fault in ("depth", "divisions"):
            yield make(MB655, f.message, f.line, f.column, f.end_column)


MB656_DOC = RuleDoc(
    "MB656",
    reports="""
A `G71` whose profile goes past the cycle's start point in X on the side of the stock (above
it for an outside profile, below it for a bore), or a `G72` likewise in Z, by more than the
cycle's depth of cut Δd (its first block's U or W, when constant). Judged on the end points of
the profile's first block and its cutting blocks; the message gives the farthest one, by how
much, and the start point.
""",
    why="""
The roughing passes run from the start point towards the profile: what lies beyond it is not
roughed, and the finishing pass (G70) takes it in one cut, deeper than any roughing pass. It
comes from a start point set to the finished diameter rather than the blank's, or a profile
copied from a larger part. With the finishing-shape check on (parameter 5104#2 FCK) the
control refuses the cycle with alarm PS0322 "FINISHING SHAPE WHICH OVER OF STARTING POINT"
(0i-F alarm list); production programs run with the check off (unverified against a manual
which is the default).
""",
    example="""
```nc
O7500
T0101
G00 X40. Z2.
G71 U2. R0.5
G71 P100 Q200 U0.4 W0.1 F0.25
N100 G00 X20.
G01 Z-20. F0.1
X50. Z-30.
N200 Z-40.
M30
```
""",
    fix="""
Start the cycle outside the blank (`G00 X62. Z2.` for a 60 mm bar), or correct the profile.
""",
    not_reported="""
G73 (its pattern starts from the escape), rapid blocks after the first, the profile's last
block when it moves in the depth axis alone (the move that leaves the profile, usually past
the start point), a profile past the start point by no more than the depth of cut, a profile
whose first block ends at the start point's X (no side to judge), values the analysis cannot
compute.
""",
)


def profile_past_start(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ProfileFault):
        if f.fault == "start":
            yield make(MB656, f.message, f.line, f.column, f.end_column)


MB657_DOC = RuleDoc(
    "MB657",
    reports="""
A `G71`, `G72` or `G73` whose profile's last block (N with Q's number) carries a chamfer or a
corner R (`,C`, `,R`).
""",
    why="""
A chamfer or a corner joins a block to the next: the profile's last block has none in the
profile, and the control stops with alarm PS0069 "LAST BLOCK OF SHAPE PROGRAM IS AN ILLEGAL
COMMAND" (0i-F alarm list).
""",
    example="""
```nc
O7600
T0101
G00 X62. Z2.
G71 U2. R0.5
G71 P100 Q200 U0.4 W0.1 F0.25
N100 G00 X20.
G01 Z-30. F0.1
N200 X62. ,C1.
M30
```
""",
    fix="""
Move the corner into the profile (on the block before), or end the profile with a plain move.
""",
    not_reported="""
G70 (it runs the profile; the roughing cycle before it is reported), the older lathe format
without the comma, and profiles the analysis does not follow.
""",
)


def profile_last_corner(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ProfileFault):
        if f.fault == "last":
            yield make(MB657, f.message, f.line, f.column, f.end_column)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    yield from profile_past_start(ctx)
    yield from profile_last_corner(ctx)
    yield from roughing_cycle_data(ctx)
    yield from profile_label_missing(ctx)
    yield from profile_not_monotone(ctx)
    yield from profile_p_q_missing(ctx)
    yield from profile_first_move(ctx)
