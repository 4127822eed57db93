"""MB64x: canned drilling and tapping cycles as the run carries them from block to block."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import DrillingFault
from .context import RuleContext

FAMILY = "drilling"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB641 = RuleInfo("MB641", "peck-without-q", Severity.ERROR,
                 "A G73 or G83 peck drilling cycle drills with no Q, or Q0.", FAMILY)
MB642 = RuleInfo("MB642", "return-in-drilling-cycle", Severity.ERROR,
                 "G27, G28 or G30 while a drilling cycle is in force, before G80.", FAMILY)
MB643 = RuleInfo("MB643", "move-before-rigid-tap", Severity.ERROR,
                 "An axis moves between M29 and its rigid tapping cycle.", FAMILY)
# fmt: on


MB641_DOC = RuleDoc(
    "MB641",
    reports="""
On a mill, a hole of the peck drilling cycles `G73` (high speed) or `G83` (deep hole), a block
that drills with the cycle in force, when no `Q` has been given since the cycle began (Q stays
in force with the cycle's other data until G80) or Q is 0. The message names the cycle.
""",
    why="""
Q is the depth of each peck. Without it the control stops at the hole with alarm PS0045
"ADDRESS Q NOT FOUND (G73/G83)" (0i-F alarm list), after the tool has moved over it; a shop
that meant a plain drilling cycle wrote G83 for G81, or lost the Q from a copied block.
""",
    example="""
```nc
O6000
G90 G17 G54 G00 X0. Y0. Z50.
S1200 M03
G99 G83 Z-25. R2. F100.
X20.
G80
M30
```
""",
    fix="""
Give the depth of each peck, `G83 Z-25. R2. Q3. F100.`, or drill in one go with `G81`.
""",
    not_reported="""
Lathes (their G83 is a face drilling cycle with other data), a Q the analysis cannot compute,
a block with I or J (a Haas control's pecks by I, J and K, with no Q; K alone is FANUC's
repeat count), and cycles the run enters through a call it cannot follow.
""",
)


def peck_without_q(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(DrillingFault):
        if f.fault == "peck":
            yield make(MB641, f.message, f.line, f.column, f.end_column)


MB642_DOC = RuleDoc(
    "MB642",
    reports="""
On a mill, a reference position return or check (`G27`, `G28`, `G30`) while a canned drilling
cycle (`G73`, `G74`, `G76`, `G81`-`G89`) is in force: no `G80` and no code of group 01 (`G00`
to `G03`) since the cycle. The message names the cycle.
""",
    why="""
The control does not return to the reference position in canned cycle mode: it stops with
alarm PS0044 "G27-G30 NOT ALLOWED IN FIXED CYC" (0i-F alarm list) at the retract before the
tool change, the tool still over the last hole.
""",
    example="""
```nc
O6100
G90 G17 G54 G00 X0. Y0. Z50.
S1200 M03
G99 G81 Z-10. R2. F100.
X20.
G91 G28 Z0.
M30
```
""",
    fix="""
Cancel the cycle first: `G80` on its own block, or `G80 G91 G28 Z0.`.
""",
    not_reported="""
Lathes, `G53` (a move in machine coordinates), and cycles the run enters through a call it
cannot follow.
""",
)


def return_in_drilling_cycle(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(DrillingFault):
        if f.fault == "return":
            yield make(MB642, f.message, f.line, f.column, f.end_column)


MB643_DOC = RuleDoc(
    "MB643",
    reports="""
A block that moves an axis after `M29` (rigid tapping) and before the tapping cycle it
prepares (`G84`, on a mill also `G74`; on a lathe `G84`, `G88`). The message names the M29
block.
""",
    why="""
M29 couples the spindle to the feed axis for the tapping cycle that follows; a move in between
is refused with alarm PS0204 "ILLEGAL AXIS OPERATION" (0i-F alarm list; 0i-MF "Rigid
tapping"). A positioning move slipped between `M29 S...` and `G84`, as with a floating tap
holder, gives it.
""",
    example="""
```nc
O6200
G90 G17 G54 G00 X0. Y0. Z50.
M29 S500
G00 X10. Y10.
G99 G84 Z-15. R5. F625.
G80
M30
```
""",
    fix="""
Position before M29, or give the hole's X Y in the tapping cycle's block:
`M29 S500` then `G99 G84 X10. Y10. Z-15. R5. F625.`.
""",
    not_reported="""
A rigid tapping M code other than M29 (parameter 5210 sets it), moves after a call the
analysis cannot follow, and M29 blocks with no tapping cycle after them in the run.
""",
)


def move_before_rigid_tap(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(DrillingFault):
        if f.fault == "rigid":
            yield make(MB643, f.message, f.line, f.column, f.end_column)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    yield from peck_without_q(ctx)
    yield from return_in_drilling_cycle(ctx)
    yield from move_before_rigid_tap(ctx)
