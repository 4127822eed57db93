"""An edit that adds or removes lines, for the incremental evaluation: the earlier run's record
and facts renumbered to the new lines.

The lines before the edit keep their numbers and those after it move by the number of lines
added or removed, so the earlier run's checkpoints and stretches of facts are renumbered, and
the resumption of :mod:`.checkpoints` then works as after an edit within lines. A checkpoint
whose state names a line of the edit (the next block is one of them) cannot be resumed from
nor met; a stretch that ran one counts as a changed stretch.
"""

from __future__ import annotations

import re
from array import array
from collections.abc import Callable, Sequence
from dataclasses import dataclass, fields, replace
from operator import attrgetter

from ..syntax.tree import Document
from ..translation import Text
from .checkpoints import LevelState, MachineState, ModalState, ProgramShape, RunRecord
from .facts import CutsWithoutFeed, DocumentFacts, Facts, Finding, Motion


class _Unmapped(Exception):
    """A line of the edit where the renumbered record needs a line that stays."""


@dataclass(frozen=True, slots=True)
class LineShift:
    """One document's edit: the lines before ``start`` and from ``old_end`` on (old numbers)
    are the same text; those from ``old_end`` on move by ``delta``."""

    start: int
    old_end: int
    delta: int

    @property
    def new_end(self) -> int:
        return self.old_end + self.delta

    def line(self, n: int) -> int | None:
        if n < self.start:
            return n
        if n >= self.old_end:
            return n + self.delta
        return None

    def changed(self) -> set[int]:
        """The new lines an evaluation treats as changed: the edit's, and the line before it
        (the run falls from it into the lines added)."""
        lines = set(range(self.start, self.new_end))
        if self.start > 0:
            lines.add(self.start - 1)
        return lines


def line_shifts(
    old: Sequence[tuple[str, Document]], new: Sequence[tuple[str, Document]]
) -> dict[str, LineShift] | None:
    """The documents whose line count changed, each with its edit as one stretch of lines
    (a common head and tail of the text kept); None when the documents are not the same ones
    or one of them is read only in part (the read limit moves with the lines)."""
    if len(old) != len(new):
        return None
    shifts: dict[str, LineShift] = {}
    for (old_uri, a), (new_uri, b) in zip(old, new, strict=True):
        if old_uri != new_uri:
            return None
        if len(a.blocks) == len(b.blocks):
            continue
        if a.unread_from is not None or b.unread_from is not None:
            return None
        x, y = a.blocks, b.blocks
        head = 0
        shortest = min(len(x), len(y))
        while head < shortest and _same(x[head].parsed, y[head].parsed):
            head += 1
        tail = 0
        while tail < shortest - head and _same(
            x[len(x) - 1 - tail].parsed, y[len(y) - 1 - tail].parsed
        ):
            tail += 1
        shifts[new_uri] = LineShift(head, len(x) - tail, len(y) - len(x))
    return shifts


def _same(p: object, q: object) -> bool:
    return p is q or getattr(p, "text", None) == getattr(q, "text", 0)


def renumbered(previous: Facts, shifts: dict[str, LineShift]) -> Facts | None:
    """``previous`` with its record in the new line numbers (None: too much to renumber,
    such as a program that begins inside the edit)."""
    old = previous.record
    if old is None:
        return None
    try:
        return _renumber(previous, old, shifts)
    except _Unmapped:
        return None


