"""The debugger's core: a run of the evaluator stepped as a control's single block would step it,
with breakpoints, stops, the macro levels and their variables. Plain data and a run thread, no
protocol: ``dap/`` speaks the Debug Adapter Protocol over it."""

from __future__ import annotations

from .session import (
    EXCEPTION_FILTERS,
    Breakpoint,
    DebugError,
    Ended,
    Launch,
    Listener,
    Output,
    Session,
    Stop,
    read_launch,
)

__all__ = (
    "EXCEPTION_FILTERS",
    "Breakpoint",
    "DebugError",
    "Ended",
    "Launch",
    "Listener",
    "Output",
    "Session",
    "Stop",
    "read_launch",
)
