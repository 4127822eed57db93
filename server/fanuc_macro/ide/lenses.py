"""Code lenses over each O line: who calls the program across the workspace, what the
analysed runs did there (how often it was entered, the threads it cut: their cuts and
depths), and its cycle time."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

from ..program.index import Program
from ..translation import joined, tr, tr_n
from .cycle_times import MODEL_NOTE, program_time
from .data import Location, Range
from .values import times
from .view import View

MAX_CALLERS = 3  # named in the title; the rest are counted
MAX_PLACES = 10  # calls listed in the tooltip


@dataclass(frozen=True)
class CodeLens:
    range: Range  # the program's O word
    title: str  # a Text, said in the user's language at the protocol's boundary
    tooltip: str = ""  # what the title sums up, in more words
    references: tuple[Location, ...] = ()  # the places the title counts, when it counts any


# Every call of a program in the workspace, by the number it calls: (document key, the
# calling program's name, the line of the call).
Callers = dict[int, list[tuple[str, str, int]]]


def _callers(view: View) -> Callers:
    found: Callers = {}
    documents = {**view.workspace, view.key: (view.doc, view.index)}
    for key in sorted(documents):
        _, index = documents[key]
        for program in index.programs:
            for call in program.calls:
                if call.program is not None:
                    found.setdefault(call.program, []).append(
                        (key, program.display_name, call.line)
                    )
    return found


def _callers_lens(
    view: View, program: Program, where: Range, all_callers: Callers
) -> CodeLens | None:
    assert program.number is not None
    callers = all_callers.get(program.number, [])
    if not callers:
        if not program.returns:
            return None  # a main program: nobody is expected to call it
        return CodeLens(where, tr("no caller in the workspace"))
    counts = Counter(name for _, name, _ in callers)
    named = [f"{name} · {count}×" for name, count in counts.most_common(MAX_CALLERS)]
    rest = len(counts) - len(named)
    title = (
        tr("called from {callers} and {more} more", callers=", ".join(named), more=rest)
        if rest
        else tr("called from {callers}", callers=", ".join(named))
    )
    references = tuple(view.location(key, line) for key, _, line in callers)
    places = [
        tr("{program}, line {line}", program=name, line=line + 1)
        if key == view.key
        else tr(
            "{program}, line {line} ({file})", program=name, line=line + 1, file=_file_name(key)
        )
        for key, name, line in callers
    ]
    more = len(places) - MAX_PLACES
    shown = places[:MAX_PLACES] + ([tr("and {more} more", more=more)] if more > 0 else [])
    return CodeLens(where, title, joined("\n", shown), references)


def _file_name(key: str) -> str:
    return key.rstrip("/").rsplit("/", 1)[-1]


def _runs_lens(view: View, program: Program, header: int, where: Range) -> CodeLens | None:
    """How often the analysed runs entered the program, and the threads it cut."""
    facts = view.facts
    if facts is None:
        return None
    parts: list[str] = []
    cut_threads = False
    entered = facts.runs.get(header)
    if entered:
        parts.append(tr("entered {times}", times=times(entered)))
    for thread in view.analysis.threads:
        job = thread.job
        if job.uri != view.key or job.program_line != program.first_line or not job.passes:
            continue
        # A cut is one threading motion; the cuts at one X are one depth (a spring pass, or
        # the two flanks of a shifted start, cut the same depth again).
        cuts = len(job.passes)
        depths = len(set(job.xs))
        lead = job.lead
        feed = f" F{lead:g}" if lead is not None else ""
        name = thread.name if thread.identified else tr("thread")
        cut_threads = True
        parts.append(
            tr(
                "{thread}: {cuts} at {depths} ({program_text})",
                thread=name,
                cuts=tr_n("{count} cut", "{count} cuts", cuts),
                depths=tr_n("{count} depth", "{count} depths", depths),
                program_text=f"{job.shown}{feed}",
            )
        )
    if not parts:
        return None
    tooltip = (
        tr("What the analysed runs did: a cut is one threading motion, a depth an X the cuts reach")
        if cut_threads
        else tr("What the analysed runs did")
    )
    return CodeLens(where, joined(" · ", parts), tooltip)


def _time_lens(view: View, program: Program, where: Range) -> CodeLens | None:
    """The program's cycle time (``cycle time 6 min 12.4 s``), its parts in the tooltip."""
    timed = program_time(view, program)
    if timed is None:
        return None
    title, parts = timed
    return CodeLens(where, title, joined("\n\n", (parts, MODEL_NOTE)) if parts else MODEL_NOTE)


def code_lenses(view: View) -> list[CodeLens]:
    """The lenses of every program with an O line, in document order."""
    out: list[CodeLens] = []
    callers = _callers(view)
    for program in view.index.programs:
        header = program.header_line
        if header is None or program.number is None:
            continue
        block = view.block(header)
        if block is None:
            continue
        span = block.statement.span if block.statement is not None else None
        start, end = (span.start, span.end) if span is not None else (0, 0)
        where = Range.of(header, start, header, end)
        for lens in (
            _callers_lens(view, program, where, callers),
            _runs_lens(view, program, header, where),
            _time_lens(view, program, where),
        ):
            if lens is not None:
                out.append(lens)
    return out


__all__ = ("CodeLens", "code_lenses")
