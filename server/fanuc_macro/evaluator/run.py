"""Evaluating a set of documents: choose the entry programs, run each, collect the facts."""

from __future__ import annotations

import time
from bisect import bisect_left
from collections.abc import Iterator, Sequence
from dataclasses import replace
from itertools import compress, repeat
from operator import attrgetter, is_not, itemgetter

from ..cancel import COMPILING, SLICE, CancelToken
from ..config import Config
from ..line_maps import Kept
from ..program.index import Program, ProgramIndex
from ..syntax.diff import line_diff
from ..syntax.parser import quiet_gc
from ..syntax.tree import Document
from .checkpoints import ProgramShape, Resumption, RunRecord, changed_in, changed_lines, plan
from .compile_lines import K_EMPTY, FullLine
from .facts import Facts, both_ways
from .line_shift import line_shifts, renumbered
from .machine import (
    Converged,
    Machine,
    ProgramContext,
    block_end_reads,
    build_contexts,
    compiled,
    locals_read_first,
)
from .toolpath import Recorder


def entry_programs(every: Sequence[ProgramContext], only_uri: str | None) -> list[ProgramContext]:
    """Programs nothing calls (by a constant P), in file order; a file's first if all are called."""
    called: set[int] = set()
    for ctx in every:
        for call in ctx.program.calls:
            if call.program is not None:
                called.add(call.program)
    entries = [
        ctx
        for ctx in every
        if (only_uri is None or ctx.uri == only_uri)
        and (ctx.program.number is None or ctx.program.number not in called)
    ]
    if not entries:
        firsts: dict[str, ProgramContext] = {}
        for ctx in every:
            if only_uri is None or ctx.uri == only_uri:
                firsts.setdefault(ctx.uri, ctx)
        entries = list(firsts.values())
    return entries


def evaluate(
    docs: Sequence[tuple[str, Document, ProgramIndex]],
    config: Config | None = None,
    only_uri: str | None = None,
    entry: int | None = None,
    previous: Facts | None = None,
    cancel: CancelToken | None = None,
    toolpath: bool = False,
) -> Facts:
    """Run every entry program (or O``entry``) of ``docs`` within the configured budgets.

    ``previous``: the facts of an earlier evaluation of other versions of the same documents
    with the same settings; the run resumes from its checkpoints where it can (see
    :mod:`.checkpoints`), with the same result as a full run. ``cancel`` may stop it (see
    :mod:`fanuc_macro.cancel`). ``toolpath``: also record the moves (``Facts.toolpath``),
    in a full run (``previous`` is not used). A run of programs that read the block end
    position follows the tool too, in a full run (see :func:`tracks_positions`).
    """
    # The run makes many small objects and no cycles: collections would only rescan them.
    with quiet_gc():
        return _evaluate(
            docs,
            config or Config(),
            only_uri,
            entry,
            None if toolpath else previous,
            cancel,
            toolpath,
        )


def tracks_positions(
    docs: Sequence[tuple[str, Document, ProgramIndex]], only_uri: str | None = None
) -> bool:
    """Whether a run of ``docs`` (of ``only_uri``'s programs) follows where the tool is, for
    reads of ``#5001``-``#5008`` (the block end position): only when a program the run may
    reach reads one directly (``machine.block_end_reads``, a look kept across edits; the
    programs reached through calls by a constant P, any program after a computed one), so
    that no other run pays for it. Such a run is a full one: the checkpoints do not hold
    where the tool is."""
    readers: set[tuple[str, int]] = set()
    for uri, doc, index in docs:
        lines = block_end_reads(doc).lines
        if not lines:
            continue
        for program in index.programs:
            at = bisect_left(lines, program.first_line)
            if at < len(lines) and lines[at] < program.end_line:
                readers.add((uri, program.first_line))
    if not readers:
        return False
    if only_uri is None:
        return True
    by_number: dict[int, tuple[str, Program]] = {}
    todo: list[tuple[str, Program]] = []
    for uri, _doc, index in docs:
        for program in index.programs:
            if program.number is not None:
                by_number.setdefault(program.number, (uri, program))
            if uri == only_uri:
                todo.append((uri, program))
    seen: set[tuple[str, int]] = set()
    while todo:
        uri, program = todo.pop()
        key = (uri, program.first_line)
        if key in seen:
            continue
        seen.add(key)
        if key in readers:
            return True
        for call in program.calls:
            if call.kind == "M97":
                continue  # a jump to an N of the same program (Haas)
            if call.program is None:
                return True  # computed: it may run any program
            found = by_number.get(call.program)
            if found is not None:
                todo.append(found)
    return False


