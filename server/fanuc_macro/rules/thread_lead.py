"""MB807, MB810, MB811, MB812: the lead a thread is cut with, and its feed.

On FANUC's threading commands (``G32``, ``G92``, ``G76``) ``F`` is the lead: what the tool
advances per spindle turn, the pitch times the number of starts. A multi-start thread is cut
start by start, each shifted by the pitch in Z (or by the start angle ``Q``, in 0.001°).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import Motion
from ..evaluator.values import fmt
from ..threads.identify import Thread
from ..threads.jobs import ThreadJob
from ..translation import tr
from .context import RuleContext
from .threading import in_program_unit, thread_related, width

FAMILY = "threading"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB807 = RuleInfo("MB807", "threading-feed", Severity.ERROR,
                 "Spindle speed times pitch is above the machine's threading feed limit.", FAMILY)
MB810 = RuleInfo("MB810", "thread-lead", Severity.ERROR,
                 "A thread is cut with an F that is not its lead (the pitch times the starts).",
                 FAMILY)
MB811 = RuleInfo("MB811", "multi-start-shift", Severity.ERROR,
                 "A multi-start thread whose passes all start at one place: one start is cut.",
                 FAMILY)
MB812 = RuleInfo("MB812", "thread-feed-mixed", Severity.ERROR,
                 "A pass of a thread is cut with another F than the rest of its passes.", FAMILY)
# fmt: on


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    for thread in ctx.threads():
        yield from _feed_limit(ctx, thread.job)
        yield from _mixed_feed(ctx, thread)
        yield from _lead(ctx, thread)
        yield from _starts(ctx, thread)


MB807_DOC = RuleDoc(
    "MB807",
    reports="""
A threading pass whose feed, spindle speed (rpm, `G97`) times the lead
`F`, is above the machine's threading feed limit, when that limit is set: the setting
`fanuc-macro.machine.maxThreadingFeed` (mm/min), command line `--max-threading-feed`. The limit
has no default.
""",
    why="""
The Z axis cannot follow the spindle: the control clamps the
feed or raises an alarm, the lead comes out wrong, and the tool runs past the planned run-out
at the end of the thread, possibly into a shoulder.
""",
    example="""
```nc
O1007 (EXTERNAL THREAD M64X6)
G97 S3500 M03
G00 X66. Z12.
G92 X63.4 Z-40. F6.
M30
```

The example assumes `"fanuc-macro.machine.maxThreadingFeed": 10000`.
""",
    fix="""
Lower the spindle speed for the thread (here S1500 gives 9000 mm/min), or set
the machine's limit in the settings if it is higher.
""",
    not_reported="""
Any threading feed while the machine's limit is not set, passes in
constant surface speed (`G96`), whose rpm depends on the diameter, and passes whose speed is not
known.
""",
)


def _feed_limit(ctx: RuleContext, job: ThreadJob) -> Iterator[Diagnostic]:
    inch = job.passes[0].inch  # G20: the lead, and so the feed, in inches
    limit = in_program_unit(ctx.config.max_threading_feed, inch)
    m = job.remember(("feed limit", limit), lambda: _too_fast(job.passes, limit), ("rpm", "F"))
    if m is None:
        return
    pitch = m.words["F"]
    assert m.rpm is not None
    feed = m.rpm * pitch
    unit = "inch/min" if inch else "mm/min"
    shown = (
        tr(
            "{limit:.1f} inch/min ({limit_mm} mm/min)",
            limit=limit,
            limit_mm=fmt(ctx.config.max_threading_feed),
        )
        if inch
        else f"{fmt(limit)} mm/min"
    )
    yield make(
        MB807,
        tr(
            "S{speed} x lead F{lead} = {feed} {unit}, above the machine's threading feed limit "
            "{limit}",
            speed=fmt(m.rpm),
            lead=fmt(pitch),
            feed=fmt(feed),
            unit=unit,
            limit=shown,
        ),
        m.line,
        0,
        width(ctx, m.line),
    )


def _too_fast(passes: list[Motion], limit: float) -> Motion | None:
    """The first pass whose feed (speed times lead) is above ``limit``."""
    for m in passes:
        pitch = m.words.get("F")
        if m.rpm is not None and pitch is not None and m.rpm * pitch > limit:
            return m
    return None


MB812_DOC = RuleDoc(
    "MB812",
    reports="""
A pass of a thread (the same program execution, the same stretch of Z) cut
with another `F` than most of the thread's passes.
""",
    why="""
