"""The rules: one module per rule family, each rule registered with its documentation beside
it. :mod:`.context` is what a rule reads: the document, its index, the settings, the facts.

Importing this package registers every rule. ``LINE_CHECKS`` run on one line's text, once per
distinct line; ``ALL_CHECKS`` run on a document (see ARCHITECTURE.md).
"""

from __future__ import annotations

from ..syntax.tree import ParsedLine
from . import (
    addresses,
    angles,
    cycles,
    dialect,
    expressions,
    flow,
    jumps,
    loops,
    math_domain,
    reading,
    statements,
    thread_lead,
    thread_passes,
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
    flow.check,
    variable_use.check,
    angles.check,
    threading.check,
    thread_passes.check,
    thread_tool.check,
    thread_lead.check,
    cycles.check,
)

__all__ = [
    "ALL_CHECKS",
    "LINE_CHECKS",
    "Check",
    "LineCheck",
    "LineFinding",
    "RuleContext",
    "plain_line_quiet",
]
