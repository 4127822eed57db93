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

from bisect import bisect_left
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, fields
from operator import attrgetter
from typing import TypeVar

from ..database import TableKey
from ..database import current as current_database
from ..evaluator.facts import Motion, same_value
from ..line_maps import Diff, Kept
from ..translation import tr

R = TypeVar("R")

THREAD_CODES = frozenset({"G32", "G33", "G34", "G76", "G92"})
CYCLES = frozenset({"G76", "G92"})


@dataclass(eq=False, repr=False)
class ThreadJob:
    """A job's passes are not changed once it is made: a later analysis whose run cuts the
    same passes takes the same job, with what its rules found of them (:meth:`remember`)."""

    uri: str
    program_line: int  # first line of the program that cuts it
    program: str  # O3331
    run: int
    passes: list[Motion] = field(default_factory=list)
    after: list[Motion | None] = field(default_factory=list)  # the motion after each pass
    internal: bool | None = None  # from the cuts alone
    side_reason: str = ""
    # What was worked out of the passes alone (and of the settings named in the key).
    memo: dict[object, object] = field(default_factory=dict, compare=False, repr=False)
    # The job this one is a copy of with a few passes replaced (their indexes): what was
    # worked out of the earlier job holds for this one when the replaced passes agree on
    # what it was worked out of (see remember). Kept until the next copy is made of this one.
    basis: tuple[ThreadJob, tuple[int, ...]] | None = field(default=None, compare=False, repr=False)
    # Of the basis, once asked: the fields in which the replaced passes differ (a word by its
    # letter), and the new pass for each old one, by id.
    _inherited: tuple[frozenset[str], dict[int, Motion]] | None = field(
        default=None, init=False, compare=False, repr=False
    )

    def remember(self, key: object, compute: Callable[[], R], reads: Reads = None) -> R:
        """``compute()``, a function of the passes and of what ``key`` names, once per job.

        ``reads`` names every field of a pass that ``compute`` decides by (a motion's
        attribute, or ``"F"`` for one of its words): a copy of a job with other passes in a
        few places then takes the earlier job's result when those passes agree with the ones
        they replace on these fields, the replaced passes in it swapped for the new ones (what
        ``compute`` gives the copy, since it returns passes but decides by those fields)."""
        memo = self.memo
        if key in memo:
            return memo[key]  # type: ignore[return-value]
        basis = self.basis
        if reads is not None and basis is not None and key in basis[0].memo:
            differing, swaps = self._inheritance(basis)
            if differing.isdisjoint(reads):
                swapped = _swapped(basis[0].memo[key], swaps)
                if swapped is not _UNSWAPPABLE:
                    memo[key] = swapped
                    return swapped  # type: ignore[return-value]
        found = memo[key] = compute()
        return found

    def _inheritance(
        self, basis: tuple[ThreadJob, tuple[int, ...]]
    ) -> tuple[frozenset[str], dict[int, Motion]]:
        found = self._inherited
        if found is None:
            old, changed = basis
            differing: set[str] = set()
            for n in changed:
                differing |= _differing(old.passes[n], self.passes[n])
            swaps = {id(old.passes[n]): self.passes[n] for n in changed}
            found = self._inherited = (frozenset(differing), swaps)
        return found

    @property
    def is_cycle(self) -> bool:
        return self.passes[0].code in CYCLES

    @property
    def code(self) -> str:
        return self.remember(
            "code", lambda: Counter(m.code for m in self.passes).most_common(1)[0][0], ("code",)
        )

    @property
    def shown(self) -> str:
        """``code`` as the program writes it (a system B or C lathe's own number): what a
        message names."""
        code = self.code
        return next((m.shown for m in self.passes if m.code == code), code)

    @property
    def lead(self) -> float | None:
        """The F of most passes: the lead the thread is cut with."""
        return self.remember("lead", self._lead, ("F",))

    def _lead(self) -> float | None:
        feeds = Counter(f for m in self.passes if (f := m.words.get("F")) is not None)
        return feeds.most_common(1)[0][0] if feeds else None

    @property
    def xs(self) -> list[float]:
        return self.remember("xs", lambda: [m.x for m in self.passes if m.x is not None], ("x",))

    @property
    def x_range(self) -> tuple[float, float]:
        """The least and the greatest X of the passes (there is one)."""
        return self.remember("x range", lambda: (min(self.xs), max(self.xs)), ("x",))

    @property
    def taper(self) -> Motion | None:
        """The first pass with a taper (R)."""
        return self.remember(
            "taper", lambda: next((m for m in self.passes if m.words.get("R")), None), ("R",)
        )

    def deepest(self, internal: bool) -> Motion:
        return self.remember(
            ("deepest", internal), lambda: self._extreme(max if internal else min), ("x",)
        )

    def shallowest(self, internal: bool) -> Motion:
        return self.remember(
            ("shallowest", internal), lambda: self._extreme(min if internal else max), ("x",)
        )

    def _extreme(self, which: Callable[..., Motion]) -> Motion:
        cut = [m for m in self.passes if m.x is not None]
        return which(cut, key=lambda m: m.x or 0.0)

    def lines(self) -> list[int]:
        return sorted({m.line for m in self.passes})


