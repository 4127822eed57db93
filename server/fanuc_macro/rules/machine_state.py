"""MB61x: what the machine is doing when a block cuts, as the run tracks it: the spindle, its
speed clamp, the tool in it and its length offset, the skip signal."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import (
    CutSpindleStopped,
    LengthOffsetOtherTool,
    SkipReadBeforeG31,
    SpeedNotClamped,
    ToolWithoutLengthOffset,
)
from .context import RuleContext

FAMILY = "machine-state"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB611 = RuleInfo("MB611", "feed-spindle-stopped", Severity.WARNING,
                 "A mill's feed move (G01-G03, a drilling cycle) while the spindle stands "
                 "still.", FAMILY)
MB612 = RuleInfo("MB612", "speed-not-clamped", Severity.WARNING,
                 "A lathe's cut in G96 towards the centre with no G50 S clamping the spindle "
                 "speed.", FAMILY)
MB613 = RuleInfo("MB613", "length-offset-other-tool", Severity.WARNING,
                 "G43 H names another tool's length offset than the tool just loaded.", FAMILY)
MB614 = RuleInfo("MB614", "tool-without-length-offset", Severity.WARNING,
                 "A tool cuts with no tool length offset called since it was loaded.", FAMILY)
MB615 = RuleInfo("MB615", "skip-before-g31", Severity.WARNING,
                 "The skip position (#5061 and on) read before any G31 of the run.", FAMILY)
# fmt: on


MB611_DOC = RuleDoc(
    "MB611",
    reports="""
On a mill, the first feed move (`G01`, `G02`, `G03`, a drilling or boring cycle) after the
spindle was stopped, by `M05` or by the tool change `M06`, with no `M03` or `M04` since. A
move in the air is left: one that stays at a positive Z (above the work's zero, where shops
set it on the top face), one with Z at the top of its travel after a reference return (`G28`,
`G30`) or `G53 Z0`, or one up to a positive Z in Z alone. Once until the spindle starts again;
the message names the block that stopped it. It is told once the tool is known to be a cutter:
when the spindle starts later, at the next tool change or at the end of the program.
""",
    why="""
The control feeds the axes whether the spindle turns or not: the tool is pushed into the
work standing still, and the insert or the drill breaks. After a tool change the spindle is
stopped (it was oriented for the changer), so a tool change with no `S... M03` after it cuts
with a still tool.
""",
    example="""
```nc
O1000 (FACE AND DRILL)
T1 M06
G43 H1 Z50.
G00 X0 Y0
G01 Z-1. F200.
M30
```
""",
    fix="""
Start the spindle before the cut: `S1200 M03` after the tool change, or after the `M05`.
""",
    not_reported="""
