"""MB805, MB806: the threading tool's nose radius against the thread it cuts.

The radius is found from its use (the term a thread module subtracts from the height, the
variable it offsets by r·tan30°, the ``ASIN[#18/[#4-#18]]`` of a fitting-method program), else
from a comment that names it.
"""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, Related, RuleDoc, RuleInfo, Severity, make
from ..threads.geometry import SIN60
from ..threads.module_shape import fitting_radii, written_value
from ..translation import tr
from .context import RuleContext
from .threading import thread_related, width

FAMILY = "threading"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB805 = RuleInfo("MB805", "nose-radius-range", Severity.WARNING,
                 "A thread tool nose radius outside 0.125P-0.144P (external) or 0-0.072P "
                 "(internal).", FAMILY)
MB806 = RuleInfo("MB806", "fitting-tool-radius", Severity.ERROR,
                 "In the fitting method, the tool radius is not smaller than the groove radius.",
                 FAMILY)
# fmt: on


def nose_radius_bounds(pitch: float, internal: bool) -> tuple[float, float]:
    """Seed paper 000: 0.125P < r < 0.144P external, 0 < r < 0.072P internal. The upper
    bounds are P/(8·sin60°) and P/(16·sin60°) rounded (the theoretical radius, = H/6 and
    H/12), so that exact value is allowed."""
    if internal:
        return 0.0, pitch / (16.0 * SIN60)
    return 0.125 * pitch, pitch / (8.0 * SIN60)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    yield from _nose_radius(ctx)
    yield from _fitting(ctx)


MB805_DOC = RuleDoc(
    "MB805",
    reports="""
The nose radius of the tool that cuts an ISO metric thread outside
0.125P–0.144P (external) or 0–0.072P (internal), the bounds of Deng Ronggang's paper. The radius is
found from its use: the variable a thread module subtracts from the height and offsets by
r·tan30° in its side step (`#3` of `#4=[7./8.]*SIN[60]*#101-#3+...` and
`[#4+#3-#6-#9]*TAN[30]-#3*TAN[30]`), else a variable whose comment names it
(`#3=0.2 (NOSE RADIUS)`). The pitch and the side are those of the identified thread. The upper
bounds 0.144P and 0.072P are P/(8 sin 60°) and P/(16 sin 60°) rounded, so those exact values,
the module's own theoretical radius, are allowed.
""",
    why="""
The nose radius forms the root of the thread. Too small, the
root is sharp (a notch where the part fails in fatigue) and under ISO 965-1's least root radius;
too large, the flanks are cut short and the thread height computed from it is wrong. Either
way the thread is not the one the formula computed.
""",
    example="""
```nc
O1005 (EXTERNAL THREAD)
#1=20. (NOMINAL DIAMETER)
#2=2.5 (PITCH)
#3=0.2 (NOSE RADIUS)
#4=1.4 (THREAD HEIGHT)
G97 S500 M03
G00 X22. Z5.
G92 X[#1-0.6] Z-30. F#2
M30
```
""",
    fix="""
Use an insert whose nose radius fits the pitch (0.31–0.36 mm for P 2.5), or
correct the value or the formula (`0.29*#101` typed for `#101/[8*SIN[60]]`).
""",
    not_reported="""
The tool of an arc thread by the fitting method (MB806 checks it),
of a taper or non-metric thread, and a radius in a program that cuts no thread.
""",
)


