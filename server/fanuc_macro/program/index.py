"""The program index of one file: O programs, N labels, DO/END pairs, jumps and calls.

Built from the parsed blocks in one pass, with no evaluation: what can be known from the text
alone. Jump targets and call targets written as constants are resolved here; computed ones
(``GOTO#1``, ``M98 P#891``) are left to the evaluator.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from dataclasses import dataclass, field
from urllib.parse import unquote

from ..line_maps import line_diff
from ..syntax.marks import constant_value
from ..syntax.tree import (
    Block,
    Document,
    End,
    Goto,
    IfGoto,
    IfNc,
    IfThen,
    Mixed,
    NcStatement,
    Num,
    ProgramStart,
    Span,
    While,
    Word,
)


@dataclass(frozen=True, slots=True)
class Loop:
    loop_id: float
    do_line: int
    end_line: int | None  # None: no END
    depth: int  # 1 for an outermost loop


@dataclass(frozen=True, slots=True)
class LoopProblem:
    kind: str  # "no-end", "no-do", "bad-id", "too-deep", "crossed"
    line: int
    span: Span
    loop_id: float
    other_line: int | None = None


@dataclass(frozen=True, slots=True)
class Jump:
    line: int
    span: Span  # the GOTO statement
    target: int | None  # None: computed (GOTO#1) or not an integer
    target_span: Span
    conditional: bool
    constant: float | None = None  # the target when written as a constant, integer or not


@dataclass(frozen=True, slots=True)
class Call:
    """M98, G65, G66, G66.1 (and Haas M97) with what the text says of its target; or a code
    the control's parameters make call a program (``code``: ``M165``, a G65-like or M98-like
    ``kind``; see :mod:`.custom_calls`)."""

    line: int
    kind: str  # "M98", "G65", "G66", "G66.1", "M97"
    span: Span  # the word that makes the call
    program: int | None  # None: computed (P#1) or missing
    program_span: Span | None
    repeat: int | None
    arguments: tuple[Word, ...]
    code: str | None = None  # the custom code that calls, as the settings name it


@dataclass(slots=True)
class Program:
    """One O program of the file (``number`` None for text before the first O number)."""

    number: int | None
    name: str | None
    header_line: int | None
    first_line: int  # first block of the program (the header line when there is one)
    end_line: int  # exclusive
    labels: dict[int, list[int]] = field(default_factory=dict)
    loops: list[Loop] = field(default_factory=list)
    loop_problems: list[LoopProblem] = field(default_factory=list)
    jumps: list[Jump] = field(default_factory=list)
    calls: list[Call] = field(default_factory=list)
    returns: list[int] = field(default_factory=list)  # lines with M99
    # The file's name when ``number`` comes from it (``O8501.NC`` with no O line in it).
    named_by_file: str | None = None
    # The loops that hold each stretch of lines, worked out on the first question (the index
    # is complete by then): (first line of each stretch, its loops outermost first).
    _loop_stretches: tuple[list[int], list[tuple[Loop, ...]]] | None = field(
        default=None, init=False, repr=False, compare=False
    )

    @property
    def display_name(self) -> str:
        if self.number is None:
            return self.name or "(main)"
        return f"O{self.number:04d}"

    def contains(self, line: int) -> bool:
        return self.first_line <= line < self.end_line

    def label_line(self, seq: int, from_line: int = -1) -> int | None:
        """The N``seq`` a GOTO at ``from_line`` reaches: the control searches forward from the
        block after the GOTO, then from the head of the program."""
        lines = self.labels.get(seq)
        if not lines:
            return None
        after = bisect_right(lines, from_line)  # the lines of a label are in order
        return lines[after] if after < len(lines) else lines[0]

    def enclosing_loops(self, line: int) -> list[Loop]:
        """Loops whose body holds ``line`` (between DO and END, END included), outermost first."""
        stretches = self._loop_stretches
        if stretches is None:
            stretches = self._loop_stretches = _loop_stretches(self.loops)
        starts, holding = stretches
        at = bisect_right(starts, line) - 1
        return list(holding[at]) if at >= 0 else []


def _loop_stretches(loops: list[Loop]) -> tuple[list[int], list[tuple[Loop, ...]]]:
    """The lines cut into stretches held by the same loops: a sweep over the loops' first and
    past-the-last body lines, so a question is a bisection, not a scan of every loop."""
    events: list[tuple[int, int, int]] = []  # (line, 0 leave / 1 enter, position in loops)
    for position, loop in enumerate(loops):
        if loop.end_line is not None and loop.do_line < loop.end_line:
            events.append((loop.do_line + 1, 1, position))
            events.append((loop.end_line + 1, 0, position))
    events.sort()
    starts: list[int] = []
    holding: list[tuple[Loop, ...]] = []
    active: dict[int, Loop] = {}
    i = 0
    while i < len(events):
        line = events[i][0]
        while i < len(events) and events[i][0] == line:
            _, enter, position = events[i]
            if enter:
                active[position] = loops[position]
            else:
                del active[position]
            i += 1
        # Outermost first, the order of ``loops`` (by DO line): the order they entered in, since
        # a loop enters the line after its DO.
        starts.append(line)
        holding.append(tuple(active.values()))
    return starts, holding


@dataclass(frozen=True, slots=True)
class ProgramIndex:
    programs: tuple[Program, ...]
    # The programs' first lines, in order, for a bisection (worked out on the first question).
    _first_lines: list[int] | None = field(default=None, init=False, repr=False, compare=False)

    def program_at(self, line: int) -> Program | None:
        firsts = self._first_lines
        if firsts is None:
            firsts = [program.first_line for program in self.programs]
            if firsts != sorted(set(firsts)):  # not in order: ask each program
                return next((p for p in self.programs if p.contains(line)), None)
            object.__setattr__(self, "_first_lines", firsts)  # a cache, not a change
        at = bisect_right(firsts, line) - 1
        # Programs do not overlap: only the last one starting at or before the line can hold it.
        if at >= 0 and self.programs[at].contains(line):
            return self.programs[at]
        return None

    def by_number(self, number: int) -> Program | None:
        for program in self.programs:
            if program.number == number:
                return program
        return None


MAX_LOOP_DEPTH = 3

# A file named by its program number: O8501.NC, o8501.nc, O09010, O8501 ROUGH.nc, O8501_ROUGH.nc,
# 8501.nc, 01000.nc, 8501 ROUGH.nc. With the O, up to 8 digits (30i); a bare number, 1-9999 in at
# most 5 digits (Haas pads to five: 09010). Not a number among words ('PART2.nc', 'SAMPLE 3.nc'),
# nor a bare number with more after it than a description ('04_variables.nc', '2024-01-05.nc').
_NAMED_BY_NUMBER = re.compile(r"(?:O(\d{1,8})(?:[ _-].*)?|(\d{1,5})(?: .*)?)", re.I | re.S)


def program_number_of_name(uri: str) -> int | None:
    """The program number a file's name gives (``.../O8501.NC`` -> 8501), or None."""
    name = uri.replace("\\", "/").rsplit("/", 1)[-1]
    if "%" in name:
        name = unquote(name)  # a file URI: 'O8501%20ROUGH.nc'
    if "." in name:
        name = name.rsplit(".", 1)[0]
    m = _NAMED_BY_NUMBER.fullmatch(name.strip())
    if m is None:
        return None
    if m.group(1) is not None:
        number = int(m.group(1))
    else:
        number = int(m.group(2))
        if number > 9999:
            return None
    return number if number >= 1 else None