A feed move before any spindle code of the run (the program may be started with the spindle
turning, or be an excerpt), lathes (a bar puller, a part catcher or a tailstock feeds with the
spindle still), `M19` orientation (a probe's moves follow it, with the spindle still), the
state after a call the analysis cannot follow or an M code it does not know (`M00`, `M01`, a
live tool's or a sub spindle's code may start or stop a spindle), tapping cycles (`G74`,
`G84`: a rigid tap drives the spindle itself), rapid moves, moves in the air, every feed
move after the first until the spindle starts, and a tool that makes a skip move (`G31`) or
orients the spindle (`M19`) before the spindle starts or the next tool change: a touch probe,
which feeds standing still.
""",
)


def feed_with_spindle_stopped(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(CutSpindleStopped):
        yield make(MB611, f.message, f.line, f.column, f.end_column)


MB612_DOC = RuleDoc(
    "MB612",
    reports="""
On a lathe, a feed move (`G01`-`G03`, the turning and facing cycles `G90`, `G94`, the roughing
cycles `G71`-`G73` from their start point) in constant
surface speed (`G96`) to a diameter where the surface speed asks for more than the machine's
maximum spindle speed (the setting `fanuc-macro.machine.maxSpindleSpeed`; unset, only a move to
the centre, X0 or past it, where it asks for any speed), when no `G50 S` (system B and C:
`G92 S`) has clamped the spindle speed earlier in the run. Once per run, with the surface speed,
the diameter and the speed asked for.
""",
    why="""
In G96 the control turns the spindle faster as the tool nears the centre: n = 1000 V / (π D).
Without a clamp it runs up to the spindle's top speed as the tool faces to X0 or parts off,
with the chuck's grip weakened by the speed and the part, the bar or the jaws out of balance.
`G50 S` sets the highest speed G96 may reach (0i-TF "Constant surface speed control", "Maximum
spindle speed clamp").
""",
    example="""
```nc
O2000 (FACE)
T0101
G96 S180 M03
G00 X52. Z0.
G01 X0. F0.15
M30
```
""",
    fix="""
Clamp the speed before the cut, `G50 S2500` (the speed the chuck and the part allow), or face
the last millimetres in G97.
""",
    not_reported="""
Mills, G97 (a speed in rpm), moves in G96 that stay at diameters the machine reaches, a run
that called a program the analysis cannot follow (the clamp may be set there), a subprogram
analysed alone (its caller may have set it), a run that set a
clamp with a value it cannot compute, threading cycles (they run at the speed in force, in G97
as a rule), and every move after the first until a clamp.
""",
)


def speed_not_clamped(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(SpeedNotClamped):
        yield make(MB612, f.message, f.line, f.column, f.end_column)


MB613_DOC = RuleDoc(
    "MB613",
    reports="""
On a mill, `G43 H` (or `G44 H`) after a tool change (`M06`) whose H is not the number of the
tool the change loaded (the last `T` before or with the `M06`), where the program numbers its
offsets by the tools: an earlier tool of the run took the offset of its own number (`T1 M06 ...
G43 H1`), or later the same tool's radius offset `D` is its number, or the next tool's H is its
T. The message names the tool, the offset, the tool change and that evidence.
""",
    why="""
The length offset says where the tool's tip is. With another tool's length the control
places the tip by the wrong length: a tool longer than the offset says plunges into the part
or the vice at the first rapid to Z, a shorter one cuts air. Shops number the offsets after
the tools, so a different H is a typing slip, most often a copy of the previous tool's block.
""",
    example="""
```nc
O3000
T1 M06
G43 H1 Z50.
T2 M06
G43 H1 Z50.
M30
```
""",
    fix="""
Call the offset of the tool in the spindle: `G43 H2` after `T2 M06`.
""",
    not_reported="""
Lathes, programs whose tools take offsets by another numbering (`T1 ... H21`, no H or D equal to
its tool), a tool whose H differs and that nothing later shows the numbering of, an H ten or
more from the tool's number when only its D shows the numbering (a second bank of a shared
offset table: `T1 ... H21 ... D1`), H0 (no offset), an H or a T the analysis cannot compute,
a tool change through a call the analysis cannot follow.
""",
)


def length_offset_other_tool(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(LengthOffsetOtherTool):
        yield make(MB613, f.message, f.line, f.column, f.end_column)


MB614_DOC = RuleDoc(
    "MB614",
    reports="""
On a mill, the first feed move (`G01`-`G03`, a drilling or boring cycle) that is not in the
air after a tool change (`M06`) with no `G43`/`G44` since, in a run where an earlier tool had
its length offset called. The message names the tool change.
""",
    why="""
Without the length offset the control takes the tool's tip at the spindle's gauge line: every
Z of the program is off by the tool's length, and the first move down goes that far too deep or
too high. A program that calls the offset for its other tools has forgotten this one.
""",
    example="""
```nc
O3100
T1 M06
G43 H1 Z50.
S1000 M03
G01 Z-1. F100.
T2 M06
S1200 M03
G00 X0. Y0.
G01 Z-2. F100.
M30
```
""",
    fix="""
Call the tool's offset after the change, with its first move to Z: `G43 H2 Z50.`.
""",
    not_reported="""
Lathes, programs that call no length offset at all (the machine may take tool lengths
another way, or the builder's tool change macro calls it), rapid moves and moves in the air,
a tool change through a call the analysis cannot follow, and every cut after the first until
the next tool change.
""",
)


def tool_without_length_offset(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ToolWithoutLengthOffset):
        yield make(MB614, f.message, f.line, f.column, f.end_column)


MB615_DOC = RuleDoc(
    "MB615",
    reports="""
A read of the skip position, `#5061`-`#5080` (where the skip signal came on in the last G31,
per axis), before any `G31` has run in the run. The message names the variable.
""",
    why="""
The skip position keeps the result of the last G31 the machine ran, whichever program ran it:
read before this program's own probing move, it is an earlier measurement, and a work offset
or a tool length computed from it is wrong by whatever has changed since.
""",
    example="""
```nc
O1010 (PROBE Z)
G90 G00 X0. Y0. Z20.
#100 = #5063
G91 G31 Z-30. F100.
G90 G00 Z20.
M30
```
""",
    fix="""
Read the skip position after the `G31` that measures.
""",
    not_reported="""
Reads after a call the analysis cannot follow (a vendor's probing cycle runs its own G31),
reads in a subprogram or macro analysed alone (its caller may have run the G31), reads after
any G31 of the run (whether that G31 is the one meant is not known), and the
same line again.
""",
)


def skip_before_g31(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(SkipReadBeforeG31):
        yield make(MB615, f.message, f.line, f.column, f.end_column)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    yield from feed_with_spindle_stopped(ctx)
    yield from speed_not_clamped(ctx)
    yield from length_offset_other_tool(ctx)
    yield from tool_without_length_offset(ctx)
    yield from skip_before_g31(ctx)
