"""Running programs as the control would: blocks, jumps, loops, calls, modal state.

The run starts from each entry program (one nothing calls; a file's first) with a step and a
time budget, and records facts (:mod:`.facts`) as it goes. Values the analysis cannot know are
:class:`Unknown`; a branch on an unknown condition takes the fall-through path (and a WHILE on
an unknown condition runs its body once), so a program analysed alone still gets its values.

:class:`Machine` is the block loop, the macro statements and the checkpoints; its parts run the
rest: :mod:`.motion` NC blocks and moves, :mod:`.canned_cycles` G70-G73 and G76, :mod:`.calls`
calls and returns, on the state of :mod:`.machine_base`. Lines are compiled by
:mod:`.compile_lines`.
"""

from __future__ import annotations

import time
from bisect import bisect_left
from collections.abc import Mapping

from ..cancel import RUNNING
from ..line_maps import LineMap
from ..program.index import ProgramIndex
from ..program.variables import classify
from ..syntax.tree import Document, ParsedLine, PlainNc
from ..translation import tr
from .checkpoints import CtxKey, LevelState, MachineState, ModalState
from .compile_lines import (
    K_ASSIGN,
    K_EMPTY,
    K_END,
    K_GOTO,
    K_HEADER,
    K_IFGOTO,
    K_IFTHEN,
    K_NC,
    K_OTHER,
    K_WHILE,
    CompiledLine,
    compiled,
)
from .facts import DocumentFacts, Facts, LoopNoTurn
from .machine_base import (
    BLOCK_END_FIRST,
    BLOCK_END_LAST,
    MAX_MOTIONS,
    Activation,
    Appendable,
    Buffers,
    Converged,
    G76Parameters,
    Lists,
    Modal,
    ProgramContext,
    Stepper,
    StopRun,
)
from .motion import MotionPart
from .values import AlarmKind, MacroAlarm, Unknown, Value, fmt

# What other modules import from here (the debugger, the run, the checkpoints).
__all__ = (
    "K_ASSIGN",
    "K_IFGOTO",
    "K_IFTHEN",
    "K_NC",
    "K_OTHER",
    "K_WHILE",
    "Activation",
    "CompiledLine",
    "Converged",
    "Machine",
    "ProgramContext",
    "Stepper",
    "block_end_reads",
    "build_contexts",
    "compiled",
    "contexts_of",
    "locals_read_first",
)

CHECK_EVERY = 1024  # blocks between two looks at the budgets and a newer edit
# Blocks between two checkpoints (at the next boundary line): a resumed run re-runs about
# this many blocks before an edit and after it, and each checkpoint costs a capture of the
# state and a stretch of facts.
CHECKPOINT_EVERY = 256


