"""MB821: a taper thread cut against the cone the program turned for it.

A taper thread (``G92 … R``, ``G76 … R``, or ``G32`` whose X changes along the cut) is cut on
a cone the program itself has turned: the thread's diameter must grow the way the cone's does.
The rule compares the two slopes over the Z both cover; it needs no designation and no idea of
which end of the part is free.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

from ..diagnostics import Diagnostic, Related, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import Motion
from ..evaluator.values import fmt
from ..threads.identify import Thread
from ..threads.pipe import PipeThread
from ..threads.surface import Line, cone_line, motion_key, thread_line
from ..threads.surface import tapered as cuts_a_cone
from ..translation import Text, tr
from .context import RuleContext
from .thread_cut import depth_line
from .threading import mm, thread_related, width

FAMILY = "threading"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB821 = RuleInfo("MB821", "thread-taper-cone", Severity.ERROR,
                 "A taper thread's taper runs the other way than, or differs from, the cone "
                 "turned for it.", FAMILY)
MB823 = RuleInfo("MB823", "thread-taper-designation", Severity.ERROR,
                 "A taper pipe thread (ISO 7-1, NPT) cut parallel, with another taper than "
                 "1:16, or with its diameter growing towards the pipe's end.", FAMILY)
# fmt: on

# How much of the thread's length the cone must cover, and how near the deepest pass its
# diameter must be, in pitches (a thread's whole height is about 0.65 of the pitch, radius: 1.3
# pitches on the diameter): a move further off is a move in the air, not the surface the
# thread is cut in.
COVER = 0.5
NEAR_PITCHES = 2.0
# The slopes of the cone turned for a thread and of the thread: within a factor of this of
# each other (farther apart, the cone is another surface); the same taper within this.
SLOPE_RATIO = 3.0
SAME_TAPER = 1.5


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    facts = ctx.facts
    if facts is None:
        return
    motions = facts.motions
    for thread in ctx.threads():
        finding = _against_cone(ctx, thread, motions)
        if finding is None and thread.pipe is not None:
            finding = _against_designation(ctx, thread, thread.pipe)
        if finding is not None:
            yield finding


def _thread_line(m: Motion) -> Line | None:
    """A taper pass's cut, or None for a parallel one."""
    line = thread_line(m)
    return line if line is not None and line.x0 != line.x1 else None


def _cone_line(m: Motion) -> Line | None:
    """A turned cone, or None for a cylinder or another move."""
    line = cone_line(m)
    return line if line is not None and line.x0 != line.x1 else None


MB821_DOC = RuleDoc(
    "MB821",
    reports="""
A taper thread (`G92` or `G76` with R, or `G32` whose X changes along the
cut) whose diameter grows along Z the other way than the cone the program turned for it before,
or more than one and a half times as fast or as slow (an R given as a diameter): the cone is a
feed move (`G01`) or turning cycle (`G90 … R`) over at least half the thread's length, whose
diameter halfway along is within two pitches of the deepest pass's (one and a half thread
heights),
with a slope within three times the thread's. The
message gives both cuts and their slopes.
""",
    why="""
R's sign says which end of the cut is larger, its size by how much. With the
sign wrong the thread runs against its blank: one end is cut far deeper than the other, the
other end barely touched, and the taper of the mating part meets it backwards; with the size
wrong the thread's depth changes along it and the mating part seats at the wrong place.
""",
    example="""
```nc
O1124 (NPT 1/2)
G97 S600 M03
G00 X23. Z2.
G01 X20.3 F0.15
X21.6 Z-19.
G00 X30.
Z5.
G92 X21.4 Z-19. R0.75 F1.814
X21. R0.75
X20.7 R0.75
X20.5 R0.75
G00 X100. Z100.
M30
```
""",
    fix="""
Give R the other sign (here `R-0.75`: the cut starts smaller at Z5 than it ends
at Z-19, as the cone grows).
""",
    not_reported="""
A taper thread with no cone turned before it in the run (bar stock
already tapered, a cone from another program), a move far from the thread's diameter (a
positioning move in the air) or much steeper or flatter than it, straight threads.
""",
)


