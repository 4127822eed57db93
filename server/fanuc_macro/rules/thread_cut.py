"""MB817-MB820: what a thread's passes cut, judged from the cross-section they leave.

:mod:`fanuc_macro.threads.cross_section` takes each pass's tool profile out of the blank over
one lead; these rules read the result: the finished pitch diameter against the class, the
passes that cut nothing, a pass that takes most of the profile at once. The spindle speed of
a thread cut under G96 is judged from the passes' X.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from functools import partial

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import Motion
from ..evaluator.machine_setup import speed_at
from ..evaluator.values import fmt
from ..threads.cross_section import (
    EPS,
    METRIC_ANGLE,
    NO_CHAIN,
    CrossSection,
    PitchVerdict,
    blank_source,
    pitch_verdict,
    thread_chains,
    thread_cuts,
)
from ..threads.identify import Thread
from ..threads.module_shape import in_turn
from ..translation import tr
from .context import RuleContext
from .thread_lead import starts_missing
from .threading import (
    formula_blamed,
    in_program_unit,
    mm,
    pass_name,
    root_passed,
    thread_related,
    width,
)

FAMILY = "threading"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB817 = RuleInfo("MB817", "thread-pitch-diameter", Severity.ERROR,
                 "The pitch diameter the passes cut is outside the thread's class.", FAMILY)
MB818 = RuleInfo("MB818", "thread-passes-in-air", Severity.WARNING,
                 "The first threading passes are outside the blank and cut nothing.", FAMILY)
MB819 = RuleInfo("MB819", "thread-pass-area", Severity.WARNING,
                 "One threading pass removes most of the thread's profile at once.", FAMILY)
MB820 = RuleInfo("MB820", "thread-under-g96", Severity.WARNING,
                 "A thread is cut under G96: the spindle speed changes pass by pass.", FAMILY)
# fmt: on

# A pass removing more than this share of the whole profile takes most of it at once.
MOST = 0.5
# A pass lighter than the tool's V cut 0.25 mm deep (radius) from flat stock, 0.036 mm², is a
# light cut whatever its share: a fine thread (P 0.5 or less) is often cut in two or three.
LIGHT_DEPTH = 0.25
# A thread cut in one pass is the programmer's choice (a fine pitch); with more, one pass
# taking most of the profile is not.
LEAST_PASSES = 2
# Passes outside the blank before the first cut: one may be a deliberate touch.
AIR_PASSES = 2


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    threads = ctx.threads()
    chains = thread_chains(threads, ctx.index)
    for thread in threads:
        yield from _under_g96(ctx, thread)
        chain = chains.get(id(thread), NO_CHAIN)
        if not chain.continued:  # the last job on a thread finishes it
            yield from _pitch_diameter(ctx, thread, chain.before)
        if chain.before:
            continue  # a job that goes on with another's cut: its passes are not all it took
        cuts = thread_cuts(thread)
        if cuts:
            yield from _in_the_air(ctx, thread, cuts)
            yield from _pass_area(ctx, thread, cuts)


MB817_DOC = RuleDoc(
    "MB817",
    reports="""
