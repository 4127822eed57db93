"""MB801, MB802, MB808, MB809: how deep a thread is cut, against ISO 68-1 / ISO 965-1.

The thread of each series of passes is identified by :mod:`fanuc_macro.threads.identify`
(from the cuts, a designation, a module's formulas, comments), and the root is the standard's,
never the program's own: the deepest X that keeps the pitch diameter inside the class with the
tool's nose radius (d2 min − H + 2r external, D2 max + H − 2r internal; for an unknown tool
0.125P, ISO 965-1's least root radius, or a sharp tool inside). A program's own thread height
is compared with the one the standard and Deng Ronggang's formula give.
"""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, Related, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import Motion
from ..evaluator.values import fmt_address
from ..program.papers import DENG_MOLYBDENUM
from ..threads.cross_section import pitch_verdict
from ..threads.geometry import SIN60
from ..threads.identify import Thread
from ..threads.module_shape import D1_FACTOR, in_turn, writes_in_document
from ..translation import tr
from .context import RuleContext

FAMILY = "threading"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB801 = RuleInfo("MB801", "thread-past-root", Severity.ERROR,
                 "A threading pass reaches past the root of the thread being cut.", FAMILY)
MB802 = RuleInfo("MB802", "thread-first-depth", Severity.ERROR,
                 "The first threading pass is deeper than the whole thread height.", FAMILY)
MB808 = RuleInfo("MB808", "thread-height", Severity.WARNING,
                 "A thread module's height puts the pitch diameter outside the thread's class.",
                 FAMILY)
MB809 = RuleInfo("MB809", "deviation-sign", Severity.WARNING,
                 "es or EI entered with its sign where the module adds it as a magnitude.", FAMILY)
# fmt: on


EPS = 0.0005  # half the least input increment (IS-B, mm)


def mm(value: float, inch: bool = False) -> str:
    """A length as the control takes it: to 0.001 mm (0.0001 inch in G20)."""
    return fmt_address(value, inch)


MM_PER_INCH = 25.4


def distance(value: float, inch: bool = False) -> str:
    """A distance in the program's unit, to its least increment: "0.120 mm", "0.0047 inch"."""
    return tr("{value:.4f} inch", value=value) if inch else tr("{value:.3f} mm", value=value)


def in_program_unit(millimetres: float, inch: bool) -> float:
    """A setting in mm (a limit per pass) in the program's unit."""
    return millimetres / MM_PER_INCH if inch else millimetres


def width(ctx: RuleContext, line: int) -> int:
    return len(ctx.doc.blocks[line].text.rstrip())


def pass_name(thread: Thread, index: int, m: Motion) -> str:
    """``G92 pass 12`` (a G76's own pass number: ``G76 pass 3``)."""
    number = m.cycle_pass or index + 1
    return tr("{code} pass {number}", code=m.shown, number=number)


def thread_related(thread: Thread) -> list[Related]:
    return [
        Related(e.line, 0, 0, tr("thread known from {source}", source=e.text))
        for e in thread.evidence
        if e.line is not None
    ][:3]


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    for thread in ctx.threads():
        if not thread.identified:
            continue
        yield from _root_checks(ctx, thread)
        sign_wrong = list(_deviation_sign(ctx, thread))
        yield from sign_wrong
        if not sign_wrong:
            yield from _height_check(ctx, thread)