def _nose_radius(ctx: RuleContext) -> Iterator[Diagnostic]:
    reported: set[int] = set()
    for thread in ctx.threads():
        r, line, pitch = thread.nose_radius, thread.nose_line, thread.pitch
        if r is None or line is None or pitch is None or thread.internal is None:
            continue
        if thread.unsupported is not None or thread.lead_conflict or line in reported:
            continue
        low, high = nose_radius_bounds(pitch, thread.internal)
        inside = low < r <= high + 1e-9 if thread.internal else low - 1e-9 <= r <= high + 1e-9
        if inside:
            continue
        reported.add(line)
        said = {
            "radius": r,
            "share": r / pitch,
            "reason": thread.nose_reason,
            "low": low,
            "high": high,
            "pitch": pitch,
            "thread": thread.name,
            "source": thread.known_from(),
        }
        message = (
            tr(
                "nose radius {radius:.4g} = {share:.3f}P ({reason}) is outside "
                "{low:.4g}–{high:.4g} allowed for an internal thread of pitch {pitch:g} (0 to "
                "0.072P); thread {thread} known from {source}",
                **said,
            )
            if thread.internal
            else tr(
                "nose radius {radius:.4g} = {share:.3f}P ({reason}) is outside "
                "{low:.4g}–{high:.4g} allowed for an external thread of pitch {pitch:g} (0.125P "
                "to 0.144P); thread {thread} known from {source}",
                **said,
            )
        )
        yield make(
            MB805,
            message,
            line,
            0,
            width(ctx, line),
            related=thread_related(thread),
        )


MB806_DOC = RuleDoc(
    "MB806",
    reports="""
In a program that cuts an arc (round) thread by the fitting method, a tool
nose radius that is not smaller than the groove radius. The two are found from the tool path's
tangency angle `ASIN[#18/[#4-#18]]` (r / (R − r)), else from comments (`(NOSE RADIUS)`,
`(GROOVE RADIUS)`).
""",
    why="""
The method moves the centre of the tool nose on an arc of
radius R − r. With r ≥ R there is no such arc: the formulas give an `ASIN` out of range or a
tool path that cuts the groove flanks away, and the groove is wider than drawn.
""",
    example="""
```nc
O3101 (ARC THREAD, FITTING METHOD)
#1=93.82 (THREAD DIAMETER)
#4=10. (GROOVE RADIUS)
#18=12. (NOSE RADIUS)
M30
```
""",
    fix="""
Use a tool whose nose radius is smaller than the groove radius, or correct the
values entered.
""",
    not_reported="""
A tool radius whose value the analysis cannot know (an argument of
a macro nobody calls), and programs that do not use the fitting method's formulas or words.
""",
)


def _fitting(ctx: RuleContext) -> Iterator[Diagnostic]:
    facts = ctx.doc_facts()
    if facts is None:
        return
    roles = None
    for program in ctx.index.programs:
        shape = fitting_radii(ctx.doc, facts, program)
        if shape is not None:
            tool, groove = shape.tool, shape.groove
            tool_line = shape.tool_line
            names = (f"#{shape.tool_var}", f"#{shape.groove_var}")
            related = [Related(shape.line, 0, 0, tr("the tool path's tangency angle, r/(R − r)"))]
        else:
            if roles is None:
                roles = ctx.roles()
            found = {
                m.role: (var, m.line)
                for (first, var), m in roles.items()
                if first == program.first_line and m.line >= 0
            }
            if "groove_radius" not in found or "nose_radius" not in found:
                continue
            (tool_var, tool_line), (groove_var, groove_line) = (
                found["nose_radius"],
                found["groove_radius"],
            )
            tool, groove = written_value(facts, tool_line), written_value(facts, groove_line)
            names = (f"#{tool_var}", f"#{groove_var}")
            related = [Related(groove_line, 0, 0, tr("the groove radius"))]
        if tool is None or groove is None or tool_line is None or tool < groove:
            continue
        yield make(
            MB806,
            tr(
                "tool radius {tool_var} = {tool:g} is not smaller than the groove radius "
                "{groove_var} = {groove:g}: the fitting method moves the tool centre on an arc "
                "of R − r = {difference:g}, which needs r < R",
                tool_var=names[0],
                tool=tool,
                groove_var=names[1],
                groove=groove,
                difference=groove - tool,
            ),
            tool_line,
            0,
            width(ctx, tool_line),
            related=related,
        )
