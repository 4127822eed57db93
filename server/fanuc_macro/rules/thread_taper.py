"""MB821: a taper thread cut against the cone the program turned for it.

A taper thread (``G92 … R``, ``G76 … R``, or ``G32`` whose X changes along the cut) is cut on
a cone the program itself has turned: the thread's diameter must grow the way the cone's does.
The rule compares the two slopes over the Z both cover; it needs no designation and no idea of
which end of the part is free.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass

from ..diagnostics import Diagnostic, Related, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import Motion
from ..evaluator.values import fmt
from ..threads.identify import Thread
from .context import RuleContext
from .threading import mm, thread_related, width

FAMILY = "threading"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB821 = RuleInfo("MB821", "thread-taper-cone", Severity.ERROR,
                 "A taper thread's taper runs the other way than, or differs from, the cone "
                 "turned for it.", FAMILY)
# fmt: on

# Moves that turn a cone: a feed move, or a turning cycle with its taper R.
CONE_CODES = frozenset({"G01", "G90"})
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


@dataclass(frozen=True, slots=True)
class _Line:
    """A straight cut in the ZX plane: diameter x0 at z0 to x1 at z1."""

    z0: float
    x0: float
    z1: float
    x1: float

    @property
    def slope(self) -> float:
        return (self.x1 - self.x0) / (self.z1 - self.z0)

    def x_at(self, z: float) -> float:
        return self.x0 + self.slope * (z - self.z0)

    @property
    def span(self) -> tuple[float, float]:
        return min(self.z0, self.z1), max(self.z0, self.z1)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    facts = ctx.facts
    if facts is None:
        return
    motions = facts.motions
    for thread in ctx.threads():
        finding = _against_cone(ctx, thread, motions)
        if finding is not None:
            yield finding


def _thread_line(m: Motion) -> _Line | None:
    """The cut of a taper pass, from where it starts to where it ends."""
    if m.x is None or m.z is None or m.start_z is None or m.z == m.start_z:
        return None
    if m.code in ("G92", "G76"):
        r = m.words.get("R")
        if not r:
            return None
        # The cycle cuts from X + 2R at its start Z to X at its end Z (0i-TF "Threading cycle").
        return _Line(m.start_z, m.x + 2.0 * r, m.z, m.x)
    if m.code in ("G32", "G33") and m.start_x is not None and m.start_x != m.x:
        return _Line(m.start_z, m.start_x, m.z, m.x)
    return None


def _cone_line(m: Motion) -> _Line | None:
    if m.code not in CONE_CODES or m.x is None or m.z is None:
        return None
    if m.start_x is None or m.start_z is None or m.z == m.start_z:
        return None
    if m.code == "G90":
        r = m.words.get("R")
        return _Line(m.start_z, m.x + 2.0 * r, m.z, m.x) if r else None
    if m.x == m.start_x:
        return None
    return _Line(m.start_z, m.start_x, m.z, m.x)


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
    tapered_at = job.remember(
        "taper lines",
        lambda: tuple(k for k, m in enumerate(passes) if _thread_line(m) is not None),
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
    for m in motions:
        if m is first:
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
            verdict = "the thread tapers the other way" + (
                "; R's sign is wrong" if word is not None else ""
            )
        elif abs(a / b) > SAME_TAPER or abs(b / a) > SAME_TAPER:
            verdict = (
                f"the thread's taper is {abs(a / b):.2g} times the cone's: one end is cut "
                "deeper than the other"
            )
        else:
            continue
        what = f"{taper_pass.shown} R{fmt(word)}" if word is not None else taper_pass.shown
        return make(
            MB821,
            f"{what} cuts the thread from X{mm(cut.x0)} at Z{mm(cut.z0)} to X{mm(cut.x1)} at "
            f"Z{mm(cut.z1)} ({_per_length(a)}), but the cone turned for it at line "
            f"{m.line + 1} runs from X{mm(cone.x0)} at Z{mm(cone.z0)} to X{mm(cone.x1)} at "
            f"Z{mm(cone.z1)} ({_per_length(b)}): {verdict}",
            taper_pass.line,
            0,
            width(ctx, taper_pass.line),
            related=[
                Related(m.line, 0, 0, "the cone the thread is cut on"),
                *thread_related(thread),
            ],
        )
    return None


def _per_length(slope: float) -> str:
    """A taper as the diameter's change per unit of Z towards -Z."""
    grows = -slope
    return f"diameter {'+' if grows > 0 else '−'}{abs(grows):.4f} per unit towards −Z"