MB801_DOC = RuleDoc(
    "MB801",
    reports="""
A threading pass (`G32`, `G92`, a pass of `G76`) whose X goes past the root
of the thread being cut: deeper than the X that keeps the pitch diameter inside the thread's
class with the tool's nose radius (d2 min − H + 2r outside, D2 max + H − 2r inside; see "How
the threading rules know the thread"). The message names the pass, its X, the root X and by
how much, and where the thread was known from. It is reported once per thread, at the first
pass too deep.
""",
    why="""
The thread comes out too deep: the pitch diameter of an
external thread is undersize (an internal one oversize), the thread fails its gauge, and the
part is scrap. The last passes also load the full flank of the insert.
""",
    example="""
```nc
O1001 (EXTERNAL THREAD M20X2.5)
G97 S500 M03
G00 X22. Z5.
G92 X19.5 Z-30. F2.5
X19.1
X18.7
X18.3
X17.9
X17.5
X17.1
X16.8
X16.5
G00 X100. Z100.
M30
```
""",
    fix="""
Stop at the root of the class (here X16.624 for M20x2.5-6g with a 0.3125
nose radius: d2 min 18.164 − H + 2r), or correct the thread height the passes are computed
from (MB808 says which term when a module computes it).
""",
    not_reported="""
Passes of a thread whose size is not known (no designation, no
module, no comment names it), of a taper cut, of an arc thread by the fitting method, or of a
trapezoidal, pipe or inch thread: there is no ISO metric profile to compare with. A class not
written is ISO 965-1's medium class (6g / 6H); a class not known at all is the loosest of the
tables, so a pass between a tight class's root and the loosest one's is not reported.
""",
)


MB802_DOC = RuleDoc(
    "MB802",
    reports="""
The first threading pass of a thread is deeper (radius, from the crest:
the nominal diameter outside, D1 inside) than the whole height of the thread down to its root.
""",
    why="""
The whole profile, or more, is cut in one pass: the insert
takes the full load on both flanks and usually breaks; the thread is torn. It is almost always a
final diameter typed where the first pass belongs.
""",
    example="""
```nc
O1002 (EXTERNAL THREAD M20X2.5)
G97 S500 M03
G00 X22. Z5.
G92 X16.0 Z-30. F2.5
G00 X100. Z100.
M30
```
""",
    fix="""
Start with a light pass and reach the full depth in steps (G76 computes them),
or correct the first X.
""",
    not_reported="""
A first pass that is deep but within the height (MB804 reports a
pass deeper than the configured maximum), and threads that are not identified (see MB801).
""",
)


def _root_checks(ctx: RuleContext, thread: Thread) -> Iterator[Diagnostic]:
    root = thread.root_x()
    full = thread.full_depth()
    if root is None or full is None:
        return
    internal = bool(thread.internal)
    sign = -1.0 if internal else 1.0
    related = thread_related(thread)
    module = thread.module
    if module is not None and module.height_line is not None and module.height is not None:
        related.append(
            Related(
                module.height_line,
                0,
                0,
                tr(
                    "the height #{var} = {height:.4f} the passes are cut to",
                    var=module.height_var,
                    height=module.height,
                ),
            )
        )
    passes = thread.job.passes
    i = thread.job.remember(
        ("past root", sign, root), lambda: _past_root(passes, sign, root), ("x",)
    )
    if i is not None:
        m = passes[i]
        assert m.x is not None
        past = sign * (root - m.x) / 2.0
        yield make(
            MB801,
            tr(
                "{pass_name} at X{x} is {past:.3f} mm (radius) past the root X{root} of "
                "{thread} ({limit}); thread known from {source}",
                pass_name=pass_name(thread, i, m),
                x=mm(m.x),
                past=past,
                root=mm(root),
                thread=thread.name,
                limit=thread.limit_text(),
                source=thread.known_from(),
            ),
            m.line,
            0,
            width(ctx, m.line),
            related=related,
        )
    first = passes[0]
    if first.x is None or thread.major is None or thread.pitch is None:
        return
    crest = thread.major - D1_FACTOR * thread.pitch if internal else thread.major
    depth = sign * (crest - first.x) / 2.0
    if depth > full + EPS:
        yield make(
            MB802,
            tr(
                "first {code} pass at X{x} is {depth:.3f} mm deep (radius), more than the whole "
                "height {full:.3f} of {thread} (crest X{crest}, root X{root})",
                code=first.shown,
                x=mm(first.x),
                depth=depth,
                full=full,
                thread=thread.name,
                crest=mm(crest),
                root=mm(root),
            ),
            first.line,
            0,
            width(ctx, first.line),
            related=related,
        )


