"""The static evaluator: runs Macro B as a FANUC control would and records what it saw.

:mod:`.values` holds macro values (numbers, vacant, unknown). :mod:`.compiler` turns
expressions into closures, and :mod:`.compile_lines` compiles each distinct statement once.
:mod:`.machine` runs blocks, jumps, loops, calls and modal state within a budget of executed
blocks. Its parts run on the shared state of :mod:`.machine_base`: :mod:`.motion` the NC blocks
and moves, :mod:`.calls` calls and returns, :mod:`.canned_cycles` G70-G73 and G76 (passes by
:mod:`.cycles`). :mod:`.run` chooses the entry programs and collects the :mod:`.facts`.
:mod:`.toolpath` is where the tool goes, when a run asks for it. :mod:`.checkpoints` and
:mod:`.line_shift` resume a run after an edit (see ARCHITECTURE.md).
"""

from __future__ import annotations

from .facts import DocumentFacts, Facts, Finding, Motion, Rounding, RunValues, ValueSummary
from .run import evaluate
from .values import Unknown, Value, fmt

__all__ = (
    "DocumentFacts",
    "Facts",
    "Finding",
    "Motion",
    "Rounding",
    "RunValues",
    "Unknown",
    "Value",
    "ValueSummary",
    "evaluate",
    "fmt",
)
