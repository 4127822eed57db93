"""MB813: a lathe cycle whose start point is on the wrong side of its cut.

``G90`` (turning), ``G92`` (threading) and ``G76`` return to their start point after every
pass: X first, then Z. An outside cut must start outside the material, an inside one inside
the bore; else the retract runs into the part (a thread is torn by its own retract) and the
return in Z drags the tool across it. ``G94`` (facing) returns in Z first: it must start on
the face's free side. Which side the cut is on is known from the passes (outside cuts go
towards the axis pass after pass, facing cuts towards -Z), from the identified thread, or
from its designation.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

from ..diagnostics import Diagnostic, Related, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import Motion, ThreadCycleFault
from ..threads.identify import Thread
from ..threads.jobs import motion_positions
from ..threads.module_shape import D1_FACTOR
from ..translation import tr
from .context import RuleContext
from .threading import EPS, mm, thread_related, width

FAMILY = "cycles"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB813 = RuleInfo("MB813", "cycle-start-side", Severity.ERROR,
                 "A lathe cycle (G90, G92, G76, G94) starts on the wrong side of its cut.", FAMILY)
MB815 = RuleInfo("MB815", "g76-tool-angle", Severity.ERROR,
                 "G76's first block gives a tool angle the cycle does not take.", FAMILY)
MB816 = RuleInfo("MB816", "g76-depths", Severity.ERROR,
                 "A G76 whose thread height or first depth is not above 0, or whose least depth "
                 "is more than the thread height.", FAMILY)
# fmt: on


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    for thread in ctx.threads():
        if thread.job.is_cycle:
            yield from _thread_start(ctx, thread)
    if ctx.facts is not None:
        for series in _series(ctx.facts.motions, ctx.doc.uri):
            yield from _series_start(ctx, series)
    yield from g76_tool_angle(ctx)
    yield from g76_depths(ctx)


MB815_DOC = RuleDoc(
    "MB815",
    reports="""
The first block of a lathe's two-block `G76`, `G76 P(m)(r)(a) Q R`, whose last two digits of P,
the tool's angle a, are not one of 80, 60, 55, 30, 29 and 0. The message gives the angle.
""",
    why="""
The cycle feeds in along the flank of the tool's angle, and takes only the angles of the usual
thread forms (0i-TF "Multiple threading cycle (G76)"): with another the control stops with
alarm PS0315 "ILLEGAL NOSE ANGLE COMMAND IS IN THE THREAD CUTTING CYCLE" (0i-F alarm list). A
P with its digits out of place (`P10060` for `P010060`, or a chamfer and an angle swapped)
gives one.
""",
    example="""
```nc
O8100
T0303
G97 S800 M03
G00 X26. Z5.
G76 P010065 Q100 R0.05
G76 X21.4 Z-30. P1300 Q400 F2.
M30
```
""",
    fix="""
Give the angle of the insert in the last two digits: `P010060` for a 60° metric thread.
""",
    not_reported="""
A P the analysis cannot compute, the one-block G76 of the Series 10/11 format (its angle is
A), and the angle of the tool itself (the program cannot say which insert is mounted).
""",
)


def g76_tool_angle(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ThreadCycleFault):
        if f.fault == "angle":
            yield make(MB815, f.message, f.line, f.column, f.end_column)


MB813_DOC = RuleDoc(
    "MB813",
    reports="""
A lathe cycle whose start point, to which it returns after every pass, is
on the wrong side of its cut: a `G92` or `G76` of an external thread that starts below the
thread's crest (about d − 0.15P) or below its first pass, of an internal one that starts above
the bore (about D1 + 0.15P) or above its first pass; a series of `G90` passes that starts on
the material's side of its first pass, a series of `G94` facing passes that starts on the
face side of its first one. The side is the one the passes go (deeper towards the axis is an
outside cut). It stands at the block that put the tool there.
""",
    why="""
The cycle retracts to the start point: into the thread just
cut, or into the stock, and its return in Z drags the tool across the part. The insert breaks
and the thread is torn.
""",
    example="""
