"""What a stop shows: the macro levels as frames, their scopes (locals, commons, system
variables, the modal state) and variables, and expressions evaluated or variables set there."""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from types import MappingProxyType

from ..evaluator.compiler import Evaluator
from ..evaluator.cycle_time import cycle_time, minutes_seconds
from ..evaluator.machine import Activation
from ..evaluator.values import MacroAlarm, Value
from ..program.knowledge import code_name
from ..program.variables import ARGUMENT_VARIABLES, classify
from ..translation import tr
from .answers import DebugError, FrameInfo, ScopeInfo, VariableInfo
from .expressions import Probe, parse_assignment, parse_condition, parse_expression, read_variable
from .run_record import RunRecord

# The G65 letter of each argument variable (#1 A, #2 B, ...).
LETTER_OF: MappingProxyType[int, str] = MappingProxyType(
    {n: letter for letter, n in ARGUMENT_VARIABLES.items()}
)
_CALL_WORD = re.compile(r"(?<![A-Z#\d.])(G0*65|G0*66(?:\.1)?|M0*98)(?![\d])", re.I)


class StopView:
    """The run stopped before ``line`` of the innermost of ``levels`` (innermost first). A
    frame's id is its place in ``levels`` from 1; a scope's reference is ``frame id * 10`` plus
    1 locals, 2 commons, 3 system variables, 4 the modal state."""

    def __init__(
        self,
        levels: Sequence[Activation],
        line: int,
        record: RunRecord,
        show: Callable[[Value], str],
    ) -> None:
        self.levels = levels
        self.line = line
        self.record = record
        self.show = show

    def frames(self) -> list[FrameInfo]:
        levels = self.levels
        out: list[FrameInfo] = []
        for i, act in enumerate(levels):
            line = self.line if i == 0 else levels[i - 1].return_pc - 1
            out.append(FrameInfo(i + 1, self._frame_name(act), act.ctx.uri, line, 0))
        return out

    def _frame_name(self, act: Activation) -> str:
        name = act.ctx.name
        caller = act.caller
        if caller is None:
            return name
        call_line = act.return_pc - 1
        text = (
            caller.ctx.doc.blocks[call_line].text
            if 0 <= call_line < len(caller.ctx.doc.blocks)
            else ""
        )
        found = _CALL_WORD.search(text)
        how = code_name(found.group(1)[0], float(found.group(1)[1:])) if found else "G66"
        if how == "M98" and act.macro_level == caller.macro_level:
            return f"{name} (M98 from {caller.ctx.name})"
        args = self.record.called_with.get(act.serial, ())
        words = " ".join(f"{LETTER_OF.get(n, f'#{n}=')}{self.show(v)}" for n, v in args)
        return f"{name} ({how} {words})".replace(" )", ")")

    def level(self, frame_id: int) -> Activation:
        if not 1 <= frame_id <= len(self.levels):
            raise DebugError(f"no stack frame {frame_id}")
        return self.levels[frame_id - 1]

    def scopes(self, frame_id: int) -> list[ScopeInfo]:
        act = self.level(frame_id)
        base = frame_id * 10
        commons = _common_numbers(act)
        system = self._system_numbers(act)
        # Short titles, that a narrow Variables view shows whole: the frame names the program
        # and how it was called; a program M98 called has its caller's locals, which it names.
        owner = act
        while owner.caller is not None and owner.macro_level == owner.caller.macro_level:
            owner = owner.caller
        locals_ = (
            tr("Locals #1-#33")
            if owner is act
            else tr("Locals #1-#33 of {program}", program=owner.ctx.name)
        )
        return [
            ScopeInfo(locals_, base + 1, 33),
            ScopeInfo(tr("Common variables"), base + 2, len(commons)),
            ScopeInfo(tr("System variables"), base + 3, len(system)),
            ScopeInfo(tr("Modal state"), base + 4, len(self._modal(act))),
        ]

    def _system_numbers(self, act: Activation) -> list[int]:
        return sorted(
            {n for n in self.record.system_seen if classify(n).kind == "system"}
            | {n for n in act.store if classify(n).kind == "system"}
        )

    def variables(self, reference: int) -> list[VariableInfo]:
        frame_id, scope = divmod(reference, 10)
        act = self.level(frame_id)
        if scope == 1:
            letters = act.caller is not None and act.macro_level > act.caller.macro_level
            return [
                VariableInfo(
                    f"#{n} ({LETTER_OF[n]})" if letters and n in LETTER_OF else f"#{n}",
                    self.show(act.locals[n]),
                    f"#{n}",
                    "local",
                )
                for n in range(1, 34)
            ]
        if scope in (2, 3):
            numbers = _common_numbers(act) if scope == 2 else self._system_numbers(act)
            out = []
            for n in numbers:
                kind = classify(n)
                name = (
                    f"#{n}"
                    if scope == 2
                    else tr("#{number} ({meaning})", number=n, meaning=kind.meaning)
                )
                out.append(
                    VariableInfo(
                        name,
                        self.show(read_variable(act, n)),
                        f"#{n}",
                        "common" if scope == 2 else "system",
                        kind.read_only,
                    )
                )
            return out
        if scope == 4:
            return self._modal(act)
        raise DebugError(f"no variables {reference}")

    def _modal(self, act: Activation) -> list[VariableInfo]:
        modal = act.machine.modal
        groups = self.record.groups
        show = self.show
        out: list[VariableInfo] = [
            VariableInfo(
                tr("G group {group}", group=group),
                code_name("G", groups[group]),
                kind="modal",
                read_only=True,
            )
            for group in sorted(groups)
        ]
        if modal.motion is not None and "01" not in groups:
            out.append(
                VariableInfo(
                    tr("G group {group}", group="01"),
                    code_name("G", modal.motion),
                    kind="modal",
                    read_only=True,
                )
            )
        out.sort(key=lambda v: v.name)
        unit = tr("inch (G20)") if modal.inch else tr("mm (G21)")
        out.append(VariableInfo(tr("unit"), unit, kind="modal", read_only=True))
        out.append(VariableInfo("F", show(modal.feed), kind="modal", read_only=True))
        speed = show(modal.speed)
        if modal.constant_surface_speed:
            speed += " m/min (G96)"
        out.append(VariableInfo("S", speed, kind="modal", read_only=True))
        out.append(VariableInfo("T", show(self.record.tool), kind="modal", read_only=True))
        machine = act.machine
        timed = cycle_time(machine.facts, machine.config)  # what ran before the stopped block
        if timed is not None:
            elapsed = minutes_seconds(timed.total.total)
            so_far = tr("cycle time so far")
            out.append(VariableInfo(so_far, elapsed, kind="modal", read_only=True))
        for axis in sorted(modal.position):
            out.append(VariableInfo(axis, show(modal.position[axis]), kind="modal", read_only=True))
        for callee, _args, _repeat in modal.modal_calls:
            out.append(
                VariableInfo(
                    tr("G66 in force"),
                    callee.name if callee else tr("a program not in these files"),
                    kind="modal",
                    read_only=True,
                )
            )
        return out

    def evaluate(self, text: str, frame_id: int | None) -> str:
        """A Macro B expression or condition at a frame (the top one by default), or an
        assignment (``#100=5``) done there."""
        text = text.strip()
        if not text:
            raise DebugError("nothing to evaluate")
        act = self.level(frame_id or 1)
        assignment = parse_assignment(text)
        if assignment is not None:
            target, value = assignment
            if target.number is None:
                raise DebugError("assign to a numbered variable (#100=5), not #[...]")
            return self.set_variable(act, int(target.number), value)
        try:
            evaluator = parse_expression(text)
        except DebugError:
            cond = parse_condition(text)
            result = cond(Probe(act))
            return {True: "true", False: "false"}.get(result, f"unknown ({result})")  # type: ignore[arg-type]
        try:
            return self.show(evaluator(Probe(act)))
        except MacroAlarm as alarm:
            raise DebugError(f"{alarm.message} (alarm {alarm.alarm})") from None

    def set_variable_at(self, reference: int, name: str, text: str) -> str:
        frame_id, scope = divmod(reference, 10)
        act = self.level(frame_id)
        if scope == 4:
            raise DebugError("the modal state is what the blocks set: change it in the program")
        found = re.match(r"\s*#(\d+)", name)
        if found is None:
            raise DebugError(f"{name!r} is not a variable")
        return self.set_variable(act, int(found.group(1)), parse_expression(text))

    def set_variable(self, act: Activation, n: int, value: Evaluator) -> str:
        kind = classify(n)
        if kind.kind == "none":
            raise DebugError(f"#{n} does not exist on this control")
        if kind.read_only:
            raise DebugError(f"#{n} is read-only ({kind.meaning})")
        try:
            result = value(Probe(act))
        except MacroAlarm as alarm:
            raise DebugError(f"{alarm.message} (alarm {alarm.alarm})") from None
        if 1 <= n <= 33:
            act.locals[n] = result
        else:
            act.store[n] = result
        return self.show(result)


def _common_numbers(act: Activation) -> list[int]:
    return sorted(
        n
        for n in act.store
        if n > 33 and classify(n).kind in ("common", "retained", "extended-common")
    )
