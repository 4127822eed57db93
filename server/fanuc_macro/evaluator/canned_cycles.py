"""The lathe's multiple repetitive cycles as the machine runs them: G70-G73's profile, G76.

G71-G73 read their profile N(ns)..N(nf) (its words evaluated, none run) and go on after N(nf);
G70 runs the profile's blocks as part of its own block (see :mod:`.motion`). G76's first block
sets modal parameters, its cutting block expands into passes (:func:`.cycles.g76_depths`).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import replace
from itertools import pairwise
from types import MappingProxyType

from ..syntax.marks import constant_value
from ..translation import tr
from .compile_lines import K_EMPTY, K_NC, K_OTHER, CompiledLine, CompiledWord
from .cycles import g76_depths
from .facts import Motion, ProfileFault, ThreadCycleFault
from .machine_base import (
    MAX_MOTIONS,
    Activation,
    G76Parameters,
    MachineBase,
    StopRun,
    system_a_block,
)
from .machine_setup import unit_of
from .toolpath import ProfileBlock
from .values import MacroAlarm, Unknown, Value, fmt

# The alarm the control stops with, by what is wrong with a G70-G73's profile (0i-F alarm
# list): P or Q missing, a P or Q naming no block, a first block that is not G00 or G01, a
# G71/G72 profile that turns back (which number for which axis is unverified).
PROFILE_ALARMS: Mapping[str, str] = MappingProxyType(
    {
        "p-q": "PS0061",
        "depth": "PS0062",
        "divisions": "PS0321",
        "label": "PS0063",
        "first": "PS0065",
        "monotone": tr("PS0064 or PS0329, unverified which"),
        "last": "PS0069",
    }
)
# The tool angles G76's P(a) takes, the last two digits of its first block's P (0i-TF
# "Multiple threading cycle (G76)").
G76_TOOL_ANGLES = frozenset({80.0, 60.0, 55.0, 30.0, 29.0, 0.0})
# The faults of a cycle's own data, not of its profile.
CYCLE_DATA = frozenset({"depth", "divisions"})
# How far a profile's end points may step back along an axis and still count as one way: the
# rounding of computed coordinates, far below the least increment.
MONOTONE_EPS = 1e-6
# The lathe's cycles that name a profile N(ns)..N(nf) by P and Q: G71-G73 read it, G70 runs it.
PROFILE_CYCLES = frozenset({70.0, 71.0, 72.0, 73.0})
# What a block of the profile may not hold for the evaluator to follow it: calls, returns, ends,
# the cycles themselves (FANUC forbids M98/M99 and the one-shot cycles in a profile: 0i-TF
# "Multiple repetitive cycle", limitations).
NOT_IN_PROFILE_G = frozenset({65.0, 66.0, 66.1, 70.0, 71.0, 72.0, 73.0, 74.0, 75.0, 76.0})
NOT_IN_PROFILE_M = frozenset({2.0, 30.0, 98.0, 99.0, 198.0})


class CyclesPart(MachineBase):
    """The machine's G70-G73 profiles and G76 threading cycle."""

    def _profile(
        self, act: Activation, values: dict[str, Value], code: float
    ) -> tuple[list[ProfileBlock] | str, int, tuple[int, int] | None]:
        """A G70-G73 that names its profile ``P(ns) Q(nf)``: what the toolpath gets of the
        profile (its blocks' words, or why it cannot be followed), the block to run next, and
        for G70 the profile's lines to run now.

        FANUC Series 0i-TF / 0i-TD Operator's Manual, "Multiple repetitive cycle (G70-G76)":
        G71, G72 and G73 read the blocks N(ns) to N(nf) to work out their passes and, done,
        go on with the block after N(nf); G70 runs them and goes on with the block after the
        G70, back at its start point. A profile the evaluator cannot follow (its N not in the
        program, a call, a jump or an assignment in it) is run as before: the block after the
        cycle comes next."""
        line = self._line
        ctx = act.ctx
        p, q = values.get("P"), values.get("Q")
        if not isinstance(p, float) or not isinstance(q, float):
            return tr("its P or Q is not known"), line + 1, None
        first = self._label(ctx, int(p), line)
        if first is None:
            why = tr("no N{label} (its P) in {program}", label=int(p), program=ctx.name)
            self._profile_fault(act, code, why, "label")
            return why, line + 1, None
        last = self._label(ctx, int(q), first - 1)
        if last is None or last < first:
            why = tr(
                "no N{label} (its Q) after N{first} in {program}",
                label=int(q),
                first=int(p),
                program=ctx.name,
            )
            self._profile_fault(act, code, why, "label")
            return why, line + 1, None
        lines = ctx.lines
        for n in range(first, last + 1):
            if not _plain_profile_line(lines[n]):
                return (
                    tr(
                        "the profile N{first}-N{last} holds a block the analysis does not "
                        "follow in a profile (line {line})",
                        first=int(p),
                        last=int(q),
                        line=n + 1,
                    ),
                    line + 1,
                    None,
                )
        if self.modal.modal_calls:
            return tr("a G66 modal call is in force"), line + 1, None
        self._profile_budget(act, last + 1 - first)
        if code == 70.0:
            return [], line + 1, (first, last)
        blocks = self._read_profile(act, first, last)
        self._check_first_block(act, code, blocks)
        self._last_block_corner(act, code, blocks)
        if code in (71.0, 72.0):
            self._check_monotone(act, code, blocks, first)
        return blocks, last + 1, None

    def _check_first_block(self, act: Activation, code: float, blocks: list[ProfileBlock]) -> None:
        """A G71-G73 profile's first block moves at G00 or G01 (0i-TF "Multiple repetitive
        cycle"): one that commands an arc, or leaves G02/G03 in force, cannot start it."""
        if not blocks:
            return
        g_codes = blocks[0][1]
        motion = next((g for g in g_codes if g in (0.0, 1.0, 2.0, 3.0)), self.modal.motion)
        if motion in (2.0, 3.0):
            self._profile_fault(
                act,
                code,
                tr(
                    "its first block moves by {code}, and a profile must begin with G00 or G01",
                    code=self._shown(motion),
                ),
                "first",
            )

    def _profile_fault(self, act: Activation, code: float, why: str, fault: str) -> None:
        """A G70-G73 the control stops at, for its profile: ``why``."""
        alarm = PROFILE_ALARMS[fault]
        if fault in CYCLE_DATA:
            message = tr(
                "{code}: {why}; the control stops ({alarm})",
                code=self._shown(code),
                why=why,
                alarm=alarm,
            )
        else:
            message = tr(
                "{code}'s profile: {why}; the control stops ({alarm})",
                code=self._shown(code),
                why=why,
                alarm=alarm,
            )
        self._block_finding(act, ProfileFault, message, fault=fault)

    def _check_monotone(
        self, act: Activation, code: float, blocks: list[ProfileBlock], first: int
    ) -> None:
        """A G71 or G72 profile must go one way in the axis its passes step along (G71: Z,
        G72: X), and in type I (the first block moves in one axis only) in the other too
        (0i-TF "Stock removal in turning (G71)", "... in facing (G72)"): judged on the
        blocks' end points, as far as the run knows them."""
        if not blocks:
            return
        facing = code == 72.0
        head = blocks[0][0]
        type_two = any(a in head for a in (("X", "U") if facing else ("Z", "W")))
        axes: tuple[str, ...] = ("X",) if facing else ("Z",)
        if not type_two:
            axes = ("X", "Z")
        ends = _profile_ends(blocks, self.modal.position, self.modal.motion)
        if ends is None:
            return
        if self._beyond_start(act, code, ends, blocks):
            return
        for axis in axes:
            steps = [b[axis] - a[axis] for a, b in pairwise(ends)]
            up = [i for i, s in enumerate(steps) if s > MONOTONE_EPS]
            down = [i for i, s in enumerate(steps) if s < -MONOTONE_EPS]
            if up and down:
                turn = max(up[0], down[0]) + 1  # the block whose end goes back
                said = {"axis": axis, "at": fmt(ends[turn][axis]), "code": self._shown(code)}
                if up[0] < down[0]:
                    why = (
                        tr(
                            "{axis} goes up and then back, at {axis}{at}: a {code} profile "
                            "must keep going one way in {axis}",
                            **said,
                        )
                        if type_two
                        else tr(
                            "{axis} goes up and then back, at {axis}{at}: a type I {code} "
                            "profile must keep going one way in {axis}",
                            **said,
                        )
                    )
                else:
                    why = (
                        tr(
                            "{axis} goes down and then back, at {axis}{at}: a {code} profile "
                            "must keep going one way in {axis}",
                            **said,
                        )
                        if type_two
                        else tr(
                            "{axis} goes down and then back, at {axis}{at}: a type I {code} "
                            "profile must keep going one way in {axis}",
                            **said,
                        )
                    )
                self._profile_fault(act, code, why, "monotone")
                return

    def _beyond_start(
        self, act: Activation, code: float, ends: list[dict[str, float]], blocks: list[ProfileBlock]
    ) -> bool:
        """A G71 (G72) profile whose cutting blocks go past the cycle's start point in X (Z), on
        the side of the stock, by more than the cycle's depth of cut: the passes start at the
        start point, so they do not rough what lies beyond it, and G70 takes it in one cut.
        With the finishing-shape check (parameter 5104#2 FCK) the control refuses the cycle
        (PS0322); production programs run with the profile's last block, the move that leaves
        it, past the start point, so the check is off by default (unverified against a
        manual). Whether it was reported."""
        axis = "Z" if code == 72.0 else "X"
        start = self.modal.position.get(axis)
        if type(start) is not float or not ends or ends[0][axis] == start:
            return False
        inward = ends[0][axis] < start  # an outside profile lies below the start (G71)
        judged: list[dict[str, float]] | None = ends
        if len(blocks) > 1 and _departure(blocks[-1][0], code):
            # The move that leaves the profile is not part of the shape.
            judged = _profile_ends(blocks[:-1], self.modal.position, self.modal.motion)
        if not judged:
            return False
        past = [e[axis] for e in judged if (e[axis] > start if inward else e[axis] < start)]
        beyond = max(past) if inward and past else min(past) if past else None
        if beyond is None:
            return False
        excess = abs(beyond - start) / (2.0 if axis == "X" else 1.0)
        depth = self._depth_of_cut(act, code)
        if excess <= max(depth or 0.0, MONOTONE_EPS):
            return False
        unit = unit_of(self.modal.inch)
        cut = (
            tr("more than its depth of cut {depth} {unit}", depth=fmt(depth), unit=unit)
            if depth
            else tr("stock")
        )
        self._block_finding(
            act,
            ProfileFault,
            tr(
                "{code}'s profile: it goes to {axis}{beyond}, {excess} {unit} past the cycle's "
                "start point {axis}{start}: the roughing passes start there and leave what "
                "lies beyond, {cut}, to one cut of the finishing pass (with the finishing-shape "
                "check on, parameter 5104#2, the control stops: PS0322)",
                code=self._shown(code),
                axis=axis,
                beyond=fmt(beyond),
                excess=fmt(round(excess, 4)),
                unit=unit,
                start=fmt(start),
                cut=cut,
            ),
            fault="start",
        )
        return True

    def _depth_of_cut(self, act: Activation, code: float) -> float | None:
        """Δd of the cycle's first block (``G71 U(Δd) R(e)``, ``G72 W(Δd) R(e)``), when it is
        one of the few blocks before this one and a constant; radius."""
        lines = act.ctx.lines
        address = "W" if code == 72.0 else "U"
        for n in range(self._line - 1, max(self._line - 4, -1), -1):
            const = lines[n].constant
            if const is None or code not in const.g_codes:
                continue
            values = const.values
            if "P" in values or "Q" in values:
                return None
            depth = values.get(address)
            return depth if isinstance(depth, float) and depth > 0.0 else None
        return None

    def _last_block_corner(self, act: Activation, code: float, blocks: list[ProfileBlock]) -> None:
        """A profile's last block may not end in a chamfer or corner R: there is no move
        after it to make the corner with (PS0069)."""
        if blocks and (",C" in blocks[-1][0] or ",R" in blocks[-1][0]):
            self._profile_fault(
                act,
                code,
                tr(
                    "its last block ends in a chamfer or corner R (,C ,R), with no move of the "
                    "profile after it"
                ),
                "last",
            )

    def _profile_budget(self, act: Activation, blocks: int) -> None:
        """The profiles' blocks run within the G70-G73 block that names them, which the step
        budget counts once: they have a budget of their own, as many blocks, so that a loop
        around a G70 ends as soon."""
        self._profile_blocks += blocks
        if self._profile_blocks > self.budget:
            self._budget_spent(act)
            self._mark_incomplete(act)
            raise StopRun("budget")

    def _read_profile(self, act: Activation, first: int, last: int) -> list[ProfileBlock]:
        """The blocks of a G71-G73's profile as the control reads them: their words evaluated
        now (with the variables' values now) and checked, each block counted as reached, none
        run (no motion, no modal change)."""
        line = self._line
        blocks: list[ProfileBlock] = []
        translate = self.other_g_code_system and self.lathe
        incremental = self.modal.incremental  # a profile's own G90/G91 hold in it only
        for n in range(first, last + 1):
            pcl = self._profile_line(act, n)
            if pcl.kind != K_NC:
                continue
            try:
                values, g_codes, order = self._words_of(act, pcl)
                if translate:
                    values, g_codes, incremental = system_a_block(
                        values, g_codes, self.config.g_code_system, incremental
                    )
                if order is not None:
                    self._check_addresses(act, pcl, order)
            except MacroAlarm as alarm:
                self._profile_alarm(act, pcl, alarm)
            blocks.append((values, g_codes))
        self._line = line
        return blocks

    def _profile_alarm(self, act: Activation, pcl: CompiledLine, alarm: MacroAlarm) -> None:
        """An alarm in a block of a profile (the run is at that block): the run stops."""
        message = self._alarm(act, pcl, alarm)
        if self.stepper is not None:
            self.stepper.alarm(act, self._line, message)
        self._mark_incomplete(act)
        raise StopRun("alarm") from None

    def _profile_line(self, act: Activation, n: int) -> CompiledLine:
        """Line ``n`` of a profile, counted as reached and its reads recorded: the block the
        evaluator is at from now on."""
        pcl = act.ctx.lines[n]
        self._line = n
        facts = act.ctx.facts
        facts.runs[n] = facts.runs.get(n, 0) + 1
        if pcl.reads:
            self._record_reads(act, pcl, facts)
        return pcl

    def _words_of(
        self, act: Activation, cl: CompiledLine
    ) -> tuple[dict[str, Value], Sequence[float], list[tuple[str, Value, CompiledWord]] | None]:
        """An NC block's words evaluated: by address (the first of each), its G codes, and
        the words in order when a check may find something in them (None: it cannot)."""
        const = cl.constant
        if const is not None:
            return const.values, const.g_codes, None if const.quiet else const.order
        values: dict[str, Value] = {}
        g_codes: list[float] = []
        order: list[tuple[str, Value, CompiledWord]] = []
        for w in cl.words:
            v = w.evaluate(act)
            if v is None:
                continue
            order.append((w.address, v, w))
            if w.address == "G" and not isinstance(v, Unknown):
                g_codes.append(round(v, 1))
            if w.address not in values:
                values[w.address] = v
        return values, g_codes, order

    def _least_increments(self, value: Value, word: CompiledWord | None) -> float | None:
        """A G76 word given in least input increments (P, Q: no decimal point, 0.001 mm); one
        written with a decimal point is taken in mm (unverified: FANUC may reject it)."""
        if not isinstance(value, float):
            return None
        if word is not None and word.decimal_point:
            return value
        return value * (0.0001 if self.modal.inch else 0.001)

    @staticmethod
    def _word(order: list[tuple[str, Value, CompiledWord]], address: str) -> CompiledWord | None:
        return next((w for a, _v, w in order if a == address), None)

    def _g76_parameters(
        self,
        act: Activation,
        values: dict[str, Value],
        order: list[tuple[str, Value, CompiledWord]],
    ) -> None:
        old = self.modal.g76
        m, chamfer, angle = old.finishing_passes, old.chamfer, old.tool_angle
        p = values.get("P")
        if isinstance(p, float):  # P mmrraa: finishing passes, chamfer, tool angle
            digits = round(p)
            m, chamfer, angle = digits // 10000, float(digits // 100 % 100), float(digits % 100)
            if angle not in G76_TOOL_ANGLES:
                self._block_finding(
                    act,
                    ThreadCycleFault,
                    tr(
                        "G76 P{digits:06d} gives the tool angle {angle:g}°, which the cycle "
                        "does not take (80, 60, 55, 30, 29 or 0): the control stops (PS0315)",
                        digits=digits,
                        angle=angle,
                    ),
                    fault="angle",
                )
        q = self._least_increments(values.get("Q"), self._word(order, "Q"))
        r = self._least_increments(values.get("R"), self._word(order, "R"))
        self.modal.g76 = G76Parameters(
            m,
            chamfer,
            angle,
            old.min_depth if q is None else q,
            old.finishing_allowance if r is None else r,
            self._line,
        )

    def _g76_passes(
        self,
        act: Activation,
        cut: Motion,
        values: dict[str, Value],
        order: list[tuple[str, Value, CompiledWord]],
    ) -> None:
        """The passes of G76's cutting block ``G76 X Z R(i) P(k) Q(Δd) F(L)``: X is the root,
        k the thread height and Δd the first depth, both radius values in least increments."""
        motions = self.facts.motions
        height = self._least_increments(values.get("P"), self._word(order, "P"))
        first = self._least_increments(values.get("Q"), self._word(order, "Q"))
        refused = self._check_g76_depths(act, height, first)
        if cut.x is None or cut.start_x is None or height is None or first is None or refused:
            if len(motions) < MAX_MOTIONS:
                motions.append(cut)  # what the control would cut cannot be known: one record
            return
        params = self.modal.g76
        outward = cut.x > cut.start_x  # an internal thread: the cuts go away from the axis
        sign = -1.0 if outward else 1.0
        depths = g76_depths(
            height, first, params.min_depth, params.finishing_allowance, params.finishing_passes
        )
        for n, (depth, finishing) in enumerate(depths, 1):
            if len(motions) >= MAX_MOTIONS:
                return
            x = round(cut.x + sign * 2.0 * (height - depth), 4)
            motions.append(
                replace(
                    cut,
                    words={**cut.words, "X": round(x, 3)},
                    x=x,
                    cycle_pass=n,
                    finishing=finishing,
                    tool_angle=params.tool_angle,
                )
            )

    def _cycle_data(
        self, act: Activation, code: float, values: dict[str, Value], depth: str
    ) -> None:
        """The data of G71/G72 (the depth of cut, ``depth``: U or W in their first block, D in
        the one-block form) and G73 (the number of divisions R in its first block): a depth of
        0 (PS0062) or fewer than one division (PS0321) stops the control (0i-TF "Multiple
        repetitive cycle")."""
        if code in (71.0, 72.0):
            d = values.get(depth)
            if d == 0.0:
                self._profile_fault(
                    act,
                    code,
                    tr(
                        "its depth of cut {address} is 0, and the cycle cuts nothing", address=depth
                    ),
                    "depth",
                )
        elif code == 73.0 and "P" not in values:
            r = values.get("R")
            if type(r) is float and r < 1.0:
                self._profile_fault(
                    act,
                    code,
                    tr(
                        "its number of divisions R is {divisions}, and the pattern needs one at "
                        "least",
                        divisions=fmt(r),
                    ),
                    "divisions",
                )

    def _check_g76_depths(self, act: Activation, height: float | None, first: float | None) -> bool:
        """G76's thread height k and first depth Δd must be above 0 (PS0317), and the least
        depth of its first block no more than k (PS0316) (0i-TF "Multiple threading cycle
        (G76)", the alarms of the cycle). Whether the control refuses the cycle."""
        why: tuple[str, str] | None = None
        if height is not None and height <= 0.0:
            why = (
                tr(
                    "its thread height P is {height} {unit}",
                    height=fmt(height),
                    unit=unit_of(self.modal.inch),
                ),
                "PS0317",
            )
        elif first is not None and first <= 0.0:
            why = (
                tr(
                    "its first depth of cut Q is {depth} {unit}",
                    depth=fmt(first),
                    unit=unit_of(self.modal.inch),
                ),
                "PS0317",
            )
        elif height is not None and self.modal.g76.min_depth > height:
            least = self.modal.g76.min_depth
            why = (
                tr(
                    "the least depth of cut {least} {unit} of its first block is more than the "
                    "thread height {height} {unit}",
                    least=fmt(least),
                    height=fmt(height),
                    unit=unit_of(self.modal.inch),
                ),
                "PS0316",
            )
        if why is not None:
            self._block_finding(
                act,
                ThreadCycleFault,
                tr("G76 cannot cut: {why}; the control stops ({alarm})", why=why[0], alarm=why[1]),
                fault="depths",
            )
        return why is not None