```nc
O1108 (M24X3)
G97 S450 M03
G00 X22. Z5.
G92 X23.5 Z-35. F3.
X23.1
X22.7
G00 X100. Z100.
M30
```
""",
    fix="""
Start the cycle outside the crest (`X26.` here), or inside the bore for an
internal thread.
""",
    not_reported="""
A single `G90` or `G94` pass (one pass does not tell the side), a
thread whose side is not known, and the Z of a threading cycle's start point (the run-in is
the programmer's choice). A mill's program (controller `0i-MF`, or `0i-F` when its codes show a
mill: `M06`, `G43 H`, `G91`, `Y` moves), where `G90` is absolute programming, `G92` the
coordinate system and `G94` the feed per minute; nor a program whose codes show neither machine
(`0i-F`): a mill's reading does not give it.
""",
)


def _report(ctx: RuleContext, m: Motion, message: str, related: list[Related]) -> Diagnostic:
    """At the block that put the tool at the start point (the line to fix), else the cycle."""
    line = m.line
    if m.start_line is not None and m.start_uri == ctx.doc.uri:
        related = [
            Related(m.line, 0, 0, tr("the {code} that starts there", code=m.shown)),
            *related,
        ]
        line = m.start_line
    return make(MB813, message, line, 0, width(ctx, line), related=related)


def _thread_start(ctx: RuleContext, thread: Thread) -> Iterator[Diagnostic]:
    internal = thread.internal
    if internal is None:
        return
    crest: float | None = None
    if thread.major is not None and thread.pitch is not None and thread.unsupported is None:
        # The blank: turned to about d - 0.125P outside, bored to D1 inside (Deng Ronggang's paper).
        crest = (
            thread.major - D1_FACTOR * thread.pitch + 0.15 * thread.pitch
            if internal
            else thread.major - 0.15 * thread.pitch
        )
    job = thread.job
    found = job.remember(
        ("start side", internal, crest),
        lambda: _wrong_start(job.passes, internal, crest),
        ("x", "start_x"),
    )
    if found is None:
        return
    m, shallowest = found
    start = m.start_x
    assert start is not None
    if crest is None:
        where = tr("its shallowest pass X{x}", x=mm(shallowest, m.inch))
    elif internal:
        where = tr("the bore of {thread}, about X{x}", thread=thread.name, x=mm(crest, m.inch))
    else:
        where = tr("the crest of {thread}, about X{x}", thread=thread.name, x=mm(crest, m.inch))
    said = {
        "code": m.shown,
        "start": mm(start, m.inch),
        "reason": thread.job.side_reason or tr("its designation"),
        "where": where,
    }
    message = (
        tr(
            "{code} starts at X{start}, but the thread is cut from the inside ({reason}): the "
            "start point must lie beyond {where}; from X{start} the cycle retracts into the "
            "thread after each pass and the return in Z crosses it",
            **said,
        )
        if internal
        else tr(
            "{code} starts at X{start}, but the thread is cut from the outside ({reason}): the "
            "start point must lie beyond {where}; from X{start} the cycle retracts into the "
            "thread after each pass and the return in Z crosses it",
            **said,
        )
    )
    yield _report(ctx, m, message, thread_related(thread))


def _wrong_start(
    all_passes: list[Motion], internal: bool, crest: float | None
) -> tuple[Motion, float] | None:
    """The first pass that starts on the material's side, with the shallowest pass's X."""
    passes = [m for m in all_passes if m.x is not None and m.start_x is not None]
    if not passes:
        return None
    xs = [m.x for m in passes if m.x is not None]
    shallowest = min(xs) if internal else max(xs)
    for m in passes:
        start = m.start_x
        assert start is not None and m.x is not None
        if internal:
            bad = start > shallowest + EPS or (crest is not None and start > crest + EPS)
        else:
            bad = start < shallowest - EPS or (crest is not None and start < crest - EPS)
        if bad:
            return m, shallowest
    return None


@dataclass(eq=False, repr=False)
class _Series:
    code: str
    passes: list[Motion] = field(default_factory=list)


def _series(motions: list[Motion], uri: str) -> Iterator[_Series]:
    """Runs of consecutive G90 / G94 passes of one program execution: another motion of the
    execution ends one."""
    current: _Series | None = None
    run = -1
    last = -1
    for i in motion_positions(motions, uri):
        m = motions[i]
        if current is not None and any(o.run == run for o in motions[last + 1 : i]):
            yield current
            current = None
        if current is None or current.code != m.code or m.run != run:
            if current is not None:
                yield current
            current, run = _Series(m.code), m.run
        current.passes.append(m)
        last = i
    if current is not None:
        yield current


def _series_start(ctx: RuleContext, series: _Series) -> Iterator[Diagnostic]:
    axis = "Z" if series.code == "G94" else "X"
    cuts = [m for m in series.passes if _cut(m, axis) is not None and _start(m, axis) is not None]
    values = [_cut(m, axis) for m in cuts]
    if len(set(values)) < 2:
        return  # one pass does not tell the side
    first, last = values[0], values[-1]
    assert first is not None and last is not None
    towards_minus = last < first
    for m, value in zip(cuts, values, strict=True):
        start = _start(m, axis)
        assert start is not None and value is not None
        wrong = start < first - EPS if towards_minus else start > first + EPS
        if wrong:
            said = {
                "code": m.shown,
                "axis": axis,
                "start": mm(start, m.inch),
                "first": mm(first, m.inch),
                "sign": "-" if towards_minus else "+",
            }
            message = (
                tr(
                    "{code} starts at {axis}{start}, on the material's side of its first pass "
                    "{axis}{first}: the facing passes go towards {axis}{sign}, so the start "
                    "point must lie beyond the first pass; from there the cycle returns through "
                    "the part",
                    **said,
                )
                if series.code == "G94"
                else tr(
                    "{code} starts at {axis}{start}, on the material's side of its first pass "
                    "{axis}{first}: the turning passes go towards {axis}{sign}, so the start "
                    "point must lie beyond the first pass; from there the cycle returns through "
                    "the part",
                    **said,
                )
            )
            yield _report(ctx, m, message, [])
            return


def _cut(m: Motion, axis: str) -> float | None:
    return m.x if axis == "X" else m.z


def _start(m: Motion, axis: str) -> float | None:
    return m.start_x if axis == "X" else m.start_z


MB816_DOC = RuleDoc(
    "MB816",
    reports="""
