"""What a run has seen that the scopes show and the machine does not keep: the system
variables read or written, the modal G codes by group, the T word, the arguments each macro
level was called with, and the stop the last block asked for (a #3006 message, an M00)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..config import SYSTEM_A
from ..evaluator.machine import K_ASSIGN, K_IFGOTO, K_IFTHEN, K_NC, K_OTHER, K_WHILE, Activation
from ..evaluator.values import MacroAlarm, Unknown, Value
from ..program.g_code_systems import ABSOLUTE, INCREMENTAL, system_a_code
from ..program.knowledge import modal_group
from ..syntax.tree import Print
from ..translation import tr
from .answers import MESSAGE_FILTER, PROGRAM_STOP_FILTER
from .breakpoints import Say
from .expressions import Probe, dprnt_line


class RunRecord:
    """Kept by the run thread, read by the front end's at a stop."""

    def __init__(self) -> None:
        self.system_seen: set[int] = set()
        self.groups: dict[str, float] = {}
        self.tool: Value = None
        self.called_with: dict[int, tuple[tuple[int, Value], ...]] = {}
        # A stop the last block asked for: filter, description, text.
        self.pending_stop: tuple[str, str, str] | None = None
        self.undecided_seen: set[tuple[str, int]] = set()

    def clear(self) -> None:
        self.system_seen.clear()
        self.groups.clear()
        self.tool = None
        self.called_with.clear()
        self.pending_stop = None
        self.undecided_seen.clear()

    def note_level(self, act: Activation) -> None:
        """A new macro level's first block: its locals are the arguments it was called with."""
        caller = act.caller
        if (
            caller is not None
            and act.macro_level > caller.macro_level
            and act.serial not in self.called_with
        ):
            self.called_with[act.serial] = tuple(
                (n, v) for n, v in enumerate(act.locals) if n and v is not None
            )

    def note_block(self, act: Activation, cl: Any, line: int, say: Say) -> None:
        """What the block about to run changes: the system variables it names, the modal G
        codes and T, a DPRNT, a #3006, an M00 or M01."""
        for n in cl.reads:
            if n >= 1000:
                self.system_seen.add(n)
        kind = cl.kind
        if kind == K_ASSIGN:
            n = cl.target_number
            if n is not None and n >= 1000:
                self.system_seen.add(n)
            if n == 3006:
                # The control stops after the block and shows its comment (FANUC custom macro,
                # "#3006 stop with message").
                text = block_comment(act, line)
                self.pending_stop = (
                    MESSAGE_FILTER,
                    tr("Stop with message (#3006)"),
                    text or "#3006",
                )
        elif kind in (K_IFGOTO, K_IFTHEN, K_WHILE) and cl.cond is not None:
            self._note_condition(act, cl, line, say)
        elif kind == K_OTHER and isinstance(cl.node, Print) and cl.node.keyword == "DPRNT":
            say("stdout", dprnt_line(cl.node.text, act), act.ctx.uri, line)
        elif kind == K_NC:
            self._note_words(act, cl, line)

    def _note_words(self, act: Activation, cl: Any, line: int) -> None:
        """An NC block's G codes by modal group, its T word, and the stop of an M00 / M01."""
        const = cl.constant
        if const is not None:
            g_codes: list[float] = list(const.g_codes)
            m_codes: list[float] = list(const.m_codes)
            tool = const.values.get("T")
        else:
            g_codes, m_codes, tool = [], [], None
            for w in cl.words:
                try:
                    v = w.evaluate(Probe(act))
                except MacroAlarm:
                    continue
                if w.address == "G" and isinstance(v, float):
                    g_codes.append(round(v, 1))
                elif w.address == "M" and isinstance(v, float):
                    m_codes.append(v)
                elif w.address == "T" and v is not None:
                    tool = v
        if 0.0 in m_codes or 1.0 in m_codes:
            code = "M00" if 0.0 in m_codes else "M01"
            said = (
                tr("{code} program stop", code=code)
                if code == "M00"
                else tr("{code} optional stop", code=code)
            )
            text = block_comment(act, line)
            self.pending_stop = (
                PROGRAM_STOP_FILTER,
                tr("Program stop ({code})", code=code),
                tr("{stop}: {comment}", stop=said, comment=text) if text else said,
            )
        lathe = act.machine.lathe
        system = act.machine.config.g_code_system if lathe else SYSTEM_A
        for g in g_codes:
            # A system B or C lathe's code shown as written, in the group of its function.
            a = system_a_code(g, system)
            if a is None and g in (ABSOLUTE, INCREMENTAL):
                group: str | None = "03"
            else:
                group = None if a is None else modal_group(a, lathe)
            if group is not None:
                self.groups[group] = g
        if tool is not None:
            self.tool = tool

    def _note_condition(self, act: Activation, cl: Any, line: int, say: Say) -> None:
        """A condition the analysis cannot decide (it reads a probe's result, a PMC signal):
        the run goes on as the checker's does, which the control may not; said once a line."""
        key = (act.ctx.uri, line)
        if key in self.undecided_seen:
            return
        try:
            result = cl.cond(Probe(act))
        except MacroAlarm:
            return  # the block's own run raises it
        if isinstance(result, bool):
            return
        self.undecided_seen.add(key)
        depends = result.describe() if isinstance(result, Unknown) else "unknown"
        say(
            "console",
            f"{Path(act.ctx.uri).name}:{line + 1}: this condition cannot be decided before the "
            f"machine runs ({depends}): the run goes on as the checker's does (an IF falls "
            "through the first time and jumps the next, a WHILE runs its body once), which "
            "the control may not.",
            act.ctx.uri,
            line,
        )


def block_comment(act: Activation, line: int) -> str:
    """The comments of the block at ``line``: what the control shows with a stop or alarm."""
    parsed = act.ctx.doc.blocks[line].parsed
    return " ".join(c.text for c in parsed.comments).strip()