def _departure(words: Mapping[str, Value], code: float) -> bool:
    """Whether a profile block moves along the cycle's depth axis alone (X for G71, Z for
    G72): the move that leaves the finished profile."""
    depth_axis = ("Z", "W") if code == 72.0 else ("X", "U")
    other = ("X", "U") if code == 72.0 else ("Z", "W")
    return any(a in words for a in depth_axis) and not any(a in words for a in other)


def _plain_profile_line(cl: CompiledLine) -> bool:
    """Whether a line of a G70-G73 profile is one the evaluator follows: an NC block with no
    call, return, end or cycle, or a line with no block (empty, a comment)."""
    kind = cl.kind
    if kind in (K_EMPTY, K_OTHER):
        return True
    if kind != K_NC or cl.cond is not None or cl.second is not None:
        return False
    const = cl.constant
    if const is not None:
        g_codes: Iterable[float] = const.g_codes
        m_codes: Iterable[float] = const.m_codes
    else:
        assert cl.nc is not None
        g_list: list[float] = []
        m_list: list[float] = []
        for w in cl.nc.words:
            if w.address in ("G", "M"):
                v = constant_value(w.value)
                if v is None:
                    return False  # a computed G or M code
                (g_list if w.address == "G" else m_list).append(round(v, 1))
        g_codes, m_codes = g_list, m_list
    return NOT_IN_PROFILE_G.isdisjoint(g_codes) and NOT_IN_PROFILE_M.isdisjoint(m_codes)


def _profile_ends(
    blocks: Sequence[ProfileBlock], position: Mapping[str, Value], motion: float | None
) -> list[dict[str, float]] | None:
    """Where the profile's cut goes: the end of its first block (the approach, where the
    shape begins) and of each cutting block after it (X a diameter), from where the cycle
    starts. A rapid block after the first is left out: the retract some programs end the
    profile with, which a Haas lathe takes (whether a FANUC does is unverified). None when a
    value is not known."""
    x, z = position.get("X"), position.get("Z")
    if type(x) is not float or type(z) is not float:
        return None
    ends: list[dict[str, float]] = []
    for i, (values, g_codes) in enumerate(blocks):
        for g in g_codes:
            if g in (0.0, 1.0, 2.0, 3.0):
                motion = g
        moved = False
        for absolute, incremental in (("X", "U"), ("Z", "W")):
            word = values.get(absolute)
            step = values.get(incremental)
            if word is None and step is None:
                continue
            value = word if word is not None else step
            if type(value) is not float:
                return None
            moved = True
            if absolute == "X":
                x = value if word is not None else x + value
            else:
                z = value if word is not None else z + value
        if moved and (i == 0 or motion != 0.0):
            ends.append({"X": x, "Z": z})
    return ends