def _evaluate(
    docs: Sequence[tuple[str, Document, ProgramIndex]],
    config: Config,
    only_uri: str | None,
    entry: int | None,
    previous: Facts | None,
    cancel: CancelToken | None,
    toolpath: bool = False,
) -> Facts:
    """Run with the block-delete switch off (every '/' block runs), and, when that run
    reached a block that begins with '/', again with the switch on (those blocks skipped):
    until it reaches one, the second run would be the first. A '/1'-'/9' block (multiple
    block skip) counts as a '/' block: the second run has every switch on. Each run resumes
    from its own run of ``previous``. (The switch and '/n': FANUC Series 16i/18i operator's
    manual B-63684EN, Part II "Program configuration", optional block skip; its section
    number and the '/n' option's text unverified here.) One wall-clock limit for the whole
    analysis, a safety net only: the step budget, per entry of each run, is what ends a run
    that goes on (see Config)."""
    docs = list(docs)
    deadline = time.monotonic() + config.time_limit
    ways = previous.ways if previous is not None else None
    previous_off = ways[0] if ways is not None else previous
    off = _evaluate_way(docs, config, only_uri, entry, previous_off, cancel, toolpath, deadline)
    if toolpath or not _reaches_block_delete(docs, off):
        return off
    previous_on = ways[1] if ways is not None else None
    on = _evaluate_way(
        docs, config, only_uri, entry, previous_on, cancel, False, deadline, skipping=True
    )
    if ways is not None and previous is not None and off is ways[0] and on is ways[1]:
        return previous  # nothing that runs changed
    return both_ways(off, on)


_SKIP = attrgetter("skip")  # ParsedLine.skip, read in C
_PARSED = itemgetter(1)  # Block.parsed

# The lines of each document that begin with '/', by URI, with the version they are of: a bare
# line may begin with one, so no LineMap finds them; like one, the next version is looked at
# only where the edit changed it.
_kept_block_delete: Kept[tuple[Document, list[int]]] = Kept("evaluator.block_delete_lines")


def _block_delete_lines(doc: Document) -> list[int]:
    """The lines of ``doc`` that begin with '/' (block delete), ascending."""
    last = _kept_block_delete.get(doc.uri)
    if last is not None and last[0] is doc:
        return last[1]
    if last is None:
        lines = _looked(doc, 0, len(doc.blocks))
    else:
        diff = line_diff(last[0], doc)
        before = last[1]
        moved = before[bisect_left(before, diff.old_end) :]
        if diff.shift:
            moved = [line + diff.shift for line in moved]
        lines = [
            *before[: bisect_left(before, diff.start)],
            *_looked(doc, diff.start, diff.end),
            *moved,
        ]
    _kept_block_delete.put(doc.uri, (doc, lines))
    return lines


def _looked(doc: Document, start: int, end: int) -> list[int]:
    skips = map(_SKIP, map(_PARSED, doc.blocks[start:end]))
    return list(compress(range(start, end), map(is_not, skips, repeat(None))))


def _reaches_block_delete(docs: Sequence[tuple[str, Document, ProgramIndex]], facts: Facts) -> bool:
    """Whether the run reached a block that begins with '/'."""
    for uri, doc, _ in docs:
        lines = _block_delete_lines(doc)
        if not lines:
            continue
        doc_facts = facts.by_uri.get(uri)
        if doc_facts is not None and not doc_facts.runs.keys().isdisjoint(lines):
            return True
    return False


def _skip_block_delete(
    docs: Sequence[tuple[str, Document, ProgramIndex]], every: Sequence[ProgramContext]
) -> None:
    """The switch on: every '/' block of the compiled lines runs as an empty one (its
    checkpoints where the switch-off run has them)."""
    # What a '/' block is with the switch on: nothing, a boundary line where its text is one.
    skipped = (FullLine(K_EMPTY), FullLine(K_EMPTY, boundary=True))
    done: set[int] = set()
    by_uri = {uri: doc for uri, doc, _ in docs}
    for ctx in every:
        lines = ctx.lines
        if id(lines) in done:
            continue
        done.add(id(lines))
        for line in _block_delete_lines(by_uri[ctx.uri]):
            lines[line] = skipped[lines[line].boundary]


