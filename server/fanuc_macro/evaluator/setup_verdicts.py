"""The verdicts on the machine's setup as blocks change and use it (:mod:`.machine_setup`):
radius compensation started or cancelled on an arc, the plane changed under it, left on; an
arc the control cannot cut; G96 near the centre with no clamp; a length offset of another
tool, or none; the skip position read before a G31.

:class:`SetupPart` is one of the machine's parts (see :mod:`.machine_base`): :mod:`.motion`
calls ``_setup_codes`` before a block's move, ``_setup_move`` with it and ``_setup_end`` at
the end of the program.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import replace

from ..translation import tr
from .facts import (
    ArcFault,
    CompensationFault,
    CornerRefused,
    CutSpindleStopped,
    DrillingFault,
    FeedUnit,
    LengthOffsetOtherTool,
    SpeedNotClamped,
    ToolWithoutLengthOffset,
)
from .machine_base import Activation, MachineBase
from .machine_setup import (
    PLANES,
    Setup,
    arc_fault,
    feed_unit_fault,
    moves_in_plane,
    speed_at,
)
from .toolpath import Plane
from .values import Value, fmt

ARCS = frozenset({2.0, 3.0})
# How far from the tool's number a length offset may stand and still be taken for a slip when
# only the tool's D shows the numbering: shops that keep lengths in a second bank of the
# offset table (H21 for T1, where H and D share it) number them 20 or more away.
OTHER_BANK = 10.0
# Rigid tapping: M29 (parameter 5210 may set another code; taken as M29) and the tapping
# cycles that must follow it (0i-MF/0i-TF "Rigid tapping").
RIGID_TAPPING_M = 29.0
TAPPING_MILL = frozenset({74.0, 84.0})
TAPPING_LATHE = frozenset({84.0, 88.0})
# A lathe's threading moves (G-code system A): their F is the lead.
THREADING_CODES = frozenset({32.0, 33.0, 34.0, 76.0, 92.0})
# What shows that a tool that fed with the spindle stopped is a cutter, not a probe: the
# spindle started at last (M03, M04), the next tool change (M06), the end (M02, M30).
CONFIRM_CUT = frozenset({3.0, 4.0, 6.0, 2.0, 30.0})
# The feed modes: per minute, per revolution (a lathe's G-code system A; a mill's). A lathe's
# G94 is its facing cycle, a mill's G98/G99 the drilling cycles' return levels.
FEED_MODES_LATHE = frozenset({98.0, 99.0})
FEED_MODES_MILL = frozenset({94.0, 95.0})
PER_REVOLUTION = frozenset({99.0, 95.0})
REFERENCE_RETURNS = frozenset({28.0, 30.0})
# The lathe's feed moves that turn at G96's surface speed besides G01-G03: the turning and
# facing cycles, and the roughing cycles (at the F of their block, from their start point);
# threads run in G97 as a rule, and their X is the root.
TURNING_CYCLES = frozenset({90.0, 94.0, 71.0, 72.0, 73.0})


def whole(v: float) -> str:
    """A tool or offset number as programs write it: T2, H12 (a fraction kept as written)."""
    return f"{v:g}" if v.is_integer() else fmt(v)


class SetupPart(MachineBase):
    """What the blocks do to the machine's setup, and the verdicts on it."""

    def _told_cut(self, cut: tuple[str, int, int, int, str]) -> None:
        """MB611's finding, once the tool that fed standing still is known to be a cutter."""
        uri, program, line, width, message = cut
        ctx = self.contexts.get((uri, program))
        if ctx is not None:
            self._finding(ctx, CutSpindleStopped(line, 0, width, message, uri))

    def _place(self, act: Activation) -> tuple[str, int]:
        return (act.ctx.uri, self._line)

    def _setup_codes(
        self,
        act: Activation,
        values: Mapping[str, Value],
        g_codes: Sequence[float],
        m_codes: Sequence[float],
    ) -> bool:
        """The setup the block's codes change, before its move; whether the block cancels
        radius compensation (G40) while it was on, for ``_setup_move``."""
        modal = self.modal
        setup = before = modal.setup
        cancels = False
        here = self._place(act)
        for g in g_codes:
            plane = PLANES.get(g)
            if plane is not None and not self.lathe:
                if plane != setup.plane and setup.compensation in (41.0, 42.0):
                    self._block_finding(
                        act,
                        CompensationFault,
                        tr(
                            "G{plane:g} changes the plane while G{compensation:g} from {where} "
                            "is on: the control stops (PS0037); cancel it with G40 first",
                            plane=g,
                            compensation=setup.compensation,
                            where=self._where(act, setup.compensation_at or here),
                        ),
                        fault="plane",
                    )
                setup = replace(setup, plane=plane)
            elif g == 40.0:
                cancels = setup.compensation in (41.0, 42.0) and setup.compensation_started
                setup = replace(
                    setup, compensation=40.0, compensation_started=False, left_on_told=False
                )
            elif g in (41.0, 42.0):
                pending, d = setup.pending_offset, values.get("D")
                if (
                    pending is not None
                    and d == pending[5]
                    and setup.tool == pending[5]
                    and setup.length_offset is not None
                    and abs(setup.length_offset - pending[5]) < OTHER_BANK
                ):
                    where = self._where(act, here)
                    self._told_offset(
                        pending,
                        tr(
                            "{offset}; the radius offset D{number} on {where} is the tool's number",
                            offset=pending[4],
                            number=whole(pending[5]),
                            where=where,
                        ),
                    )
                    setup = replace(setup, pending_offset=None)
                if setup.compensation == 40.0 or setup.compensation is None:
                    setup = replace(
                        setup,
                        compensation=g,
                        compensation_at=here,
                        compensation_started=setup.compensation is None,
                    )
                else:
                    setup = replace(setup, compensation=g)
            elif g == 31.0:
                if setup.compensation in (41.0, 42.0):
                    self._block_finding(
                        act,
                        CompensationFault,
                        tr(
                            "G31 skips while radius compensation G{compensation:g} is on: the "
                            "control stops (PS0035); cancel it with G40 before the probing move",
                            compensation=setup.compensation,
                        ),
                        fault="skip",
                    )
                setup = replace(setup, skipped=True)
            elif g in (FEED_MODES_LATHE if self.lathe else FEED_MODES_MILL):
                setup = replace(setup, feed_mode=(g, here[0], here[1]), feed_told=False)
            elif g == 50.0 and self.lathe and "S" in values:
                clamp = values.get("S")
                setup = replace(
                    setup,
                    clamped=True,
                    clamp_speed=clamp if isinstance(clamp, float) else None,
                    unclamped_told=False,
                )
            elif g in (43.0, 44.0) and not self.lathe:
                setup = self._length_offset(act, setup, g, values.get("H"))
            elif g == 49.0 and not self.lathe:
                setup = replace(setup, length_offset=None)
        if setup.pending_cut is not None and (31.0 in g_codes or 19.0 in m_codes):
            setup = replace(setup, pending_cut=None)  # a probe's move: it feeds standing still
        elif setup.pending_cut is not None and not CONFIRM_CUT.isdisjoint(m_codes):
            self._told_cut(setup.pending_cut)
            setup = replace(setup, pending_cut=None)
        if RIGID_TAPPING_M in m_codes:
            setup = replace(setup, rigid_at=here)
        if not self.lathe:
            tool = values.get("T")
            if tool is not None:
                setup = replace(setup, selected=tool if type(tool) is float else None)
            if 6.0 in m_codes:
                setup = replace(
                    setup,
                    tool=setup.selected,
                    tool_at=here,
                    length_offset=None,
                    length_told=False,
                )
        if setup is not before:
            modal.setup = setup
        return cancels

    def _length_offset(self, act: Activation, setup: Setup, g: float, h: Value) -> Setup:
        """G43/G44 H: the offset called, checked against the tool in the spindle."""
        if type(h) is not float:
            return replace(setup, length_offset=math.nan, offset_used=True)
        tool, loaded = setup.tool, setup.tool_at
        if tool is not None and h != 0.0 and loaded is not None:
            pending = setup.pending_offset
            if pending is not None:  # an earlier tool's H, not its number: this one decides
                if h == tool:
                    self._told_offset(
                        pending,
                        tr(
                            "{offset}; the next tool takes the offset of its number",
                            offset=pending[4],
                        ),
                    )
                setup = replace(setup, pending_offset=None)
            message = tr(
                "G{code:g} H{offset} applies offset {offset} to tool {tool}, loaded on {where}",
                code=g,
                offset=whole(h),
                tool=whole(tool),
                where=self._where(act, loaded),
            )
            if h == tool:
                setup = replace(setup, offset_by_tool=True)
            elif setup.offset_by_tool:
                self._block_finding(
                    act,
                    LengthOffsetOtherTool,
                    tr(
                        "{offset}: the earlier tools of this run took the offset of their number",
                        offset=message,
                    ),
                )
            else:
                ctx = act.ctx
                width = len(ctx.doc.blocks[self._line].text.rstrip())
                setup = replace(
                    setup,
                    pending_offset=(
                        ctx.uri,
                        ctx.program.first_line,
                        self._line,
                        width,
                        message,
                        tool,
                    ),
                )
        return replace(setup, length_offset=h, offset_used=True)

    def _told_offset(self, pending: tuple[str, int, int, int, str, float], message: str) -> None:
        """MB613's finding on an earlier block, now that the program shows that it numbers
        the offsets by the tools: ``message``, the pending one's with the reason."""
        uri, program, line, width, _offset, _tool = pending
        ctx = self.contexts.get((uri, program))
        if ctx is not None:
            self._finding(ctx, LengthOffsetOtherTool(line, 0, width, message, uri))

    def _setup_move(
        self,
        act: Activation,
        values: Mapping[str, Value],
        code: float,
        cancels: bool,
        start: Mapping[str, Value] | None,
        end: Mapping[str, Value] | None,
    ) -> None:
        """The verdicts on a block's move: compensation started or cancelled on an arc, left
        on at a reference return; the arc's geometry (``start`` and ``end``: where the tool
        was and goes, given for arcs)."""
        modal = self.modal
        setup = modal.setup
        plane: Plane = "XZ" if self.lathe else setup.plane
        arc = code in ARCS
        if arc and start is not None and end is not None:
            fault = arc_fault(start, end, values, plane, self.lathe, modal.inch)
            if fault is not None:
                kind, why = fault
                alarm = "PS0022" if kind == "no-centre" else "PS0020"
                self._block_finding(
                    act,
                    ArcFault,
                    tr(
                        "{code} cannot be cut: {why}; the control stops ({alarm})",
                        code=self._shown(code),
                        why=why,
                        alarm=alarm,
                    ),
                    fault=kind,
                )
        if ",C" in values or ",R" in values:
            self._corner_refused(act, values, code, cancels)
        rigid = setup.rigid_at
        if rigid is not None and rigid[1] != self._line:
            tapping = TAPPING_LATHE if self.lathe else TAPPING_MILL
            if code not in tapping:
                self._block_finding(
                    act,
                    DrillingFault,
                    tr(
                        "{code} moves an axis after M29 on {where} and before the tapping "
                        "cycle: the control stops (PS0204); give the tapping cycle right after "
                        "M29, the hole's X Y with it",
                        code=self._shown(code),
                        where=self._where(act, rigid),
                    ),
                    fault="rigid",
                )
            modal.setup = setup = replace(setup, rigid_at=None)
        if cancels and arc and moves_in_plane(values, plane, self.lathe):
            self._block_finding(
                act,
                CompensationFault,
                tr(
                    "G40 cancels radius compensation in a {code} block: the control stops "
                    "(PS0034); cancel it on a G00 or G01 move",
                    code=self._shown(code),
                ),
                fault="arc",
            )
        if (
            setup.compensation in (41.0, 42.0)
            and not setup.compensation_started
            and moves_in_plane(values, plane, self.lathe)
        ):
            if arc:
                at = setup.compensation_at or self._place(act)
                self._block_finding(
                    act,
                    CompensationFault,
                    tr(
                        "G{compensation:g} from {where} starts radius compensation on this "
                        "{code}: the control stops (PS0034); start it on a G00 or G01 move",
                        compensation=setup.compensation,
                        where=self._where(act, at),
                        code=self._shown(code),
                    ),
                    fault="arc",
                )
            modal.setup = setup = replace(setup, compensation_started=True)
        if code in REFERENCE_RETURNS:
            self._left_on(act, tr("at the reference return {code}", code=self._shown(code)))

    def _corner_refused(
        self, act: Activation, values: Mapping[str, Value], code: float, cancels: bool
    ) -> None:
        """A chamfer or corner R (``,C``, ``,R``) where the control takes none: on a thread
        (PS0050), or on the block that starts or cancels radius compensation (PS0039) (0i-F
        alarm list; 0i-MF "Optional chamfering and corner R")."""
        setup = self.modal.setup
        plane: Plane = "XZ" if self.lathe else setup.plane
        corner = ",C" if ",C" in values else ",R"
        what = tr("a chamfer") if corner == ",C" else tr("a corner R")
        if self.lathe and code in THREADING_CODES:
            message = tr(
                "{what} ({corner}) on this block, and {code} cuts a thread: the control stops "
                "(PS0050); put the corner on a move of its own",
                what=what,
                corner=corner,
                code=self._shown(code),
            )
        elif cancels:
            message = tr(
                "{what} ({corner}) on this block, and G40 cancels radius compensation in it: "
                "the control stops (PS0039); put the corner on the block before",
                what=what,
                corner=corner,
            )
        elif (
            setup.compensation in (41.0, 42.0)
            and not setup.compensation_started
            and moves_in_plane(values, plane, self.lathe)
        ):
            message = tr(
                "{what} ({corner}) on this block, and it starts radius compensation "
                "G{compensation:g}: the control stops (PS0039); put the corner on the next block",
                what=what,
                corner=corner,
                compensation=setup.compensation,
            )
        else:
            return
        self._block_finding(act, CornerRefused, message)

    def _setup_end(self, act: Activation, m: float) -> None:
        """M02 or M30: radius compensation still on."""
        self._left_on(act, tr("at M{code:02g}, the end of the program", code=m))

    def _left_on(self, act: Activation, where: str) -> None:
        setup = self.modal.setup
        if setup.compensation not in (41.0, 42.0) or setup.left_on_told:
            return
        at = setup.compensation_at
        if at is None:
            message = tr(
                "radius compensation G{compensation:g} is still on {where}: the moves to it "
                "are offset; cancel it with G40 on the retract",
                compensation=setup.compensation,
                where=where,
            )
        else:
            message = tr(
                "radius compensation G{compensation:g} from {since} is still on {where}: the "
                "moves to it are offset; cancel it with G40 on the retract",
                compensation=setup.compensation,
                since=self._where(act, at),
                where=where,
            )
        self._block_finding(act, CompensationFault, message, fault="left-on")
        self.modal.setup = replace(setup, left_on_told=True)

    def _setup_cut(self, act: Activation, code: float, x: float | None) -> None:
        """A feed move: on a mill, the first after a tool change with no length offset; on a
        lathe in G96, one to a diameter the spindle cannot reach unclamped."""
        modal = self.modal
        setup = modal.setup
        mode, feed = setup.feed_mode, modal.feed
        if mode is not None and not setup.feed_told and not setup.lead_feed and type(feed) is float:
            why = feed_unit_fault(feed, mode[0] in PER_REVOLUTION, modal.inch)
            if why is not None:
                self._block_finding(
                    act,
                    FeedUnit,
                    tr(
                        "{code} cuts at F{feed} in G{mode:g} (from {where}): {why}",
                        code=self._shown(code),
                        feed=fmt(feed),
                        mode=mode[0],
                        where=self._where(act, (mode[1], mode[2])),
                        why=why,
                    ),
                )
                modal.setup = setup = replace(setup, feed_told=True)
        if not self.lathe:
            if (
                setup.tool_at is not None
                and setup.length_offset is None
                and setup.offset_used
                and not setup.length_told
            ):
                where = self._where(act, setup.tool_at)
                if setup.tool is None:
                    message = tr(
                        "{code} cuts with no tool length offset since the tool change on "
                        "{where}: the earlier tools of this run called theirs with G43 H",
                        code=self._shown(code),
                        where=where,
                    )
                else:
                    message = tr(
                        "{code} cuts with no tool length offset since the tool change on "
                        "{where} (tool {tool}): the earlier tools of this run called theirs "
                        "with G43 H",
                        code=self._shown(code),
                        where=where,
                        tool=whole(setup.tool),
                    )
                self._block_finding(act, ToolWithoutLengthOffset, message)
                modal.setup = replace(setup, length_told=True)
            return
        surface = modal.speed
        if (
            not modal.constant_surface_speed
            or setup.clamped is not False
            or setup.unclamped_told
            or x is None
            or type(surface) is not float
            or surface <= 0.0
        ):
            return
        limit = self.config.max_spindle_speed
        needed = speed_at(surface, x, modal.inch)
        if needed <= limit and not (math.isinf(needed) and math.isinf(limit)):
            return
        asked = (
            tr("a speed without limit at the centre")
            if math.isinf(needed)
            else f"{fmt(round(needed))} rpm"
        )
        top = (
            tr("the machine's maximum")
            if math.isinf(limit)
            else tr("the machine's maximum, {maximum} rpm", maximum=fmt(limit))
        )
        self._block_finding(
            act,
            SpeedNotClamped,
            tr(
                "{code} to X{x} in G96 S{surface} asks for {asked}, and no G50 S clamps the "
                "spindle in this run: it speeds up to {top}",
                code=self._shown(code),
                x=fmt(x),
                surface=fmt(surface),
                asked=asked,
                top=top,
            ),
        )
        modal.setup = replace(setup, unclamped_told=True)