def _file_name(uri: str) -> str:
    name = uri.replace("\\", "/").rsplit("/", 1)[-1]
    return unquote(name) if "%" in name else name


def _call_words(nc: NcStatement) -> tuple[str, Word] | None:
    for word in nc.words:
        value = constant_value(word.value)
        if word.address == "G" and value in (65.0, 66.0, 66.1):
            return ("G66.1" if value == 66.1 else f"G{int(value)}", word)
        if word.address == "M" and value in (98.0, 97.0):
            return (f"M{int(value)}", word)
    return None


def _p_number(word: Word | None) -> tuple[int | None, str | None]:
    if word is None:
        return None, None
    value = constant_value(word.value)
    if value is None or value != int(value) or value < 0:
        return None, None
    text = word.value.text if isinstance(word.value, Num) else None
    return int(value), text


def call_of(line: int, nc: NcStatement) -> Call | None:
    found = _call_words(nc)
    if found is None:
        return None
    kind, call_word = found
    p_word = nc.find("P")
    l_word = nc.find("L")
    program, p_text = _p_number(p_word)
    repeat: int | None = None
    if l_word is not None:
        l_value = constant_value(l_word.value)
        repeat = int(l_value) if l_value is not None and l_value == int(l_value) else None
    elif kind == "M98" and program is not None and p_text is not None:
        digits = p_text.split(".")[0].lstrip("+")
        if len(digits) > 4:
            # M98 P0013331: the leading digits are the repeat count, the last four the program
            # (unverified: the reference gives it medium confidence, for 4-digit O numbers).
            repeat = int(digits[:-4]) or 1
            program = int(digits[-4:])
    if repeat is None and kind != "G66" and kind != "G66.1":
        repeat = 1 if l_word is None else None
    arguments: tuple[Word, ...] = ()
    if kind in ("G65", "G66", "G66.1"):
        after = False
        args: list[Word] = []
        for word in nc.words:
            if word is call_word:
                after = True
                continue
            if after and word.address not in ("P", "L"):
                args.append(word)
        arguments = tuple(args)
    return Call(
        line,
        kind,
        call_word.span,
        program,
        p_word.span if p_word is not None else None,
        repeat,
        arguments,
    )


def has_m99(nc: NcStatement) -> bool:
    return any(w.address == "M" and constant_value(w.value) == 99.0 for w in nc.words)


