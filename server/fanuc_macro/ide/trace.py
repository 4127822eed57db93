"""The executed motion blocks of a program, with computed addresses and the positions the tool
goes through (``fanuc-macro trace``)."""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import TypedDict

from ..config import Config
from ..evaluator import Facts, evaluate
from ..evaluator.cycle_time import PART_NAMES, Breakdown, CycleTime, cycle_time, minutes_seconds
from ..evaluator.toolpath import LostTrack, Move, Toolpath
from ..evaluator.values import Value, fmt, fmt_address
from ..program.index import ProgramIndex
from ..program.machine_kind import machine_config
from ..syntax.tree import Document
from ..threads.cross_section import NO_CHAIN, cut_summary, thread_chains
from ..threads.identify import identify
from ..translation import joined, tr, tr_n

# A move's kind as a user reads it (the trace's JSON keeps the kind's own name).
MOVE_NAMES: Mapping[str, str] = MappingProxyType(
    {"rapid": tr("rapid"), "feed": tr("feed"), "thread": tr("thread"), "arc": tr("arc")}
)

# The trace is sent to the editor and written by ``trace --format json`` as it is: TypedDicts,
# built in the order their keys are written. A key a record may lack is in a ``total=False``
# class of its own (Python 3.10 has no NotRequired).

Point = dict[str, float]  # the axes known, in X, Y, Z order
VariableValue = float | str | None  # a number, None (vacant), or a text ("depends on #500")


class _TraceMoveRequired(TypedDict):
    kind: str
    start: Point
    end: Point


class TraceMove(_TraceMoveRequired, total=False):
    """One move of a canned cycle's record; an arc's with its centre and direction."""

    centre: Point
    clockwise: bool | None


class _TraceMotionRequired(TypedDict):
    program: str
    line: int  # 1-based
    code: str
    words: dict[str, float]


class TraceMotion(_TraceMotionRequired, total=False):
    """One executed motion block; ``path`` when it is in another file than the traced one;
    the spindle speed in force, ``speed`` in G97 (rpm) or ``surface_speed`` in G96."""

    path: str
    speed: float
    surface_speed: float
    values: dict[str, VariableValue]
    start: Point
    end: Point
    centre: Point
    moves: list[TraceMove]
    cycle: str
    clock: float  # the cycle time when the block begins, seconds (evaluator/cycle_time.py)


class _LostTrackRequired(TypedDict):
    program: str
    line: int
    axes: list[str]
    reason: str


class TraceLostTrack(_LostTrackRequired, total=False):
    """Where the path stops being known for some axes, and why."""

    path: str


class TraceToolpath(TypedDict):
    moves: int
    units: str  # "mm" or "inch"
    lathe: bool
    truncated: bool
    lost: list[TraceLostTrack]


class TraceFinding(TypedDict):
    line: int
    kind: str
    message: str


class _ReadInPartRequired(TypedDict):
    last_line_read: int
    message: str


class ReadInPart(_ReadInPartRequired, total=False):
    """A file the analysis read only up to a line: the run stops there."""

    path: str


class TraceLargestPass(TypedDict):
    line: int
    index: int  # 1-based, among the thread's passes
    area: float  # mm² (in² in G20)


class TraceThreadCut(TypedDict):
    """The cross-section the passes cut (:mod:`fanuc_macro.threads.cross_section`): one value
    per nose radius taken (two, the ends of ISO 965-1's range, when it is not given)."""

    pitch_diameter: list[float]
    root_diameter: list[float]
    crest_diameter: float
    nose_radius: list[float]
    nose_radius_known: bool
    limits: list[float] | None  # the class's pitch diameters, least and greatest
    verdict: str  # "within", "tight" (too shallow), "loose" (past the class), "" (no class)
    area: float
    largest_pass: TraceLargestPass
    passes_in_air: int
    blank: float  # the diameter the passes cut into (a taper thread's: where its cone is read)
    blank_from: str  # the turned surface's line, or the designation


class _TraceThreadRequired(TypedDict):
    program: str
    line: int  # the first pass's
    code: str
    passes: int
    lead: float | None
    side: str  # "external", "internal" or "not known"
    thread: str  # its designation, or "the thread"
    identified: bool
    known_from: str


