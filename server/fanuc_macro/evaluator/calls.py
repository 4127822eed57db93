"""Calls and returns: M98 and M99, G65 and the G66 modal calls, and calls the run cannot follow.

A call pushes an :class:`.machine_base.Activation`: M98 shares the caller's locals, G65 and
G66 open a new level of them with the arguments; the control's nesting limits raise its alarms.
"""

from __future__ import annotations

from ..program.variables import ARGUMENT_VARIABLES
from .compile_lines import CompiledLine, CompiledWord
from .facts import ProgramNotFound
from .machine_base import Activation, MachineBase, ProgramContext, StopRun
from .values import UNKNOWN, AlarmKind, MacroAlarm, Unknown, Value

MAX_MACRO_LEVEL = 5  # G65/G66 levels (0i-D/30i); 16i has 4
MAX_NESTING = 10


class CallsPart(MachineBase):
    """The machine's calls and returns."""

    def _find(
        self, act: Activation, cl: CompiledLine, number: Value, what: str
    ) -> ProgramContext | None:
        if isinstance(number, Unknown) or number is None:
            return None
        ctx = self.programs.get(int(number))
        if ctx is None:
            message = (
                f"{what} calls O{int(number):04d}, which the analysis does not "
                "have; the call is skipped"
            )
            width = len(act.ctx.doc.blocks[self._line].text)
            self._finding(
                act.ctx,
                ProgramNotFound(self._line, 0, width, message, act.ctx.uri, program=int(number)),
            )
        return ctx

    def _sub_call(self, act: Activation, cl: CompiledLine, values: dict[str, Value]) -> Activation:
        p = values.get("P")
        l_value = values.get("L")
        repeat = 1
        if (
            isinstance(p, float)
            and l_value is None
            and self.config.four_digit_programs
            and (p >= 10000)
        ):
            repeat = int(p) // 10000
            p = float(int(p) % 10000)
        elif isinstance(l_value, float):
            repeat = int(l_value)
        callee = self._find(act, cl, p, "M98")
        if callee is None or repeat <= 0:
            if repeat > 0:
                self._call_unknown(act, shares_locals=True)
            act.pc = self._line + 1
            return act
        # M98 opens no new local level: the callee shares the caller's locals.
        return self._enter(act, callee, act.locals, False, self._line + 1, repeat)

    def _macro_call(
        self,
        act: Activation,
        cl: CompiledLine,
        order: list[tuple[str, Value, CompiledWord]],
        modal_call: bool,
    ) -> Activation:
        p: Value = None
        repeat = 1
        args: list[Value] = [None] * 34
        seen_g = False
        ijk_set = -1
        ijk_seen: set[str] = set()
        for address, v, _w in order:
            if address == "G" and not seen_g:
                seen_g = True
                continue
            if address == "P":
                p = v
            elif address == "L":
                repeat = int(v) if isinstance(v, float) else 1
            elif address in "IJK":
                # Specification II: repeated I/J/K fill #4-#33 in sets of three.
                if (
                    ijk_set < 0
                    or address in ijk_seen
                    or "IJK".index(address) < max("IJK".index(a) for a in ijk_seen)
                ):
                    ijk_set += 1
                    ijk_seen = set()
                ijk_seen.add(address)
                n = 4 + 3 * ijk_set + "IJK".index(address)
                if n <= 33:
                    args[n] = v
            elif address in ARGUMENT_VARIABLES:
                args[ARGUMENT_VARIABLES[address]] = v
        callee = self._find(act, cl, p, "G66" if modal_call else "G65")
        if modal_call:
            self.modal.modal_calls.append((callee, args, repeat))
            return act
        if callee is None:
            self._call_unknown(act, shares_locals=False)
            act.pc = self._line + 1
            return act
        return self._enter(act, callee, args, True, self._line + 1, repeat)

    def _call_unknown(self, act: Activation, shares_locals: bool) -> None:
        """After a call the analysis cannot follow (a program not in the analysed files, such
        as a probe vendor's O9814, or a P it cannot compute), what the callee may have changed
        is unknown: the run goes on, but no verdict rests on a value from before the call."""
        # The callee may write every common variable (#100-#199, #500-#999, the extended
        # ranges) and every writable system variable (tool offsets #2001+/#10001+, work
        # offsets #5201+, #7001+, #14001+, #15801+ on some controls), and what it does moves
        # the read-only ones (positions, modal information). The store holds only what this
        # run set, and a number missing from it reads as unknown ("depends on #135").
        # [shared reference macro-b.md §9; the ranges are unverified against a manual]
        self.store.clear()
        if shares_locals:
            # M98 opens no local level: the callee reads and writes the caller's #1-#33
            # [M FANUC-16i-PB, custom macro: "local variables"].
            locals_ = act.locals
            for n in range(1, 34):
                locals_[n] = self.unknown_of(n)
        modal = self.modal
        # F, S and where the tool stands are modal: the callee leaves its own.
        modal.feed = UNKNOWN
        modal.speed = UNKNOWN
        modal.position.clear()
        modal.position_line.clear()
        if self.toolpath is not None:
            ctx = act.ctx
            self.toolpath.lose_all(
                self._line,
                ctx.name,
                ctx.uri,
                "a call the analysis cannot follow moves the tool where it does not know",
            )

    def _enter(
        self,
        act: Activation,
        callee: ProgramContext,
        locals_: list[Value],
        new_level: bool,
        return_pc: int,
        repeat: int,
    ) -> Activation:
        depth = 0
        level = act.macro_level
        a: Activation | None = act
        while a is not None:
            depth += 1
            a = a.caller
        if new_level:
            level += 1
            if level > MAX_MACRO_LEVEL:
                raise MacroAlarm(
                    "PS0077",
                    AlarmKind.NESTING,
                    f"macro call nesting deeper than "
                    f"{MAX_MACRO_LEVEL} levels (TOO MANY SUB,MACRO NESTING)",
                )
        if depth > MAX_NESTING:
            raise MacroAlarm(
                "PS0077",
                AlarmKind.NESTING,
                f"call nesting deeper than {MAX_NESTING} (TOO MANY SUB,MACRO NESTING)",
            )
        callee.facts.analysed_programs.add(callee.program.first_line)
        locals_list = list(locals_) if new_level else locals_
        new = Activation(self, callee, locals_list, level, act, return_pc, repeat - 1)
        if new_level and repeat > 1:
            new.arguments = tuple(locals_)  # G65 L: each repetition starts from the arguments
        new.undecided_loops = set()
        return new

    def _return(self, act: Activation, p: Value, line: int) -> Activation:
        if act.repeats_left > 0:
            act.repeats_left -= 1
            act.pc = act.ctx.program.first_line
            if act.arguments is not None:
                act.locals[:] = act.arguments
            return act
        caller = act.caller
        if caller is None:
            # M99 in a program nobody called: the control restarts it (unverified); the run
            # stops here rather than loop.
            raise StopRun("end of program")
        if isinstance(p, float):
            target = self._label(caller.ctx, int(p), caller.pc)
            if target is None:
                raise MacroAlarm(
                    "PS0078",
                    AlarmKind.RETURN_MISSING,
                    f"M99 P{int(p)}: no N{int(p)} in {caller.ctx.name} (SEQUENCE NUMBER NOT FOUND)",
                    p,
                )
            caller.pc = target
        else:
            caller.pc = act.return_pc
        return caller
