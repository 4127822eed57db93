"""The rules: one module per rule family. :mod:`.context` is what a rule reads: the document,
its index, the settings, the facts.

Each family declares its rules as ``RuleInfo`` constants named by code (``MB101``), and each
rule's documentation as a ``RuleDoc`` (``MB101_DOC``) beside the function that finds it;
:func:`declared` collects them once into a read-only table. ``LINE_CHECKS`` run on one line's
text, once per distinct line; ``ALL_CHECKS`` run on a document (see ARCHITECTURE.md).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from types import MappingProxyType, ModuleType
from typing import TypeVar

from ..diagnostics import RuleDoc, RuleInfo
from ..syntax.tree import ParsedLine
from . import (
    addresses,
    angles,
    arcs,
    compensation,
    cycles,
    dialect,
    drilling,
    expressions,
    flow,
    jumps,
    loops,
    machine_state,
    math_domain,
    profiles,
    reading,
    statements,
    suppression,
    thread_arc,
    thread_cut,
    thread_lead,
    thread_passes,
    thread_taper,
    thread_tool,
    threading,
    variable_use,
)
from .context import Check, LineCheck, LineFinding, RuleContext

# Rules on one line's text: run once per distinct line, cached while the line is unchanged.
LINE_CHECKS: tuple[LineCheck, ...] = (
    reading.check_line,
    dialect.check_line,
    expressions.check_line,
    statements.check_line,
)


def plain_line_quiet(parsed: ParsedLine) -> bool:
    """Whether no line rule finds anything in a line whose statement is a ``PlainNc`` (words of
    numbers), from its flags and its G and M codes: nothing the reader notes (lower case, a
    tape mark, a note), no other control's code; the expressions and statements rules find
    nothing in numbers. ``tests/test_plain_blocks.py`` checks it against ``LINE_CHECKS``."""
    return reading.nothing_to_read(parsed) and dialect.no_foreign_code(parsed)


ALL_CHECKS: tuple[Check, ...] = (
    reading.check,
    jumps.check,
    loops.check,
    expressions.check,
    statements.check,
    statements.check_programs,
    math_domain.check,
    addresses.check,
    machine_state.check,
    arcs.check,
    compensation.check,
    drilling.check,
    profiles.check,
    flow.check,
    variable_use.check,
    angles.check,
    threading.check,
    thread_passes.check,
    thread_tool.check,
    thread_lead.check,
    thread_cut.check,
    thread_taper.check,
    thread_arc.check,
    cycles.check,
)

# The modules that declare rules, one per family.
FAMILIES: tuple[ModuleType, ...] = (
    reading,
    dialect,
    jumps,
    loops,
    expressions,
    statements,
    math_domain,
    addresses,
    machine_state,
    arcs,
    compensation,
    drilling,
    profiles,
    flow,
    variable_use,
    angles,
    threading,
    thread_passes,
    thread_tool,
    thread_lead,
    thread_cut,
    thread_taper,
    thread_arc,
    cycles,
    suppression,
)

D = TypeVar("D", RuleInfo, RuleDoc)


def declared(kind: type[D], modules: Iterable[ModuleType], *more: D) -> Mapping[str, D]:
    """Every ``kind`` (``RuleInfo`` or ``RuleDoc``) the modules declare at their top level, and
    ``more``, by code, in code order: read-only. Two declarations of one code are an error."""
    found: dict[str, D] = {}
    for value in [v for module in modules for v in vars(module).values()] + list(more):
        if isinstance(value, kind):
            known = found.setdefault(value.code, value)
            if known is not value:
                raise ValueError(f"rule code {value.code} declared twice")
    return MappingProxyType(dict(sorted(found.items())))


__all__ = (
    "ALL_CHECKS",
    "FAMILIES",
    "LINE_CHECKS",
    "Check",
    "LineCheck",
    "LineFinding",
    "RuleContext",
    "declared",
    "plain_line_quiet",
)