def root_passed(thread: Thread) -> bool:
    """Whether a pass of the thread goes past its root (what MB801 reports)."""
    root = thread.root_x()
    if root is None:
        return False
    sign = -1.0 if thread.internal else 1.0
    passes = thread.job.passes
    return (
        thread.job.remember(
            ("past root", sign, root), lambda: _past_root(passes, sign, root), ("x",)
        )
        is not None
    )


def formula_blamed(ctx: RuleContext, thread: Thread) -> bool:
    """Whether MB808 or MB809 names a thread module's formula or input as the cause of the
    thread's depth."""
    return any(True for _ in _deviation_sign(ctx, thread)) or any(
        True for _ in _height_check(ctx, thread)
    )


def _past_root(passes: list[Motion], sign: float, root: float) -> int | None:
    """The first pass past the root."""
    for i, m in enumerate(passes):
        if m.x is not None and sign * (root - m.x) / 2.0 > EPS:
            return i
    return None


def expected_height(thread: Thread) -> float | None:
    """Seed paper 000's thread height with the standard's es / Td2 and the program's nose
    radius: 7H/8 − r + |es|/2 + Td2/4 external, 6H/8 − r + EI/2 + TD2/4 internal."""
    c = thread.pitch_class
    if c is None or not thread.class_exact or thread.pitch is None:
        return None
    big_h = SIN60 * thread.pitch
    r = thread.nose_radius
    if r is None:
        r = thread.pitch / (16.0 * SIN60) if thread.internal else thread.pitch / (8.0 * SIN60)
    base = (6.0 if thread.internal else 7.0) / 8.0 * big_h
    return base - r + abs(c.deviation) / 2.0 + c.tolerance / 4.0


MB808_DOC = RuleDoc(
    "MB808",
    reports="""
A thread module's own thread height (the variable its last pass is cut
to: `#4` of `X[#100-2.*#4]`) that differs from the height the standard and Deng Ronggang's
formula give for the identified thread, 7H/8 − r + es/2 + Td2/4 outside or 6H/8 − r + EI/2 +
TD2/4 inside (es and Td2 of the class, r the program's nose radius), by more than a quarter of
Td2, when the passes the module runs cut a pitch diameter outside the class (MB817's verdict,
from the cross-section of the cut): the formula is reported as the cause of a cut out of its
class, never alone. The message gives the expected
height, the difference, the pitch diameter the passes cut, and the term of the formula that
differs (`#103 is taken ×2 where the formula has es/2`), or the input that is not the class's
(`#104 = 0.7 where M50x3-5g6g's Td2 is 0.17`); it stands at the formula, or at that input.
""",
    why="""
Every pass is computed from the height: a typo in the formula
moves the whole thread, and the gauge shows it only after the part is cut.
""",
    example="""
```nc
O4001 (M30X2)
G97 S600 M03
G00 X32. Z5.
#100=30.
#101=2.
#103=0.038
#104=0.170
M98 P3001
M30
O3001
#3=#101/[8*SIN[60]]
#4=[7./8.]*SIN[60]*#101-#3+#103*2.+#104/4.
#9=0.15
N10 G92 X[#100-2.*#9] Z-30. F#101
#9=#9+0.15
IF[#9LT#4]GOTO10
G92 X[#100-2.*#4] Z-30. F#101
M99
```
""",
    fix="""
Correct the term the message names (here `#103/2.`), or the input.
""",
    not_reported="""
A height within a quarter of Td2 of the standard's: that is the
tuning Deng Ronggang's paper leaves to `#103` (coarse) and `#104` (fine). A height whose passes
still cut a pitch diameter within the class (a height variable that is not the one the last
pass is cut to). Heights of hand-written
pass lists (only MB801 checks their depth), and threads whose class is not known.
""",
)


