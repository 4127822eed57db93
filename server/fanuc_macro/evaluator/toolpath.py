"""The toolpath: where the tool goes, move by move, in work coordinates.

A ``Move`` is one straight or circular stretch of the tool's path: a rapid, a feed, a
threading pass or an arc. Positions are absolute work coordinates in the program's units; on
a lathe X is a diameter, as the program writes it. An axis the evaluator cannot place (no
absolute start, an unknown value) is absent from the move's positions, and the ``Toolpath``
says where it lost track of it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

MoveKind = Literal["rapid", "feed", "thread", "arc"]
MOVE_KINDS: tuple[MoveKind, ...] = ("rapid", "feed", "thread", "arc")

Plane = Literal["XY", "XZ", "YZ"]


@dataclass(frozen=True, slots=True)
class Move:
    """One stretch of the path; ``line`` is the 0-based line of the block that made it."""

    kind: MoveKind
    start: dict[str, float]
    end: dict[str, float]
    line: int
    program: str
    uri: str = ""
    # Arcs: the centre (absolute, same axes as the positions) and the direction, seen along
    # the axis normal to the arc's plane as the control sees it (G02 clockwise).
    centre: dict[str, float] | None = None
    clockwise: bool | None = None
    plane: Plane = "XY"
    # Which motion record of the trace the move belongs to (its index in Facts.motions):
    # a canned cycle is one record of several moves.
    motion: int = -1


@dataclass(frozen=True, slots=True)
class LostTrack:
    """Where the path stops being known for some axes, and why."""

    line: int
    program: str
    axes: tuple[str, ...]
    reason: str
    uri: str = ""


@dataclass(slots=True)
class Toolpath:
    """Every move of a run, in the order the control makes them."""

    moves: list[Move] = field(default_factory=list)
    lost: list[LostTrack] = field(default_factory=list)
    lathe: bool = True
    inch: bool = False  # G20 in force at the first move: the positions are in inches
    truncated: bool = False  # more moves than kept

    def axes(self) -> tuple[str, ...]:
        """The axes any move places, in X, Y, Z order."""
        seen = {a for m in self.moves for a in (*m.start, *m.end)}
        return tuple(a for a in "XYZ" if a in seen)
