"""MB803, MB804, MB814, MB822: the sequence of a thread's passes, pass after pass.

Cycles only (``G92``, ``G76``), but for MB822: the single ``G32`` cuts of a fitting-method
program move around a profile on purpose, always the same way along Z. Two passes at the same
X from different start points (the left and right steps of the symmetric module, a flank
infeed) are not a repeat; the same pass again at the full depth is a spring pass.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Iterator
from functools import partial
from itertools import pairwise

from ..diagnostics import Diagnostic, Related, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import DocumentFacts, Motion
from ..program.index import Program
from ..syntax.tree import Call, Var
from ..syntax.walk import subexpressions
from ..threads.identify import Thread
from ..threads.linear import expr_text
from ..threads.module_shape import assignment, word, writes_of
from ..translation import Text, tr
from .context import RuleContext
from .threading import EPS, distance, in_program_unit, mm, pass_name, width

FAMILY = "threading"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB803 = RuleInfo("MB803", "thread-depth-not-growing", Severity.WARNING,
                 "A threading pass is shallower than the one before it.", FAMILY)
MB804 = RuleInfo("MB804", "thread-pass-too-deep", Severity.WARNING,
                 "A threading pass takes more depth than the configured maximum per pass.", FAMILY)
MB814 = RuleInfo("MB814", "thread-pass-repeated", Severity.WARNING,
                 "A threading pass repeats the previous pass's X, or one of the program's own "
                 "sequence of depths is never cut.", FAMILY)
MB822 = RuleInfo("MB822", "thread-pass-reversed", Severity.ERROR,
                 "A threading move runs back along the thread, inside it, against the other "
                 "passes' direction.", FAMILY)
# fmt: on


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    for thread in ctx.threads():
        job = thread.job
        if not job.is_cycle and len(job.passes) >= 2:
            yield from _reversed(ctx, thread)
        if not job.is_cycle or len(job.passes) < 2:
            continue
        internal = thread.internal if thread.internal is not None else job.internal
        if internal is None:
            continue
        yield from _growing(ctx, thread, internal)
        yield from _repeated(ctx, thread, internal)


MB803_DOC = RuleDoc(
    "MB803",
    reports="""
A threading cycle pass (`G92`, `G76`) that is shallower than the pass
before it. Passes of a taper thread (`G92 R`) are compared where the first pass ends, on the
line each cut follows: a pass moved along Z (flank infeed) ends on the cone at another
diameter for the same depth.
""",
    why="""
The pass cuts nothing or rubs the flank it has already cut:
wasted time at best, work hardening and a poor finish at worst. It usually shows a pass list
typed out of order, so the passes after it may not be the ones intended either.
""",
    example="""
```nc
O1003 (EXTERNAL THREAD M20X2.5)
G97 S500 M03
G00 X22. Z5.
G92 X19.5 Z-30. F2.5
X18.5
X18.8
G00 X100. Z100.
M30
```
""",
    fix="""
Put the passes in order of growing depth.
""",
    not_reported="""
The same depth again (a spring pass, or the left and right steps
of the symmetric module); a return to the first depth, which starts the next start of a
multi-start thread or cuts the thread again; the first pass of a `G76`, whose passes the control
works out itself (a second `G76` over the thread re-chases it); `G32` single cuts, which
fitting-method programs move around a profile on purpose.
""",
)


def _growing(ctx: RuleContext, thread: Thread, internal: bool) -> Iterator[Diagnostic]:
    passes = thread.job.passes
    inch = passes[0].inch  # G20: the passes' lengths, and so the limit, in inches
    limit = in_program_unit(ctx.config.max_depth_per_pass, inch)
    events = thread.job.remember(
        ("growing", internal, limit),
        lambda: _growing_events(passes, internal, limit),
        ("x", "z", "start_z", "R"),
    )
    xs = _cone_xs(passes)
    for code, i, before in events:
        m, previous = passes[i], passes[before]
        x, x_before = xs[i], xs[before]
        assert m.x is not None and previous.x is not None
        assert x is not None and x_before is not None
        step = (-1.0 if internal else 1.0) * (x_before - x) / 2.0
        surface = thread.surface
        if code == MB804.code and surface is not None:
            # Where the program turned the thread's blank, a pass after passes in the air
            # takes only what lies below it.
            x, x_before = surface.frame_x(m), surface.frame_x(previous)
            assert x is not None and x_before is not None
            top = max(x_before, surface.blank) if internal else min(x_before, surface.blank)
            step = (-1.0 if internal else 1.0) * (top - x) / 2.0
            if step <= limit + EPS:
                continue
        if code == "MB803":
            message = tr(
                "{pass_name} at X{x} is {step} shallower than the pass before (X{before}): the "
                "depth should grow pass after pass",
                pass_name=pass_name(thread, i, m),
                x=mm(m.x, inch),
                step=distance(-step, inch),
                before=mm(previous.x, inch),
            )
        else:
            maximum = (
                tr(
                    "{limit:.4f} inch ({limit_mm:g} mm)",
                    limit=limit,
                    limit_mm=ctx.config.max_depth_per_pass,
                )
                if inch
                else f"{limit:g} mm"
            )
            message = tr(
                "{pass_name} takes {step} (radius) in one pass, above the maximum {maximum} per "
                "pass",
                pass_name=pass_name(thread, i, m),
                step=distance(step, inch),
                maximum=maximum,
            )
        yield make(MB803 if code == MB803.code else MB804, message, m.line, 0, width(ctx, m.line))


MB804_DOC = RuleDoc(
    "MB804",
    reports="""
