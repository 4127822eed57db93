"""Checkpoints of a run, and resuming a run after an edit instead of running it all again.

When each program of the evaluation begins, and then at the first block of a boundary line
once ``CHECKPOINT_EVERY`` blocks have run since the last checkpoint (boundary lines are chosen by
their text, so the checkpoints mostly fall on the same blocks in runs that executed more or
fewer blocks before them; a resumed run also takes one at each boundary line where the
earlier run has a checkpoint it may meet, so that the two meet even where the count puts
their own checkpoints apart), the machine records its state (the call stack with each level's locals
and place, the variables the run set, the modal state, what it has found so far) and begins
a new stretch of facts. After an edit the evaluation resumes from the checkpoint before the
first stretch that ran a changed line, with the new program, and stops as soon as its state
equals the earlier run's at one of the earlier run's checkpoints after which no changed line
ran: from there on the earlier run's stretches are the new run's, their block counts moved by
the blocks the edit added or removed (:mod:`.line_shift` renumbers the record after an edit
that added or removed lines). The run is deterministic, so the result equals a full
run's (the tests compare them after random edits); resuming only saves the blocks before the
edit and after the point where the change no longer shows.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from itertools import pairwise
from operator import itemgetter
from typing import TYPE_CHECKING

from ..config import Config
from ..program.index import Loop
from ..syntax.diff import Diff, common_prefix, common_suffix, line_diff
from ..syntax.tree import Document
from .facts import DocumentFacts, Facts, same_value
from .machine_setup import Setup

if TYPE_CHECKING:
    from .machine import CompiledLine
from .values import Value

CtxKey = tuple[str, int]  # a program: its document and its first line


@dataclass(frozen=True, slots=True, eq=False, repr=False)
class LevelState:
    """One running program of the call stack (an ``Activation``)."""

    ctx: CtxKey
    locals: tuple[Value, ...]
    shares_locals_with_caller: bool  # M98: the same #1-#33 as the level below
    pc: int
    macro_level: int
    return_pc: int
    repeats_left: int
    serial: int
    arguments: tuple[Value, ...] | None
    undecided_loops: frozenset[int]
    loops_turning: frozenset[int]
    modal_depth: int | None


@dataclass(frozen=True, slots=True, eq=False, repr=False)
class ModalState:
    motion: float | None
    feed: Value
    speed: Value
    constant_surface_speed: bool
    modal_calls: tuple[tuple[CtxKey | None, tuple[Value, ...], int], ...]
    position: tuple[tuple[str, Value], ...]
    position_line: tuple[tuple[str, tuple[str, int]], ...]
    inch: bool
    g76: object  # G76Parameters: frozen
    cycle: tuple[float | None, float | None]  # G90/G92/G94's end Z and R in force
    incremental: bool  # G91 of a lathe in G code system B or C
    spindle: str
    spindle_stop: tuple[str, int, str] | None
    z_at_top: bool
    setup: Setup  # frozen
    drilling: tuple[float, float | None] | None


@dataclass(frozen=True, slots=True, eq=False, repr=False)
class MachineState:
    """The machine before a block: everything the rest of the evaluation depends on."""

    run: int  # which run of the evaluation (its place in the sequence of entry programs)
    done: int  # blocks that run has executed
    levels: tuple[LevelState, ...]  # the entry program first
    store: dict[int, Value]
    modal: ModalState
    speculative: bool
    activations: int  # programs entered so far (each call's serial number)
    # The findings reported so far (kind, document, line, column), in chunks: each checkpoint
    # adds those found since the one before and shares the earlier chunks with it, so that a
    # run's checkpoints hold each key once (a whole set per checkpoint grows with their square).
    seen_findings: tuple[frozenset[tuple[str, str, int, int]], ...]
    motions: int  # motion records so far
    run_values: tuple[int, ...]  # the serials whose variables were kept, in order
    findings: tuple[tuple[str, int], ...]  # per document: findings so far
    analysed: tuple[tuple[str, frozenset[int]], ...]  # per document: programs run so far
    # Per document: the assumed arguments, (program, ((local, line of its first read), ...)).
    assumed: tuple[tuple[str, tuple[tuple[int, tuple[tuple[int, int], ...]], ...]], ...]
    # Blocks of G70-G73 profiles read or run so far in the run (their own budget: see
    # Machine._profile_budget).
    profile_blocks: int = 0

    def meeting_key(self) -> tuple[object, ...]:
        """What two states that may be the same have alike, whatever their counts of blocks
        and motions: a resumed run that ran more or fewer blocks (an edit added or removed
        some), or recorded more or fewer motions (a block that moved no longer does, as while
        a bracket is being typed), meets the earlier run at a state equal but for the counts."""
        return (
            self.run,
            self.levels[-1].pc if self.levels else -1,
            len(self.levels),
            self.activations,
            self.findings,
            len(self.store),
        )

    def same_as(self, other: MachineState, counted: bool = True) -> bool:
        """Equal, value for value (``counted``: the blocks done and the motions too)."""
        return (
            self.run == other.run
            and (not counted or (self.done == other.done and self.motions == other.motions))
            and self.speculative == other.speculative
            and self.activations == other.activations
            and self.run_values == other.run_values
            and self.findings == other.findings
            and self.analysed == other.analysed
            and _same_keys(self.seen_findings, other.seen_findings)
            and self.assumed == other.assumed
            and self.profile_blocks == other.profile_blocks
            and len(self.levels) == len(other.levels)
            and all(_same_level(a, b) for a, b in zip(self.levels, other.levels, strict=True))
            and _same_modal(self.modal, other.modal)
            and same_value(self.store, other.store)
        )


FindingKeys = tuple[frozenset[tuple[str, str, int, int]], ...]


def _same_keys(a: FindingKeys, b: FindingKeys) -> bool:
    """Whether two chunked sets of finding keys hold the same keys (chunks are disjoint)."""
    if a == b:
        return True
    if sum(map(len, a)) != sum(map(len, b)):
        return False
    return set().union(*a) == set().union(*b)


def _same_level(a: LevelState, b: LevelState) -> bool:
    return (
        a.ctx == b.ctx
        and a.pc == b.pc
        and a.shares_locals_with_caller == b.shares_locals_with_caller
        and a.macro_level == b.macro_level
        and a.return_pc == b.return_pc
        and a.repeats_left == b.repeats_left
        and a.serial == b.serial
        and a.undecided_loops == b.undecided_loops
        and a.loops_turning == b.loops_turning
        and a.modal_depth == b.modal_depth
        and same_value(a.locals, b.locals)
        and same_value(a.arguments, b.arguments)
    )


def _same_modal(a: ModalState, b: ModalState) -> bool:
    return (
        a.motion == b.motion
        and a.constant_surface_speed == b.constant_surface_speed
        and a.inch == b.inch
        and a.g76 == b.g76
        and a.cycle == b.cycle
        and a.incremental == b.incremental
        and a.spindle == b.spindle
        and a.spindle_stop == b.spindle_stop
        and a.z_at_top == b.z_at_top
        and a.setup == b.setup
        and a.drilling == b.drilling
        and a.position_line == b.position_line
        and same_value(a.feed, b.feed)
        and same_value(a.speed, b.speed)
        and same_value(a.position, b.position)
        and len(a.modal_calls) == len(b.modal_calls)
        and all(
            x[0] == y[0] and x[2] == y[2] and same_value(x[1], y[1])
            for x, y in zip(a.modal_calls, b.modal_calls, strict=True)
        )
    )


@dataclass(frozen=True, slots=True)
class ProgramShape:
    """What the machine reads of a program besides its lines' code: its number and name,
    where it begins and ends, its labels, loops, jumps and calls, and whether it ends the run
    (M30). Spans and argument words are left out: the lines' code stands for them."""

    key: CtxKey
    number: int | None
    name: str
    end_line: int
    labels: tuple[tuple[int, tuple[int, ...]], ...]
    loops: tuple[Loop, ...]  # frozen, no spans
    jumps: tuple[tuple[int, int | None, bool], ...]  # line, target, conditional
    calls: tuple[tuple[int, str, int | None], ...]  # line, kind, program
    is_main: bool
    program_end: int | None


