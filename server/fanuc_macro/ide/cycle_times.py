"""The cycle time of a document's programs as the editor shows it: on the code lens and the
hover of each O line. It is worked out of a run with the toolpath recorded (what the trace
runs), kept with the analysis it follows, and left out for a run longer than
:data:`MAX_TIMED_BLOCKS` (the trace still gives it)."""

from __future__ import annotations

from ..database import Derived
from ..evaluator.cycle_time import PART_NAMES, PARTS, CycleTime, cycle_time, minutes_seconds
from ..program.index import Program
from ..translation import joined, tr, tr_n
from .trace import run_with_toolpath
from .view import View

# Blocks the analysis's runs executed past which the editor does not run the programs again
# for their time: the run with the toolpath costs about what the analysis's own did.
MAX_TIMED_BLOCKS = 50_000


def _inputs(view: View) -> tuple[object, ...]:
    analysis = view.analysis
    return (analysis.doc, analysis.index, analysis.facts, view.config, view.workspace)


def _compute(view: View) -> tuple[CycleTime | None, bool]:
    facts = view.analysis.facts
    if facts is None or facts.steps > MAX_TIMED_BLOCKS:
        return None, True
    others = [(key, doc, index) for key, (doc, index) in view.workspace.items() if key != view.key]
    timed = run_with_toolpath(view.key, view.doc, view.index, others, view.config)
    return cycle_time(timed, view.config), True


_DOCUMENT_TIME: Derived[View, CycleTime | None] = Derived("cycle time", _inputs, _compute, kept=4)


def document_cycle_time(view: View) -> CycleTime | None:
    """The cycle time of the runs of the document's programs (None: not worked out)."""
    return _DOCUMENT_TIME(view.key, view)


def program_time(view: View, program: Program) -> tuple[str, str] | None:
    """What the O line of ``program`` says of its time: a title (``cycle time 6 min 12.4 s``
    for a program run as an entry, the seconds in its own blocks for one only called) and
    its parts, one a line; None when it took no time or was not timed."""
    timed = document_cycle_time(view)
    if timed is None:
        return None
    run = timed.run_of(view.key, program.first_line)
    if run is not None:
        parts = run.breakdown.parts()
        title = tr("cycle time {time}", time=minutes_seconds(run.seconds))
        extra: list[str] = []
        if run.tool_changes:
            extra.append(tr_n("{count} tool change", "{count} tool changes", run.tool_changes))
        if run.untimed:
            extra.append(tr_n("{count} move not timed", "{count} moves not timed", run.untimed))
    else:
        seconds = timed.in_program.get((view.key, program.first_line), 0.0)
        if seconds <= 0.0:
            return None
        title = tr("{time} in its own blocks", time=minutes_seconds(seconds))
        parts, extra = {}, []
    lines: list[str] = [
        tr("{part}: {time}", part=PART_NAMES[part], time=minutes_seconds(parts[part]))
        for part in PARTS
        if parts.get(part)
    ]
    lines += extra
    return title, joined("\n", lines)


MODEL_NOTE = tr(
    "Feeds at F (per minute, or per revolution at the spindle speed), threads at the lead "
    "times the speed, rapids at each axis's rate (settings cycleTime.*); no acceleration, "
    "look-ahead, overrides or spindle ramp-up."
)