class Machine(MotionPart):
    """Runs programs block by block (:meth:`run`, :meth:`resume`), recording facts."""

    def run(
        self, entry: ProgramContext, deadline: float, preset: Mapping[int, Value] | None = None
    ) -> str:
        """Run from ``entry``; returns why the run ended. ``preset``: variables set before the
        first block (a debugger's launch: the entry's arguments #1-#33, with the locals not
        given vacant, as after a G65 with those words; commons and system variables)."""
        self.store = {}
        self.speculative = False  # the path went through a condition that was not decided
        self.deadline = deadline
        self.modal = Modal()
        self._entry_name = entry.name
        self._no_feed = {}
        self.use_machine_of(entry)
        locals_: list[Value] = [None] * 34
        # A program that reads #1-#33 before it sets them receives arguments: a G65 from a
        # program outside the analysed files calls it, even if it ends with M30.
        read_first = locals_read_first(entry) if entry.is_main else ()
        if self.record is not None and entry.is_main:
            self.record.read_first[(entry.uri, entry.program.first_line)] = read_first
        if not entry.is_main or read_first:
            self.modal.feed = Unknown(frozenset())  # the caller's F, which a lone run cannot know
            # and its setup: compensation, the clamp, a G31 may all be the caller's.
            self.modal.setup = self.modal.setup.after_unknown_call()
            # A macro analysed alone: its arguments are unknown, not vacant.
            for n in range(1, 34):
                locals_[n] = self.unknown_of(n)
        if read_first:
            entry.facts.assumed_arguments[entry.program.first_line] = read_first
        if preset:
            if any(1 <= n <= 33 for n in preset):
                locals_ = [None] * 34
            for n, value in preset.items():
                if 1 <= n <= 33:
                    locals_[n] = value
                elif n > 33:
                    self.store[n] = value
        act = Activation(self, entry, locals_, 0, None, 0, 0)
        entry.facts.analysed_programs.add(entry.program.first_line)
        if self.toolpath is not None:
            self.toolpath.begin_run(
                len(self.facts.motions),
                self.lathe,
                (entry.uri, entry.program.first_line, entry.name),
            )
        self._steps = 0
        self._profile_blocks = 0
        self._checkpoint(act, 0)
        return self._run_loop(act, 0)

    def resume(self, state: MachineState, deadline: float) -> str:
        """Go on with a run from a checkpoint of an earlier evaluation (its facts so far are
        the caller's to restore); returns why the run ended."""
        self.deadline = deadline
        act = self._restore(state)
        self._begin_segment(state)
        return self._run_loop(act, state.done)

    def _run_loop(self, act: Activation, done: int) -> str:
        try:
            self._loop(act, done)
        except StopRun as stop:
            return stop.reason
        finally:
            self._flush_values()
            self.steps = self._steps
        return "end"

    def _checkpoint(self, act: Activation, done: int) -> None:
        """Record the state before the next block and begin a new stretch of facts; in a
        resumed run, stop when the state is the earlier run's (see :mod:`.checkpoints`)."""
        if self.record is None:
            return
        self._flush_values()  # the stretch's facts are complete at its checkpoint
        state = self.capture(act, done)
        resumption = self.resumption
        if resumption is not None:
            for index in resumption.convergeable.get(state.meeting_key(), ()):
                old = resumption.record.checkpoints[index]
                if not state.same_as(old, counted=False):
                    continue
                # Met, perhaps with more or fewer blocks done: the rest of the run then ends
                # as many blocks later or sooner, and must stay within the budget; with more
                # or fewer motions, neither run may reach the records kept (a full run keeps
                # the first MAX_MOTIONS).
                total = resumption.record.results[state.run][2] + done - old.done
                recorded = len(resumption.previous.motions)
                moved = state.motions - old.motions
                if total <= self.budget and (
                    not moved or max(recorded, recorded + moved) < MAX_MOTIONS
                ):
                    raise Converged(index, done)
        self._begin_segment(state)

    def _begin_segment(self, state: MachineState) -> None:
        record = self.record
        assert record is not None
        self._flush_values()
        self._buffers_of.clear()  # those of the stretch that ends
        self._checkpointed = state.done
        self._cuts_seen = {}
        record.checkpoints.append(state)
        segment = {uri: base.segment() for uri, base in self.facts.by_uri.items()}
        record.segments.append(segment)
        for ctx in self.contexts.values():
            ctx.facts = segment[ctx.uri]

    def capture(self, act: Activation, done: int) -> MachineState:
        chain: list[Activation] = []
        a: Activation | None = act
        while a is not None:
            chain.append(a)
            a = a.caller
        chain.reverse()
        levels = tuple(
            LevelState(
                (a.ctx.uri, a.ctx.program.first_line),
                tuple(a.locals),
                i > 0 and a.locals is chain[i - 1].locals,
                a.pc,
                a.macro_level,
                a.return_pc,
                a.repeats_left,
                a.serial,
                a.arguments,
                frozenset(a.undecided_loops),
                frozenset(a.loops_turning),
                a.modal_depth,
            )
            for i, a in enumerate(chain)
        )
        m = self.modal
        modal = ModalState(
            m.motion,
            m.feed,
            m.speed,
            m.constant_surface_speed,
            tuple(
                (None if c is None else (c.uri, c.program.first_line), tuple(args), repeat)
                for c, args, repeat in m.modal_calls
            ),
            tuple(m.position.items()),
            tuple(m.position_line.items()),
            m.inch,
            m.g76,
            m.cycle,
            m.incremental,
            m.spindle,
            m.spindle_stop,
            m.z_at_top,
            m.setup,
            m.drilling,
        )
        if self._seen_since:
            self._seen_chunks = (*self._seen_chunks, frozenset(self._seen_since))
            self._seen_since = []
        facts = self.facts
        bases = facts.by_uri
        return MachineState(
            self.run_index,
            done,
            levels,
            dict(self.store),
            modal,
            self.speculative,
            self.runs,
            self._seen_chunks,
            len(facts.motions),
            tuple(facts.run_values),
            tuple((uri, len(b.reported)) for uri, b in bases.items()),
            tuple((uri, frozenset(b.analysed_programs)) for uri, b in bases.items()),
            tuple((uri, tuple(b.assumed_arguments.items())) for uri, b in bases.items()),
            self._profile_blocks,
        )

    def _restore(self, state: MachineState) -> Activation:
        """The machine as it was at ``state``, on the programs of this evaluation."""
        self.run_index = state.run
        self.store = store = dict(state.store)
        self.speculative = state.speculative
        self.runs = state.activations
        self._seen_chunks = state.seen_findings
        self._seen_since = []
        self._seen_findings = set().union(*state.seen_findings)
        self._steps = state.done
        self._profile_blocks = state.profile_blocks
        contexts = self.contexts
        ms = state.modal
        assert isinstance(ms.g76, G76Parameters)
        self.modal = Modal(
            ms.motion,
            ms.feed,
            ms.speed,
            ms.constant_surface_speed,
            [
                (None if key is None else contexts[key], list(args), repeat)
                for key, args, repeat in ms.modal_calls
            ],
            dict(ms.position),
            dict(ms.position_line),
            ms.inch,
            ms.g76,
            ms.cycle,
            ms.incremental,
            ms.spindle,
            ms.spindle_stop,
            ms.z_at_top,
            ms.setup,
            ms.drilling,
        )
        caller: Activation | None = None
        for level in state.levels:
            a = Activation.__new__(Activation)
            a.machine = self
            a.ctx = contexts[level.ctx]
            a.locals = (
                caller.locals
                if caller is not None and level.shares_locals_with_caller
                else list(level.locals)
            )
            a.store = store
            a.macro_level = level.macro_level
            a.caller = caller
            a.return_pc = level.return_pc
            a.repeats_left = level.repeats_left
            a.pc = level.pc
            a.undecided_loops = set(level.undecided_loops)
            a.loops_turning = set(level.loops_turning)
            a.arguments = level.arguments
            a.serial = level.serial
            a.modal_depth = level.modal_depth
            caller = a
        assert caller is not None
        self._entry_name = contexts[state.levels[0].ctx].name
        self._no_feed = {}
        self.use_machine_of(contexts[state.levels[0].ctx])
        return caller

    def _loop_start(self, done: int) -> tuple[int, int, frozenset[tuple[CtxKey, int]] | None]:
        """When the loop of :meth:`_loop` first looks at the budgets (``next_check``) and
        takes a checkpoint (``next_due``), and where a resumed run may meet the earlier one."""
        budget = self.budget
        # Block budget + 1: the budget's last block still runs, and the run stops before the
        # next, at the same block on any machine.
        next_check = min((done + 1) // CHECK_EVERY * CHECK_EVERY + CHECK_EVERY, budget + 1)
        # A checkpoint is taken at the first block of a boundary line (see CompiledLine) once
        # CHECKPOINT_EVERY blocks have run since the last one: chosen by the text, not by the
        # count, so that a run with more or fewer blocks before (an edit added or removed
        # some) takes its checkpoints at the same blocks as the earlier run after the edit.
        recording = self.record is not None
        # A resumed run also checks at each boundary line where the earlier run has a
        # checkpoint it may meet (see Resumption.meet_at).
        meet_at = self.resumption.meet_at if recording and self.resumption is not None else None
        next_due = self._checkpointed + CHECKPOINT_EVERY + 1 if recording else budget + 1
        return next_check, next_due, meet_at

    def _events(
        self,
        act: Activation,
        cl: CompiledLine,
        steps: int,
        next_check: int,
        next_due: int,
        wanted: bool,
        meet_at: frozenset[tuple[CtxKey, int]] | None,
    ) -> tuple[int, int, int, bool]:
        """Before block ``steps`` of :meth:`_loop`: the look at the budgets (:meth:`_event`)
        or the checkpoint due at this boundary line; the next of each and the first of them,
        and whether a checkpoint is wanted at the next boundary line."""
        self._steps = steps
        looking = bool(meet_at)
        if steps >= min(next_check, next_due):
            next_check, next_due, wanted = self._event(act, cl, next_check, next_due, wanted)
            wanted = wanted or looking
        elif not looking or steps - 1 - self._checkpointed >= CHECKPOINT_EVERY:
            wanted = looking
            next_due = self._checkpoint_here(act)
        elif meet_at is not None and ((act.ctx.uri, act.ctx.program.first_line), act.pc) in meet_at:
            next_due = self._checkpoint_here(act)
        return next_check, next_due, min(next_check, next_due), wanted

    def _loop(self, act: Activation, done: int = 0) -> None:
        steps = self._steps = done
        next_check, next_due, meet_at = self._loop_start(done)
        wanted = bool(meet_at)  # a checkpoint is due at the next boundary line
        next_event = min(next_check, next_due)
        stepper = self.stepper
        custom_calls = self.config.custom_calls  # codes the parameters make call (often none)
        smallest, largest = self.value_range
        # ``self._steps`` is set where something else reads it (an event, the debugger, a stop);
        # what the loop reads of the program and of the facts, when either changes.
        while True:
            running = act
            ctx = act.ctx
            lines = ctx.lines
            end_line = ctx.program.end_line
            loop_do = ctx.loop_do
            locals_ = act.locals
            facts = ctx.facts
            runs, buffers, read_buffers = self._recording(facts)
            while True:
                pc = act.pc
                if pc >= end_line:
                    act = self._past_end(act, steps)
                    break
                cl = lines[pc]
                self._line = pc  # the block being executed, for the facts and findings
                steps += 1
                if steps >= next_event or (wanted and cl.boundary):
                    next_check, next_due, next_event, wanted = self._events(
                        act, cl, steps, next_check, next_due, wanted, meet_at
                    )
                    if ctx.facts is not facts:  # a checkpoint began a stretch of facts
                        facts = ctx.facts
                        runs, buffers, read_buffers = self._recording(facts)
                if stepper is not None:
                    self._steps = steps
                    stepper.before(act, pc)
                try:
                    if cl.reads:  # the list of its reads counts its runs
                        kept = read_buffers.get(pc)
                        if kept is None:  # its first or second run in the stretch
                            found: Appendable = self._first_reads(buffers, facts, pc, cl, act)
                        else:
                            n = cl.read_local
                            if n:
                                kept.append(locals_[n])
                            elif (getter := cl.read_locals) is not None:
                                kept += getter(locals_)
                            else:
                                self._read_into(act, cl, kept)
                            found = kept  # takes its write or turn
                    else:
                        runs[pc] = runs.get(pc, 0) + 1
                    kind = cl.kind
                    if kind == K_ASSIGN:
                        value = cl.value(act)  # type: ignore[misc]
                        n = cl.local_target
                        # A number to a local, within the control's range and not below its
                        # smallest magnitude: the rest in _store.
                        if (
                            n
                            and value.__class__ is float
                            and (smallest <= value <= largest or -largest <= value <= -smallest)
                        ):
                            locals_[n] = value
                        else:
                            stored = self._store(act, cl, value)
                            if stored is None:
                                act.pc = pc + 1
                                continue
                            n, value = stored
                        if cl.writes_after_reads:
                            found.append(value)  # with its reads
                        else:
                            self._write(buffers, facts, pc, n, value)
                        act.pc = pc + 1
                    elif kind == K_WHILE:
                        result = True if cl.cond is None else cl.cond(act)
                        if result is True and not self.speculative:
                            if cl.turns_after_reads:
                                found.append(True)  # counted with its reads
                            else:
                                facts.jump_count(pc).taken += 1
                            act.loops_turning.add(pc)
                            act.pc = pc + 1
                        else:
                            if cl.turns_after_reads:
                                found.append(None)  # counted by _while
                            act.pc = self._while(act, cl, facts, result)
                    elif kind == K_END:
                        do_line = loop_do.get(pc)
                        act.pc = pc + 1 if do_line is None else do_line
                    elif kind == K_NC:  # after the macro statements, which cost less
                        if custom_calls and (call := self._custom_setting(act, cl)) is not None:
                            act = self._custom_call(act, cl, call)
                        else:
                            act = self._nc(act, cl)
                        if cl.second is not None and act.ctx is ctx and act.pc == pc + 1:
                            act.pc = pc
                            self._run_second(act, cl.second, facts)
                        if act is not running:  # a call or a return
                            break
                    elif kind == K_IFGOTO:
                        act.pc = self._if_goto(act, cl, facts)
                    elif kind in (K_EMPTY, K_OTHER, K_HEADER):
                        act.pc = pc + 1
                    elif kind == K_GOTO:
                        act.pc = self._goto(act, cl)
                    elif kind == K_IFTHEN:
                        act.pc = self._if_then(act, cl, facts)
                except BaseException as stop:
                    self._steps = steps
                    if isinstance(stop, MacroAlarm):
                        self._stop_at_alarm(act, cl, stop)
                    if isinstance(stop, StopRun) and stop.reason != "end of program":
                        self._mark_incomplete(act)
                    raise

    def _recording(self, facts: DocumentFacts) -> tuple[dict[int, int], Buffers, Lists]:
        """What the block loop records into, of ``facts``: the runs, the lists of values read
        and written, those of the values read."""
        buffers = self._buffers(facts)
        return facts.runs, buffers, buffers[0]

    def _past_end(self, act: Activation, steps: int) -> Activation:
        """The run is past the last line of its program, ``steps`` blocks done: it returns,
        as after M99."""
        self._steps = steps
        ctx = act.ctx
        unread = ctx.doc.unread_from
        if unread is not None and ctx.program.end_line >= unread:
            # The program goes on in the part of the file the analysis does not read
            # (MB013): its run is not over.
            self._mark_incomplete(act)
            raise StopRun("unread")
        return self._return(act, None, ctx.program.end_line - 1)

    def _event(
        self, act: Activation, cl: CompiledLine, next_check: int, next_due: int, wanted: bool
    ) -> tuple[int, int, bool]:
        """Before block ``self._steps`` runs, a look at the budgets, the deadline and a newer
        edit (at ``next_check``) or a checkpoint (at ``next_due``): the next of each, and
        whether a checkpoint is wanted at the next boundary line."""
        steps = self._steps
        self._steps = steps - 1  # this block has not run yet
        budget = self.budget
        if steps >= next_check:
            if steps > budget:  # nor does it run
                self._budget_spent(act)
                self._mark_incomplete(act)
                raise StopRun("budget")
            if time.monotonic() > self.deadline:
                # The safety net: how far a run gets in seconds depends on the machine
                # and its load, so nothing is concluded from where it stopped.
                self._mark_incomplete(act)
                raise StopRun("time")
            if self.cancel is not None:
                self.cancel.reached(RUNNING, steps - 1, budget)
            next_check = min(steps + CHECK_EVERY, budget + 1)
            if self.record is None:
                self._flush_values()  # no checkpoints (a debugger's run): keep the lists short
        if self.record is not None:
            since = steps - 1 - self._checkpointed
            # No boundary line in four intervals (a loop without one): take it here.
            if since >= 4 * CHECKPOINT_EVERY or (since >= CHECKPOINT_EVERY and cl.boundary):
                wanted = False
                self._checkpoint(act, steps - 1)
                next_due = steps + CHECKPOINT_EVERY
            elif since >= CHECKPOINT_EVERY:
                wanted = True
                next_due = self._checkpointed + 4 * CHECKPOINT_EVERY + 1
            else:  # a checkpoint taken since (a program began)
                next_due = self._checkpointed + CHECKPOINT_EVERY + 1
        self._steps = steps
        return next_check, next_due, wanted

    def _checkpoint_here(self, act: Activation) -> int:
        """The checkpoint wanted at this boundary line, before its block; the next one due."""
        steps = self._steps
        self._steps = steps - 1
        self._checkpoint(act, steps - 1)
        self._steps = steps
        return steps + CHECKPOINT_EVERY

    def _stop_at_alarm(self, act: Activation, cl: CompiledLine, alarm: MacroAlarm) -> None:
        """The control stops at an alarm: reported, shown to a debugger, the run ended."""
        self.steps = self._steps
        message = self._alarm(act, cl, alarm)
        if self.stepper is not None:
            self.stepper.alarm(act, self._line, message)
        self._mark_incomplete(act)
        raise StopRun("alarm") from None

    def _if_goto(self, act: Activation, cl: CompiledLine, facts: DocumentFacts) -> int:
        """``IF [c] GOTO n``: the line to run next."""
        assert cl.cond is not None
        pc = self._line
        result = cl.cond(act)
        jc = facts.jumps.get(pc) or facts.jump_count(pc)
        if result is True:
            jc.taken += 1
            jc.guessed += self.speculative
            return self._goto(act, cl)
        if result is False:
            jc.not_taken += 1
            jc.guessed += self.speculative
            return pc + 1
        jc.undecided += 1
        self.speculative = True
        # Unknown: fall through the first time; if the path comes back here, it is a loop
        # whose exit is unknown, so take the jump to leave it.
        seen = act.undecided_loops
        if pc in seen:
            seen.discard(pc)
            return self._goto(act, cl)
        seen.add(pc)
        return pc + 1

    def _if_then(self, act: Activation, cl: CompiledLine, facts: DocumentFacts) -> int:
        """``IF [c] THEN #n = ...``; the line to run next."""
        assert cl.cond is not None
        result = cl.cond(act)
        jc = facts.jump_count(self._line)
        if result is True:
            jc.taken += 1
            jc.guessed += self.speculative
            self._assign(act, cl, facts)
        elif result is False:
            jc.not_taken += 1
            jc.guessed += self.speculative
        else:
            jc.undecided += 1
            self.speculative = True
            self._assign(act, cl, facts, unknown=result)
        return self._line + 1

    def _run_second(self, act: Activation, cl: CompiledLine, facts: DocumentFacts) -> None:
        if cl.kind == K_ASSIGN:
            self._assign(act, cl, facts)
            act.pc = self._line + 1
        elif cl.kind == K_GOTO:
            act.pc = self._goto(act, cl)
        else:
            act.pc = self._line + 1

    def _assign(
        self,
        act: Activation,
        cl: CompiledLine,
        facts: DocumentFacts,
        unknown: Unknown | None = None,
    ) -> None:
        assert cl.value is not None
        stored = self._store(act, cl, cl.value(act), unknown)
        if stored is None:
            return
        self._write(self._buffers(facts), facts, self._line, stored[0], stored[1])

    def _store(
        self, act: Activation, cl: CompiledLine, value: Value, unknown: Unknown | None = None
    ) -> tuple[int, Value] | None:
        """Assign ``value`` to the line's target; the variable and the value written, or None
        when nothing is recorded (an unknown index, a Haas variable)."""
        if value.__class__ is float:
            smallest, largest = self.value_range
            if not -largest <= value <= largest:  # NaN fails both comparisons
                raise MacroAlarm(
                    "PS0111",
                    AlarmKind.OVERFLOW,
                    tr(
                        "the result {value} is beyond the control's range ±{largest:.3g} "
                        "(CALCULATED DATA OVERFLOW)",
                        value=fmt(value),
                        largest=largest,
                    ),
                )
            if -smallest < value < smallest:
                value = 0.0  # below the smallest magnitude the control holds (unverified)
        if unknown is not None:
            # IF [unknown] THEN #n=...: afterwards #n may or may not have changed.
            deps = set(unknown.deps)
            if isinstance(value, Unknown):
                deps |= value.deps
            value = Unknown(frozenset(deps))
        n = cl.target_number
        if n is None:
            assert cl.target is not None
            index = cl.target(act)
            if isinstance(index, Unknown):
                return None
            n = 0 if index is None else round(index)
            kind = classify(n)
            if kind.kind == "none":
                raise MacroAlarm(
                    "PS0115",
                    AlarmKind.NO_SUCH_VARIABLE,
                    tr(
                        "#[...] = ... writes #{number}, which does not exist (VARIABLE NO. OUT "
                        "OF RANGE)",
                        number=n,
                    ),
                    float(n),
                )
            if kind.read_only:
                raise MacroAlarm(
                    "PS0116",
                    AlarmKind.WRITE_READ_ONLY,
                    tr(
                        "#[...] = ... writes #{number}, which is read-only ({meaning})",
                        number=n,
                        meaning=kind.meaning,
                    ),
                    float(n),
                )
        if n < 0:
            return None  # #30001.116 and the like: not FANUC, reported by MB002
        if 1 <= n <= 33:
            act.locals[n] = value
        elif n == 0:
            raise MacroAlarm("PS0116", AlarmKind.WRITE_READ_ONLY, tr("#0 is read-only"), 0.0)
        else:
            if n == 3000 and self.speculative:
                # Reached through a condition the analysis could not decide (an argument
                # check, typically): the control may never come here.
                pass
            elif n == 3000 and value is not None and not isinstance(value, Unknown):
                raise MacroAlarm(
                    "3000",
                    AlarmKind.MACRO_ALARM,
                    tr(
                        "#3000 = {value}: the program raises macro alarm {alarm}",
                        value=fmt(value),
                        alarm=3000 + int(value),
                    ),
                    value,
                )
            if not _volatile(n):
                self.store[n] = value
        return n, value

    def _goto(self, act: Activation, cl: CompiledLine) -> int:
        assert cl.target is not None
        target = cl.target(act)
        ctx = act.ctx
        if isinstance(target, Unknown):
            raise StopRun("unknown jump")
        if target is None or target != int(target) or not 1 <= target <= 99999:
            raise MacroAlarm(
                "PS0128",
                AlarmKind.GOTO_TARGET,
                tr(
                    "GOTO {target}: not a sequence number 1-99999 (ILLEGAL MACRO SEQUENCE NUMBER)",
                    target=fmt(target),
                ),
                target if target is not None else 0.0,
            )
        line = self._label(ctx, int(target), self._line)
        if line is None:
            raise MacroAlarm(
                "PS0128",
                AlarmKind.GOTO_MISSING,
                tr(
                    "GOTO {target}: no N{target} in {program} (ILLEGAL MACRO SEQUENCE NUMBER)",
                    target=int(target),
                    program=ctx.name,
                ),
                target,
            )
        return line

    def _while(
        self, act: Activation, cl: CompiledLine, facts: DocumentFacts, result: object
    ) -> int:
        """The line after a WHILE whose condition gave ``result``."""
        pc = self._line
        end = act.ctx.loop_end.get(pc)
        jc = facts.jump_count(pc)
        if result is True:
            jc.taken += 1
            jc.guessed += self.speculative
            act.loops_turning.add(pc)
            return pc + 1
        if result is False:
            if (
                pc not in act.loops_turning
                and not self.speculative
                and jc.taken + self._turns_kept(facts, cl, pc) >= 2
            ):
                self._no_turn(act, cl, pc, end)  # entered again, and runs no turn
            act.loops_turning.discard(pc)
            jc.not_taken += 1
            jc.guessed += self.speculative
        else:
            jc.undecided += 1
            self.speculative = True  # the control may never run the body, nor what follows
            if pc not in act.undecided_loops:
                act.undecided_loops.add(pc)  # run the body once to learn its values
                return pc + 1
        act.undecided_loops.discard(pc)
        if end is None:
            raise StopRun("no END")
        return end + 1

    def _turns_kept(self, facts: DocumentFacts, cl: CompiledLine, line: int) -> int:
        """The turns of a WHILE in its list of reads, not yet counted in its jumps."""
        found = self._buffers(facts)[0].get(line)
        if found is None or not cl.turns_after_reads:
            return 0
        count = len(cl.reads)
        return found[count :: count + 1].count(True)

    def _no_turn(self, act: Activation, cl: CompiledLine, pc: int, end: int | None) -> None:
        """A WHILE that ran turns before in the run and now runs none, its condition on a
        common variable the loop counts with: where the loop's earlier turns left it."""
        if end is None:
            return
        lines = act.ctx.lines
        counted = {lines[n].target_number for n in range(pc + 1, end)} & set(cl.reads)
        counters = sorted(n for n in counted if n is not None and n > 33)
        if len(counters) != 1:
            return
        n = counters[0]
        value = self.store.get(n)
        if type(value) is not float:
            return
        caller = act.caller
        if caller is None:
            message = tr(
                "this entry of the loop runs no turn: its counter #{number} is {value}, and the "
                "loop counts it on from where it stands; set it to its start value before the "
                "WHILE",
                number=n,
                value=fmt(value),
            )
        else:
            message = tr(
                "this entry of the loop (the call on {where}) runs no turn: its counter "
                "#{number} is {value}, and the loop counts it on from where it stands; set it "
                "to its start value before the WHILE",
                where=self._where(act, (caller.ctx.uri, act.return_pc - 1)),
                number=n,
                value=fmt(value),
            )
        self._block_finding(act, LoopNoTurn, message)


_PROGRAM_ENDS = (("M", 2.0), ("M", 30.0))


def _ends_program_line(parsed: ParsedLine) -> bool | None:
    statement = parsed.statement
    if type(statement) is PlainNc:  # its M codes say it, without the compiled line
        return any(code in statement.codes for code in _PROGRAM_ENDS) or None
    return compiled(parsed).ends_program or None


# The blocks with M02 or M30, by document: kept across edits, where a look at every block for
# a program's first end took milliseconds per analysis of a long program (it ends at its last).
_program_end_lines: LineMap[bool] = LineMap(_ends_program_line)


def _reads_block_end(parsed: ParsedLine) -> bool | None:
    """Whether a line reads #5001-#5008 directly (the block end position)."""
    if type(parsed.statement) is PlainNc:
        return None  # numbers only
    reads = compiled(parsed).reads
    return any(BLOCK_END_FIRST <= n <= BLOCK_END_LAST for n in reads) or None


# The lines that read the block end position, by document (see run.tracks_positions).
block_end_reads: LineMap[bool] = LineMap(_reads_block_end)


def _volatile(number: int) -> bool:
    """System variables the control changes by itself: clocks, signals, positions."""
    return (
        number in (3001, 3002)
        or 1000 <= number <= 1133
        or 5001 <= number <= 5120
        or (4001 <= number <= 4430)
    )


def build_contexts(
    docs: list[tuple[str, Document, ProgramIndex]],
    facts: Facts,
    compiled_before: dict[str, list[CompiledLine]] | None = None,
    changed: dict[str, set[int]] | None = None,
) -> tuple[dict[int, ProgramContext], list[ProgramContext]]:
    """Compile every program of the given documents: by number, and all in order.

    ``compiled_before``: the compiled lines of an earlier version of the documents, in which
    only the ``changed`` lines differ (same line counts): those alone are compiled again."""
    contexts: dict[int, ProgramContext] = {}
    every: list[ProgramContext] = []
    for uri, doc, index in docs:
        lines: list[CompiledLine] | None = None
        if compiled_before is not None and changed is not None and uri in compiled_before:
            lines = list(compiled_before[uri])
            for line in changed.get(uri, ()):
                lines[line] = compiled(doc.blocks[line].parsed)
        for ctx in contexts_of(uri, doc, index, facts, lines):
            every.append(ctx)
            if ctx.program.number is not None and ctx.program.number not in contexts:
                contexts[ctx.program.number] = ctx
    return contexts, every


def locals_read_first(ctx: ProgramContext) -> tuple[tuple[int, int], ...]:
    """The locals a program reads before any block of it sets them, in the order of the text,
    each with the line of its first read: (number, line)."""
    set_: set[int] = set()
    found: dict[int, int] = {}
    lines = ctx.lines
    for line in range(ctx.program.first_line, ctx.program.end_line):
        part: CompiledLine | None = lines[line]
        assert part is not None
        for n in part.reads:
            if n <= 33 and n not in set_ and n not in found:
                found[n] = line
        while part is not None:  # the assignment, or the macro part of a mixed block
            target = part.target_number
            if target is not None and 1 <= target <= 33:
                set_.add(target)
                if len(set_) == 33:  # every local set: no later read comes first
                    return tuple(found.items())
            part = part.second
    return tuple(found.items())


def contexts_of(
    uri: str,
    doc: Document,
    index: ProgramIndex,
    facts: Facts,
    lines: list[CompiledLine] | None = None,
) -> list[ProgramContext]:
    doc_facts = facts.document(uri)
    if lines is None:
        lines = [compiled(b.parsed) for b in doc.blocks]
    out: list[ProgramContext] = []
    ends = _program_end_lines(doc).lines
    for program in index.programs:
        loop_end = {lp.do_line: lp.end_line for lp in program.loops if lp.end_line is not None}
        loop_do = {e: d for d, e in loop_end.items()}
        at = bisect_left(ends, program.first_line)
        first_end = ends[at] if at < len(ends) and ends[at] < program.end_line else None
        is_main = first_end is not None
        if first_end is not None:
            doc_facts.program_ends[program.first_line] = first_end
        out.append(ProgramContext(uri, doc, program, lines, loop_end, loop_do, doc_facts, is_main))
    return out