def _height_check(ctx: RuleContext, thread: Thread) -> Iterator[Diagnostic]:
    module = thread.module
    c = thread.pitch_class
    if module is None or module.height is None or module.height_line is None or c is None:
        return
    expected = expected_height(thread)
    if expected is None or thread.pitch is None:
        return
    difference = module.height - expected
    # Within a quarter of the pitch-diameter tolerance the pitch diameter stays in its band:
    # that much is the tuning the paper leaves to #103 / #104.
    if abs(difference) <= c.tolerance / 4.0 + EPS:
        return
    # The formula is a cause only of a cut out of its class.
    verdict = pitch_verdict(thread)
    if verdict is None or not verdict.side:
        return
    k = "6H/8" if thread.internal else "7H/8"
    r = thread.nose_radius
    tool = (
        tr("nose radius {radius:.4g}", radius=r)
        if r is not None
        else tr("the theoretical nose radius")
    )
    cause = _formula_cause(thread)
    line = module.height_line
    related = thread_related(thread)
    if not cause:
        wrong_input = _input_cause(thread)
        if wrong_input is not None:
            # The formula is the paper's: the value fed to it is what to correct.
            cause, input_var = wrong_input
            facts = ctx.doc_facts()
            value = module.inputs.get(input_var)
            writes = writes_in_document(facts, input_var, value) if facts is not None else []
            if writes:
                related = [
                    Related(
                        module.height_line,
                        0,
                        0,
                        tr("#{var} computed here", var=module.height_var),
                    ),
                    *related,
                ]
                line = writes[-1]
    formula = f"{k} − r + EI/2 + TD2/4" if thread.internal else f"{k} − r + es/2 + Td2/4"
    low, high = verdict.limits
    cut = verdict.least if (verdict.side == "tight") != bool(thread.internal) else verdict.greatest
    said: dict[str, object] = {
        "var": module.height_var,
        "height": module.height,
        "difference": abs(difference),
        "expected": expected,
        "thread": thread.name,
        "nose": tool,
        "formula": formula,
        "cut": cut,
        "low": low,
        "high": high,
    }
    height = (
        tr(
            "thread height #{var} = {height:.4f} (radius) is {difference:.3f} mm deeper than "
            "the {expected:.4f} that {thread} needs with {nose} ({formula}); the passes cut a "
            "pitch diameter of {cut:.3f}, outside {low:.3f}–{high:.3f}",
            **said,
        )
        if difference > 0
        else tr(
            "thread height #{var} = {height:.4f} (radius) is {difference:.3f} mm shallower "
            "than the {expected:.4f} that {thread} needs with {nose} ({formula}); the passes "
            "cut a pitch diameter of {cut:.3f}, outside {low:.3f}–{high:.3f}",
            **said,
        )
    )
    source = thread.known_from()
    yield make(
        MB808,
        tr(
            "{height} ({cause}); thread known from {source}",
            height=height,
            cause=cause,
            source=source,
        )
        if cause
        else tr("{height}; thread known from {source}", height=height, source=source),
        line,
        0,
        width(ctx, line),
        related=related,
    )


def _input_cause(thread: Thread) -> tuple[str, int] | None:
    """A module input whose value is not the class's (a Td2 typed 0.70 for 0.170)."""
    module, c = thread.module, thread.pitch_class
    if module is None or c is None or thread.designation is None:
        return None
    es_name, tol_name = ("EI", "TD2") if thread.internal else ("es", "Td2")
    for var, want, name in (
        (thread.deviation_var, abs(c.deviation), es_name),
        (thread.tolerance_var, c.tolerance, tol_name),
    ):
        if var is None:
            continue
        value = module.inputs.get(var)
        if value is not None and abs(abs(value) - want) > c.tolerance / 4.0:
            said = tr(
                "#{var} = {value:g} where {thread}'s {name} is {want:g}",
                var=var,
                value=value,
                thread=thread.name,
                name=name,
                want=want,
            )
            return said, var
    return None