An identified ISO metric thread whose passes, taken out of the blank one by
one with the tool's profile (a 60° V with its nose radius), leave a pitch diameter outside the
class: above d2 max (external) or below D2 min (internal), where the thread is too shallow for
its GO gauge; or past the other limit when no single pass goes past the root (the flanks cut
wider by passes shifted along the lead, MB801 reports a pass past the root). The message gives
the pitch diameter cut, the limits, the pass that finished the flanks and the X that would
reach the middle of the class; for a G76 whose tool angle a is steeper than the thread's 60°
(the passes stepped along a 40° flank cut past the last one's), the angle instead, at the
cycle's first block; for a pass shifted along the lead whose flank lies past the finished
one, that pass. Without a nose radius in the program, the verdict holds for every radius of
ISO 965-1's range for the side (0.125P-0.144P outside, 0-0.072P inside).
""",
    why="""
The pitch diameter is what the gauge and the mating part check: an
oversize external thread does not take its nut, an undersize one is loose and fails the NO-GO
gauge. The control cuts whatever X the program gives; only the part shows it.
""",
    example="""
```nc
O1120 (M20X2.5-6G)
G97 S500 M03
G00 X22. Z5.
G92 X19.3 Z-30. F2.5
X18.7
X18.2
X17.8
X17.5
X17.3
X17.3
G00 X100. Z100.
M30
```
""",
    fix="""
Cut to the root the message names (here about X16.8 for the middle of 6g), or
correct the depth the passes are computed from.
""",
    not_reported="""
Threads whose size or class is not known (see MB801), taper and
arc threads, threads of another form; a pitch diameter within the class for some nose radius
of the range; a cut too deep by a pass past the root (MB801 says it at that pass), and a
module whose height formula or deviation is wrong (MB808, MB809 name the cause).
""",
)


def _pitch_diameter(
    ctx: RuleContext, thread: Thread, before: tuple[Motion, ...]
) -> Iterator[Diagnostic]:
    verdict = pitch_verdict(thread, before)
    if verdict is None or not verdict.side or formula_blamed(ctx, thread):
        return
    if starts_missing(thread):
        return  # one start of several cut: MB811 says so
    if verdict.side == "loose" and root_passed(thread):
        return
    cut = verdict.cuts[-1]
    deciding = cut.deciding()
    if deciding is None:
        return
    m = thread.job.passes[deciding.index]
    assert m.x is not None
    internal = bool(thread.internal)
    low, high = verdict.limits
    which = ("D2" if internal else "d2") + (
        " min" if internal == (verdict.side == "tight") else " max"
    )
    limit = low if internal == (verdict.side == "tight") else high
    middle = (low + high) / 2.0
    cut_d2 = verdict.least if (verdict.side == "tight") != internal else verdict.greatest
    # The pitch diameter moves as the deepest X does (the V's flanks): this X reaches the middle.
    target = m.x - (cut_d2 - middle)
    gauge = (
        tr("too shallow: its GO gauge does not go")
        if verdict.side == "tight"
        else tr("cut too wide: its NO-GO gauge goes")
    )
    angle = m.tool_angle if m.code == "G76" else None
    line = depth_line(m)
    fix = tr(
        "about X{target:.3f} reaches the middle of the class ({middle:.3f})",
        target=target,
        middle=middle,
    )
    wide = cut.past_the_flank() if verdict.side == "loose" else None
    if verdict.side == "loose" and angle is not None and angle > METRIC_ANGLE:
        # The cycle steps each pass along a flank steeper than the thread's: the passes
        # before the last cut past its flank.
        fix = tr(
            "G76's tool angle a = {angle:g}° steps the passes along a {flank:g}° flank, the "
            "thread's is {thread_flank:g}°: the passes before the last cut past its flank; give "
            "the cycle a = 60",
            angle=angle,
            flank=angle / 2,
            thread_flank=METRIC_ANGLE / 2,
        )
        line = _g76_first_block(ctx, m.line, m.program_line) or m.line
    elif wide is not None and wide[1] > EPS:
        # A pass shifted along the lead cut past the finished flank: it is the one to mend.
        shifted = thread.job.passes[wide[0].index]
        apart = abs(wide[0].place - cut.cuts[-1].place) % cut.lead
        apart = min(apart, cut.lead - apart)
        fix = tr(
            "{pass_name} starts {apart:.3f} mm along the lead from the deepest pass, more than "
            "its depth allows: its flank lies {past:.3f} mm (radius) past the finished one",
            pass_name=pass_name(thread, wide[0].index, shifted),
            apart=apart,
            past=wide[1],
        )
        line = depth_line(shifted)
    said = {
        "diameters": _diameters(verdict),
        "off": abs(cut_d2 - limit),
        "which": which,
        "limit": limit,
        "thread": thread.name,
        "tolerance_class": _class_part(thread),
        "gauge": gauge,
        "pass_name": pass_name(thread, deciding.index, m),
        "x": mm(m.x),
        "fix": fix,
        "nose": _tool_text(thread, verdict),
        "source": thread.known_from(),
    }
    message = (
        tr(
            "the passes cut a pitch diameter of {diameters}, {off:.3f} mm above {which} "
            "{limit:.3f} of {thread} ({tolerance_class}): the thread is {gauge}; {pass_name} at "
            "X{x} finishes the flanks, and {fix}; {nose}; thread known from {source}",
            **said,
        )
        if cut_d2 > limit
        else tr(
            "the passes cut a pitch diameter of {diameters}, {off:.3f} mm below {which} "
            "{limit:.3f} of {thread} ({tolerance_class}): the thread is {gauge}; {pass_name} at "
            "X{x} finishes the flanks, and {fix}; {nose}; thread known from {source}",
            **said,
        )
    )
    yield make(
        MB817,
        message,
        line,
        0,
        width(ctx, line),
        related=thread_related(thread),
    )


def depth_line(m: Motion) -> int:
    """The block that gives a pass its depth: its own, or for a G32 with no X the block that
    put the tool at its X (a pass list of G00 X and G32 Z blocks)."""
    if (
        m.code in ("G32", "G33")
        and "X" not in m.words
        and "U" not in m.words
        and m.start_line is not None
        and (not m.start_uri or m.start_uri == m.uri)
    ):
        return m.start_line
    return m.line


_G76 = re.compile(r"G0*76(?![.\d])", re.I)
_AXIS_WORD = re.compile(r"[XZUW]\s*[-+.\d#\[]", re.I)


def _g76_first_block(ctx: RuleContext, line: int, program_line: int) -> int | None:
    """The first block of the two-block G76 (``G76 P(m)(r)(a) Q(dmin) R(d)``) whose data a
    cutting block at ``line`` cuts with: the last before it in its program."""
    blocks = ctx.doc.blocks
    for n in range(line - 1, max(program_line, 0) - 1, -1):
        text = blocks[n].text.split("(", 1)[0]
        if _G76.search(text) and not _AXIS_WORD.search(text):
            return n
    return None


def _class_part(thread: Thread) -> str:
    if thread.class_exact:
        return thread.class_text()
    return tr("its class not known: the limit every class keeps")


def _diameters(verdict: PitchVerdict) -> str:
    if verdict.greatest - verdict.least < 0.0005:
        return f"{verdict.least:.3f}"
    return tr("{least:.3f} to {greatest:.3f}", least=verdict.least, greatest=verdict.greatest)


def _tool_text(thread: Thread, verdict: PitchVerdict) -> str:
    radii = [c.tool.nose_radius for c in verdict.cuts]
    if thread.nose_radius is not None:
        return tr("with the tool's nose radius {radius:.4g}", radius=radii[0])
    return tr(
        "for any nose radius from {low:.4g} to {high:.4g} (ISO 965-1's range: the program does "
        "not give it)",
        low=min(radii),
        high=max(radii),
    )


MB818_DOC = RuleDoc(
    "MB818",
    reports="""
Two or more threading passes, before the first one that touches the
material, that lie wholly outside the blank: the surface the program turned (or bored) for
the thread before it, read along the thread (for a taper thread, along its cone); else, for
an identified ISO metric thread, beyond its major diameter (external) or inside its basic
minor diameter D1 (internal), so that they cut nothing on any part of the thread's size.
For G76 the cause is its thread height P: the cycle starts its passes that far
above the root it is given.
""",
    why="""
Each pass in the air costs a full stroke, and the passes that do cut are
fewer and deeper than planned: with G76, a height P given as a diameter (twice the height)
puts half the passes outside the part and leaves the insert the remaining depth in fewer
passes.
""",
    example="""
```nc
O1121 (M12X1.75-6G)
G97 S800 M03
G00 X14. Z5.
G76 P010060 Q50 R0.02
G76 X9.85 Z-20. P2150 Q300 F1.75
G00 X100. Z100.
M30
```
""",
    fix="""
Give G76 the thread's height (radius: about 0.61P outside, here P1070), or start
the pass list at the crest.
""",
    not_reported="""
A single pass outside the blank (a touch pass), passes at the
final depth that remove nothing (spring passes, MB814 reports repeated rough passes), threads
whose blank is not known (nothing turned for them in the run, no ISO metric designation), X
given on the far side of the axis.
""",
)


def _in_the_air(ctx: RuleContext, thread: Thread, cuts: list[CrossSection]) -> Iterator[Diagnostic]:
    # The fewest over the nose radii: a pass is in the air with any tool.
    air = min((c.in_the_air() for c in cuts), key=len)
    if len(air) < AIR_PASSES or len(air) == len(cuts[0].cuts):
        return
    passes = thread.job.passes
    first, last = passes[air[0].index], passes[air[-1].index]
    cut = cuts[0]
    blank = cut.blank
    assert first.x is not None and last.x is not None
    internal = cut.internal
    # The passes' X where the blank is read (a taper thread's in the frame of its cone).
    x_first, x_last = 2.0 * air[0].tip, 2.0 * air[-1].tip
    outside = abs(x_first - blank) / 2.0
    where = tr("inside the bore") if internal else tr("outside the blank")
    surface = thread.surface
    if surface is not None and x_first != first.x:
        z = mm(surface.z)
        passes_said = tr("X{first} to X{last} at Z{z}", first=mm(x_first), last=mm(x_last), z=z)
        blank_said: str = tr("X{x} at Z{z}", x=mm(blank), z=z)
        source: str = tr("the cone turned at line {line}", line=surface.line + 1)
    else:
        passes_said = tr(
            "{first_pass} at X{first} to {last_pass} at X{last}",
            first_pass=pass_name(thread, air[0].index, first),
            first=mm(first.x),
            last_pass=pass_name(thread, air[-1].index, last),
            last=mm(last.x),
        )
        blank_said = f"X{mm(blank)}"
        source = blank_source(thread)
    parts = [
        tr(
            "the first {count} of {total} passes ({passes}) are {where} {blank} ({source}) and "
            "cut nothing",
            count=len(air),
            total=len(cut.cuts),
            passes=passes_said,
            where=where,
            blank=blank_said,
            source=source,
        )
    ]
    if first.code == "G76":
        parts.append(
            tr(
                "G76's thread height P starts the cycle {outside:.3f} mm (radius) {where}: P is "
                "more than the thread's height",
                outside=outside,
                where=where,
            )
        )
    yield make(
        MB818,
        in_turn(parts),
        depth_line(first),
        0,
        width(ctx, depth_line(first)),
        related=thread_related(thread),
    )


MB819_DOC = RuleDoc(
    "MB819",
    reports="""
A threading pass that removes more than half of the area the whole job
removes from the thread's profile, in a job of two passes or more: the passes' tool profiles
are taken out of the blank in order (the blank as MB818 reads it; the tool a V of the
thread's angle: 60°, G76's tool angle for a thread not identified, 55° for ISO 7-1), and each
pass's share is what it alone removed. For G76
the usual cause is a first depth Q at or past the thread's height, or a finishing allowance R
as large as the thread.
""",
    why="""
The chip's area is the load on the insert's nose and flanks: a pass that
takes most of the profile at once breaks or chips the insert and tears the flanks, however
light the other passes are.
""",
    example="""
```nc
O1122 (M16X1.5-6G)
G97 S700 M03
G00 X18. Z5.
G76 P010060 Q50 R0.02
G76 X14.16 Z-25. P920 Q1000 F1.5
G00 X100. Z100.
M30
```
""",
    fix="""
Spread the depth over the passes (G76's Q about a quarter of the height or less;
decreasing depths in a pass list, each pass about the same area).
""",
    not_reported="""
A thread cut in a single pass (a fine pitch may be cut so), passes
that remove up to half the profile, a pass lighter than the tool's V 0.25 mm deep (0.036 mm²:
a fine thread is often cut in two or three passes), threads whose blank is not known (as
MB818), arc threads cut by the fitting method.
""",
)


def _pass_area(ctx: RuleContext, thread: Thread, cuts: list[CrossSection]) -> Iterator[Diagnostic]:
    if len(cuts[0].cuts) < LEAST_PASSES:
        return
    # The least share over the nose radii: most of the profile with any tool.
    shares: list[tuple[float, int, float, float]] = []
    for cut in cuts:
        total = cut.area
        largest = cut.largest()
        if largest is None or total <= 0.0:
            return
        shares.append((largest.area / total, largest.index, largest.area, total))
    share, index, area, total = min(shares)
    if share <= MOST or any(s[1] != index for s in shares):
        return
    m = thread.job.passes[index]
    light = in_program_unit(LIGHT_DEPTH, m.inch)
    if area <= light * light * math.tan(math.radians(cuts[0].tool.included_angle / 2.0)):
        return
    assert m.x is not None
    before = sum(c.area for c in cuts[0].cuts if c.index < index) / max(total, 1e-12)
    context = (
        tr("its first pass")
        if index == 0
        else tr("after passes that removed {before:.0%}", before=before)
    )
    parts = [
        tr(
            "{pass_name} at X{x} removes {area:.3f} mm² in one pass, {share:.0%} of the "
            "{total:.3f} mm² the thread's {count} passes remove ({context}): the insert takes "
            "most of the profile at once",
            pass_name=pass_name(thread, index, m),
            x=mm(m.x),
            area=area,
            share=share,
            total=total,
            count=len(cuts[0].cuts),
            context=context,
        )
    ]
    line = depth_line(m)
    if m.code == "G76" and index == 0:
        parts.append(
            tr(
                "G76's first depth Q is not less than its height P less the finishing "
                "allowance, so the cycle cuts that whole depth first"
            )
        )
    elif m.code == "G76" and m.finishing:
        first_block = _g76_first_block(ctx, m.line, m.program_line)
        if first_block is None:
            parts.append(
                tr(
                    "it is the cycle's finishing pass: the finishing allowance R of its first "
                    "block leaves that much to it"
                )
            )
        else:
            parts.append(
                tr(
                    "it is the cycle's finishing pass: the finishing allowance R of its first "
                    "block (line {line}) leaves that much to it",
                    line=first_block + 1,
                )
            )
        line = depth_line(m) if first_block is None else first_block
    yield make(
        MB819,
        in_turn(parts),
        line,
        0,
        width(ctx, line),
        related=thread_related(thread),
    )


MB820_DOC = RuleDoc(
    "MB820",
    reports="""