@dataclass(eq=False, repr=False)
class RunRecord:
    """What an evaluation leaves for the next one to resume from."""

    settings: tuple[Config, str | None, int | None]  # config, only_uri, entry
    documents: tuple[tuple[str, Document], ...]
    shapes: tuple[ProgramShape, ...]
    # The locals each program run as an entry reads before it sets them (its run begins
    # with them unknown), by program.
    read_first: dict[CtxKey, tuple[tuple[int, int], ...]] = field(default_factory=dict)
    lines: dict[str, list[CompiledLine]] = field(default_factory=dict)  # compiled, by document
    checkpoints: list[MachineState] = field(default_factory=list)
    # Stretch i: the facts of the blocks from checkpoint i to checkpoint i + 1, by document.
    segments: list[dict[str, DocumentFacts]] = field(default_factory=list)
    # Per run of the evaluation: its place in the sequence, why it ended, blocks executed.
    results: list[tuple[int, str, int]] = field(default_factory=list)
    executed: int = 0  # blocks this evaluation ran itself (the rest it took from the earlier)
    # After an edit that added or removed lines, the record renumbered (see .line_shift): its
    # documents whose lines moved, the stretches that ran a line of the edit, the checkpoints
    # whose state names one.
    shifted: frozenset[str] = frozenset()
    touched: frozenset[int] = frozenset()
    unusable: frozenset[int] = frozenset()
    resumed_at: tuple[int, int] | None = None  # (run, blocks done) it resumed from
    converged_at: tuple[int, int] | None = None  # where it met the earlier run


