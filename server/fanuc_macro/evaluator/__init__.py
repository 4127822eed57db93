"""The static evaluator: runs Macro B as a FANUC control would and records what it saw."""

from __future__ import annotations

from .facts import DocumentFacts, Facts, Finding, Motion, Rounding, RunValues, ValueSummary
from .run import evaluate
from .values import Unknown, Value, fmt

__all__ = [
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
]
