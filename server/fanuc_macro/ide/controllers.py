"""The controllers an analysis can be for, as an editor offers them: the setting's value, the
kind of machine and the series name FANUC gives it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from ..config import CONTROLLERS, Config

__all__ = ("DEFAULT_CONTROLLER", "Controller", "controller_choices")

MachineKind = Literal["lathe", "mill", "lathe and mill"]

DEFAULT_CONTROLLER = Config().controller


@dataclass(frozen=True)
class Controller:
    id: str
    kind: MachineKind
    series: str


def _kind(config: Config) -> MachineKind:
    if config.is_lathe:
        return "lathe"
    return "mill" if config.controller.endswith(("M", "MF")) else "lathe and mill"


def _series(controller: str) -> str:
    # The 30i setting stands for the 30i, 31i and 32i, which share the macro language.
    return "FANUC Series 30i/31i/32i" if controller == "30i" else f"FANUC Series {controller}"


def controller_choices() -> tuple[Controller, ...]:
    """Every controller of the ``controller`` setting, in the order of its choices."""
    return tuple(
        Controller(name, _kind(Config(controller=name)), _series(name)) for name in CONTROLLERS
    )