A threading cycle pass that takes more depth (radius) than the maximum per
pass, the setting `fanuc-macro.threading.maxDepthPerPass` (0.5 mm by default; in a program in
inches, `G20`, the same length in inches: 0.0197 inch). The depth is from the pass before, or
where the program turned the thread's blank and the pass before lies outside it, from the
blank.
""",
    why="""
Depth of cut in threading grows the chip area quickly, since
the insert cuts on its flanks: an overloaded pass chatters, tears the flank or breaks the
insert, and a broken insert in the thread usually scraps the part.
""",
    example="""
```nc
O1004 (EXTERNAL THREAD M20X2.5)
G97 S500 M03
G00 X22. Z5.
G92 X19.5 Z-30. F2.5
X19.1
X17.9
G00 X100. Z100.
M30
```
""",
    fix="""
Split the depth over more passes (decreasing depths with a constant chip area
are the usual rule), or raise the setting if the insert and the material allow it.
""",
    not_reported="""
The first pass (measured from the crest, it is MB802's),
`G32` single cuts, and a pass after passes in the air that takes no more than the maximum
below the turned blank (MB818 reports the passes in the air).
""",
)


def _growing_events(
    passes: list[Motion], internal: bool, limit: float
) -> list[tuple[str, int, int]]:
    """The first pass shallower than the one before (MB803) and the first deeper than the
    limit per pass (MB804): (code, the pass, the pass before), in pass order."""
    sign = -1.0 if internal else 1.0
    events: list[tuple[str, int, int]] = []
    reported: set[str] = set()
    previous: int | None = None
    xs = _cone_xs(passes)
    top = next((x for x in xs if x is not None), None)
    for i, x in enumerate(xs):
        if x is None or top is None:
            continue
        before = xs[previous] if previous is not None else None
        if previous is not None and before is not None:
            step = sign * (before - x) / 2.0
            # Back to the first depth is the next start of a multi-start thread, or the
            # whole thread cut again: a new series, not a pass out of order. So is a G76's
            # first pass: the control works out each cycle's passes, and a second G76 over
            # the thread (a re-chase, another insert) starts its own.
            restart = sign * (top - x) <= EPS or passes[i].cycle_pass == 1
            if step < -EPS and "back" not in reported and not restart:
                reported.add("back")
                events.append(("MB803", i, previous))
            elif step > limit + EPS and "deep" not in reported:
                reported.add("deep")
                events.append(("MB804", i, previous))
        previous = i
    return events


def _cone_xs(passes: list[Motion]) -> list[float | None]:
    """Each pass's X, for a taper pass (G92 R) the X its cut reaches where the first pass ends.

    Passes of a taper thread moved along Z (flank infeed, the steps of the symmetric module)
    end on the cone at other diameters for one depth: compared at one Z, their X differ by
    the depth alone.  G92's R is the radius at the cut's start less the one at its end (0i-TF
    manual, "Canned cycle for lathe"; unverified on a machine); a block that repeats the
    cycle has the R and end Z in force (the evaluator's motion carries them)."""
    z_ref = next((m.z for m in passes if m.z is not None), None)
    xs: list[float | None] = []
    for m in passes:
        taper = m.words.get("R")
        if m.x is None or not taper or None in (z_ref, m.z, m.start_z) or m.start_z == m.z:
            xs.append(m.x)
            continue
        assert z_ref is not None and m.z is not None and m.start_z is not None
        xs.append(m.x + 2.0 * taper * (z_ref - m.z) / (m.start_z - m.z))
    return xs


def _same_pass(a: Motion, b: Motion) -> bool:
    if a.x is None or b.x is None or abs(a.x - b.x) > EPS:
        return False
    if a.start_z is None or b.start_z is None:
        return a.start_z is b.start_z
    return abs(a.start_z - b.start_z) <= EPS


def _repeated(ctx: RuleContext, thread: Thread, internal: bool) -> Iterator[Diagnostic]:
    """A pass cut twice before the full depth, or a depth of a regular sequence never cut."""
    found = thread.job.remember(
        ("repeated", internal),
        lambda: _repeated_pass(thread.job.passes, internal),
        ("x", "finishing", "start_z"),
    )
    if found is None:
        return
    passes, kind, i, usual = found
    m, before = passes[i], passes[i - 1]
    assert m.x is not None and before.x is not None
    said: dict[str, object] = {
        "pass_name": pass_name(thread, i, m),
        "x": mm(m.x, m.inch),
        "line": m.line + 1,
    }
    if kind == "repeat":
        said["before_pass"] = pass_name(thread, i - 1, before)
        yield _pass_finding(ctx, thread, m, partial(_repeat_message, said))
        return
    sign = -1.0 if internal else 1.0
    said["step"] = distance(usual, m.inch)
    said["skipped"] = mm(before.x - sign * 2.0 * usual, m.inch)
    yield _pass_finding(ctx, thread, m, partial(_skip_message, said))


def _repeat_message(said: dict[str, object], cause: str) -> Text:
    if not cause:
        return tr(
            "{pass_name} at X{x} (line {line}) repeats {before_pass} before the full depth: "
            "that depth is cut twice",
            **said,
        )
    return tr(
        "{pass_name} at X{x} (line {line}) repeats {before_pass} before the full depth: that "
        "depth is cut twice and one depth of the sequence is never cut; {cause}",
        cause=cause,
        **said,
    )


def _skip_message(said: dict[str, object], cause: str) -> Text:
    if not cause:
        return tr(
            "{pass_name} at X{x} (line {line}) takes twice the program's step of {step}: "
            "X{skipped} is never cut",
            **said,
        )
    return tr(
        "{pass_name} at X{x} (line {line}) takes twice the program's step of {step}: "
        "X{skipped} is never cut; {cause}",
        cause=cause,
        **said,
    )


def _repeated_pass(
    all_passes: list[Motion], internal: bool
) -> tuple[list[Motion], str, int, float] | None:
    """(the passes before the finishing ones, "repeat" or "skip", the pass, the usual step)."""
    passes = [m for m in all_passes if m.x is not None and not m.finishing]
    if len(passes) < 4:
        return None
    sign = -1.0 if internal else 1.0
    deepest = max(sign * -(m.x or 0.0) for m in passes)
    same_x = sum(
        1
        for a, b in pairwise(passes)
        if a.x is not None
        and b.x is not None
        and abs(a.x - b.x) <= EPS
        and sign * -b.x < deepest - EPS
    )
    if same_x * 5 > len(passes) - 1:
        return None  # depths cut in pairs (left and right steps, flank infeed): the plan
    repeats = [
        i
        for i in range(1, len(passes))
        if _same_pass(passes[i], passes[i - 1])
        and sign * -(passes[i].x or 0.0) < deepest - EPS  # before the full depth
    ]
    if not repeats:
        skipped = _skipped(passes, sign)
        return None if skipped is None else (passes, "skip", skipped[0], skipped[1])
    # A program that repeats every pass on purpose (an idle pass after each cut) is not wrong.
    depths = len({round(m.x or 0.0, 3) for m in passes})
    if len(repeats) > 2 or depths < 4:
        return None
    return passes, "repeat", repeats[0], 0.0


MB814_DOC = RuleDoc(
    "MB814",
    reports="""
In a thread whose passes go down in single steps, a pass that repeats the
previous one (the same X from the same start point) before the full depth, or a step of twice
the program's usual step (a depth never cut). When the pass's X is computed through `FIX` or
`FUP` of a value a hair off a whole number (`FIX[#30*10.]` with `#30` added up in steps of 0.1
gives 7 for 7.999999999999999), the message names it and stands at that line; it names `ROUND`
too when the X comes through one.
""",
    why="""
One depth is cut twice and another never: the pass after the
missing one takes a double depth, and a pass list computed with `FIX` of a sum of decimal steps
loses its last pass. The control computes in binary floating point like the analysis: 0.1 added
ten times is not exactly 1.
""",
    example="""
```nc
O1102 (M24X3-6G)
G97 S450 M03
G00 X26. Z5.
#20=24.
#30=0.1
WHILE[#30LE1.]DO1
#31=FIX[#30*10.]
#32=#20-#31*0.36
G92 X#32 Z-32. F3.
#30=#30+0.1
END1
M30
```
""",
    fix="""
Count passes with an integer counter, or use `ROUND` where a whole number is
meant (`#31=ROUND[#30*10.]`).
""",
    not_reported="""
Spring passes at the full depth, `G76`'s finishing passes,
threads cut in pairs of passes per depth (the symmetric module's left and right steps) or that
repeat every pass on purpose, and `G32` single cuts.
""",
)


def _pass_finding(
    ctx: RuleContext, thread: Thread, m: Motion, said: Callable[[str], Text]
) -> Diagnostic:
    """MB814 at the rounding that causes it when there is one (the line to fix), else at the
    pass; ``said`` makes the message with the cause (or "")."""
    cause, fix_line, related = _rounding_cause(ctx, thread, m)
    line = m.line if fix_line is None else fix_line
    message = said(cause)
    return make(MB814, message, line, 0, width(ctx, line), related=related)


def _steps(passes: list[Motion], sign: float) -> list[float]:
    """Radius depth gained from each pass to the next."""
    return [round(sign * ((a.x or 0.0) - (b.x or 0.0)) / 2.0, 6) for a, b in pairwise(passes)]


def _usual_step(steps: list[float]) -> float | None:
    """The step most passes take, when the program cuts a regular sequence of depths."""
    positive = [round(s, 4) for s in steps if s > EPS]
    if len(positive) < 3:
        return None
    step, count = Counter(positive).most_common(1)[0]
    return step if count * 4 >= len(positive) * 3 else None


def _skipped(passes: list[Motion], sign: float) -> tuple[int, float] | None:
    """A regular sequence of depths with one step of twice the usual, a depth never cut: (the
    pass after it, the usual step)."""
    steps = _steps(passes, sign)
    usual = _usual_step(steps)
    if usual is None:
        return None
    for i, step in enumerate(steps):
        if abs(step - 2.0 * usual) <= EPS:
            return i + 1, usual
    return None


def _rounding_cause(
    ctx: RuleContext, thread: Thread, m: Motion
) -> tuple[str, int | None, list[Related]]:
    """FIX, FUP or ROUND of a computed value on the way to the pass's X, when there is one:
    (what it did, the line to fix when it is the cause, related places)."""
    facts = ctx.doc_facts()
    program = ctx.index.program_at(thread.job.program_line)
    x_expr = word(ctx.doc, m.line, "X")
    if facts is None or program is None or x_expr is None:
        return "", None, []
    here = Related(m.line, 0, 0, tr("the {code} pass it repeats or skips", code=m.shown))
    for line, call in _roundings_feeding(ctx, facts, program, m.line, x_expr):
        text = expr_text(call)
        seen = facts.roundings.get(line)
        if seen is not None:
            said = {
                "call_text": text,
                "line": line + 1,
                "result": seen.result,
                "argument": seen.argument,
                "whole": round(seen.argument),
                "argument_text": expr_text(call.args[0]),
            }
            why = (
                tr(
                    "{call_text} at line {line} gave {result:g} for {argument!r}, a hair under "
                    "{whole:g}: the steps it is computed from do not add up exactly in floating "
                    "point; ROUND[{argument_text}] gives the whole number meant",
                    **said,
                )
                if seen.function == "FIX"
                else tr(
                    "{call_text} at line {line} gave {result:g} for {argument!r}, a hair over "
                    "{whole:g}: the steps it is computed from do not add up exactly in floating "
                    "point; ROUND[{argument_text}] gives the whole number meant",
                    **said,
                )
            )
            return why, line, [here]
        if call.name in ("FIX", "FUP", "ROUND"):
            return (
                tr("the X comes through {call_text} at line {line}", call_text=text, line=line + 1),
                None,
                [Related(line, 0, 0, tr("{call_text} rounds the pass's depth", call_text=text))],
            )
    return "", None, []


def _roundings_feeding(
    ctx: RuleContext, facts: DocumentFacts, program: Program, line: int, expr: object
) -> Iterator[tuple[int, Call]]:
    """Rounding calls in ``expr`` and in the assignments its variables come from (3 deep)."""
    frontier: list[tuple[int, object]] = [(line, expr)]
    seen: set[int] = set()
    for _depth in range(4):
        following: list[tuple[int, object]] = []
        for at, node in frontier:
            for sub in subexpressions(node):  # type: ignore[arg-type]
                if isinstance(sub, Call) and sub.name in ("FIX", "FUP", "ROUND"):
                    yield at, sub
                if isinstance(sub, Var) and sub.number is not None:
                    n = int(sub.number)
                    if n in seen:
                        continue
                    seen.add(n)
                    for write in writes_of(facts, program, n):
                        if write < at:
                            assign = assignment(ctx.doc, write, n)
                            if assign is not None:
                                following.append((write, assign.value))
        frontier = following


MB822_DOC = RuleDoc(
    "MB822",
    reports="""
A single threading move (`G32`) that runs along Z the other way than the
thread's other passes, at an X inside the groove they cut (below the shallowest of them on an
external thread, above it on an internal one), over their stretch of Z. Once per thread, at
the move; the message gives its X and Z and the other passes' direction.
""",
    why="""
`G32` is modal: a block of Z alone after a threading pass is one more threading move. Fed
back along the thread with the spindle turning the same way, the tool follows a helix of the
other hand and cuts across the flanks just cut: the thread is ruined and the insert, loaded on
its back, often breaks. It is nearly always a retract (`G00 X…`) left out before the return to
the start.
""",
    example="""
```nc
O1125 (M16X1.5-6G)
G97 S700 M03
G00 X20. Z5.
X15.4
G32 Z-22. F1.5
G00 X20.
Z5.
X14.9
G32 Z-22.
Z5.
X14.5
G32 Z-22.
G00 X20.
Z5.
M30
```
""",
    fix="""
Put the retract back before the return (`G00 X20.` before `Z5.`).
""",
    not_reported="""
Cycles (`G92`, `G76`: the control retracts and returns itself), a move outside the groove (a
return above the thread at the threading feed is slow, not a cut), a thread all of whose passes
run one way, whichever it is (a left-hand thread cut towards +Z).
""",
)


def _reversed(ctx: RuleContext, thread: Thread) -> Iterator[Diagnostic]:
    passes = [
        m
        for m in thread.job.passes
        if m.z is not None and m.start_z is not None and m.x is not None and m.z != m.start_z
    ]
    ways = Counter(m.z > m.start_z for m in passes if m.z is not None and m.start_z is not None)
    if len(ways) < 2:
        return
    (forward, count), (_back, fewer) = ways.most_common(2)
    if count == fewer:
        return  # no way the thread is cut
    along = [m for m in passes if ((m.z or 0.0) > (m.start_z or 0.0)) == forward]
    xs = [m.x for m in along if m.x is not None]
    zs = [z for m in along for z in (m.z, m.start_z) if z is not None]
    internal = thread.internal if thread.internal is not None else thread.job.internal
    if not xs or not zs or internal is None:
        return
    low, high = min(zs), max(zs)
    for m in passes:
        assert m.x is not None and m.z is not None and m.start_z is not None
        if (m.z > m.start_z) == forward:
            continue
        inside = m.x > min(xs) if internal else m.x < max(xs)
        overlap = min(high, max(m.z, m.start_z)) - max(low, min(m.z, m.start_z))
        if not inside or overlap <= 0.0:
            continue
        yield make(
            MB822,
            tr(
                "{code} runs from Z{start} to Z{end} at X{x}, inside the thread the other {count} "
                "passes cut towards {way}: fed back along it, the tool cuts across the flanks (a "
                "retract before the return left out?)",
                code=m.shown,
                start=mm(m.start_z),
                end=mm(m.z),
                x=mm(m.x),
                count=count,
                way="+Z" if forward else "−Z",
            ),
            m.line,
            0,
            width(ctx, m.line),
        )
        return