That pass follows another helix: it cuts across the flanks
the other passes formed, and the thread is scrap. It is usually one block of a copied pair
edited and its twin forgotten.
""",
    example="""
```nc
O1107 (M24X3)
G97 S450 M03
G00 X26. Z5.
G92 X23.5 Z-35. F3.
X23.1
G92 X22.7 Z-35. F1.5
G92 X22.4 Z-35. F3.
G00 X100. Z100.
M30
```
""",
    fix="""
Cut every pass with the thread's lead.
""",
    not_reported="""
Threads of two passes or fewer, passes over another stretch of Z
(another thread), and variable-lead threads (`G34`).
""",
)


def _mixed_feed(ctx: RuleContext, thread: Thread) -> Iterator[Diagnostic]:
    job = thread.job
    found = job.remember("mixed feed", lambda: _other_feeds(job.passes), ("F", "line"))
    if found is None:
        return
    usual, count, others = found
    for m in others:
        yield make(
            MB812,
            tr(
                "this {code} cuts with F{feed:g}, the other {count} passes of the same thread "
                "with F{usual:g}: it cuts another helix across the thread's flanks",
                code=m.shown,
                feed=m.words["F"],
                count=count,
                usual=usual,
            ),
            m.line,
            0,
            width(ctx, m.line),
        )


def _other_feeds(passes: list[Motion]) -> tuple[float, int, list[Motion]] | None:
    """(the F of most passes, how many, the first pass of each line with another F) when one
    F is most passes' and another is used."""
    feeds = Counter(m.words.get("F") for m in passes if m.words.get("F") is not None)
    if len(passes) < 3 or len(feeds) < 2:
        return None
    usual, count = feeds.most_common(1)[0]
    if usual is None or count * 2 <= len(passes):
        return None
    reported: set[int] = set()
    others: list[Motion] = []
    for m in passes:
        feed = m.words.get("F")
        if feed is None or feed == usual or m.line in reported:
            continue
        reported.add(m.line)
        others.append(m)
    return usual, count, others


MB810_DOC = RuleDoc(
    "MB810",
    reports="""
A thread cut with an `F` that is not its lead, the pitch times the number
of starts, where the pitch is known apart from the cut: from a designation whose size fits the
passes (`M16X1.5`), or from a variable named `(PITCH)`.
""",
    why="""
On FANUC's threading commands `F` is the lead: with another
value the tool follows another helix, the thread does not screw on, and the passes after the
first tear the flanks the first one cut.
""",
    example="""
```nc
O1105 (M16X1.5-6G)
G97 S700 M03
G00 X18. Z4.
G92 X15.6 Z-20. F2.
X15.3
X15.0
G00 X100. Z100.
M30
```
""",
    fix="""
Cut with the lead (`F1.5` here; `F` = Ph for a multi-start thread).
""",
    not_reported="""
Threads whose pitch is known only from the cut's own `F`, and a
file whose comments hold several designations that fit the passes (which one is meant cannot
be told).
""",
)


def _lead(ctx: RuleContext, thread: Thread) -> Iterator[Diagnostic]:
    lead = thread.job.lead
    want = thread.lead
    if lead is None or want is None or thread.pitch_source not in ("designation", "comment"):
        return
    if abs(lead - want) < 1e-6:
        return
    job = thread.job
    m = job.remember(
        ("first with F", lead),
        lambda: next(p for p in job.passes if p.words.get("F") == lead),
        ("F",),
    )
    pitch = thread.pitch
    assert pitch is not None
    starts = (
        tr("pitch {pitch:g} and {count} starts", pitch=pitch, count=thread.starts)
        if thread.starts > 1
        else tr("pitch {pitch:g} and one start", pitch=pitch)
    )
    hint = None
    if thread.starts == 1 and abs(lead - 2 * pitch) < 1e-6:
        hint = tr("a lead for two starts, or the lead typed where the pitch belongs")
    elif thread.starts > 1 and abs(lead - pitch) < 1e-6:
        hint = tr("the pitch typed where the lead belongs (F is the lead)")
    said = {
        "code": m.shown,
        "lead": lead,
        "thread": thread.name,
        "starts": starts,
        "want": want,
        "source": thread.known_from(),
    }
    message = (
        tr(
            "{code} cuts with F{lead:g}, but {thread} has {starts}: its lead, the F to cut with, "
            "is {want:g}; thread known from {source}",
            **said,
        )
        if hint is None
        else tr(
            "{code} cuts with F{lead:g}, but {thread} has {starts}: its lead, the F to cut with, "
            "is {want:g}: {hint}; thread known from {source}",
            hint=hint,
            **said,
        )
    )
    yield make(
        MB810,
        message,
        m.line,
        0,
        width(ctx, m.line),
        related=thread_related(thread),
    )