def _evaluate_way(
    docs: list[tuple[str, Document, ProgramIndex]],
    config: Config,
    only_uri: str | None,
    entry: int | None,
    previous: Facts | None,
    cancel: CancelToken | None,
    toolpath: bool,
    deadline: float,
    skipping: bool = False,
) -> Facts:
    """One run of the programs, the block-delete switch on if ``skipping``."""
    documents = tuple((uri, doc) for uri, doc, _ in docs)
    facts = Facts()
    follow = not toolpath and tracks_positions(docs, only_uri)
    if follow:
        previous = None
    previous, changed = _aligned(previous, documents)
    earlier = previous.record if previous is not None else None
    compiled_before = earlier.lines if earlier is not None and changed is not None else None
    if cancel is not None and compiled_before is None:
        _compile_lines(docs, cancel)
    programs, every = build_contexts(docs, facts, compiled_before, changed)
    if skipping:
        _skip_block_delete(docs, every)
    if entry is not None:
        chosen = programs.get(entry)
        entries = [chosen] if chosen is not None else []
    else:
        entries = entry_programs(every, only_uri)
    machine = Machine(programs, config, facts, every, cancel)
    if toolpath:
        timed = frozenset(code for code, _ in config.m_code_seconds)
        recorder = machine.toolpath = Recorder(config.is_lathe, timed_codes=timed)
        facts.toolpath = recorder.toolpath
    elif follow:
        machine.toolpath = Recorder(config.is_lathe, keep=False)
    record = RunRecord((config, only_uri, entry), documents, _shapes(every))
    for ctx in every:
        record.lines.setdefault(ctx.uri, ctx.lines)
    machine.record = record
    sequence = _Sequence(entries, every, only_uri, alone=entry is None)
    how = None
    if previous is not None and changed is not None:
        by_key = machine.contexts
        how = plan(previous, record, changed, lambda key: locals_read_first(by_key[key]))
    if isinstance(how, Facts):
        return how  # nothing that runs changed
    try:
        if how is None:
            _run_from(machine, sequence, 0, deadline)
        else:
            _resume(machine, how, sequence, deadline)
    except Converged as met:
        assert how is not None
        _splice(machine, how, met.index, met.done)
    _finish(facts, record, config)
    return facts


class _Sequence:
    """The runs of an evaluation, in order: the entry programs, then the programs no run
    reached (a subprogram whose caller is elsewhere), each analysed alone. A run's place in
    it is a number: an entry's position, or ``len(entries)`` + its position in ``every``."""

    def __init__(
        self,
        entries: list[ProgramContext],
        every: list[ProgramContext],
        only_uri: str | None,
        alone: bool,
    ) -> None:
        self.entries = entries
        self.every = every if alone else []
        self.only_uri = only_uri

    def from_place(self, place: int) -> Iterator[tuple[int, ProgramContext]]:
        for i in range(place, len(self.entries)):
            yield i, self.entries[i]
        first = len(self.entries)
        for i in range(max(place, first) - first, len(self.every)):
            ctx = self.every[i]
            if self.only_uri is not None and ctx.uri != self.only_uri:
                continue
            # Decided when its turn comes: an earlier run may have called it.
            if ctx.program.first_line in ctx.facts.analysed_programs:
                continue
            yield first + i, ctx


def _aligned(
    previous: Facts | None, documents: tuple[tuple[str, Document], ...]
) -> tuple[Facts | None, dict[str, set[int]] | None]:
    """The earlier facts in the new documents' line numbers, and the lines that changed
    (None: nothing to resume from)."""
    earlier = previous.record if previous is not None else None
    if previous is None or earlier is None:
        return previous, None
    changed = changed_lines(earlier.documents, documents)
    if changed is not None:
        return previous, changed
    shifts = line_shifts(earlier.documents, documents)
    if not shifts:
        return previous, None
    moved = renumbered(previous, shifts)
    if moved is None or moved.record is None:
        return previous, None
    changed = {}
    for (uri, old_doc), (_, doc) in zip(earlier.documents, documents, strict=True):
        shift = shifts.get(uri)
        if shift is None:
            lines = changed_in(old_doc, doc)
            if lines is None:
                return previous, None
        else:
            lines = shift.changed()
            before = earlier.lines.get(uri)
            if before is None:
                return previous, None
            # The lines compiled before, moved; the edit's lines are compiled again.
            moved.record.lines[uri] = [
                *before[: shift.start],
                *(compiled(b.parsed) for b in doc.blocks[shift.start : shift.new_end]),
                *before[shift.old_end :],
            ]
        if lines:
            changed[uri] = lines
    return moved, changed


def _run_from(machine: Machine, sequence: _Sequence, place: int, deadline: float) -> None:
    record = machine.record
    assert record is not None
    for at, ctx in sequence.from_place(place):
        machine.run_index = len(record.results)
        machine.steps = 0
        try:
            why = machine.run(ctx, deadline)
        finally:
            record.executed += machine.steps
        record.results.append((at, why, machine.steps))