Reads = tuple[str, ...] | None
_UNSWAPPABLE = object()


def _differing(a: Motion, b: Motion) -> set[str]:
    """The fields in which two motions differ, a word by its letter (0.0 and -0.0 differ)."""
    out: set[str] = set()
    if a is b:
        return out
    for name, x, y in zip(_MOTION_FIELDS, _fields_of(a), _fields_of(b), strict=True):
        if x is y:
            continue
        if name == "words":
            assert isinstance(x, dict) and isinstance(y, dict)
            out.update(k for k in x.keys() | y.keys() if not same_value(x.get(k), y.get(k)))
        elif not same_value(x, y):
            out.add(name)
    return out


_LEAVES = frozenset({Motion, float, int, str, bool, type(None)})


def _swapped(value: object, passes: dict[int, Motion]) -> object:
    """``value`` with the motions in ``passes`` (by id) replaced; _UNSWAPPABLE when it holds
    something this does not look into. A list or tuple of leaves without such a motion is
    ``value`` itself (what was worked out is not changed afterwards), and so is a value whose
    class says it holds no motion (``HOLDS_NO_MOTION``: passes by their index)."""
    if isinstance(value, Motion):
        return passes.get(id(value), value)
    if value is None or isinstance(value, bool | int | float | str):
        return value
    if getattr(type(value), "HOLDS_NO_MOTION", False):
        return value
    if isinstance(value, tuple | list):
        kinds = set(map(type, value))  # in C: most results are long lists of one kind
        if kinds <= _LEAVES:
            if Motion not in kinds or passes.keys().isdisjoint(map(id, value)):
                return value
            swapped = [passes.get(id(item), item) for item in value]
            return tuple(swapped) if isinstance(value, tuple) else swapped
        out = [_swapped(item, passes) for item in value]
        if any(item is _UNSWAPPABLE for item in out):
            return _UNSWAPPABLE
        return tuple(out) if isinstance(value, tuple) else out
    return _UNSWAPPABLE


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
                    tr("the passes go deeper towards the axis")
                    if inward
                    else tr("the passes go deeper away from the axis"),
                )
        start = job.passes[0].start_x
        if start is not None and start != xs[0]:
            return start < xs[0], _side(start, xs[0])
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
            return not outward, (
                tr("each cut retracts outwards") if outward else tr("each cut retracts inwards")
            )
    return None, ""


def _side(start: float, x: float) -> str:
    """Where the cycle starts, for a message."""
    if start > x:
        return tr("the cycle starts at X{start:g}, on the outside of the cut", start=start)
    return tr("the cycle starts at X{start:g}, on the axis side of the cut", start=start)