def index_after_edit(index: ProgramIndex, old: Document, new: Document) -> ProgramIndex:
    """The index of ``new``, a version of ``old`` (whose index is ``index``): ``index`` itself
    when the edit kept the line count and changed only lines the index skips, inside a program
    (a line the index does not need adds nothing to it once a program has begun)."""
    if old.uri != new.uri or len(old.blocks) != len(new.blocks) or not index.programs:
        return build_index(new)
    diff = line_diff(old, new)
    if diff.start <= index.programs[0].first_line:
        return build_index(new)
    x, y = old.blocks, new.blocks
    for line in range(diff.start, diff.end):
        if x[line].parsed.indexed or y[line].parsed.indexed:
            return build_index(new)
    return index


def build_index(doc: Document) -> ProgramIndex:
    programs: list[Program] = []
    current: Program | None = None
    open_loops: list[tuple[float, int, Span]] = []
    pending: list[Loop] = []

    def close_program(end: int) -> None:
        nonlocal current
        if current is None:
            return
        for loop_id, do_line, span in open_loops:
            current.loop_problems.append(LoopProblem("no-end", do_line, span, loop_id))
            pending.append(Loop(loop_id, do_line, None, 0))
        open_loops.clear()
        current.loops = sorted(pending, key=lambda lp: lp.do_line)
        pending.clear()
        current.end_line = end
        programs.append(current)
        current = None

    for block in doc.blocks:
        parsed = block.parsed
        if not parsed.indexed:
            if current is None and parsed.statement is not None:
                current = Program(None, None, None, block.line, block.line + 1)
            continue
        statement = parsed.statement
        line = block.line
        if isinstance(statement, ProgramStart):
            close_program(line)
            current = Program(statement.number, statement.name, line, line, line + 1)
            continue
        if current is None:
            if parsed.is_empty and not parsed.tape_mark:
                continue
            if parsed.tape_mark and statement is None and parsed.seq is None:
                continue
            current = Program(None, None, None, line, line + 1)
        if parsed.seq is not None:
            current.labels.setdefault(parsed.seq, []).append(line)
        if statement is not None:
            _index_statement(current, block, open_loops, pending)
    close_program(len(doc.blocks))
    if len(programs) == 1 and programs[0].header_line is None and doc.uri:
        # No O line in the file: the shop keeps the program under its number as the file's
        # name, and a control loads it under the number given at input. Calls of that number
        # in other files reach it. (How a control numbers a file read without an O line
        # depends on the input path and the control: unverified.)
        number = program_number_of_name(doc.uri)
        if number is not None:
            programs[0].number = number
            programs[0].named_by_file = _file_name(doc.uri)
    return ProgramIndex(tuple(programs))


def _index_statement(
    program: Program,
    block: Block,
    open_loops: list[tuple[float, int, Span]],
    loops: list[Loop],
) -> None:
    statement = block.statement
    line = block.line
    parts = (statement.nc, statement.macro) if isinstance(statement, Mixed) else (statement,)
    for part in parts:
        if isinstance(part, NcStatement):
            call = call_of(line, part)
            if call is not None:
                program.calls.append(call)
            if has_m99(part):
                program.returns.append(line)
        elif isinstance(part, Goto | IfGoto):
            goto = part if isinstance(part, Goto) else part.goto
            value = constant_value(goto.target)
            target = int(value) if value is not None and value == int(value) else None
            program.jumps.append(
                Jump(line, goto.span, target, goto.target.span, isinstance(part, IfGoto), value)
            )
        elif isinstance(part, IfNc):
            call = call_of(line, part.words)
            if call is not None:
                program.calls.append(call)
        elif isinstance(part, While):
            if part.loop_id not in (1.0, 2.0, 3.0):
                program.loop_problems.append(
                    LoopProblem("bad-id", line, part.id_span, part.loop_id)
                )
            if len(open_loops) >= MAX_LOOP_DEPTH:
                program.loop_problems.append(
                    LoopProblem("too-deep", line, part.span, part.loop_id, open_loops[0][1])
                )
            open_loops.append((part.loop_id, line, part.span))
        elif isinstance(part, End):
            if part.loop_id not in (1.0, 2.0, 3.0):
                program.loop_problems.append(
                    LoopProblem("bad-id", line, part.id_span, part.loop_id)
                )
            if open_loops and open_loops[-1][0] == part.loop_id:
                loop_id, do_line, _ = open_loops.pop()
                loops.append(Loop(loop_id, do_line, line, len(open_loops) + 1))
            else:
                match = [i for i, (lid, _, _) in enumerate(open_loops) if lid == part.loop_id]
                if match:
                    # DO1 ... DO2 ... END1: ranges cross, which FANUC forbids.
                    i = match[-1]
                    inner_line = open_loops[-1][1]
                    program.loop_problems.append(
                        LoopProblem("crossed", line, part.span, part.loop_id, inner_line)
                    )
                    loop_id, do_line, _ = open_loops.pop(i)
                    loops.append(Loop(loop_id, do_line, line, i + 1))
                else:
                    program.loop_problems.append(
                        LoopProblem("no-do", line, part.span, part.loop_id)
                    )
        elif isinstance(part, IfThen):
            pass
