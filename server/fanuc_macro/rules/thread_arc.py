"""MB824: a roughing pass of a thread finished by a traced profile, cut past that profile.

An arc (round) thread, or any thread whose last job moves the tool around the groove (the
fitting method: ``G32`` passes, each at its own shift along the lead and its own depth), is
roughed first by passes of the same tool (``G92`` or ``G32`` layers). What the finishing passes
leave is the thread's profile: a roughing pass whose tool reaches past it has cut metal the
profile keeps, and no finishing pass can put it back. Both are taken out of the blank with the
round tool (:mod:`fanuc_macro.threads.cross_section`), the roughing passes one by one against
the profile the finishing passes alone cut.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

from ..diagnostics import Diagnostic, Related, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import Motion
from ..threads.cross_section import (
    NO_CHAIN,
    ToolShape,
    cut_cross_section,
    pass_place,
    penetration,
    thread_chains,
)
from ..threads.identify import Thread
from ..threads.module_shape import word
from ..translation import tr
from .context import RuleContext
from .threading import distance, mm, thread_related, width

FAMILY = "threading"

# fmt: off
MB824 = RuleInfo("MB824", "thread-roughing-past-profile", Severity.ERROR,
                 "A roughing pass cuts past the profile the finishing passes trace.", FAMILY)
# fmt: on

# A traced profile: passes at this many places along the lead or more, and as many depths.
TRACED = 3
# A round tool: its edge is the nose arc to the horizontal (the flanks of a V of no angle).
ROUND = 0.0
# What a roughing pass may reach past the profile (radius): the least input increment twice.
TOLERANCE = 0.002


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    threads = ctx.threads()
    chains = thread_chains(threads, ctx.index)
    for thread in threads:
        chain = chains.get(id(thread), NO_CHAIN)
        if chain.continued or not chain.before:
            continue  # the last job of several on one thread finishes it
        finding = _past_profile(ctx, thread, chain.before)
        if finding is not None:
            yield finding


def traced(passes: Sequence[Motion], lead: float) -> bool:
    """Whether passes trace a profile: several places along the lead, several depths."""
    places = {round(p % lead, 4) for m in passes if (p := pass_place(m, lead, None)) is not None}
    depths = {round(m.x, 4) for m in passes if m.x is not None}
    return len(places) >= TRACED and len(depths) >= TRACED


MB824_DOC = RuleDoc(
    "MB824",
    reports="""
A thread cut by two or more jobs of one tool radius in one program (its
roughing layers, then the passes that trace the profile: three places along the lead or more at
three depths or more, as the fitting method of an arc thread moves the tool around the groove)
when a roughing pass reaches past the profile the tracing passes leave: each pass is taken out
of the blank with a round tool of the nose radius the program names (a comment such as
`(TOOL RADIUS)` on its assignment, or the fitting formula's r), and the roughing pass's edge
compared with the profile the finishing passes alone cut. The message gives the pass, how far
past the profile it reaches (radius) and the tool radius.
""",
    why="""
The profile is the thread: the roughing pass that reaches past it has
removed metal the groove's arc keeps, and no later pass can put it back. The mating part then
has play on that flank, or the roll or the gauge shows the step.
""",
    example="""
```nc
O1130 (ROUND THREAD LEAD 8 R3)
#13=1.5 (TOOL RADIUS)
G97 S250 M03
G00 X66. Z17.
#1=0
WHILE [#1 LE 11] DO1
G92 X[59.4-0.4*#1] Z-64. F8.
#1=#1+1
END1
#2=10.
WHILE [#2 LE 170.] DO1
G00 Z[16.+1.5*COS[#2]]
X[61.-3.*SIN[#2]-2*#13]
G32 Z-64. F8.
G00 X66.
#2=#2+8.
END1
G00 X100. Z100.
M30
```
""",
    fix="""
Stop the roughing layers short of the profile where they are shifted along the
lead (here `#1 LE 8` at Z17, X56.2), or rough at the groove's centre only.
""",
    not_reported="""
Jobs cut with another tool between them (a `T` word: the roughing
tool's shape is not known), a tool radius the program does not name, threads finished by one
pass or by passes at one place along the lead (MB801 and MB817 judge those), a roughing pass
deeper than the finishing passes' root (the finishing passes fall short: their profile is what
is wrong), and a reach of up to 0.002 mm.
""",
)


def _past_profile(ctx: RuleContext, thread: Thread, before: Sequence[Motion]) -> Diagnostic | None:
    job = thread.job
    lead = job.lead
    radius = thread.nose_radius
    internal = thread.internal if thread.internal is not None else job.internal
    passes = [m for m in job.passes if m.x is not None]
    if lead is None or radius is None or radius <= 0.0 or internal is None or not passes:
        return None
    if not traced(passes, lead):
        return None
    roughing = [m for m in before if m.x is not None and m.uri == job.uri]
    if not roughing or _tool_changed(ctx, roughing[0].line, passes[0].line):
        return None
    tool = ToolShape(ROUND, radius)
    # The blank does not change the profile below it: the surface turned, else a blank a tool
    # diameter above the passes' outermost tip.
    xs = [m.x for m in [*roughing, *passes] if m.x is not None]
    blank = (
        thread.surface.blank
        if thread.surface is not None
        else (min(xs) - 4.0 * radius if internal else max(xs) + 4.0 * radius)
    )
    profile = cut_cross_section(passes, lead, internal, blank, tool)
    if profile is None:
        return None
    root_x = (max if internal else min)(m.x for m in passes if m.x is not None)
    worst: tuple[float, Motion] | None = None
    for m in roughing:
        assert m.x is not None
        if (m.x > root_x) if internal else (m.x < root_x):
            # Deeper than the finishing passes' root: the finish falls short of the roughing
            # (its profile is what is wrong), not the roughing past a profile.
            return None
        place = pass_place(m, lead, root_x)
        if place is None:
            continue
        reach = penetration(profile, place, m.x / 2.0)
        if reach > TOLERANCE and (worst is None or reach > worst[0]):
            worst = (reach, m)
    if worst is None:
        return None
    reach, m = worst
    finish = passes[0]
    assert m.x is not None
    roughing_pass = (
        tr("{code} at X{x} (start Z{z})", code=m.shown, x=mm(m.x), z=mm(m.start_z))
        if m.start_z is not None
        else tr("{code} at X{x}", code=m.shown, x=mm(m.x))
    )
    return make(
        MB824,
        tr(
            "the roughing {roughing_pass} reaches {reach} (radius) past the profile the {count} "
            "finishing passes from line {line} trace with the tool radius {radius:g}: it cuts "
            "metal the finished groove keeps",
            roughing_pass=roughing_pass,
            reach=distance(reach, m.inch),
            count=len(passes),
            line=finish.line + 1,
            radius=radius,
        ),
        m.line,
        0,
        width(ctx, m.line),
        related=[
            Related(finish.line, 0, 0, tr("the first finishing pass")),
            *thread_related(thread),
        ],
    )


def _tool_changed(ctx: RuleContext, start: int, end: int) -> bool:
    """Whether a block between two lines of the document gives a T word."""
    low, high = min(start, end), max(start, end)
    return any(word(ctx.doc, line, "T") is not None for line in range(low, high + 1))