def thread_jobs(motions: Sequence[Motion], uri: str) -> list[ThreadJob]:
    """The threading jobs of ``uri``'s programs, in the order the run cut them.

    The jobs of the last run seen are kept: when a later run's threading motions (and the
    retracts after single cuts) are the same records or records of the same values, its jobs
    are those same objects, with what was worked out of their passes (the rules keep what
    they find of a job's passes in :attr:`ThreadJob.memo`)."""
    seen = _seen(motions, uri)
    jobs = seen.jobs
    if jobs is None:
        jobs, seen.owners = _jobs(seen)
        seen.jobs = jobs
    return jobs


def motion_positions(motions: Sequence[Motion], uri: str) -> list[int]:
    """Where in ``motions`` the turning and facing cycles (G90, G94) of ``uri`` are."""
    return _seen(motions, uri).turning


TURNING = frozenset({"G90", "G94"})
# After how many motions a single cut's retract is looked for.
AFTER = 3
# The work done, for the tests of reuse after an edit: "grouped", the threading motions
# grouped into jobs; "compared", the old jobs looked at for a new one.
WORK_DONE: TableKey[str, int] = TableKey("threads.work_done")


def work_done(kind: str) -> int:
    """How much work of ``kind`` ("grouped", "compared") the current database's analyses did."""
    return current_database().table(WORK_DONE).get(kind, 0)


def _count(kind: str, amount: int) -> None:
    work = current_database().table(WORK_DONE)
    work[kind] = work.get(kind, 0) + amount


class _Seen:
    """A run's motions as last seen for one document: where its threading and turning motions
    are, its jobs (once asked for), and the run seen before it (until its jobs are made)."""

    __slots__ = ("base", "copy", "diff", "jobs", "motions", "owners", "threads", "turning")

    def __init__(
        self,
        motions: Sequence[Motion],
        threads: list[int],
        turning: list[int],
        base: _Seen | None = None,
        diff: Diff | None = None,
    ) -> None:
        self.motions = motions
        self.copy = list(motions)  # its items then, whatever becomes of the list
        self.threads = threads
        self.turning = turning
        self.jobs: list[ThreadJob] | None = None
        # For each threading motion (by its place in ``threads``): its job and its pass.
        self.owners: list[tuple[int, int]] = []
        self.base = base
        self.diff = diff


_kept: Kept[_Seen] = Kept()


def _seen(motions: Sequence[Motion], uri: str) -> _Seen:
    kept = _kept.get(uri)
    if kept is not None and kept.motions is motions and kept.copy == motions:
        return kept  # the same run: asked again by another rule
    if kept is None:
        seen = _Seen(
            motions,
            _positions(motions, uri, THREAD_CODES, 0, len(motions)),
            _positions(motions, uri, TURNING, 0, len(motions)),
        )
    else:
        diff = Diff(kept.copy, motions, identical=True)
        # A single cut before the change may take its retract from the changed stretch.
        start = max(0, diff.start - AFTER)
        seen = _Seen(
            motions,
            _spliced(
                kept.threads, diff, start, _positions(motions, uri, THREAD_CODES, start, diff.end)
            ),
            _spliced(kept.turning, diff, start, _positions(motions, uri, TURNING, start, diff.end)),
            None if kept.jobs is None else kept,
            diff,
        )
    _kept.put(uri, seen)
    return seen


def _spliced(old: list[int], diff: Diff, start: int, middle: list[int]) -> list[int]:
    """Old positions before ``start`` and after the change (moved), with ``middle``."""
    tail = old[bisect_left(old, diff.old_end) :]
    if diff.shift:
        tail = [at + diff.shift for at in tail]
    return [*old[: bisect_left(old, start)], *middle, *tail]


Owners = list[tuple[int, int]]


