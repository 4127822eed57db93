"""The threads a run cuts: executed threading passes grouped into jobs, one job a thread.

A job is the series of threading passes (``G32``, ``G92``, ``G76``: every pass the evaluator
ran, a modal ``G92`` repeat and each pass of a ``G76`` included) that one execution of one
program makes over the same stretch of Z. Another call of the program is another job (the same
module cuts a second thread with other inputs), and so is a series over another stretch of Z.
Cycles and single cuts (``G32``) are not mixed.

What the cuts alone tell of the thread, in the first place of trust: the lead (their ``F``),
the side (an external thread is cut towards the axis, an internal one away from it), the X
range of the passes and where each cycle starts.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property

from ..evaluator.facts import Motion

THREAD_CODES = frozenset({"G32", "G33", "G34", "G76", "G92"})
CYCLES = frozenset({"G76", "G92"})


@dataclass
class ThreadJob:
    uri: str
    program_line: int  # first line of the program that cuts it
    program: str  # O3331
    run: int
    passes: list[Motion] = field(default_factory=list)
    after: list[Motion | None] = field(default_factory=list)  # the motion after each pass
    internal: bool | None = None  # from the cuts alone
    side_reason: str = ""

    @property
    def is_cycle(self) -> bool:
        return self.passes[0].code in CYCLES

    @property
    def code(self) -> str:
        return Counter(m.code for m in self.passes).most_common(1)[0][0]

    @cached_property
    def lead(self) -> float | None:
        """The F of most passes: the lead the thread is cut with."""
        feeds = Counter(m.words.get("F") for m in self.passes if m.words.get("F") is not None)
        return feeds.most_common(1)[0][0] if feeds else None

    @cached_property
    def xs(self) -> list[float]:
        return [m.x for m in self.passes if m.x is not None]

    def deepest(self, internal: bool) -> Motion:
        cut = [m for m in self.passes if m.x is not None]
        return (max if internal else min)(cut, key=lambda m: m.x or 0.0)

    def shallowest(self, internal: bool) -> Motion:
        cut = [m for m in self.passes if m.x is not None]
        return (min if internal else max)(cut, key=lambda m: m.x or 0.0)

    def lines(self) -> list[int]:
        return sorted({m.line for m in self.passes})


def _span(m: Motion) -> tuple[float, float] | None:
    if m.z is None or m.start_z is None:
        return None
    return (min(m.z, m.start_z), max(m.z, m.start_z))


def _overlaps(a: tuple[float, float] | None, b: tuple[float, float] | None) -> bool:
    """Whether two stretches of Z are the same thread's: they share a quarter of the shorter."""
    if a is None or b is None:
        return True
    common = min(a[1], b[1]) - max(a[0], b[0])
    shorter = min(a[1] - a[0], b[1] - b[0])
    return common >= 0.25 * shorter - 1e-9


def _side_of_cuts(job: ThreadJob) -> tuple[bool | None, str]:
    xs = job.xs
    if not xs:
        return None, ""
    if job.is_cycle:
        distinct = sorted(set(xs))
        if len(distinct) >= 2:
            third = max(1, len(xs) // 3)
            early = sum(xs[:third]) / third
            late = sum(xs[-third:]) / third
            if late != early:
                inward = late < early
                return (
                    not inward,
                    "the passes go "
                    + ("deeper towards the axis" if inward else "deeper away from the axis"),
                )
        start = job.passes[0].start_x
        if start is not None and start != xs[0]:
            return start < xs[0], f"the cycle starts at X{start:g}, on the {_side(start, xs[0])}"
        return None, ""
    # Single cuts: each is left by a retract away from the material.
    votes = Counter(
        after.x > m.x
        for m, after in zip(job.passes, job.after, strict=True)
        if after is not None and after.x is not None and m.x is not None and after.x != m.x
    )
    if votes:
        outward, count = votes.most_common(1)[0]
        if count * 2 > sum(votes.values()):
            return not outward, "each cut retracts " + ("outwards" if outward else "inwards")
    return None, ""


def _side(start: float, x: float) -> str:
    return "outside of the cut" if start > x else "axis side of the cut"


def thread_jobs(motions: Sequence[Motion], uri: str) -> list[ThreadJob]:
    """The threading jobs of ``uri``'s programs, in the order the run cut them."""
    jobs: list[ThreadJob] = []
    current: dict[tuple[int, bool], ThreadJob] = {}
    spans: dict[int, tuple[float, float] | None] = {}
    for i, m in enumerate(motions):
        if m.code not in THREAD_CODES or m.uri != uri:
            continue
        key = (m.run, m.code in CYCLES)
        job = current.get(key)
        span = _span(m)
        if job is None or not _overlaps(spans[id(job)], span):
            job = ThreadJob(m.uri, m.program_line, m.program, m.run)
            jobs.append(job)
            current[key] = job
            spans[id(job)] = span
        elif span is not None:
            old = spans[id(job)]
            spans[id(job)] = span if old is None else (min(old[0], span[0]), max(old[1], span[1]))
        job.passes.append(m)
        # Single cuts tell their side by the retract after them; cycles do not need it.
        job.after.append(None if key[1] else _next_motion(motions, i))
    for job in jobs:
        job.internal, job.side_reason = _side_of_cuts(job)
    return jobs


def _next_motion(motions: Sequence[Motion], i: int) -> Motion | None:
    run = motions[i].run
    for m in motions[i + 1 : i + 4]:
        if m.run == run:
            return m
    return None