def _against_cone(ctx: RuleContext, thread: Thread, motions: Sequence[Motion]) -> Diagnostic | None:
    passes = thread.job.passes
    job = thread.job
    if job.is_cycle and job.taper is None:
        return None  # a cycle's passes taper by R only
    tapered_at = job.remember(
        "taper lines",
        lambda: tuple(k for k, m in enumerate(passes) if cuts_a_cone(m)),
        ("x", "z", "start_x", "start_z", "R", "code"),
    )
    if not tapered_at:
        return None
    tapered = [(passes[k], line) for k in tapered_at if (line := _thread_line(passes[k]))]
    first = passes[0]
    taper_pass = tapered[0][0]
    # The deepest pass's line: where the thread meets the surface it is cut in.
    inward = sum(m.x or 0.0 for m, _l in tapered[-3:]) < sum(m.x or 0.0 for m, _l in tapered[:3])
    cut = (min if inward else max)(tapered, key=lambda t: t[0].x or 0.0)[1]
    pitch = thread.pitch or thread.job.lead or 1.0
    low, high = cut.span
    first_key = motion_key(first)
    for m in motions:
        if m.code == first.code and motion_key(m) == first_key:
            break  # only what was turned before the thread
        if m.uri != first.uri or m.run != first.run:
            continue
        cone = _cone_line(m)
        if cone is None:
            continue
        c_low, c_high = cone.span
        common = min(high, c_high) - max(low, c_low)
        if common < COVER * (high - low):
            continue
        middle = (max(low, c_low) + min(high, c_high)) / 2.0
        if abs(cone.x_at(middle) - cut.x_at(middle)) > NEAR_PITCHES * pitch:
            continue
        a, b = cut.slope, cone.slope
        if b == 0.0 or not 1.0 / SLOPE_RATIO <= abs(a / b) <= SLOPE_RATIO:
            continue
        word = taper_pass.words.get("R")
        if a * b < 0.0:
            verdict = (
                tr("the thread tapers the other way")
                if word is None
                else tr("the thread tapers the other way; R's sign is wrong")
            )
        elif abs(a / b) > SAME_TAPER or abs(b / a) > SAME_TAPER:
            verdict = tr(
                "the thread's taper is {ratio:.2g} times the cone's: one end is cut deeper than "
                "the other",
                ratio=abs(a / b),
            )
        else:
            continue
        what = f"{taper_pass.shown} R{fmt(word)}" if word is not None else taper_pass.shown
        return make(
            MB821,
            tr(
                "{cut_code} cuts the thread from X{x0} at Z{z0} to X{x1} at Z{z1} "
                "({thread_taper}), but the cone turned for it at line {line} runs from X{cone_x0} "
                "at Z{cone_z0} to X{cone_x1} at Z{cone_z1} ({cone_taper}): {verdict}",
                cut_code=what,
                x0=mm(cut.x0),
                z0=mm(cut.z0),
                x1=mm(cut.x1),
                z1=mm(cut.z1),
                thread_taper=_per_length(a),
                line=m.line + 1,
                cone_x0=mm(cone.x0),
                cone_z0=mm(cone.z0),
                cone_x1=mm(cone.x1),
                cone_z1=mm(cone.z1),
                cone_taper=_per_length(b),
                verdict=verdict,
            ),
            taper_pass.line,
            0,
            width(ctx, taper_pass.line),
            related=[
                Related(m.line, 0, 0, tr("the cone the thread is cut on")),
                *thread_related(thread),
            ],
        )
    return None


def _per_length(slope: float) -> str:
    """A taper as the diameter's change per unit of Z towards -Z."""
    grows = -slope
    return tr(
        "diameter {sign}{rate:.4f} per unit towards −Z",
        sign="+" if grows > 0 else "−",
        rate=abs(grows),
    )


MB823_DOC = RuleDoc(
    "MB823",
    reports="""
A thread whose comments name a taper pipe thread that fits its passes (the
pitch of ISO 7-1's R, Rc, Rp, or of NPT, and a diameter near its size) when the passes do not
cut the designation's taper: a taper thread (R, Rc, NPT: 1:16 on the diameter) cut parallel,
the parallel Rp cut tapered, a taper more than one and a half times or less than two thirds
of 1:16 (R given as a diameter, or halved), or, for passes that cut towards −Z, a diameter
that shrinks towards −Z on an external thread or grows on an internal one (the pipe's end,
the small end, is the part's free end, towards +Z). Said when no cone turned for the thread
says it (MB821).
""",
    why="""
A taper pipe thread seals on its taper: the mating part screws on until the
flanks meet at the gauge plane. Cut parallel or with another taper, the flanks touch along a
line and leak; cut the wrong way round, the fitting does not go on past the first turns.
""",
    example="""
```nc
O1125 (NIPPLE NPT 3/4)
G97 S500 M03
G00 X30. Z5.
G92 X25.5 Z-20. R0.78 F1.814
X25. R0.78
X24.6 R0.78
X24.3 R0.78
X24.1 R0.78
G00 X100. Z100.
M30
```
""",
    fix="""
Give R the thread's taper with the sign that makes the start of the cut the
small end: here `R-0.78` (1/32 of the 25 mm from Z5 to Z-20 on the radius).
""",
    not_reported="""
Threads whose comments name no taper pipe thread, or one whose pitch or
size does not fit the passes; the direction of a thread cut towards +Z (the free end is not
known then); a taper within a factor of one and a half of 1:16 (the gauge plane's place is
not judged).
""",
)