def _renumber(previous: Facts, old: RunRecord, shifts: dict[str, LineShift]) -> Facts:
    def line(uri: str, n: int) -> int:
        shift = shifts.get(uri)
        if shift is None:
            return n
        mapped = shift.line(n)
        if mapped is None:
            raise _Unmapped
        return mapped

    def maybe(uri: str, n: int | None) -> int | None:
        if n is None:
            return None
        shift = shifts.get(uri)
        return n if shift is None else shift.line(n)

    record = RunRecord(
        old.settings,
        old.documents,
        tuple(_shape(s, shifts) for s in old.shapes),
        read_first={
            (uri, line(uri, first)): tuple((n, line(uri, at)) for n, at in pairs)
            for (uri, first), pairs in old.read_first.items()
        },
        lines={uri: lines for uri, lines in old.lines.items() if uri not in shifts},
        results=list(old.results),
        shifted=old.shifted | frozenset(shifts),
    )
    unusable = set(old.unusable)
    # The chunks renumbered so far, by the id of the earlier one (which the record keeps).
    chunks: dict[int, Keys] = {}
    for i, state in enumerate(old.checkpoints):
        try:
            record.checkpoints.append(_state(state, line, chunks))
        except _Unmapped:
            record.checkpoints.append(state)  # kept for its place, never used
            unusable.add(i)
    record.unusable = frozenset(unusable)
    touched = set(old.touched)
    for i, segment in enumerate(old.segments):
        renamed: dict[str, DocumentFacts] = {}
        for uri, facts in segment.items():
            shift = shifts.get(uri)
            if shift is None:
                renamed[uri] = facts
                continue
            moved, ran_edit = _segment(facts, shift)
            renamed[uri] = moved
            if ran_edit:
                touched.add(i)
        record.segments.append(renamed)
    record.touched = frozenset(touched)

    out = Facts(steps=previous.steps, stopped=previous.stopped, time_limit=previous.time_limit)
    out.run_values = previous.run_values
    for uri, facts in previous.by_uri.items():
        shift = shifts.get(uri)
        if shift is None:
            out.by_uri[uri] = facts
            continue
        doc = DocumentFacts()
        # The cuts without F are not kept: the evaluation takes them from the stretches.
        doc.reported = [_finding(f, maybe) for f in facts.reported]
        doc.analysed_programs = {line(uri, n) for n in facts.analysed_programs}
        doc.assumed_arguments = {
            line(uri, first): tuple((n, line(uri, at)) for n, at in pairs)
            for first, pairs in facts.assumed_arguments.items()
        }
        out.by_uri[uri] = doc
    out.motions = [_motion(m, shifts, maybe) for m in previous.motions]
    out.record = record
    return out


def _shape(shape: ProgramShape, shifts: dict[str, LineShift]) -> ProgramShape:
    uri = shape.key[0]
    shift = shifts.get(uri)
    if shift is None:
        return shape

    def line(n: int) -> int:
        mapped = shift.line(n)
        if mapped is None:
            raise _Unmapped
        return mapped

    end = shape.end_line
    if end >= shift.old_end:
        end += shift.delta
    elif end > shift.start:
        raise _Unmapped  # the edit crosses the program's end
    return ProgramShape(
        (uri, line(shape.key[1])),
        shape.number,
        shape.name,
        end,
        tuple((seq, tuple(line(n) for n in lines)) for seq, lines in shape.labels),
        tuple(
            replace(
                loop,
                do_line=line(loop.do_line),
                end_line=None if loop.end_line is None else line(loop.end_line),
            )
            for loop in shape.loops
        ),
        tuple((line(at), target, conditional) for at, target, conditional in shape.jumps),
        tuple((line(at), kind, program) for at, kind, program in shape.calls),
        shape.is_main,
        None if shape.program_end is None else line(shape.program_end),
    )


Renumber = Callable[[str, int], int]  # (document, old line) -> new line, or _Unmapped
MaybeRenumber = Callable[[str, int | None], int | None]  # None for a line of the edit


Keys = frozenset[tuple[str, str, int, int]]


def _chunk(chunk: Keys, line: Renumber, done: dict[int, Keys]) -> Keys:
    """A chunk of finding keys renumbered, once for all the checkpoints that share it."""
    found = done.get(id(chunk))
    if found is None:
        found = done[id(chunk)] = frozenset(
            (kind, uri, line(uri, n), col) for kind, uri, n, col in chunk
        )
    return found