@dataclass(frozen=True, eq=False, repr=False)
class Resumption:
    """Where a new evaluation picks up an earlier one."""

    previous: Facts
    record: RunRecord
    start: int  # the checkpoint to resume from
    # Checkpoints the new run may meet, by their meeting key: the indexes, earliest first.
    convergeable: dict[tuple[object, ...], list[int]]
    # Where those are (the running program and its next line): a resumed run looks for the
    # earlier run there too, not only where its own count of blocks puts a checkpoint. An edit
    # that adds or removes blocks moves that count, and where boundary lines are dense (a
    # program of few distinct lines) the two runs' checkpoints could stay apart for good.
    meet_at: frozenset[tuple[CtxKey, int]] = frozenset()


def changed_lines(
    old: Sequence[tuple[str, Document]], new: Sequence[tuple[str, Document]]
) -> dict[str, set[int]] | None:
    """The lines whose text differs between two versions of the same documents; None when
    the documents are not the same ones or a line count changed (a full run follows)."""
    if len(old) != len(new):
        return None
    changed: dict[str, set[int]] = {}
    for (old_uri, a), (new_uri, b) in zip(old, new, strict=True):
        if old_uri != new_uri:
            return None
        lines = changed_in(a, b)
        if lines is None:
            return None
        if lines:
            changed[new_uri] = lines
    return changed


def changed_in(a: Document, b: Document) -> set[int] | None:
    """The lines of one document whose text differs (None: not the same line count)."""
    if len(a.blocks) != len(b.blocks) or a.unread_from != b.unread_from:
        return None
    if a is b:
        return set()
    # The stretch between the first and the last change, found by comparing slices in C; the
    # lines in it compared one by one (two edits far apart leave the same lines between).
    diff = line_diff(a, b)
    x, y = a.blocks, b.blocks
    return {
        line
        for line in range(diff.start, diff.end)
        if x[line].parsed is not y[line].parsed and x[line].parsed.text != y[line].parsed.text
    }


def plan(
    previous: Facts,
    record: RunRecord,
    changed: dict[str, set[int]],
    read_first: Callable[[CtxKey], tuple[tuple[int, int], ...]],
) -> Resumption | Facts | None:
    """How the evaluation recorded in ``record`` (not yet run) can reuse ``previous``, whose
    documents differ in the ``changed`` lines: the earlier facts themselves when nothing that
    runs changed, a resumption, or None (run it all). ``read_first`` computes what
    :attr:`RunRecord.read_first` holds, for a program of the new evaluation."""
    old = previous.record
    if old is None or previous.stopped == "time" or old.settings != record.settings:
        return None
    if old.shapes != record.shapes:
        return None
    # A run of an entry program begins with the locals it reads before it sets them unknown:
    # an edit that changes which those are changes the run from its first block.
    moved = set(old.shifted)
    for uri, lines in changed.items():
        # A record holds the compiled lines of the documents that have a program only: one
        # without (empty, or unread as not text) in either version leaves nothing to reuse.
        before, after = old.lines.get(uri), record.lines.get(uri)
        if before is None or after is None:
            return None
        if any(local_access(before[line]) != local_access(after[line]) for line in lines):
            moved.add(uri)
    for key, first in old.read_first.items():
        if key[0] in moved and read_first(key) != first:
            return None
    record.read_first.update(old.read_first)

    def touches(segment: dict[str, DocumentFacts]) -> bool:
        for uri, lines in changed.items():
            facts = segment.get(uri)
            if facts is None:
                continue
            runs = facts.runs
            # set.isdisjoint(dict) iterates over the dict: look up the few edited lines.
            if (
                any(line in runs for line in lines)
                if len(lines) < len(runs)
                else not lines.isdisjoint(runs)
            ):
                return True
        return False

    touched = [i for i, segment in enumerate(old.segments) if i in old.touched or touches(segment)]
    if not touched:
        if not old.shifted:
            return previous  # no changed line ran: the run is the same
        if not old.segments:
            return None
        # The same run in new line numbers: its facts are made again from the renumbered
        # stretches, by resuming at the last of them.
        touched = [len(old.segments) - 1]
    last = touched[-1]
    # The last checkpoint before the first changed stretch whose state is whole (after an
    # edit of lines, the next block of a checkpoint may be one the edit removed).
    usable = [i for i in range(touched[0], -1, -1) if i not in old.unusable]
    if not usable:
        return None
    start = usable[0]
    # A run that runs out of its step budget reports its endless loop from the counts of the
    # whole document so far, the changed stretch included: converging before it would keep
    # the earlier verdict. Only checkpoints of runs after the last such run qualify.
    last_budget = max(
        (i for i, (_, why, _) in enumerate(old.results) if why == "budget"), default=-1
    )
    convergeable: dict[tuple[object, ...], list[int]] = {}
    for i in range(last + 1, len(old.checkpoints)):
        c = old.checkpoints[i]
        if c.run > last_budget and i not in old.unusable and not _returns_into(c, changed):
            convergeable.setdefault(c.meeting_key(), []).append(i)
    meet_at = frozenset(
        (old.checkpoints[i].levels[-1].ctx, old.checkpoints[i].levels[-1].pc)
        for indexes in convergeable.values()
        for i in indexes
        if old.checkpoints[i].levels
    )
    return Resumption(previous, old, start, convergeable, meet_at)


