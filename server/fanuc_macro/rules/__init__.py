"""Rule families, one module each. Importing this package registers every rule."""

from __future__ import annotations

from . import (
    addresses,
    dialect,
    expressions,
    flow,
    jumps,
    loops,
    math_domain,
    reading,
    statements,
    threading,
    variable_use,
)
from .context import Check, RuleContext

ALL_CHECKS: tuple[Check, ...] = (
    reading.check,
    dialect.check,
    jumps.check,
    loops.check,
    expressions.check,
    statements.check,
    math_domain.check,
    addresses.check,
    flow.check,
    variable_use.check,
    threading.check,
)

__all__ = ["ALL_CHECKS", "Check", "RuleContext"]
