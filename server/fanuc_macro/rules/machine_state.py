"""MB61x: what the machine is doing when a block cuts, as the run tracks it: the spindle."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import CutSpindleStopped
from .context import RuleContext

FAMILY = "machine-state"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB611 = RuleInfo("MB611", "feed-spindle-stopped", Severity.WARNING,
                 "A mill's feed move (G01-G03, a drilling cycle) while the spindle stands "
                 "still.", FAMILY)
# fmt: on


MB611_DOC = RuleDoc(
    "MB611",
    reports="""
On a mill, the first feed move (`G01`, `G02`, `G03`, a drilling or boring cycle) after the
spindle was stopped, by `M05` or by the tool change `M06`, with no `M03` or `M04` since. A
move in the air is left: one that stays at a positive Z (above the work's zero, where shops
set it on the top face), one with Z at the top of its travel after a reference return (`G28`,
`G30`) or `G53 Z0`, or one up to a positive Z in Z alone. Once until the spindle starts again;
the message names the block that stopped it.
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
`G84`: a rigid tap drives the spindle itself), rapid moves, moves in the air, and every feed
move after the first until the spindle starts.
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(CutSpindleStopped):
        yield make(MB611, f.message, f.line, f.column, f.end_column)
