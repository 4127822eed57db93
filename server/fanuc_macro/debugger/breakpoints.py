"""The session's breakpoints: where each stops in the text as read now (or why it does not),
and which of them a block about to run hits (their conditions, hit counts and logpoints)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from ..evaluator.machine import Activation, compiled
from ..evaluator.values import MacroAlarm, Value
from ..workspace import Workspace
from .answers import Breakpoint, DebugError
from .expressions import Probe, hit_test, interpolate, parse_condition

# What the table says to the front end: (category, text, file, 0-based line).
Say = Callable[[str, str, str | None, int | None], None]


class BreakpointTable:
    """The breakpoints of every file, by the file's key. The front end's thread replaces a
    file's list (under the session's lock); the run thread reads them before each block."""

    def __init__(self) -> None:
        self.by_key: dict[str, list[Breakpoint]] = {}
        self._next_id = 0

    def __iter__(self) -> Iterator[Breakpoint]:
        for bps in self.by_key.values():
            yield from bps

    def made(
        self, key: str, asked: list[tuple[int, str, str, str]], workspace: Workspace
    ) -> tuple[str, list[Breakpoint]]:
        """New breakpoints for ``key`` (its resolved path and them), verified in ``workspace``:
        (0-based line, condition, hit condition, log message) each."""
        resolved = str(Path(key).resolve()) if not key.startswith("untitled:") else key
        made: list[Breakpoint] = []
        for line, condition, hit, log in asked:
            self._next_id += 1
            bp = Breakpoint(
                self._next_id,
                resolved,
                line,
                condition=condition,
                hit_condition=hit,
                log_message=log,
            )
            verify(bp, workspace)
            made.append(bp)
        return resolved, made

    def reset_hits(self) -> None:
        for bp in self:
            bp.hits = 0

    def hit_at(
        self, act: Activation, key: str, line: int, say: Say, show: Callable[[Value], str]
    ) -> list[int]:
        """The ids of the breakpoints that stop before ``line`` of ``key`` now; a logpoint
        says its message instead, a condition that cannot be decided says so once."""
        bps = self.by_key.get(key)
        if not bps:
            return []
        hit: list[int] = []
        for bp in bps:
            if not bp.verified or bp.actual_line != line:
                continue
            if bp._cond is not None and not _condition_holds(bp, act, key, line, say):
                continue
            bp.hits += 1
            if bp._hit is not None and not bp._hit(bp.hits):
                continue
            if bp.log_message:
                say("console", interpolate(bp.log_message, act, show), key, line)
                continue
            hit.append(bp.id)
        return hit


def _condition_holds(bp: Breakpoint, act: Activation, key: str, line: int, say: Say) -> bool:
    assert bp._cond is not None
    try:
        result = bp._cond(Probe(act))
    except MacroAlarm as alarm:
        say("console", f"breakpoint condition {bp.condition}: {alarm.message}", None, None)
        return False
    if result is True:
        return True
    if result is not False and not bp._told_unknown:
        bp._told_unknown = True
        say(
            "console",
            f"line {line + 1}: the condition {bp.condition} cannot be "
            "decided here (it reads a value set outside the program); the "
            "breakpoint stops only where it is true.",
            key,
            line,
        )
    return False


def verify(bp: Breakpoint, workspace: Workspace) -> None:
    """Where ``bp`` stops in the text as read now, or why it does not. A breakpoint on a line
    that runs nothing moves to the next block of its program that does; outside every
    program it is not verified, and says why."""
    bp.verified, bp.actual_line, bp.message = False, None, ""
    line = bp.line
    doc = workspace.document(bp.key)
    if doc is None:
        bp.message = "this file is not the program under the debugger nor in its folder"
        return
    index = workspace.index(bp.key)
    program = next((p for p in index.programs if p.contains(line)), None)
    if program is None:
        # Before a program (a '%', a comment): its first block, if nothing runs between.
        program = next((p for p in index.programs if p.first_line > line), None)
        if program is not None and any(
            _runs(doc.blocks[n].parsed) for n in range(line, program.first_line)
        ):
            program = None
    if program is None:
        bp.message = "no program here (outside O...%): the control runs nothing here"
        return
    target = next((n for n in range(line, program.end_line) if _runs(doc.blocks[n].parsed)), None)
    if target is None:
        bp.message = f"no block runs from here to the end of {program.display_name}"
        return
    try:
        bp._cond = parse_condition(bp.condition) if bp.condition.strip() else None
        bp._hit = hit_test(bp.hit_condition) if bp.hit_condition.strip() else None
    except DebugError as err:
        bp.message = str(err)
        return
    bp.verified = True
    bp.actual_line = target


def _runs(parsed: Any) -> bool:
    """Whether the control runs something on this line (a statement, not a comment alone)."""
    return parsed.statement is not None and compiled(parsed).kind not in (0,)