class TraceThread(_TraceThreadRequired, total=False):
    """One thread the run cut; ``cut`` for an identified ISO metric thread, ``why_not`` for
    one that is not."""

    path: str
    cut: TraceThreadCut
    why_not: str


class _TraceRunTimeRequired(TypedDict):
    program: str
    line: int  # the O line's, 1-based
    seconds: float
    text: str  # "6 min 12.4 s"
    parts: dict[str, float]  # seconds by part: cutting, threading, rapid, dwell, ...
    tool_changes: int
    untimed_moves: int  # moves whose F or spindle speed the run does not know


class TraceRunTime(_TraceRunTimeRequired, total=False):
    """The cycle time of one run (an entry program); ``path`` when in another file."""

    path: str


class TraceCycleTime(TypedDict):
    """The cycle time of every run together, and of each (:mod:`..evaluator.cycle_time`)."""

    seconds: float
    text: str
    parts: dict[str, float]
    untimed_moves: int
    runs: list[TraceRunTime]


class TraceSummary(TypedDict):
    motions: int
    by_code: dict[str, int]
    blocks_executed: int
    stopped: str | None
    stop_message: str | None
    findings: list[TraceFinding]
    read_in_part: list[ReadInPart]
    threads: list[TraceThread]
    cycle_time: TraceCycleTime


class Trace(TypedDict):
    """What ``trace`` answers (see :func:`trace`)."""

    motions: list[TraceMotion]
    toolpath: TraceToolpath
    summary: TraceSummary


def run_with_toolpath(
    uri: str,
    doc: Document,
    index: ProgramIndex,
    others: Sequence[tuple[str, Document, ProgramIndex]] = (),
    config: Config | None = None,
    entry: int | None = None,
) -> Facts:
    """One full run of ``uri``'s programs (or of ``entry``, with ``others`` for its calls), the
    toolpath recorded: what ``trace``, ``plot`` and the Toolpath view show. The machine is
    ``doc``'s (controller 0i-F: as its codes show, ``program.machine_kind``)."""
    return evaluate(
        [(uri, doc, index), *others],
        machine_config(config or Config(), doc, index),
        only_uri=None if entry else uri,
        entry=entry,
        toolpath=True,
    )


def trace(
    uri: str,
    doc: Document,
    index: ProgramIndex,
    others: Sequence[tuple[str, Document, ProgramIndex]] = (),
    config: Config | None = None,
    entry: int | None = None,
) -> Trace:
    """``{"motions": [{program, line, code, words[, speed | surface_speed], start, end[, centre]
    [, moves][, values]}],
    "toolpath": {...}, "summary": {...}}``; lines are 1-based. ``start`` and ``end`` are the
    positions before and after the block (the axes known; a lathe's X a diameter); a canned
    cycle's record lists its ``moves``; ``values`` are what the variables the block reads held
    when it ran (``{"#101": 3.5}``: a number, ``null`` vacant, or a text such as "depends on
    #500" for a value the analysis cannot compute), in the order the block names them. The
    summary's ``read_in_part`` lists the files the analysis read only up to a line, with why
    (``[{"last_line_read": 10, "message": "analysed the first 10 blocks of 32: ... (setting
    ...)"[, "path"]}]``): the run stops there."""
    facts = run_with_toolpath(uri, doc, index, others, config, entry)
    path = facts.toolpath
    assert path is not None
    by_motion = _moves_by_motion(path)
    timed = cycle_time(facts, machine_config(config or Config(), doc, index))
    assert timed is not None
    motions: list[TraceMotion] = []
    for i, m in enumerate(facts.motions):
        record: TraceMotion = {
            "program": m.program,
            "line": m.line + 1,
            "code": m.shown,  # as the program writes it (G code system B, C)
            "words": m.words,
        }
        if m.uri != uri:
            record["path"] = m.uri
        if m.rpm is not None:
            record["speed"] = m.rpm
        elif m.surface_speed is not None:
            record["surface_speed"] = m.surface_speed
        read = path.values.get(i)
        if read:
            record["values"] = {f"#{n}": _value(v) for n, v in read.items()}
        moves = by_motion.get(i)
        if moves:
            record["start"] = _point(moves[0].start)
            record["end"] = _point(moves[-1].end)
            if len(moves) == 1 and moves[0].centre is not None and not moves[0].cycle:
                record["centre"] = _point(moves[0].centre)
            if moves[0].cycle:
                record["moves"] = [_move(mv) for mv in moves]
                if moves[0].cycle != m.code:
                    record["cycle"] = moves[0].cycle
        else:
            here = _point(path.standing.get(i, {}))
            record["start"] = here
            record["end"] = here
        record["clock"] = _seconds(timed.so_far(i))
        motions.append(record)
    codes = Counter(m.shown for m in facts.motions)
    findings: list[TraceFinding] = [
        {"line": f.line + 1, "kind": f.kind, "message": f.message}
        for df in facts.by_uri.values()
        for f in df.findings
    ]
    return {
        "motions": motions,
        "toolpath": {
            "moves": len(path.moves),
            "units": "inch" if path.inch else "mm",
            "lathe": path.lathe,
            "truncated": path.truncated,
            "lost": [_lost_track(lt, uri) for lt in path.lost],
        },
        "summary": {
            "motions": len(motions),
            "by_code": dict(sorted(codes.items())),
            "blocks_executed": facts.steps,
            "stopped": facts.stopped,
            "stop_message": facts.stop_message(),
            "findings": findings,
            "read_in_part": _read_in_part(uri, doc, others),
            "threads": _threads(uri, doc, index, facts),
            "cycle_time": _cycle_time(uri, timed),
        },
    }