def _jobs(seen: _Seen) -> tuple[list[ThreadJob], Owners]:
    motions, positions, base, diff = seen.copy, seen.threads, seen.base, seen.diff
    seen.base = None  # not kept past the next run
    if base is None or base.jobs is None or diff is None:
        return _group(motions, positions)
    old_motions, old_positions = base.copy, base.threads
    start = max(0, diff.start - AFTER)
    a = bisect_left(old_positions, start)
    b = bisect_left(old_positions, diff.old_end)
    c = bisect_left(positions, start)
    middle = positions[c : c + len(positions) - len(old_positions) + b - a]
    if len(middle) == b - a:
        # The threading motions in the changed stretch, by their place among all of them
        # (the same in both runs: as many before the stretch and in it).
        changed = [
            t
            for t, (i, j) in enumerate(zip(middle, old_positions[a:b], strict=True), start=a)
            if not _same_cut(motions, i, old_motions, j)
        ]
        if not changed:
            return base.jobs, base.owners
        if all(
            _joins_alike(motions[positions[t]], old_motions[old_positions[t]], base, t)
            for t in changed
        ):
            return _patched(base.jobs, base.owners, changed, motions, positions), base.owners
    jobs, owners = _group(motions, positions)
    return _reused(jobs, base.jobs), owners


def _joins_alike(new: Motion, old: Motion, base: _Seen, t: int) -> bool:
    """Whether a pass that changed (the ``t``-th threading motion) joins the job the one it
    replaces joined and leaves the grouping of the passes after it as it was: it groups alike
    (:func:`_groups_alike`), or it is not the first pass of its job, and its stretch of Z and
    the old pass's lie within the stretch of the job's passes before it (both join it, and
    neither widens it)."""
    if _groups_alike(new, old):
        return True
    if not _alike_but_z(new, old):
        return False
    assert base.jobs is not None
    k, n = base.owners[t]
    if n == 0:
        return False
    before: tuple[float, float] | None = None
    for m in base.jobs[k].passes[:n]:
        span = _span(m)
        if span is not None:
            before = span if before is None else (min(before[0], span[0]), max(before[1], span[1]))
    return _within(_span(new), before) and _within(_span(old), before)


def _within(span: tuple[float, float] | None, outer: tuple[float, float] | None) -> bool:
    return span is None or (outer is not None and outer[0] <= span[0] and span[1] <= outer[1])


def _alike_but_z(new: Motion, old: Motion) -> bool:
    return (
        new.run == old.run
        and new.uri == old.uri
        and new.program == old.program
        and new.program_line == old.program_line
        and (new.code in CYCLES) == (old.code in CYCLES)
    )


def _groups_alike(new: Motion, old: Motion) -> bool:
    """Whether a pass that changed joins the job the one it replaces joined, and leaves the
    grouping of the passes after it as it was: the same run, program and kind of cut over the
    same stretch of Z (what :func:`_group` decides by)."""
    return _alike_but_z(new, old) and _span(new) == _span(old)


def _patched(
    jobs: list[ThreadJob],
    owners: Owners,
    changed: list[int],
    motions: Sequence[Motion],
    positions: list[int],
) -> list[ThreadJob]:
    """``jobs`` with the threading motions ``changed`` (their places among all) replaced, when
    each groups as the one it replaces (:func:`_groups_alike`): the jobs without a changed
    pass are the same objects, the others copies with the new passes (and retracts after
    them)."""
    _count("grouped", len(changed))
    copies: dict[int, ThreadJob] = {}
    for t in changed:
        i = positions[t]
        k, n = owners[t]
        job = copies.get(k)
        if job is None:
            old = jobs[k]
            job = copies[k] = ThreadJob(
                old.uri, old.program_line, old.program, old.run, list(old.passes), list(old.after)
            )
            old.basis = None  # no chain of copies: one earlier job at most
            job.basis = (old, ())
        m = job.passes[n] = motions[i]
        job.after[n] = None if m.code in CYCLES else _next_motion(motions, i)
        assert job.basis is not None
        job.basis = (job.basis[0], (*job.basis[1], n))
    out = list(jobs)
    for k, job in copies.items():
        job.internal, job.side_reason = _side_of_cuts(job)
        out[k] = job
    return out


def _positions(
    motions: Sequence[Motion], uri: str, codes: frozenset[str], start: int, end: int
) -> list[int]:
    return [
        i
        for i in range(start, end)
        if (m := motions[i]).code in codes and m.uri == uri and not m.drilling
    ]


