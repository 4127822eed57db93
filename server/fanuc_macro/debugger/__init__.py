"""The debugger's core: a run of the evaluator stepped as a control's single block would step it,
with breakpoints, stops, the macro levels and their variables. Plain data and a run thread, no
protocol: ``dap/`` speaks the Debug Adapter Protocol over it.

- :mod:`.session`: the session, its run thread and the front end's commands;
- :mod:`.launch`: a launch request read and checked;
- :mod:`.breakpoints`: where breakpoints stop and which a block hits;
- :mod:`.run_record`: what a run has seen that a stop shows;
- :mod:`.views`: the frames, scopes and variables of a stop;
- :mod:`.expressions`: Macro B typed at a stop, and DPRNT's text;
- :mod:`.answers`: the plain data the front end gets.
"""

from __future__ import annotations

from .answers import EXCEPTION_FILTERS, Breakpoint, DebugError, Ended, Listener, Output, Stop
from .launch import Launch, read_launch
from .session import Session

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