def _centres(passes: list[Motion], lead: float) -> list[float]:
    """Where along the lead each pass starts (its Z, or its start angle Q, modulo the lead);
    the two passes of a depth cut left and right of one centre (the symmetric module) count
    as their centre."""
    groups: list[list[Motion]] = []
    for m in passes:
        if groups and groups[-1][0].x == m.x:
            groups[-1].append(m)
        else:
            groups.append([m])
    centres: list[float] = []
    for group in groups:
        zs = [m.start_z for m in group]
        if len(group) == 2 and not any(_angle(m) for m in group) and None not in zs:
            a, b = group[0].start_z, group[1].start_z
            assert a is not None and b is not None
            centres.append(((a + b) / 2) % lead)
        else:
            centres.extend(p for p in (_phase(m, lead) for m in group) if p is not None)
    return centres


def _angle(m: Motion) -> float | None:
    """The threading start angle shift Q (0.001°) of G32 / G92; G76's Q is its first depth."""
    return m.words.get("Q") if m.code != "G76" else None


def _phase(m: Motion, lead: float) -> float | None:
    q = _angle(m)
    if q:
        return (q / 360000.0 * lead) % lead
    if m.start_z is None:
        return None
    return m.start_z % lead


def _cut_starts(passes: list[Motion], lead: float, starts: int) -> bool:
    """Whether the passes start at each of the starts (or tell nothing of where they do)."""
    centres = _centres(passes, lead)
    return len(centres) < 1 or _starts_cut(centres, lead, starts) >= starts


def _starts_cut(centres: list[float], lead: float, starts: int) -> int:
    """How many of the evenly spaced starts have a pass, around the median centre."""
    ordered = sorted(centres)
    origin = ordered[len(ordered) // 2]
    spacing = lead / starts
    hit = {round(((c - origin) % lead) / spacing) % starts for c in centres}
    return len(hit)


MB811_DOC = RuleDoc(
    "MB811",
    reports="""
A thread with several starts (a designation `M20xPh3P1.5`, or `2 START`,
`双线` in a comment) whose passes all start around one place along the lead: no pass is
shifted by the pitch in Z, nor by a start angle `Q`. The left and right steps of a
symmetric module count as their centre.
""",
    why="""
Only one of the starts is cut: the part has a single helix at
the multi-start lead, and the mating part does not screw on.
""",
    example="""
```nc
O1106 (M20XPH3P1.5-6G TWO STARTS)
G97 S600 M03
G00 X22. Z6.
G92 X19.6 Z-25. F3.
X19.3
X19.
X18.8
G00 X100. Z100.
M30
```
""",
    fix="""
Cut every start: the same passes again from a start point shifted by the pitch
(`Z7.5` here), or with `Q180000` (the start angle, 0.001°) for the second start.
""",
    not_reported="""
A thread cut with another lead than pitch × starts (MB810), and
starts whose shift is not one pitch but any other whole part of the lead.
""",
)


def _starts(ctx: RuleContext, thread: Thread) -> Iterator[Diagnostic]:
    lead = thread.job.lead
    if not starts_missing(thread) or lead is None or thread.pitch is None:
        return
    first = thread.job.passes[0]
    yield make(
        MB811,
        tr(
            "{thread} has {starts} starts, but its {count} passes all start around one place "
            "along the lead {lead:g}: only one start is cut; cut the next start shifted by the "
            "pitch {pitch:g} in Z (or with Q{angle}, the start angle); thread known from {source}",
            thread=thread.name,
            starts=thread.starts,
            count=len(thread.job.passes),
            lead=lead,
            pitch=thread.pitch,
            angle=round(360000 / thread.starts),
            source=thread.known_from(),
        ),
        first.line,
        0,
        width(ctx, first.line),
        related=thread_related(thread),
    )


def starts_missing(thread: Thread) -> bool:
    """Whether a thread of several starts, cut with its lead, has only one of them cut."""
    lead = thread.job.lead
    if thread.starts < 2 or lead is None or thread.pitch is None:
        return False
    if abs(lead - thread.pitch * thread.starts) > 1e-6:
        return False  # cut with another lead: MB810 says so
    job, starts = thread.job, thread.starts
    return not job.remember(
        ("starts cut", lead, starts),
        lambda: _cut_starts(job.passes, lead, starts),
        ("x", "start_z", "Q", "code"),
    )