def _state(state: MachineState, line: Renumber, chunks: dict[int, Keys]) -> MachineState:
    def key(k: tuple[str, int]) -> tuple[str, int]:
        return (k[0], line(k[0], k[1]))

    def pairs(uri: str, items: tuple[tuple[int, int], ...]) -> tuple[tuple[int, int], ...]:
        return tuple((n, line(uri, at)) for n, at in items)

    levels = tuple(
        LevelState(
            key(lv.ctx),
            lv.locals,
            lv.shares_locals_with_caller,
            line(lv.ctx[0], lv.pc),
            lv.macro_level,
            # The block after the call: where the call now stands, plus one.
            line(state.levels[i - 1].ctx[0], lv.return_pc - 1) + 1 if i > 0 else lv.return_pc,
            lv.repeats_left,
            lv.serial,
            lv.arguments,
            frozenset(line(lv.ctx[0], n) for n in lv.undecided_loops),
            frozenset(line(lv.ctx[0], n) for n in lv.loops_turning),
            lv.modal_depth,
        )
        for i, lv in enumerate(state.levels)
    )
    m = state.modal
    modal = ModalState(
        m.motion,
        m.feed,
        m.speed,
        m.constant_surface_speed,
        tuple((None if k is None else key(k), args, rep) for k, args, rep in m.modal_calls),
        m.position,
        tuple((axis, (uri, line(uri, n))) for axis, (uri, n) in m.position_line),
        m.inch,
        m.g76,
        m.cycle,
        m.incremental,
        m.spindle,
        None
        if m.spindle_stop is None
        else (m.spindle_stop[0], line(m.spindle_stop[0], m.spindle_stop[1]), m.spindle_stop[2]),
        m.z_at_top,
        m.setup.shifted(line),
        m.drilling,
    )
    return MachineState(
        state.run,
        state.done,
        levels,
        state.store,
        modal,
        state.speculative,
        state.activations,
        tuple(_chunk(chunk, line, chunks) for chunk in state.seen_findings),
        state.motions,
        state.run_values,
        state.findings,
        tuple((uri, frozenset(line(uri, n) for n in firsts)) for uri, firsts in state.analysed),
        tuple(
            (uri, tuple((line(uri, first), pairs(uri, items)) for first, items in assumed))
            for uri, assumed in state.assumed
        ),
        state.profile_blocks,
    )


def _segment(facts: DocumentFacts, shift: LineShift) -> tuple[DocumentFacts, bool]:
    """A stretch's facts in the new numbers, and whether it ran a line of the edit."""
    if not facts.runs or max(facts.runs) < shift.start:
        return facts, False  # it ran only lines before the edit (every fact has its run)
    ran_edit = False

    def ok(n: int) -> int | None:
        nonlocal ran_edit
        mapped = shift.line(n)
        if mapped is None:
            ran_edit = True
        return mapped

    out = DocumentFacts(stretch=facts.stretch)  # the same stretch in new numbers
    out.runs = {m: v for n, v in facts.runs.items() if (m := ok(n)) is not None}
    out.reads = {(m, v): s for (n, v), s in facts.reads.items() if (m := ok(n)) is not None}
    out.writes = {m: w for n, w in facts.writes.items() if (m := ok(n)) is not None}
    out.jumps = {m: j for n, j in facts.jumps.items() if (m := ok(n)) is not None}
    out.roundings = {m: r for n, r in facts.roundings.items() if (m := ok(n)) is not None}
    out.incomplete_programs = {
        m for n in facts.incomplete_programs if (m := shift.line(n)) is not None
    }
    out.cuts = [moved for cuts in facts.cuts if (moved := _cuts(cuts, shift)) is not None]
    return out, ran_edit


