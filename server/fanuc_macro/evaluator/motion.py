"""NC blocks as the machine runs them: modal codes, moves, where the tool goes, cuts without F.

:meth:`MotionPart._nc` runs a block of words: its modal G codes, the address checks, a call
(G65, G66, M98, M99), the move it commands and the motion record, the profile a G70-G73 names.
"""

from __future__ import annotations

import math
from array import array
from collections.abc import Mapping, Sequence
from dataclasses import replace
from types import MappingProxyType

from ..program.g_code_systems import written
from ..translation import tr
from .calls import CallsPart
from .canned_cycles import PROFILE_CYCLES, CyclesPart
from .compile_lines import AXES, K_NC, CompiledLine, CompiledWord, recorded_words
from .direct_drawing import missing_coordinate
from .facts import (
    POWER_ON_FEED_MODE,
    BlockFault,
    CutsWithoutFeed,
    DrillingFault,
    Motion,
    RunValues,
)
from .machine_base import (
    LOCAL_COORDINATES,
    MAX_MOTIONS,
    RAPID_ONE_SHOTS,
    SPINDLE_KEEPS,
    SPINDLE_OFF,
    SPINDLE_ON,
    SPINDLE_STARTS,
    SPINDLE_STOPS,
    SPINDLE_TOLD,
    SPINDLE_UNKNOWN,
    Activation,
    ProgramContext,
    StopRun,
    g_name,
    system_a_block,
)
from .setup_verdicts import ARCS, THREADING_CODES, TURNING_CYCLES, SetupPart, whole
from .toolpath import NOT_MOVES, ProfileBlock
from .values import AlarmKind, MacroAlarm, Unknown, Value

MOTION_GROUP = frozenset({0.0, 1.0, 2.0, 3.0, 32.0, 33.0, 34.0})
LATHE_CYCLES = frozenset({90.0, 92.0, 94.0})  # G-code system A: modal canned cycles of group 01
ONE_SHOT_CYCLES = frozenset({70.0, 71.0, 72.0, 73.0, 74.0, 75.0, 76.0})  # group 00: no repeat
FEED_MOTIONS = frozenset({1.0, 2.0, 3.0})  # cutting at the modal F (G32, cycles: F the lead)
LEFT_UNKNOWN = frozenset({28.0, 30.0, 53.0})
# A lathe's multiple repetitive cycles (system A), whose D is a depth or a relief in the FS10/11
# program format (one block: G71 P Q U W D F) and on a Haas lathe, not an offset number.
REPETITIVE_CYCLES = frozenset({71.0, 72.0, 73.0, 74.0, 75.0, 76.0})
MAX_SHARED_WORDS = 4096  # distinct motion words a run looks up to share (Machine._words)
# The lathe's moves that cut at F besides G01-G03: threads (F the lead), turning and facing.
LATHE_FED = frozenset({32.0, 33.0, 34.0, 76.0, 90.0, 92.0, 94.0})
# The mill's cycles that cut besides G01-G03, which need the spindle turning: drilling and
# boring (tapping, G74 and G84, left out: a rigid tap drives the spindle itself).
MILL_CUTS = frozenset({73.0, 76.0, 81.0, 82.0, 83.0, 85.0, 86.0, 87.0, 88.0, 89.0})
# The mill's canned drilling cycles (group 09), tapping with them: a block with an axis word
# drills a hole at its X Y while one is in force.
DRILLING_CYCLES = MILL_CUTS | {74.0, 84.0}
PECK_CYCLES = frozenset({73.0, 83.0})  # high-speed and deep hole peck drilling: Q each peck
# A lathe's blocks that take no T code: G50 (coordinate system, spindle clamp), G10 (data
# setting), G04 (dwell) (0i-F alarm list, PS0245).
T_REFUSED = frozenset({50.0, 10.0, 4.0})
MAX_REMEMBERED_RUNS = 1000  # executions whose variables are kept when they start a thread