def _returns_into(state: MachineState, changed: dict[str, set[int]]) -> bool:
    """Whether a call in ``state`` returns to a changed line. The earlier run went on from
    there with the line that stood there then: after lines were added just past an ``M98``,
    it returned to the block that now follows them, and no stretch of it ran the new lines,
    so meeting the new run inside the called program would skip them."""
    levels = state.levels
    for caller, level in pairwise(levels):
        lines = changed.get(caller.ctx[0])
        if lines and level.return_pc in lines:
            return True
    return False


def local_access(cl: CompiledLine) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """The locals (#1-#33, and #0 read) a line reads and those it sets: what the locals a
    program reads before it sets them are found from (``machine.locals_read_first``)."""
    targets: list[int] = []
    part: CompiledLine | None = cl
    while part is not None:
        target = part.target_number
        if target is not None and 1 <= target <= 33:
            targets.append(target)
        part = part.second
    return tuple(n for n in cl.reads if n <= 33), tuple(targets)


def stretches_of(facts: Facts, uri: str) -> list[DocumentFacts] | None:
    """A document's facts by stretch of the run, in order: what its whole facts are merged
    from (None: the evaluation kept no record). Facts of both positions of the block-delete
    switch give the switch-off run's stretches, then the switch-on run's: each run resumes
    from its own, so no stretch is in both."""
    if facts.ways is not None:
        off, on = (stretches_of(way, uri) for way in facts.ways)
        return None if off is None or on is None else [*off, *on]
    record = facts.record
    if record is None:
        return None
    return [segment[uri] for segment in record.segments if uri in segment]


def lines_with_other_facts(
    old: Sequence[DocumentFacts], new: Sequence[DocumentFacts], diff: Diff
) -> set[int]:
    """The lines (new numbers) whose runs, reads, writes or jumps may differ between two
    evaluations of versions of a document, given by stretch (:func:`stretches_of`); ``diff``
    is how the document's lines moved (the lines it changed may be among those given).

    A resumed evaluation takes the earlier one's stretches before the one it resumed in and
    after the one where it met the earlier run (renumbered, after an edit of lines, under the
    same stretch number): a line that only those stretches ran has the facts it had, merged
    from the same stretches in the same order. The others are the lines the stretches in
    between ran, in either evaluation."""
    a = [s.stretch for s in old]
    b = [s.stretch for s in new]
    head = common_prefix(a, b)
    tail = common_suffix(a, b, min(len(a), len(b)) - head)
    lines: set[int] = set()
    for facts in new[head : len(new) - tail]:
        _add_lines(lines, facts)
    earlier: set[int] = set()
    for facts in old[head : len(old) - tail]:
        _add_lines(earlier, facts)
    if diff.shift:
        lines.update(m for line in earlier if (m := diff.moved(line)) is not None)
    else:
        lines |= earlier  # the same numbers, the changed lines' too
    return lines


def _add_lines(lines: set[int], facts: DocumentFacts) -> None:
    lines.update(facts.runs)
    lines.update(facts.jumps)
    lines.update(facts.writes)
    lines.update(map(itemgetter(0), facts.reads))  # (line, variable) keys, read in C