def _cuts(cuts: CutsWithoutFeed, shift: LineShift) -> CutsWithoutFeed | None:
    program = shift.line(cuts.program)
    if program is None:
        return None
    if min(cuts.lines) >= shift.old_end:
        lines = array("i", [n + shift.delta for n in cuts.lines])
    else:
        lines = array("i", [m for n in cuts.lines if (m := shift.line(n)) is not None])
    if not lines:
        return None
    # The numbering keeps the order of the lines it keeps: an ascending record stays one.
    return CutsWithoutFeed(cuts.uri, program, cuts.message, cuts.after, lines, cuts.ascending)


def _finding(f: Finding, maybe: MaybeRenumber) -> Finding:
    line = maybe(f.uri, f.line)
    related = maybe(f.uri, f.related_line)
    message = _message(f, maybe) if "line " in f.message else f.message
    if line == f.line and related == f.related_line and message is f.message:
        return f
    # A finding of the edit's lines: it belongs to a stretch that runs again, and is replaced.
    return replace(f, line=f.line if line is None else line, related_line=related, message=message)


# A block of the finding's own document that its message names ("M06 on line 5"): one of
# another document is named with it ("line 5 of file:///o9010.nc") and left as it is.
_LINE_NAMED = re.compile(r"\bline (\d+)\b(?! of )")


# The same in a translatable message's template: the field that holds the line's number.
_LINE_FIELD = re.compile(r"\bline \{(\w+)\}(?! of )")


def _message(f: Finding, maybe: MaybeRenumber) -> str:
    """The finding's message with the lines it names in the new numbers (the same string
    when none moves). A :class:`Text` stays one: the numbers in its parameters move."""
    moved = False

    def renumbered(m: re.Match[str]) -> str:
        nonlocal moved
        n = maybe(f.uri, int(m.group(1)) - 1)
        if n is None or n + 1 == int(m.group(1)):
            return m.group(0)
        moved = True
        return f"line {n + 1}"

    def number(line: object) -> object:
        nonlocal moved
        if type(line) is not int:
            return line
        n = maybe(f.uri, line - 1)
        if n is None or n + 1 == line:
            return line
        moved = True
        return n + 1

    def text_renumbered(text: Text) -> Text:
        lines = set(_LINE_FIELD.findall(text.template))
        params = {
            name: (
                number(value)
                if name in lines
                else text_renumbered(value)
                if isinstance(value, Text)
                else _LINE_NAMED.sub(renumbered, value)
                if isinstance(value, str) and "line " in value
                else value
            )
            for name, value in text.params.items()
        }
        return Text(text.template, params, text.plural, text.number)

    if isinstance(f.message, Text):
        said = text_renumbered(f.message)
        return said if moved else f.message
    text = _LINE_NAMED.sub(renumbered, f.message)
    return text if moved else f.message


_MOTION_FIELDS: tuple[str, ...] = tuple(f.name for f in fields(Motion))


def _motion(m: Motion, shifts: dict[str, LineShift], maybe: MaybeRenumber) -> Motion:
    shift = shifts.get(m.uri)
    start_shift = shifts.get(m.start_uri) if m.start_line is not None else None
    if (shift is None or (m.line < shift.start and m.program_line < shift.start)) and (
        start_shift is None or (m.start_line is not None and m.start_line < start_shift.start)
    ):
        return m  # before the edit: the same numbers
    line = maybe(m.uri, m.line)
    program_line = maybe(m.uri, m.program_line)
    start_line = maybe(m.start_uri, m.start_line)
    fields = list(_motion_fields(m))  # read in C, the record made by its constructor
    fields[_LINE] = m.line if line is None else line
    fields[_PROGRAM_LINE] = m.program_line if program_line is None else program_line
    fields[_START_LINE] = start_line
    return Motion(*fields)


_motion_fields = attrgetter(*_MOTION_FIELDS)
_LINE = _MOTION_FIELDS.index("line")
_PROGRAM_LINE = _MOTION_FIELDS.index("program_line")
_START_LINE = _MOTION_FIELDS.index("start_line")