class MotionPart(CyclesPart, CallsPart, SetupPart):
    """The machine's NC blocks and moves."""

    def _nc(self, act: Activation, cl: CompiledLine) -> Activation:
        """An NC block: its modal codes, checks, call or move, and the block that runs next."""
        if cl.cond is not None:  # Haas IF [c] <words>
            result = cl.cond(act)
            if result is not True:
                act.pc = self._line + 1
                return act
        const = cl.constant
        g_codes: Sequence[float]
        m_codes: Sequence[float]
        # A constant block's words in order: made only when something below needs them.
        order: list[tuple[str, Value, CompiledWord]] | None = None
        if const is not None:
            values, g_codes, m_codes = const.values, const.g_codes, const.m_codes
            self._values_of = const  # values made from it (see _move_words)
            self._const_values = values
        else:
            values, g_codes, m_codes, order = self._evaluated_words(act, cl)
        if self.other_g_code_system and self.lathe:
            values, g_codes = self._as_system_a(values, g_codes)
        call_kind = self._modal_codes(g_codes) if g_codes else None
        if self.lathe and "T" in values and not T_REFUSED.isdisjoint(g_codes):
            refused = next(g for g in g_codes if g in T_REFUSED)
            self._block_finding(
                act,
                BlockFault,
                tr(
                    "a T code in a G{code:02g} block: the control stops (PS0245); give the "
                    "tool in a block of its own",
                    code=refused,
                ),
                fault="t-code",
            )
        quiet = const is not None and const.quiet  # no word of it can get a finding
        if call_kind is not None:
            return self._call_block(act, cl, order, call_kind, quiet)
        if not quiet:
            if order is None:
                assert const is not None
                order = const.order
            self._check_addresses(
                act,
                cl,
                order,
                98.0 in m_codes or 99.0 in m_codes,
                self.lathe and not REPETITIVE_CYCLES.isdisjoint(g_codes),
            )
        modal = self.modal
        if "F" in values:
            modal.feed = values["F"]
            lead = self.lathe and (
                not THREADING_CODES.isdisjoint(g_codes)
                or (modal.motion in THREADING_CODES and MOTION_GROUP.isdisjoint(g_codes))
            )
            if lead != modal.setup.lead_feed:
                modal.setup = replace(modal.setup, lead_feed=lead)
        if "S" in values and not (self.lathe and 50.0 in g_codes):
            # A lathe's G50 S is the clamp on the speed (_setup_codes), not a speed to run at
            # (0i-TF operator's manual, "Clamp of maximum spindle speed").
            modal.speed = values["S"]
        stops: float | None = None  # an M code that stops the spindle, after the block's move
        for m in m_codes:
            if m in SPINDLE_STARTS:
                modal.spindle = SPINDLE_ON  # with the block's move (FANUC: M03 before it)
            elif m in SPINDLE_STOPS:
                stops = m
            elif m not in SPINDLE_KEEPS:
                modal.spindle = SPINDLE_UNKNOWN
        cancels = self._setup_codes(act, values, g_codes, m_codes) if g_codes or m_codes else False
        moved = self._motion(act, cl, values, g_codes, order, cancels)
        if stops is not None:
            modal.spindle = SPINDLE_OFF
            modal.spindle_stop = (act.ctx.uri, self._line, f"M{stops:02g}")
        next_pc = self._line + 1
        blocks = act.ctx.doc.blocks
        if next_pc < len(blocks):
            # The block's own number (an int object the document holds already): the run keeps
            # the line of every block it runs, in its counts and motions.
            next_pc = blocks[next_pc].line
        profile: list[ProfileBlock] | str | None = None
        finishing: tuple[int, int] | None = None
        if self._profile_code is not None:
            profile, next_pc, finishing = self._profile(act, values, self._profile_code)
            self._profile_code = None
        if self.toolpath is not None:
            ctx = act.ctx
            read = self._values_read(act, cl) if cl.reads else None
            self.toolpath.block(
                ctx.name, ctx.uri, self._line, values, g_codes, self.facts.motions, profile, read
            )
            if g_codes or m_codes or "T" in values:
                where = (ctx.name, ctx.uri, self._line, ctx.program.first_line)
                self.toolpath.timed(where, values, g_codes, m_codes, len(self.facts.motions))
        if finishing is not None:
            self._run_profile(act, *finishing)
        for m in m_codes:
            if m == 98.0:
                return self._sub_call(act, cl, values)
            if m == 99.0:
                return self._return(act, values.get("P"), self._line)
            if m in (2.0, 30.0):
                self._setup_end(act, m)
                raise StopRun("end of program")
        act.pc = next_pc
        if moved and modal.modal_calls:
            return self._modal_call_after_move(act)
        return act

    def _evaluated_words(
        self, act: Activation, cl: CompiledLine
    ) -> tuple[dict[str, Value], list[float], list[float], list[tuple[str, Value, CompiledWord]]]:
        """A computed block's words: by address (the first of each), its G and M codes, and
        the words in order (a vacant variable omits its word)."""
        values: dict[str, Value] = {}
        g_codes: list[float] = []
        m_codes: list[float] = []
        order: list[tuple[str, Value, CompiledWord]] = []
        for w in cl.words:
            v = w.evaluate(act)
            if v is None:
                continue  # a vacant variable omits the word
            order.append((w.address, v, w))
            if w.address == "G" and not isinstance(v, Unknown):
                g_codes.append(round(v, 1))
            elif w.address == "M" and not isinstance(v, Unknown):
                m_codes.append(v)
            if w.address not in values:
                values[w.address] = v
        return values, g_codes, m_codes, order

    def _as_system_a(
        self, values: dict[str, Value], g_codes: Sequence[float]
    ) -> tuple[dict[str, Value], Sequence[float]]:
        """A block of a system B or C lathe program as system A reads it; G90/G91 set."""
        modal = self.modal
        values, g_codes, modal.incremental = system_a_block(
            values, g_codes, self.config.g_code_system, modal.incremental
        )
        return values, g_codes

    def _modal_codes(self, g_codes: Sequence[float]) -> str | None:
        """Set the modal state the block's G codes set; the call it makes ("G65", "G66")."""
        modal = self.modal
        call_kind: str | None = None
        for g in g_codes:
            if g in MOTION_GROUP or (self.lathe and g in LATHE_CYCLES):
                modal.motion = g
                modal.drilling = None  # a code of group 01 ends a drilling cycle
                if g not in LATHE_CYCLES:
                    modal.cycle = (None, None)
            elif not self.lathe and g in DRILLING_CYCLES:
                q = None if modal.drilling is None else modal.drilling[1]
                modal.drilling = (g, q)
            elif g == 80.0:
                modal.drilling = None
            elif g == 65.0:
                call_kind = "G65"
            elif g in (66.0, 66.1):
                call_kind = "G66"
            elif g == 67.0 and modal.modal_calls:
                modal.modal_calls.pop()
            elif g == 96.0:
                modal.constant_surface_speed = True
            elif g == 97.0:
                modal.constant_surface_speed = False
            elif g in (90.0, 91.0) and not self.lathe:
                modal.incremental = g == 91.0  # a mill's G91: the axis words are distances
            elif g == 20.0:
                modal.inch = True
            elif g == 21.0:
                modal.inch = False
        return call_kind

    def _call_block(
        self,
        act: Activation,
        cl: CompiledLine,
        order: list[tuple[str, Value, CompiledWord]] | None,
        call_kind: str,
        quiet: bool,
    ) -> Activation:
        """A G65 block (the call) or a G66 block (the modal call specified, no move)."""
        if order is None:
            assert cl.constant is not None
            order = cl.constant.order
        if not quiet:  # after G65/G66 the words are arguments (#1-#26): only P names a program
            self._check_addresses(act, cl, [w for w in order if w[0] == "P"], calls=True)
        if call_kind == "G65":
            return self._macro_call(act, cl, order, modal_call=False)
        self._macro_call(act, cl, order, modal_call=True)
        act.pc = self._line + 1
        return act

    def _modal_call_after_move(self, act: Activation) -> Activation:
        """The G66 macro called after a move: the program to run next."""
        # FANUC calls the macro after each move; a move in a modal macro calls the one
        # specified before it, and none in the first. Source: a FANUC operator's manual page,
        # custom macro "multiple modal call" (photo shipped with NCVC's G66 sample; series
        # not named on it).
        calls = self.modal.modal_calls
        target = len(calls) - 1 if act.modal_depth is None else act.modal_depth - 1
        if target < 0:
            return act
        callee, args, _ = calls[target]
        if callee is None:
            self._call_unknown(act, shares_locals=False)
            return act
        new = self._enter(act, callee, list(args), True, self._line + 1, 1)
        new.modal_depth = target
        return new

    def _run_profile(self, act: Activation, first: int, last: int) -> None:
        """G70: the blocks N(ns) to N(nf) run as blocks of the G70 (the step budget counts the
        G70 once), then the tool is back at the G70's start point."""
        line = self._line
        modal = self.modal
        start, start_lines = dict(modal.position), dict(modal.position_line)
        for n in range(first, last + 1):
            pcl = self._profile_line(act, n)
            if pcl.kind != K_NC:
                continue
            try:
                self._nc(act, pcl)
            except MacroAlarm as alarm:
                self._profile_alarm(act, pcl, alarm)
        self._line = line
        modal.position = start
        modal.position_line = start_lines
        if self.toolpath is not None:
            self.toolpath.end_profile()

    def _cut_without_feed(self, ctx: ProgramContext, message: str) -> None:
        """MB603's finding at the block being run, recorded by line (see CutsWithoutFeed)."""
        line = self._line
        uri = ctx.uri
        seen = self._cuts_seen.get(uri)
        if seen is None:
            seen = self._cuts_seen[uri] = set()
        elif line in seen:
            return
        seen.add(line)
        facts = ctx.facts
        records = facts.cuts
        after = len(facts.reported)
        program = ctx.program.first_line
        last = records[-1] if records else None
        if (
            last is None
            or last.after != after
            or last.program != program
            or last.message != message
        ):
            records.append(CutsWithoutFeed(uri, program, message, after, array("i", (line,))))
        else:
            if line <= last.lines[-1]:
                last.ascending = False
            last.lines.append(line)

    def _shared_words(self, words: dict[str, float]) -> dict[str, float]:
        """``words``, or an equal dict an earlier motion of the run holds."""
        key: tuple[object, ...] = tuple(words.items())
        if 0.0 in words.values():  # 0.0 and -0.0 are equal but print differently
            key += tuple(math.copysign(1.0, v) for v in words.values())
        table = self._words
        shared = table.get(key)
        if shared is not None:
            return shared
        if len(table) < MAX_SHARED_WORDS:  # a run of all different moves keeps no more
            table[key] = words
        return words

    def _axis(self, values: dict[str, Value], absolute: str, incremental: str) -> float | None:
        """Where a block sends an axis: its absolute word, else where it is plus the
        incremental word (U, W on a lathe in G-code system A), else where it is."""
        v = values.get(absolute)
        if isinstance(v, float):
            return v
        here = self.modal.position.get(absolute)
        if not isinstance(here, float):
            return None
        step = values.get(incremental)
        if step is None:
            return here
        return here + step if isinstance(step, float) else None

    def _motion(
        self,
        act: Activation,
        cl: CompiledLine,
        values: dict[str, Value],
        g_codes: Sequence[float],
        order: list[tuple[str, Value, CompiledWord]] | None,  # None: the constant block's
        cancels: bool = False,  # the block's G40 cancels radius compensation that was on
    ) -> bool:
        """The move a block commands, if any (True): its motion record, where the tool goes."""
        lathe = self.lathe
        const = cl.constant
        has_axis = const.has_axis if const is not None else not AXES.isdisjoint(values)
        if g_codes and (
            (lathe and not ONE_SHOT_CYCLES.isdisjoint(g_codes))
            or (has_axis and not self._own_codes.isdisjoint(g_codes))
        ):
            code = self._cycle_or_own_code(act, values, g_codes, has_axis)
        else:
            code = self._modal_move() if has_axis else None
        if code is None:
            return False
        if not lathe and self.modal.drilling is not None and code == self.modal.drilling[0]:
            self._drill(act, values, code)
        if code == 76.0 and lathe:
            order = const.order if order is None and const is not None else order
            assert order is not None
            if not any(a in values for a in "XUZW"):
                self._g76_parameters(act, values, order)  # G76's first block sets, no cut
                return False
        modal = self.modal
        lathe_cycle = lathe and code in LATHE_CYCLES
        words = self._move_words(act, cl, values, code, lathe_cycle)
        y: Value = None
        if lathe:
            # An axis's absolute word (most blocks) is where it goes, without _axis.
            x = values.get("X")
            if type(x) is not float:
                x = self._axis(values, "X", "U")
            z = values.get("Z")
            if type(z) is not float:
                z = self._axis(values, "Z", "W")
        else:
            x, y, z = self._mill_end(values)
            if code in DRILLING_CYCLES:
                z = None  # back at the initial level (G98) or the R point (G99): not kept
        if lathe_cycle or code in LEFT_UNKNOWN:
            x, z = self._cycle_end(values, words, lathe_cycle, x, z)
        elif lathe and ",A" in values and code in (0.0, 1.0):
            x, z = self._end_by_angle(values, x, z)
        position = modal.position
        arc = code in ARCS
        start = dict(position) if arc else None
        cuts = code in FEED_MOTIONS or (code in TURNING_CYCLES if lathe else code in MILL_CUTS)
        if cuts and (lathe or not self._in_air(values)):
            self._setup_cut(act, code, x if isinstance(x, float) else None)
        start_x = position.get("X")
        start_z = position.get("Z")
        ctx = act.ctx
        where = modal.position_line.get("X")
        speed = modal.speed
        name = G_NAMES.get(code) or g_name(code)
        surface_speed = speed if modal.constant_surface_speed and isinstance(speed, float) else None
        clamp = None  # the G50 S clamp, in G96
        setup = modal.setup
        if surface_speed is not None:
            clamp = math.inf if setup.clamped is False else setup.clamp_speed
        mode = setup.feed_mode  # recorded only when not the power-on mode
        feed_mode = None if mode is None or mode[0] == POWER_ON_FEED_MODE[lathe] else mode[0]
        motion = Motion(
            ctx.name,
            self._line,
            name,
            words,
            ctx.uri,
            x,
            None if modal.constant_surface_speed or not isinstance(speed, float) else speed,
            ctx.program.first_line,
            z,
            start_x if isinstance(start_x, float) else None,
            start_z if isinstance(start_z, float) else None,
            None if where is None else where[1],
            "" if where is None else where[0],
            act.serial,
            written=written(name, self.config.g_code_system)
            if self.other_g_code_system and lathe
            else "",
            inch=bool(modal.inch),
            drilling=not lathe and code in DRILLING_CYCLES,
            surface_speed=surface_speed,
            speed_clamp=clamp,
            feed_mode=feed_mode,
        )
        facts = self.facts
        if lathe and code in THREADING_CODES and act.serial not in facts.run_values:
            self._remember_run(act)
        if code == 76.0 and lathe:
            assert order is not None
            self._g76_passes(act, motion, values, order)
        elif len(facts.motions) < MAX_MOTIONS:
            facts.motions.append(motion)
        if not lathe or (code not in LATHE_CYCLES and code not in ONE_SHOT_CYCLES):
            # (a lathe's cycles end where they began)
            here = (ctx.uri, self._line)
            if x is not None or "X" in values or "U" in values:
                position["X"] = x
                modal.position_line["X"] = here
            if z is not None or "Z" in values or "W" in values:
                position["Z"] = z
                modal.position_line["Z"] = here
            if "Y" in values:
                position["Y"] = None if code in LEFT_UNKNOWN else y
        if "Z" in values and not lathe:
            modal.z_at_top = code in (28.0, 30.0) or (code == 53.0 and values["Z"] == 0.0)
        self._setup_move(act, values, code, cancels, start, dict(position) if arc else None)
        return True

    def _mill_end(self, values: dict[str, Value]) -> tuple[float | None, Value, float | None]:
        """Where a mill's block sends X, Y and Z: the word, or in G91 where the axis is plus
        the word; where the axis is without one; None where not known."""
        position = self.modal.position
        incremental = self.modal.incremental
        out: list[float | None] = []
        for axis in ("X", "Y", "Z"):
            word = values.get(axis)
            here = position.get(axis)
            if word is None:
                out.append(here if type(here) is float else None)
            elif type(word) is not float:
                out.append(None)
            elif incremental:
                out.append(here + word if type(here) is float else None)
            else:
                out.append(word)
        return out[0], out[1], out[2]

    def _end_by_angle(
        self, values: dict[str, Value], x: float | None, z: float | None
    ) -> tuple[float | None, float | None]:
        """A lathe's ",A" with X (U) or Z (W) alone: the other from the angle (diameter X)."""
        angle = values[",A"]
        start_x = self.modal.position.get("X")
        start_z = self.modal.position.get("Z")
        has_x = "X" in values or "U" in values
        has_z = "Z" in values or "W" in values
        if has_x == has_z:  # both (or neither) given: the angle moves nothing more
            return x, z
        found = None  # the other axis moves, to a place not known
        if (
            isinstance(angle, float)
            and isinstance(start_x, float)
            and isinstance(start_z, float)
            and (x if has_x else z) is not None
        ):
            found = missing_coordinate(
                (start_z, start_x), z if has_z else None, x if has_x else None, angle, 2.0
            )
            found = None if found is None else round(found, 4 if self.modal.inch else 3)
        return (found, z) if has_z else (x, found)

    def _move_words(
        self,
        act: Activation,
        cl: CompiledLine,
        values: dict[str, Value],
        code: float,
        lathe_cycle: bool,
    ) -> dict[str, float]:
        """A move's words as its motion records them: the modal F (and a lathe cycle's taper)
        added, shared with an equal earlier motion's. A cut at F 0 raises the control's alarm;
        a cut with no F commanded is reported."""
        const = cl.constant
        inch = self.modal.inch
        # A constant block's words are rounded as in mm; not renamed (_as_system_a).
        same = (
            const is not None
            and not inch
            and (
                values is const.kept_values
                or (values is self._const_values and const is self._values_of)
            )
        )
        words = const.motion_words if same and const is not None else recorded_words(values, inch)
        feed = self.modal.feed
        if "F" not in words and isinstance(feed, float) and code and code not in RAPID_ONE_SHOTS:
            words = {**words, "F": feed}
        if lathe_cycle:
            words = self._taper_in_force(values, words)
        if words.get("F") == 0.0 and (code in FEED_MOTIONS or (self.lathe and code in LATHE_FED)):
            _feed_zero(code, self._shown(code))
        if const is None or words is not const.motion_words:
            words = self._shared_words(words)
        if feed is None and (code in FEED_MOTIONS or (not self.lathe and code in DRILLING_CYCLES)):
            self._cut_without_feed(act.ctx, self._no_feed_message(code))
        if (
            self.modal.spindle == SPINDLE_OFF
            and not self.lathe  # a lathe feeds a bar puller or a part catcher standing still
            and (code in FEED_MOTIONS or code in MILL_CUTS)
            and not self._in_air(values)
        ):
            self._cut_spindle_stopped(act, code)
        return words

    def _in_air(self, values: dict[str, Value]) -> bool:
        """A mill's feed move that stays at a positive Z, above the work's zero (where shops
        set it, on the top face), or with Z at the top of its travel, or a move in Z alone to a
        positive Z (up, in G91 too): no cut, whatever the spindle does."""
        z = values.get("Z")
        here = self.modal.position.get("Z")
        if z is None and self.modal.z_at_top:
            return True  # Z at the top of its travel (G28, G30, G53 Z0)
        if z is not None and not isinstance(z, float):
            return False
        end = here if z is None else z
        if not isinstance(end, float) or end < 0.0:
            return False
        if z is not None and AXES.isdisjoint(values.keys() - {"Z"}):
            return True  # up to a positive Z: a retract
        return isinstance(here, float) and here >= 0.0

    def _cut_spindle_stopped(self, act: Activation, code: float) -> None:
        """The first feed move while the spindle stands still: once, until it starts."""
        modal = self.modal
        modal.spindle = SPINDLE_TOLD
        stop = modal.spindle_stop
        assert stop is not None  # SPINDLE_OFF is set with the block that stopped it
        uri, line, m = stop
        where = self._where(act, (uri, line))
        ctx = act.ctx
        # Told when the tool is known to be a cutting one: at the next spindle start, tool
        # change or end of the program; not if a G31 comes first (a probe feeds standing still).
        modal.setup = replace(
            modal.setup,
            pending_cut=(
                ctx.uri,
                ctx.program.first_line,
                self._line,
                len(ctx.doc.blocks[self._line].text.rstrip()),
                tr(
                    "{code} feeds with the spindle stopped: {stop} on {where} stopped it, and "
                    "no M03 or M04 started it again",
                    code=self._shown(code),
                    stop=m,
                    where=where,
                ),
            ),
        )

    def _cycle_end(
        self,
        values: dict[str, Value],
        words: dict[str, float],
        lathe_cycle: bool,
        x: float | None,
        z: float | None,
    ) -> tuple[float | None, float | None]:
        """Where a lathe cycle's block (its end Z and taper kept for a repeat) or a move to
        the reference point or in machine coordinates (the axes it names: not known) ends."""
        if lathe_cycle:
            if "Z" not in values and "W" not in values:
                z = self.modal.cycle[0]  # the cycle repeated: its end Z stays
            r = words.get("R")
            self.modal.cycle = (z, r if isinstance(r, float) else None)
            return x, z
        if "X" in values or "U" in values:
            x = None
        if "Z" in values or "W" in values:
            z = None
        return x, z

    def _cycle_or_own_code(
        self, act: Activation, values: dict[str, Value], g_codes: Sequence[float], has_axis: bool
    ) -> float | None:
        """The move of a block with a lathe's one-shot cycle, or with a G code that runs instead
        of the modal motion (``_own_codes``); None: it moves nothing."""
        # G70-G76 are the lathe's multiple repetitive cycles; on a mill G73-G76 are canned
        # drilling and boring cycles (G76 fine boring), which the analysis does not run.
        if self.lathe and not ONE_SHOT_CYCLES.isdisjoint(g_codes):
            code = next(g for g in g_codes if g in ONE_SHOT_CYCLES)
            if code in PROFILE_CYCLES:
                has_p, has_q = "P" in values, "Q" in values
                if has_p and has_q:
                    self._profile_code = code
                    self._cycle_data(act, code, values, "D")  # one block (Series 10/11 format)
                elif not (has_p or has_q) and code != 70.0:
                    self._cycle_data(act, code, values, "W" if code == 72.0 else "U")
                else:
                    why = (
                        tr("it gives P alone, and the cycle needs both")
                        if has_p
                        else tr("it gives Q alone, and the cycle needs both")
                        if has_q
                        else tr("it gives neither P nor Q, and the cycle needs both")
                    )
                    self._profile_fault(act, code, why, "p-q")
            return code
        if has_axis and not self._own_codes.isdisjoint(g_codes):
            own = next(g for g in g_codes if g in self._own_codes)
            p = values.get("P")
            if own == 30.0 and type(p) is float and p not in (2.0, 3.0, 4.0):
                self._block_finding(
                    act,
                    BlockFault,
                    tr(
                        "G30 P{p}: the second, third or fourth reference position is P2, P3 or "
                        "P4; the control stops (PS0046)",
                        p=whole(p),
                    ),
                    fault="g30-p",
                )
            if own in RAPID_ONE_SHOTS:
                drilling = self.modal.drilling
                if drilling is not None and not self.lathe and own != 53.0 and 80.0 not in g_codes:
                    self._block_finding(
                        act,
                        DrillingFault,
                        tr(
                            "{code} returns to the reference position while the drilling cycle "
                            "{cycle} is in force: the control stops (PS0044); cancel the cycle "
                            "with G80 first",
                            code=self._shown(own),
                            cycle=self._shown(drilling[0]),
                        ),
                        fault="return",
                    )
                return own
            if own not in NOT_MOVES:  # no move: a dwell, a setting
                self._coordinates_set(act, values, own)
            return None
        return self._modal_move() if has_axis else None

    def _modal_move(self) -> float | None:
        """What a block with an axis word and no code of its own runs: a mill's drilling cycle
        in force, else the motion of group 01."""
        drilling = self.modal.drilling
        if drilling is not None and not self.lathe:
            return drilling[0]
        return self.modal.motion

    def _drill(self, act: Activation, values: dict[str, Value], code: float) -> None:
        """A hole of a drilling cycle: its Q kept in force; a peck cycle's Q checked."""
        modal = self.modal
        assert modal.drilling is not None
        q: float | None = modal.drilling[1]
        if "Q" in values:
            word = values["Q"]
            q = word if type(word) is float else math.nan
            modal.drilling = (code, q)
        haas_pecks = "I" in values or "J" in values  # a Haas G83: pecks by I J K, no Q
        if code in PECK_CYCLES and (q is None or q == 0.0) and not haas_pecks:
            message = (
                tr(
                    "{code} drills with no Q: a peck cycle needs the depth of each peck; the "
                    "control stops (PS0045)",
                    code=self._shown(code),
                )
                if q is None
                else tr(
                    "{code} drills with Q0: a peck cycle needs the depth of each peck; the "
                    "control stops (PS0045)",
                    code=self._shown(code),
                )
            )
            self._block_finding(act, DrillingFault, message, fault="peck")
            modal.drilling = (code, math.nan)  # the control stops at the first: once

    def _taper_in_force(
        self, values: dict[str, Value], words: dict[str, float]
    ) -> dict[str, float]:
        """A lathe cycle's words, with the taper R in force when the block repeats the cycle."""
        taper = values.get("R") if "R" in values else self.modal.cycle[1]
        if "R" not in words and isinstance(taper, float) and taper != 0.0:
            return {**words, "R": taper}  # a repeat of a taper cycle: the cone in force
        return words

    def _no_feed_message(self, code: float) -> str:
        """What a cut without F is told: one string for the many blocks that give it (a CAM
        file: every block)."""
        message = self._no_feed.get(code)
        if message is None:
            message = self._no_feed[code] = tr(
                "G{code:02g} cuts with no F commanded before it since {program} started",
                code=code,
                program=self._entry_name,
            )
        return message

    def _coordinates_set(self, act: Activation, values: dict[str, Value], code: float) -> None:
        """G52 and the coordinate system setting (G50 on a lathe, G92 on a mill) move nothing,
        but where the tool is in work coordinates changes: to the words' values after a
        setting (0i-TF "Setting a workpiece coordinate system"), to a place not known here
        after G52 (its offset is added to every work coordinate system, 0i-TF "Local
        coordinate system"; unverified against the manual's text)."""
        modal = self.modal
        here = (act.ctx.uri, self._line)
        for axis, incremental in (("X", "U"), ("Z", "W")):
            if axis in values or incremental in values:
                v = values.get(axis)
                modal.position[axis] = v if code != LOCAL_COORDINATES and type(v) is float else None
                modal.position_line[axis] = here
        if "Y" in values:
            v = values["Y"]
            modal.position["Y"] = v if code != LOCAL_COORDINATES and type(v) is float else None

    def _remember_run(self, act: Activation) -> None:
        runs = self.facts.run_values
        if len(runs) < MAX_REMEMBERED_RUNS:
            runs[act.serial] = RunValues(tuple(act.locals), dict(self.store))


def _feed_zero(code: float, shown: str) -> None:
    """PS0011 FEED ZERO (COMMAND), 0i-TF/0i-MF alarm lists: the control stops here. (For a
    threading lead of 0 the alarm number is unverified.) ``shown``: the code as written."""
    if code in THREADING_CODES:
        raise MacroAlarm(
            "PS0011", AlarmKind.LEAD_ZERO, tr("{code} runs with the lead F = 0", code=shown)
        )
    raise MacroAlarm(
        "PS0011", AlarmKind.FEED_ZERO, tr("{code} runs with the feed F = 0", code=shown)
    )


# The names of the G codes a motion records, G00-G99.9 (others are named when met).
G_NAMES: Mapping[float, str] = MappingProxyType(
    {round(n / 10, 1): g_name(round(n / 10, 1)) for n in range(1000)}
)
