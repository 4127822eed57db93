"""MB8xx: threading: passes past the root, depths, tool nose radius, threading feed.

The thread being cut is known from a known module's inputs (the symmetric module's nominal
diameter #100 and its thread height #4; variables named by their comments, see
:mod:`fanuc_macro.meanings`), or from a designation such as ``(M50X3-5G6G)`` in a comment whose
pitch matches the cut's F. Cuts are the executed G32/G92/G76 motions, grouped by program and F.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from dataclasses import dataclass

from ..diagnostics import Diagnostic, Related, RuleInfo, Severity, make, register
from ..evaluator.facts import DocumentFacts, Motion
from ..evaluator.values import fmt
from ..meanings import Meaning, program_is_internal, variable_roles
from ..per_line import PerLine
from ..syntax import ParsedLine
from ..threads.designation import parse_designation
from .context import RuleContext

FAMILY = "threading"
register(
    RuleInfo("MB801", "thread-past-root", Severity.ERROR,
             "A threading pass reaches past the root of the thread being cut.", FAMILY),
    RuleInfo("MB802", "thread-first-depth", Severity.ERROR,
             "The first threading pass is deeper than the whole thread height.", FAMILY),
    RuleInfo("MB803", "thread-depth-not-growing", Severity.WARNING,
             "A threading pass is shallower than the one before it.", FAMILY),
    RuleInfo("MB804", "thread-pass-too-deep", Severity.WARNING,
             "A threading pass takes more depth than the configured maximum per pass.", FAMILY),
    RuleInfo("MB805", "nose-radius-range", Severity.WARNING,
             "A thread tool nose radius outside 0.125P-0.144P (external) or 0-0.072P "
             "(internal).", FAMILY),
    RuleInfo("MB806", "fitting-tool-radius", Severity.ERROR,
             "In the fitting method, the tool radius is not smaller than the groove radius.",
             FAMILY),
    RuleInfo("MB807", "threading-feed", Severity.ERROR,
             "Spindle speed times pitch is above the machine's threading feed limit.", FAMILY),
)  # fmt: skip

THREAD_CODES = frozenset({"G32", "G33", "G34", "G76", "G92"})
_DESIGNATION = re.compile(
    r"\bM\d+(?:\.\d+)?\s*[X×*]\s*\d+(?:\.\d+)?(?:\s*-\s*\d[A-Za-z]\d?[A-Za-z]?)?", re.I
)
EPS = 0.0005  # half the least input increment


@dataclass
class Thread:
    major: float  # nominal diameter d / D
    pitch: float | None
    height: float | None  # radial thread height as the program means it
    internal: bool
    source: str
    line: int  # where it is known from


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    facts = ctx.doc_facts()
    if facts is None or ctx.facts is None:
        return
    roles = variable_roles(ctx.doc, ctx.index)
    yield from _tool_radius_checks(ctx, facts, roles)
    cuts: dict[tuple[int, float | None], list[Motion]] = {}
    for m in ctx.facts.motions:
        if m.uri == ctx.doc.uri and m.code in THREAD_CODES and m.x is not None:
            cuts.setdefault((m.program_line, m.words.get("F")), []).append(m)
    designations = _designations(ctx)
    for (program_line, feed), group in cuts.items():
        yield from _feed_checks(ctx, group)
        thread = _thread_of(ctx, facts, roles, program_line, feed, group, designations)
        yield from _depth_checks(ctx, group, thread)


def _value(facts: DocumentFacts, meaning: Meaning | None) -> float | None:
    if meaning is None or meaning.line < 0:
        return None
    write = facts.writes.get(meaning.line)
    if write is None or not write[1].constant:
        return None
    return float(write[1].minimum)


def _find_role(
    roles: dict[tuple[int, int], Meaning], program_line: int, role: str
) -> Meaning | None:
    for (first, _var), meaning in roles.items():
        if first == program_line and meaning.role == role and meaning.line >= 0:
            return meaning
    return None


def _designations(ctx: RuleContext) -> list[tuple[int, str]]:
    return [(b.line, text) for b in ctx.doc.blocks for text in _designations_of(b.parsed)]


def _line_designations(parsed: ParsedLine) -> tuple[str, ...]:
    return tuple(
        m.group(0) for comment in parsed.comments for m in _DESIGNATION.finditer(comment.text)
    )


# Thread designations such as (M50X3-5G6G) in a line's comments, per distinct line.
_designations_of: PerLine[tuple[str, ...]] = PerLine(_line_designations)


def _thread_of(
    ctx: RuleContext,
    facts: DocumentFacts,
    roles: dict[tuple[int, int], Meaning],
    program_line: int,
    feed: float | None,
    group: list[Motion],
    designations: list[tuple[int, str]],
) -> Thread | None:
    xs = [m.x for m in group if m.x is not None]
    program = ctx.index.program_at(program_line)
    end = program.end_line if program else program_line + 1
    said = program_is_internal(ctx.doc, program_line, end)
    moving_out = len(xs) > 1 and xs[-1] > xs[0]
    internal = said if said is not None else moving_out
    height_m = _find_role(roles, program_line, "thread_height")
    height = _value(facts, height_m)
    # The main program's inputs: the nominal diameter, read where the cut reads it.
    major: float | None = None
    for meaning in roles.values():
        if meaning.role == "nominal_diameter" and meaning.line >= 0:
            major = _value(facts, meaning)
            if major is not None:
                break
    if major is not None and height is not None:
        return Thread(
            major,
            feed,
            height,
            internal,
            "the module's inputs",
            height_m.line if height_m else program_line,
        )
    for line, text in designations:
        try:
            d = parse_designation(text.replace(" ", ""), internal=internal)
        except ValueError:
            continue
        if feed is not None and abs(d.pitch - feed) > 1e-6:
            continue
        h_root = 7.0 / 8.0 * math.sqrt(3) / 2 * d.pitch  # to the sharp root of the profile
        return Thread(
            d.nominal_diameter,
            d.pitch,
            h_root if height is None else height,
            d.internal,
            f"the designation {text}",
            line,
        )
    return None


def _depth_checks(
    ctx: RuleContext, group: list[Motion], thread: Thread | None
) -> Iterator[Diagnostic]:
    sign = 1.0
    if thread is not None:
        sign = -1.0 if thread.internal else 1.0
    elif len(group) > 1 and group[-1].x is not None and group[0].x is not None:
        sign = -1.0 if group[-1].x > group[0].x else 1.0
    reported: set[str] = set()
    previous: float | None = None
    limit = ctx.config.max_depth_per_pass
    for i, m in enumerate(group):
        x = m.x
        assert x is not None
        if thread is not None and thread.height is not None:
            root = thread.major - sign * 2.0 * thread.height
            depth = sign * (thread.major - x) / 2.0
            related = [Related(thread.line, 0, 0, f"thread known from {thread.source}")]
            if sign * (root - x) > EPS and "root" not in reported:
                reported.add("root")
                yield make(
                    "MB801",
                    f"{m.code} pass at X{fmt(x)} is {fmt(round(depth - thread.height, 4))} "
                    f"mm (radius) past the root X{fmt(round(root, 4))} of the thread "
                    f"(d {fmt(thread.major)}, height {fmt(round(thread.height, 4))}, from "
                    f"{thread.source})",
                    m.line,
                    0,
                    _width(ctx, m.line),
                    related=related,
                )
            if i == 0 and depth > thread.height + EPS:
                yield make(
                    "MB802",
                    f"first {m.code} pass is {fmt(round(depth, 4))} mm deep "
                    f"(radius), more than the thread height {fmt(round(thread.height, 4))}",
                    m.line,
                    0,
                    _width(ctx, m.line),
                    related=related,
                )
        if previous is not None and m.code != "G32":
            # Not for G32: fitting-method programs move single cuts around a profile, so their
            # depth goes down and up by design. Cycles (G92, G76) cut at X.
            step = sign * (previous - x) / 2.0
            if step < -EPS and "back" not in reported:
                reported.add("back")
                yield make(
                    "MB803",
                    f"{m.code} pass at X{fmt(x)} is {fmt(round(-step, 4))} mm "
                    f"shallower than the pass before (X{fmt(previous)}): the depth should "
                    "grow pass after pass",
                    m.line,
                    0,
                    _width(ctx, m.line),
                )
            elif step > limit + EPS and "deep" not in reported:
                reported.add("deep")
                yield make(
                    "MB804",
                    f"{m.code} pass takes {fmt(round(step, 4))} mm (radius) in one "
                    f"pass, above the maximum {fmt(limit)} mm per pass",
                    m.line,
                    0,
                    _width(ctx, m.line),
                )
        previous = x


def _feed_checks(ctx: RuleContext, group: list[Motion]) -> Iterator[Diagnostic]:
    limit = ctx.config.max_threading_feed
    for m in group:
        pitch = m.words.get("F")
        if m.rpm is None or pitch is None:
            continue
        feed = m.rpm * pitch
        if feed > limit:
            yield make(
                "MB807",
                f"S{fmt(m.rpm)} x pitch {fmt(pitch)} = {fmt(feed)} mm/min, above "
                f"the machine's threading feed limit {fmt(limit)} mm/min",
                m.line,
                0,
                _width(ctx, m.line),
            )
            return


def _tool_radius_checks(
    ctx: RuleContext, facts: DocumentFacts, roles: dict[tuple[int, int], Meaning]
) -> Iterator[Diagnostic]:
    for program in ctx.index.programs:
        first = program.first_line
        nose_m = _find_role(roles, first, "nose_radius")
        nose = _value(facts, nose_m)
        if nose is None or nose_m is None:
            continue
        groove_m = _find_role(roles, first, "groove_radius")
        groove = _value(facts, groove_m)
        span = _assignment_span(ctx, nose_m.line)
        if groove is not None:
            if nose >= groove:
                yield make(
                    "MB806",
                    f"tool radius {fmt(nose)} is not smaller than the groove "
                    f"radius {fmt(groove)}: the fitting method needs r < R",
                    nose_m.line,
                    span[0],
                    span[1],
                )
            continue
        pitch_m = _find_role(roles, first, "pitch")
        pitch = _value(facts, pitch_m) if pitch_m else None
        if pitch is None:
            pitch = _pitch_of_cuts(ctx, first)
        if pitch is None or _find_role(roles, first, "thread_height") is None:
            continue
        internal = program_is_internal(ctx.doc, first, program.end_line) or False
        sin60 = math.sin(math.radians(60))
        # The stated bounds 0.144P and 0.072P are P/(8 sin60) and P/(16 sin60) rounded.
        low, high = (
            (0.0, pitch / (16 * sin60)) if internal else (0.125 * pitch, pitch / (8 * sin60))
        )
        if not (low < nose <= high + 1e-9 if internal else low <= nose <= high + 1e-9):
            kind = "internal" if internal else "external"
            yield make(
                "MB805",
                f"nose radius {fmt(nose)} is outside {fmt(round(low, 4))}-"
                f"{fmt(round(high, 4))} allowed for an {kind} thread of pitch {fmt(pitch)}",
                nose_m.line,
                span[0],
                span[1],
            )


def _pitch_of_cuts(ctx: RuleContext, program_line: int) -> float | None:
    if ctx.facts is None:
        return None
    for m in ctx.facts.motions:
        if m.uri == ctx.doc.uri and m.program_line == program_line and m.code in THREAD_CODES:
            return m.words.get("F")
    return None


def _assignment_span(ctx: RuleContext, line: int) -> tuple[int, int]:
    text = ctx.doc.blocks[line].text
    return 0, len(text.rstrip())


def _width(ctx: RuleContext, line: int) -> int:
    return len(ctx.doc.blocks[line].text.rstrip())