def _seconds(seconds: float) -> float:
    """Seconds to the millisecond: what the trace prints and compares."""
    return round(seconds, 3)


def _parts(breakdown: Breakdown) -> dict[str, float]:
    return {part: _seconds(s) for part, s in breakdown.parts().items()}


def _cycle_time(uri: str, timed: CycleTime) -> TraceCycleTime:
    runs: list[TraceRunTime] = []
    for run in timed.runs:
        record: TraceRunTime = {
            "program": run.program,
            "line": run.program_line + 1,
            "seconds": _seconds(run.seconds),
            "text": minutes_seconds(run.seconds),
            "parts": _parts(run.breakdown),
            "tool_changes": run.tool_changes,
            "untimed_moves": run.untimed,
        }
        if run.uri != uri:
            record["path"] = run.uri
        runs.append(record)
    return {
        "seconds": _seconds(timed.total.total),
        "text": minutes_seconds(timed.total.total),
        "parts": _parts(timed.total),
        "untimed_moves": timed.untimed,
        "runs": runs,
    }


def cycle_time_text(summary: TraceSummary) -> str:
    """The trace's line of the cycle time: ``cycle time 10 min 1.3 s (cutting 11.4 s,
    threading 9 min 18.0 s, rapid 29.9 s, tool change 2.0 s)``, the parts that took time, and
    the moves it could not time."""
    timed = summary["cycle_time"]
    parts = [
        tr("{part} {time}", part=PART_NAMES.get(part, part), time=minutes_seconds(seconds))
        for part, seconds in timed["parts"].items()
        if seconds
    ]
    total = tr("cycle time {time}", time=timed["text"])
    if parts:
        total = tr("{total} ({parts})", total=total, parts=joined(", ", parts))
    untimed = timed["untimed_moves"]
    if untimed:
        not_timed = tr_n(
            "{count} move not timed (F or speed not known)",
            "{count} moves not timed (F or speed not known)",
            untimed,
        )
        return tr("{total}; {not_timed}", total=total, not_timed=not_timed)
    return total


def _threads(uri: str, doc: Document, index: ProgramIndex, facts: Facts) -> list[TraceThread]:
    doc_facts = facts.by_uri.get(uri)
    if doc_facts is None:
        return []
    found: list[TraceThread] = []
    threads = identify(doc, index, doc_facts, facts.motions, facts.run_values)
    chains = thread_chains(threads, index)
    for thread in threads:
        job = thread.job
        record: TraceThread = {
            "program": job.program,
            "line": job.passes[0].line + 1,
            "code": job.shown,
            "passes": len(job.passes),
            "lead": job.lead,
            "side": {True: tr("internal"), False: tr("external"), None: tr("not known")}[
                thread.internal
            ],
            "thread": thread.name,
            "identified": thread.identified,
            "known_from": thread.known_from(),
        }
        if job.uri != uri:
            record["path"] = job.uri
        why = thread.unsupported or thread.missing
        if why:
            record["why_not"] = why
        summary = cut_summary(thread, chains.get(id(thread), NO_CHAIN).before)
        if summary is not None:
            record["cut"] = {
                "pitch_diameter": _rounded(summary.pitch_diameter),
                "root_diameter": _rounded(summary.root_diameter),
                "crest_diameter": round(summary.crest_diameter, 4),
                "nose_radius": _rounded(summary.nose_radius),
                "nose_radius_known": summary.nose_radius_known,
                "limits": None if summary.limits is None else _rounded(summary.limits),
                "verdict": summary.verdict,
                "area": round(summary.area, 4),
                "largest_pass": {
                    "line": summary.largest_pass.line + 1,
                    "index": summary.largest_index + 1,
                    "area": round(summary.largest_area, 4),
                },
                "passes_in_air": summary.in_the_air,
                "blank": round(summary.blank, 4),
                "blank_from": summary.blank_from,
            }
        found.append(record)
    return found