A lathe's two-block `G76` whose cutting block gives a thread height `P(k)` or a first depth
`Q(Δd)` of 0 or less, or whose first block's least depth of cut `Q(Δdmin)` is more than the
thread height. The message gives the values, in the program's unit.
""",
    why="""
The cycle divides the thread height into passes from the first depth: with no height or no
first depth there is nothing to divide, and a least depth past the height leaves no pass. The
control stops with alarm PS0317 "ILLEGAL THREAD COMMAND IS IN THE THREAD CUTTING CYCLE" or
PS0316 "ILLEGAL CUTTING AMOUNT IS IN THE THREAD CUTTING CYCLE" (0i-F alarm list). A height or a
depth given with a decimal point, in millimetres where the cycle takes least increments, gives
the last (`Q0.1` for `Q100`).
""",
    example="""
```nc
O8200
T0303
G97 S800 M03
G00 X26. Z5.
G76 P010060 Q1500 R0.05
G76 X21.546 Z-30. P1227 Q400 F2.
M30
```
""",
    fix="""
Give k and Δd in least increments without a decimal point (`P1227 Q400` for 1.227 and
0.4 mm), and a least depth below the height (`Q100`).
""",
    not_reported="""
Values the analysis cannot compute, the one-block G76 of the Series 10/11 format, and a G76
whose first block the run did not meet (its least depth is parameter 5140's).
""",
)


def g76_depths(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ThreadCycleFault):
        if f.fault == "depths":
            yield make(MB816, f.message, f.line, f.column, f.end_column)