def _resume(machine: Machine, how: Resumption, sequence: _Sequence, deadline: float) -> None:
    """Restore the facts of the earlier evaluation up to the checkpoint, and go on from it."""
    record = machine.record
    assert record is not None
    old, previous = how.record, how.previous
    state = old.checkpoints[how.start]
    record.checkpoints = old.checkpoints[: how.start]
    record.segments = old.segments[: how.start]
    record.results = old.results[: state.run]
    facts = machine.facts
    findings = dict(state.findings)
    analysed = dict(state.analysed)
    assumed = dict(state.assumed)
    for uri, base in facts.by_uri.items():
        before = previous.by_uri.get(uri)
        base.reported[:] = before.reported[: findings.get(uri, 0)] if before is not None else []
        base.analysed_programs.clear()
        base.analysed_programs.update(analysed.get(uri, ()))
        base.assumed_arguments.clear()
        base.assumed_arguments.update(assumed.get(uri, ()))
    facts.motions[:] = previous.motions[: state.motions]
    facts.run_values.clear()
    for serial in state.run_values:
        facts.run_values[serial] = previous.run_values[serial]
    machine.resumption = how
    at = old.results[state.run][0]
    machine.steps = 0
    record.resumed_at = (state.run, state.done)
    try:
        why = machine.resume(state, deadline)
    finally:
        record.executed += machine.steps - state.done
    record.results.append((at, why, machine.steps))
    _run_from(machine, sequence, at + 1, deadline)


def _splice(machine: Machine, how: Resumption, index: int, done: int) -> None:
    """The resumed run met the earlier one at its checkpoint ``index`` after ``done`` blocks
    of its run: the rest of the evaluation is the earlier one's, that run's block counts
    moved by the blocks the edit added or removed, and every later count of motions by the
    motions it added or removed (a block that no longer moves, or that moves now)."""
    record = machine.record
    assert record is not None
    old, previous = how.record, how.previous
    state = old.checkpoints[index]
    offset = done - state.done
    moved = len(machine.facts.motions) - state.motions
    record.converged_at = (state.run, done)
    record.checkpoints.extend(
        replace(
            c,
            done=c.done + offset if c.run == state.run else c.done,
            motions=c.motions + moved,
        )
        if (offset and c.run == state.run) or moved
        else c
        for c in old.checkpoints[index:]
    )
    record.segments.extend(old.segments[index:])
    for run, (place, why, blocks) in enumerate(old.results):
        if run >= len(record.results):
            record.results.append((place, why, blocks + offset if run == state.run else blocks))
    facts = machine.facts
    findings = dict(state.findings)
    for uri, base in facts.by_uri.items():
        before = previous.by_uri.get(uri)
        if before is None:
            continue
        base.reported.extend(before.reported[findings.get(uri, 0) :])
        base.analysed_programs.clear()
        base.analysed_programs.update(before.analysed_programs)
        base.assumed_arguments.clear()
        base.assumed_arguments.update(before.assumed_arguments)
    facts.motions.extend(previous.motions[state.motions :])
    serials = list(previous.run_values)
    for serial in serials[len(state.run_values) :]:
        facts.run_values[serial] = previous.run_values[serial]


def _finish(facts: Facts, record: RunRecord, config: Config) -> None:
    for uri, base in facts.by_uri.items():
        base.take_segments([segment[uri] for segment in record.segments if uri in segment])
    reasons = [why for _, why, _ in record.results]
    facts.steps = sum(blocks for _, _, blocks in record.results)
    if "time" in reasons:
        facts.stopped = "time"
        facts.time_limit = config.time_limit
    elif "budget" in reasons:
        facts.stopped = "budget"
    facts.record = record


def _shapes(every: Sequence[ProgramContext]) -> tuple[ProgramShape, ...]:
    shapes: list[ProgramShape] = []
    for ctx in every:
        program = ctx.program
        shapes.append(
            ProgramShape(
                (ctx.uri, program.first_line),
                program.number,
                ctx.name,
                program.end_line,
                tuple((seq, tuple(lines)) for seq, lines in program.labels.items()),
                tuple(program.loops),
                tuple((j.line, j.target, j.conditional) for j in program.jumps),
                tuple((c.line, c.kind, c.program) for c in program.calls),
                ctx.is_main,
                ctx.facts.program_ends.get(program.first_line),
            )
        )
    return tuple(shapes)


def _compile_lines(docs: Sequence[tuple[str, Document, ProgramIndex]], cancel: CancelToken) -> None:
    """Compile the documents' lines a slice at a time, looking at ``cancel`` between slices:
    :func:`build_contexts` then finds them in the per-line cache (a cold 200,000-block file
    takes seconds to compile, too long to wait for a newer edit)."""
    total = sum(len(doc.blocks) for _, doc, _ in docs)
    done = 0
    for _, doc, _ in docs:
        blocks = doc.blocks
        for start in range(0, len(blocks), SLICE):
            if done >= SLICE:
                cancel.reached(COMPILING, done, total)
            for block in blocks[start : start + SLICE]:
                compiled(block.parsed)
            done += min(SLICE, len(blocks) - start)