def _rounded(values: Sequence[float]) -> list[float]:
    return [round(v, 4) for v in values]


def _read_in_part(
    uri: str, doc: Document, others: Sequence[tuple[str, Document, ProgramIndex]]
) -> list[ReadInPart]:
    """The documents the analysis reads only up to a line (the limits on blocks and size,
    MB013's note): what is past it is not run."""
    out: list[ReadInPart] = []
    for other_uri, other, _ in ((uri, doc, None), *others):
        if other.unread_from is None or other.unread_note is None:
            continue
        part: ReadInPart = {"last_line_read": other.unread_from, "message": other.unread_note}
        if other_uri != uri:
            part["path"] = other_uri
        out.append(part)
    return out


def _lost_track(lost: LostTrack, uri: str) -> TraceLostTrack:
    out: TraceLostTrack = {
        "program": lost.program,
        "line": lost.line + 1,
        "axes": list(lost.axes),
        "reason": lost.reason,
    }
    if lost.uri != uri:
        out["path"] = lost.uri
    return out


def _value(value: Value) -> VariableValue:
    """A variable's value in JSON: a number, ``None`` (vacant), or a text (unknown, overflow)."""
    if value is None or (isinstance(value, float) and math.isfinite(value)):
        return value
    return fmt(value)


def _moves_by_motion(path: Toolpath) -> dict[int, list[Move]]:
    out: dict[int, list[Move]] = {}
    for move in path.moves:
        if move.motion >= 0:
            out.setdefault(move.motion, []).append(move)
    return out


def _point(position: dict[str, float]) -> Point:
    """The axes in X, Y, Z order (the values are at the least increment already)."""
    return {a: position[a] for a in "XYZ" if a in position}


def _move(move: Move) -> TraceMove:
    out: TraceMove = {"kind": move.kind, "start": _point(move.start), "end": _point(move.end)}
    if move.centre is not None:
        out["centre"] = _point(move.centre)
        out["clockwise"] = move.clockwise
    return out


def position_text(position: dict[str, float]) -> str:
    """``X51. Z5.964``, or ``?`` when no axis is known."""
    return " ".join(f"{a}{fmt_address(v)}" for a, v in position.items()) or "?"


def motion_text(motion: TraceMotion) -> str:
    """One motion of a trace as the command line prints it: program, line, code, its words at
    the control's precision, where it goes from and to, and a cycle's moves."""
    words = " ".join(f"{k}{fmt_address(v)}" for k, v in motion["words"].items())
    parts: list[str] = [
        tr(
            "{program:<6} line {line:<5} {code:<4} {words_text}",
            program=motion["program"],
            line=motion["line"],
            code=motion["code"],
            words_text=words,
        )
    ]
    if "start" in motion:
        parts.append(f"  [{position_text(motion['start'])} -> {position_text(motion['end'])}]")
    if "centre" in motion:
        parts.append(tr(" centre {position}", position=position_text(motion["centre"])))
    moves = motion.get("moves")
    if moves:
        steps = joined(
            ", ",
            [
                tr(
                    "{kind} {position}",
                    kind=MOVE_NAMES.get(m["kind"], m["kind"]),
                    position=position_text(m["end"]),
                )
                for m in moves
            ],
        )
        if "cycle" in motion:
            parts.append(tr(" {cycle} moves: {steps}", cycle=motion["cycle"], steps=steps))
        else:
            parts.append(tr(" moves: {steps}", steps=steps))
    return joined("", parts)