Threading passes (`G32`, `G92`, `G76`) at two or more diameters cut while
G96, constant surface speed, is in force: the spindle speed follows X, so each pass runs at
another speed. Once per thread, at its first pass, with the speeds at its first and deepest
passes.
""",
    why="""
A thread's passes follow one helix only if each starts at the same point of
the spindle's turn with the same following error; FANUC's manual for the lathe advises
cancelling constant surface speed (G97) before threading, since the servo's response to a
changing speed is not allowed for (0i-TF Operator's Manual, "Constant surface speed control",
unverified wording). The passes of a changing speed can cut beside one another and ruin the
flanks.
""",
    example="""
```nc
O1123 (M24X2-6G)
G50 S2500
G96 S150 M03
G00 X26. Z5.
G01 X24. F0.2
G00 X26.
G92 X23.3 Z-30. F2.
X22.8
X22.4
X22.0
X21.7
X21.6
G00 X100. Z100.
M30
```
""",
    fix="""
Give `G97 S…` (a fixed spindle speed) before the thread, and G96 again after it.
""",
    not_reported="""
A thread cut at one diameter (one pass, or passes at one X), passes
the G50 clamp holds at one speed, a thread whose speed mode or clamp is not known (a subprogram
analysed alone, after a call the analysis cannot follow), a mill's threading.
""",
)


def _under_g96(ctx: RuleContext, thread: Thread) -> Iterator[Diagnostic]:
    job = thread.job
    passes, speeds = job.remember(
        "under G96", partial(_g96_passes, job.passes), ("surface_speed", "speed_clamp", "x")
    )
    if speeds < 2:
        return  # one diameter, or the clamp holds every pass at one speed
    first = passes[0]
    deepest = thread.job.deepest(bool(thread.internal)) if thread.internal is not None else None
    last = deepest if deepest in passes else passes[-1]
    assert first.surface_speed is not None and first.x is not None and last.x is not None
    clamp = first.speed_clamp
    said = {
        "code": first.shown,
        "speed": fmt(first.surface_speed),
        "unit": "ft/min" if first.inch else "m/min",
        "rpm_first": _rpm(first),
        "x_first": mm(first.x),
        "rpm_last": _rpm(last),
        "x_last": mm(last.x),
    }
    message = (
        tr(
            "{code} cuts the thread under G96 S{speed} ({unit}): the spindle speed follows X, "
            "{rpm_first:,.0f} rpm at X{x_first} and {rpm_last:,.0f} rpm at X{x_last}, so each "
            "pass starts at another speed and may not follow the helix of the one before; cut "
            "threads in G97",
            **said,
        )
        if clamp is None or math.isinf(clamp)
        else tr(
            "{code} cuts the thread under G96 S{speed} ({unit}): the spindle speed follows X, "
            "{rpm_first:,.0f} rpm at X{x_first} and {rpm_last:,.0f} rpm at X{x_last}, within the "
            "G50 clamp S{clamp}, so each pass starts at another speed and may not follow the "
            "helix of the one before; cut threads in G97",
            clamp=fmt(clamp),
            **said,
        )
    )
    yield make(
        MB820,
        message,
        first.line,
        0,
        width(ctx, first.line),
        related=thread_related(thread),
    )


def _g96_passes(passes: list[Motion]) -> tuple[list[Motion], int]:
    """The passes cut under G96 with their clamp known, and how many speeds they run at."""
    found = [m for m in passes if m.surface_speed is not None and m.speed_clamp is not None and m.x]
    return found, len({round(_rpm(m)) for m in found})


def _rpm(m: Motion) -> float:
    """The spindle speed of a pass in G96: the surface speed's at its X, clamped."""
    assert m.surface_speed is not None and m.x is not None and m.speed_clamp is not None
    return min(speed_at(m.surface_speed, abs(m.x), m.inch), m.speed_clamp)