def _same_cut(new: Sequence[Motion], i: int, old: Sequence[Motion], j: int) -> bool:
    """Whether two threading motions are the same cut and, a single cut, have the same
    retract after them."""
    a, b = new[i], old[j]
    if not same_motion(a, b):
        return False
    if a.code in CYCLES:
        return True
    after_a, after_b = _next_motion(new, i), _next_motion(old, j)
    if after_a is None or after_b is None:
        return after_a is after_b
    return same_motion(after_a, after_b)


_MOTION_FIELDS = tuple(f.name for f in fields(Motion))
_fields_of = attrgetter(*_MOTION_FIELDS)


def same_motion(a: Motion, b: Motion) -> bool:
    """The same record, or one of the same values (0.0 and -0.0 differ: they print apart)."""
    if a is b:
        return True
    if a != b:
        return False
    if 0.0 not in (a.x, a.z, a.start_x, a.start_z, a.rpm) and 0.0 not in a.words.values():
        return True  # equal, and no zero whose sign could differ
    return all(same_value(getattr(a, f), getattr(b, f)) for f in _MOTION_FIELDS)


def _start_key(job: ThreadJob) -> tuple[object, ...]:
    """What two jobs of the same passes have alike, their first pass's place included: a
    program of many one-pass jobs (a chain of G32 segments) has as many keys as jobs."""
    first = job.passes[0] if job.passes else None
    place = () if first is None else (first.line, first.x, first.z, first.start_x, first.start_z)
    return (job.program_line, job.run, len(job.passes), *place)


def _reused(jobs: list[ThreadJob], old_jobs: list[ThreadJob]) -> list[ThreadJob]:
    """``jobs``, each one of ``old_jobs`` cut by the same passes taken in its stead."""
    by_start: dict[tuple[object, ...], list[ThreadJob]] = {}
    for old in old_jobs:
        by_start.setdefault(_start_key(old), []).append(old)
    out: list[ThreadJob] = []
    looked_at = 0
    for job in jobs:
        candidates = by_start.get(_start_key(job), ())
        looked_at += len(candidates)
        same = next(
            (
                old
                for old in candidates
                if old.uri == job.uri
                and old.program == job.program
                and all(map(same_motion, job.passes, old.passes))
                and all(
                    a is b or (a is not None and b is not None and same_motion(a, b))
                    for a, b in zip(job.after, old.after, strict=True)
                )
            ),
            None,
        )
        out.append(job if same is None else same)
    _count("compared", looked_at)
    return out


def _group(motions: Sequence[Motion], positions: list[int]) -> tuple[list[ThreadJob], Owners]:
    """The threading motions at ``positions`` grouped into jobs, and the job and pass of each."""
    _count("grouped", len(positions))
    jobs: list[ThreadJob] = []
    owners: Owners = []
    current: dict[tuple[int, bool], tuple[ThreadJob, int]] = {}
    spans: dict[int, tuple[float, float] | None] = {}
    for i in positions:
        m = motions[i]
        key = (m.run, m.code in CYCLES)
        found = current.get(key)
        span = _span(m)
        if found is None or not _overlaps(spans[id(found[0])], span):
            job = ThreadJob(m.uri, m.program_line, m.program, m.run)
            found = current[key] = (job, len(jobs))
            jobs.append(job)
            spans[id(job)] = span
        else:
            job = found[0]
            if span is not None:
                old = spans[id(job)]
                spans[id(job)] = (
                    span if old is None else (min(old[0], span[0]), max(old[1], span[1]))
                )
        owners.append((found[1], len(job.passes)))
        job.passes.append(m)
        # Single cuts tell their side by the retract after them; cycles do not need it.
        job.after.append(None if key[1] else _next_motion(motions, i))
    for job in jobs:
        job.internal, job.side_reason = _side_of_cuts(job)
    return jobs, owners


def _next_motion(motions: Sequence[Motion], i: int) -> Motion | None:
    run = motions[i].run
    for m in motions[i + 1 : i + 1 + AFTER]:
        if m.run == run:
            return m
    return None