def _formula_cause(thread: Thread) -> str:
    """Which term of the height's formula differs from Deng Ronggang's."""
    module = thread.module
    if module is None or module.height_form is None or thread.pitch is None:
        return ""
    form = module.height_form
    causes: list[str] = []
    if module.pitch_var is not None:
        k = (6.0 if thread.internal else 7.0) / 8.0 * SIN60
        got = form.coefficient(module.pitch_var)
        if abs(got - k) > 1e-4:
            causes.append(
                tr(
                    "#{var} (P) is taken ×{got:.4g} where {want:.4g} belongs",
                    var=module.pitch_var,
                    got=got,
                    want=k,
                )
            )
        value = module.pitch
        if value is not None and abs(value - thread.pitch) > 1e-6:
            causes.append(
                tr(
                    "#{var} = {value:g} is the lead, the pitch is {pitch:g}",
                    var=module.pitch_var,
                    value=value,
                    pitch=thread.pitch,
                )
            )
    for var, want, name in (
        (thread.deviation_var, 0.5, "es/2" if not thread.internal else "EI/2"),
        (thread.tolerance_var, 0.25, "Td2/4" if not thread.internal else "TD2/4"),
        (module.radius_var, -1.0, "− r"),
    ):
        if var is None:
            continue
        got = form.coefficient(var)
        if abs(got - want) > 1e-6:
            causes.append(
                tr(
                    "#{var} is taken ×{got:.4g} where the formula has {term}",
                    var=var,
                    got=got,
                    term=name,
                )
            )
    return in_turn(causes)


MB809_DOC = RuleDoc(
    "MB809",
    reports="""
A thread module whose height adds the fundamental deviation (es, or EI)
with a coefficient of +1/2, fed with a signed value that makes the thread shallower: es
entered as ISO 965-1 writes it (`#103=-0.048`) where the module expects its magnitude (seed
paper 000, table 2: `0.048` for es = −0.048), or a negative EI, which no internal class has. It
stands at the assignment of the value.
""",
    why="""
The height loses |es| instead of gaining it: the thread is
cut |es| (radius) shallower than its class, its pitch diameter stays above d2 max and the ring
gauge does not go on.
""",
    example="""
```nc
O4003 (M30X2-6G)
G97 S600 M03
G00 X32. Z5.
#100=30.
#101=2.
#103=-0.038
#104=0.170
M98 P3003
M30
O3003
#3=#101/[8*SIN[60]]
#4=[7./8.]*SIN[60]*#101-#3+#103/2.+#104/4.
#9=0.15
N10 G92 X[#100-2.*#9] Z-30. F#101
#9=#9+0.15
IF[#9LT#4]GOTO10
G92 X[#100-2.*#4] Z-30. F#101
M99
```
""",
    fix="""
Enter the magnitude (`#103=0.038`), or change the module to subtract es
(`-#103/2.`) if signed values are the shop's habit.
""",
    not_reported="""
A module that takes es with its sign (`-#103/2.` fed
`-0.048`): the height is right. When this rule fires, MB808 is not reported for the same
thread.
""",
)


def _deviation_sign(ctx: RuleContext, thread: Thread) -> Iterator[Diagnostic]:
    module = thread.module
    facts = ctx.doc_facts()
    var = thread.deviation_var
    if module is None or var is None or module.height_form is None or facts is None:
        return
    value = module.inputs.get(var)
    coefficient = module.height_form.coefficient(var)
    if value is None or value == 0.0 or coefficient * value >= 0.0:
        return
    lines = writes_in_document(facts, var, value)
    line = lines[-1] if lines else module.height_line
    if line is None:
        return
    name = "EI" if thread.internal else "es"
    shallower = abs(2.0 * coefficient * value)
    yield make(
        MB809,
        tr(
            "#{var} = {value:g} enters the height #{height_var} as {name} with its sign, but the "
            "module adds {name} as a magnitude ({paper}, table 2: 0.048 for es = −0.048): the "
            "thread comes out {shallower:.3f} mm (radius) shallower than {thread} needs; enter "
            "{magnitude:g}",
            var=var,
            value=value,
            height_var=module.height_var,
            name=name,
            paper=DENG_MOLYBDENUM.by,
            shallower=shallower,
            thread=thread.name,
            magnitude=abs(value),
        ),
        line,
        0,
        width(ctx, line),
        related=[]
        if module.height_line is None
        else [Related(module.height_line, 0, 0, tr("#{var} added to the height here", var=var))],
    )