def _against_designation(ctx: RuleContext, thread: Thread, pipe: PipeThread) -> Diagnostic | None:
    passes = [m for m in thread.job.passes if m.x is not None and thread_line(m) is not None]
    if not passes:
        return None
    internal = thread.internal if thread.internal is not None else thread.job.internal
    # The deepest pass, of the tapered ones if any: the X and R the program gives the thread.
    tapering = [p for p in passes if _thread_line(p) is not None] or passes
    m = (max if internal else min)(tapering, key=lambda p: p.x or 0.0)
    line = thread_line(m)
    assert line is not None and m.start_z is not None and m.z is not None and m.x is not None
    slope = line.slope
    towards_minus = m.start_z > m.z
    # The slope the designation asks for: the small end towards +Z, the free end (external:
    # the diameter grows towards -Z, dx/dz < 0; internal the other way).
    wanted = pipe.taper * (1.0 if internal else -1.0)
    cut = tr(
        "the thread's deepest pass ({code}, line {line}) runs from X{x0} at Z{z0} to X{x1} at "
        "Z{z1}",
        code=m.shown,
        line=m.line + 1,
        x0=mm(line.x0),
        z0=mm(line.z0),
        x1=mm(line.x1),
        z1=mm(line.z1),
    )
    word = m.words.get("R")
    expected_r = fmt(round(wanted * (m.start_z - m.z) / 2.0, 3))
    if pipe.taper == 0.0:
        if slope == 0.0:
            return None
        verdict = (
            tr(
                "{pipe} is a parallel thread, but tapers it {ratio} on the diameter",
                pipe=pipe.name,
                ratio=_ratio(slope),
            )
            if word is None
            else tr(
                "{pipe} is a parallel thread, but R{r} tapers it {ratio} on the diameter",
                pipe=pipe.name,
                r=fmt(word),
                ratio=_ratio(slope),
            )
        )
    elif slope == 0.0:
        verdict = tr(
            "{pipe} tapers 1:16 on the diameter, but the passes are parallel: the taper R is "
            "missing (R{r} over this cut)",
            pipe=pipe.name,
            r=expected_r,
        )
    elif not 1.0 / SAME_TAPER <= abs(slope / wanted) <= SAME_TAPER:
        said = {"ratio": _ratio(slope), "times": abs(slope / wanted), "pipe": pipe.name}
        verdict = (
            tr("a taper of {ratio} on the diameter, {times:.2g} times {pipe}'s 1:16", **said)
            if word is None
            else tr(
                "a taper of {ratio} on the diameter, {times:.2g} times {pipe}'s 1:16 (R is a "
                "radius: R{r} over this cut)",
                r=expected_r,
                **said,
            )
        )
    elif towards_minus and slope * wanted < 0.0:
        verdict = _wrong_way(pipe, slope < 0.0, bool(internal))
        if word is not None:
            verdict = tr("{verdict}: R's sign is wrong (R{r})", verdict=verdict, r=expected_r)
    else:
        return None
    # Said at the first pass that gives the taper (or would): where R is first written.
    where = depth_line(tapering[0])
    return make(
        MB823,
        tr("{cut}: {verdict}", cut=cut, verdict=verdict),
        where,
        0,
        width(ctx, where),
        related=thread_related(thread),
    )


def _wrong_way(pipe: PipeThread, grows: bool, internal: bool) -> Text:
    """A taper pipe thread whose diameter changes the wrong way along -Z."""
    if grows and internal:
        return tr(
            "its diameter grows towards −Z, but {pipe} is an internal taper whose small end is "
            "the pipe's end, at +Z",
            pipe=pipe.name,
        )
    if grows:
        return tr(
            "its diameter grows towards −Z, but {pipe} is an external taper whose small end is "
            "the pipe's end, at +Z",
            pipe=pipe.name,
        )
    if internal:
        return tr(
            "its diameter shrinks towards −Z, but {pipe} is an internal taper whose small end "
            "is the pipe's end, at +Z",
            pipe=pipe.name,
        )
    return tr(
        "its diameter shrinks towards −Z, but {pipe} is an external taper whose small end is "
        "the pipe's end, at +Z",
        pipe=pipe.name,
    )


def _ratio(slope: float) -> str:
    return f"1:{1.0 / abs(slope):.3g}" if slope else tr("none")
