"""Stopping an analysis that a newer text has made useless, and telling how far it got.

An analysis checks its :class:`CancelToken` at block boundaries: between slices of lines while
it reads them, every few hundred blocks the evaluator runs, between rules. Another thread sets
the token; the analysis then raises :class:`Cancelled` at the next check, before it stores
anything: what it leaves in the caches (parsed lines, compiled lines, line findings) is keyed by
a line's text and complete, so the next analysis reuses it. The command line never cancels.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class Stage:
    """A part of an analysis, for the progress shown to the user."""

    name: str
    start: float  # the share of the analysis done when it begins, 0 to 1
    end: float
    counts_blocks: bool = True  # its ``done`` and ``total`` count blocks (not rules)


READING = Stage("reading blocks", 0.0, 0.25)
COMPILING = Stage("compiling blocks", 0.25, 0.4)
RUNNING = Stage("running the program", 0.4, 0.65)
CHECKING = Stage("checking blocks", 0.65, 0.85)
RULE_CHECKS = Stage("rules", 0.85, 1.0, counts_blocks=False)

# Lines read, compiled or checked between two looks at the token: about 1-20 ms of work.
SLICE = 1024

Observer = Callable[[Stage, int, int], None]


class Cancelled(BaseException):
    """The analysis was stopped by its token. A BaseException, as asyncio's CancelledError:
    the ``except Exception`` that keep one failing rule from hiding the others must let it by."""

    def __init__(self, stage: Stage | None, done: int, total: int) -> None:
        super().__init__(stage.name if stage is not None else "before it began")
        self.stage = stage
        self.done = done
        self.total = total

    def where(self) -> str:
        """How far the analysis got: ``while running the program, after 2,048 blocks``."""
        stage = self.stage
        if stage is None:
            return "before it began"
        if not stage.counts_blocks:
            return f"in the {stage.name}, after {self.done} of {self.total}"
        if stage is RUNNING:
            return f"while {stage.name}, after {self.done:,} blocks"
        return f"while {stage.name}, after {self.done:,} of {self.total:,} blocks"


class CancelToken:
    """Set from any thread with :meth:`cancel`; read by the analysis at its checkpoints.

    ``observer`` is told each checkpoint reached (the stage, what of it is done, its total), in
    the analysis's thread: it must be quick (the language server throttles its reports)."""

    __slots__ = ("cancelled", "done", "observer", "stage", "total")

    def __init__(self, observer: Observer | None = None) -> None:
        self.cancelled = False  # a plain flag: one attribute read per check
        self.observer = observer
        self.stage: Stage | None = None
        self.done = 0
        self.total = 0

    def cancel(self) -> None:
        self.cancelled = True

    def check(self) -> None:
        """Raise :class:`Cancelled` if the token was set."""
        if self.cancelled:
            raise Cancelled(self.stage, self.done, self.total)

    def reached(self, stage: Stage, done: int, total: int) -> None:
        """A checkpoint: ``done`` of ``total`` of ``stage`` are done. Raises :class:`Cancelled`
        if the token was set."""
        self.stage, self.done, self.total = stage, done, total
        if self.cancelled:
            raise Cancelled(stage, done, total)
        if self.observer is not None:
            self.observer(stage, done, total)


def raise_if_cancelled(token: CancelToken | None) -> None:
    """:meth:`CancelToken.check` for an optional token."""
    if token is not None and token.cancelled:
        raise Cancelled(token.stage, token.done, token.total)


__all__ = (
    "CHECKING",
    "COMPILING",
    "READING",
    "RULE_CHECKS",
    "RUNNING",
    "SLICE",
    "CancelToken",
    "Cancelled",
    "Stage",
    "raise_if_cancelled",
)
