"""Calls and returns: M98 and M99, G65 and the G66 modal calls, and calls the run cannot follow.

A call pushes an :class:`.machine_base.Activation`: M98 shares the caller's locals, G65 and
G66 open a new level of them with the arguments; the control's nesting limits raise its alarms.
"""

from __future__ import annotations

from ..config import CustomCallSetting, on_control
from ..program.custom_calls import called_by_code, calling_word
from ..program.variables import ARGUMENT_VARIABLES
from ..program.vendor_cycles import known_cycle
from ..translation import tr
from .compile_lines import CompiledLine, CompiledWord
from .facts import ProgramNotFound
from .machine_base import SPINDLE_UNKNOWN, Activation, MachineBase, ProgramContext, StopRun
from .values import UNKNOWN, AlarmKind, MacroAlarm, Unknown, Value

MAX_MACRO_LEVEL = 5  # G65/G66 levels (0i-D/30i); 16i has 4
MAX_NESTING = 10


class CallsPart(MachineBase):
    """The machine's calls and returns."""

    # The custom call each compiled NC line makes (by the line's id, with the line kept alive),
    # worked out when the run first meets it: most runs set up no custom code and never ask.
    _custom_lines: dict[int, tuple[CompiledLine, CustomCallSetting | None]] | None = None

    def _find(
        self, act: Activation, cl: CompiledLine, number: Value, what: str, quiet: bool = False
    ) -> ProgramContext | None:
        """The program a call runs; a finding when it is not there, unless the settings say the
        control has it (``quiet``: a custom code's program, which its parameter names;
        machine.programsOnControl) or it is a vendor's known cycle."""
        if isinstance(number, Unknown) or number is None:
            return None
        ctx = self.programs.get(int(number))
        if ctx is None and not (
            quiet or on_control(self.config, int(number)) or known_cycle(int(number))
        ):
            message = tr(
                "{call} calls O{program:04d}, which the analysis does not "
                "have; the call is skipped",
                call=what,
                program=int(number),
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
        if p is None and isinstance(values.get("Q"), float):
            return self._internal_call(act, values["Q"], repeat)
        callee = self._find(act, cl, p, "M98")
        if callee is None or repeat <= 0:
            if repeat > 0:
                self._call_unknown(act, shares_locals=True)
            act.pc = self._line + 1
            return act
        # M98 opens no new local level: the callee shares the caller's locals.
        return self._enter(act, callee, act.locals, False, self._line + 1, repeat)

    def _internal_call(self, act: Activation, q: Value, repeat: int) -> Activation:
        """``M98 Q<n>`` without P: a subprogram call of the block N<n> of the program running
        (FANUC Series 0i-F / 30i, "Subprogram call": the sequence number in the program;
        unverified against the manual's text, seen in a 0i-MF shop's programs). M99 returns to
        the block after the call. A Q the program has no N for is MB405's, said from the text."""
        target = None
        if isinstance(q, float) and q == int(q):
            target = self._internal_entry(act.ctx, int(q))
        if target is None or repeat <= 0:
            if repeat > 0:
                self._call_unknown(act, shares_locals=True)
            act.pc = self._line + 1
            return act
        new = self._enter(act, act.ctx, act.locals, False, self._line + 1, repeat)
        new.pc = target
        return new

    def _internal_entry(self, ctx: ProgramContext, seq: int) -> int | None:
        """The line an ``M98 Q<seq>`` of ``ctx``'s program enters (its N<seq> from the head)."""
        return ctx.program.label_line(seq)

    def _restart_line(self, act: Activation) -> int:
        """Where a repeated subprogram starts again: its head, or the N<q> an internal call
        ``M98 Q<q> L<k>`` entered (read again from the calling block)."""
        caller = act.caller
        if caller is not None and caller.ctx is act.ctx and act.return_pc > 0:
            cl = act.ctx.lines[act.return_pc - 1]
            q: Value = None
            has_p = False
            if cl.constant is not None:
                q, has_p = cl.constant.values.get("Q"), "P" in cl.constant.values
            for w in cl.words:
                if w.address == "Q" and q is None:
                    try:
                        q = w.evaluate(caller)
                    except MacroAlarm:
                        break
                elif w.address == "P":
                    has_p = True
            if not has_p and isinstance(q, float) and q == int(q):
                target = self._internal_entry(act.ctx, int(q))
                if target is not None:
                    return target
        return act.ctx.program.first_line

    def _custom_setting(self, act: Activation, cl: CompiledLine) -> CustomCallSetting | None:
        """The custom code an NC line calls with, as the settings set up; None inside a program
        such a code calls, where the codes are plain codes."""
        settings = self.config.custom_calls
        if called_by_code(act.ctx.program.number, settings):
            return None
        lines = self._custom_lines
        if lines is None:
            lines = self._custom_lines = {}
        known = lines.get(id(cl))
        if known is None:
            # Not a Haas ``IF [c] <words>`` block: another control's (MB002), run by _nc.
            found = calling_word(cl.nc, settings) if cl.nc is not None and not cl.cond else None
            known = lines[id(cl)] = (cl, found[1] if found is not None else None)
        return known[1]

    def _custom_call(
        self, act: Activation, cl: CompiledLine, setting: CustomCallSetting
    ) -> Activation:
        """A block whose code the control's parameters make call a program: a macro call whose
        arguments are the other words, like G65; or a subprogram call, like M98, the code's
        value in its common variable (T: #149). The block's other words do not run as NC words
        (unverified: on the control those of a subprogram call run before the call)."""
        order: list[tuple[str, Value, CompiledWord]] = []
        code_value: Value = None
        if cl.constant is not None:
            words = cl.constant.order
        else:  # a vacant variable omits its word
            words = [(w.address, v, w) for w in cl.words if (v := w.evaluate(act)) is not None]
        number = setting.number
        for address, v, w in words:
            if code_value is None and address == setting.address and number in (None, v):
                code_value = v  # the code itself: no argument (M08 M165: M08 is one, #13)
                continue
            order.append((address, v, w))
        callee = self._find(act, cl, float(setting.program), setting.code, quiet=True)
        if setting.macro and callee is not None:
            return self._macro_call(act, cl, order, modal_call=False, callee=callee)
        if setting.value_variable is not None and code_value is not None:
            self.store[setting.value_variable] = code_value
        if callee is None:
            self._call_unknown(act, shares_locals=not setting.macro)
            act.pc = self._line + 1
            return act
        return self._enter(act, callee, act.locals, False, self._line + 1, 1)

    def _macro_call(
        self,
        act: Activation,
        cl: CompiledLine,
        order: list[tuple[str, Value, CompiledWord]],
        modal_call: bool,
        callee: ProgramContext | None = None,
    ) -> Activation:
        """G65 or G66 (``order`` the block's words), or a custom macro call (``callee`` given,
        ``order`` the words but the code)."""
        p: Value = None
        repeat = 1
        args: list[Value] = [None] * 34
        seen_g = False  # the G65/G66 itself (G is no argument letter)
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
        if callee is None:
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
        modal.spindle = SPINDLE_UNKNOWN
        modal.z_at_top = False
        modal.setup = modal.setup.after_unknown_call()
        modal.position.clear()
        modal.position_line.clear()
        if self.toolpath is not None:
            ctx = act.ctx
            self.toolpath.lose_all(
                self._line,
                ctx.name,
                ctx.uri,
                tr("a call the analysis cannot follow moves the tool where it does not know"),
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
                    tr(
                        "macro call nesting deeper than "
                        "{levels} levels (TOO MANY SUB,MACRO NESTING)",
                        levels=MAX_MACRO_LEVEL,
                    ),
                )
        if depth > MAX_NESTING:
            raise MacroAlarm(
                "PS0077",
                AlarmKind.NESTING,
                tr(
                    "call nesting deeper than {levels} (TOO MANY SUB,MACRO NESTING)",
                    levels=MAX_NESTING,
                ),
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
            act.pc = self._restart_line(act)
            act.loops_turning.clear()
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
                    tr(
                        "M99 P{label}: no N{label} in {program} (SEQUENCE NUMBER NOT FOUND)",
                        label=int(p),
                        program=caller.ctx.name,
                    ),
                    p,
                )
            caller.pc = target
        else:
            caller.pc = act.return_pc
        return caller
