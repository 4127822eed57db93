"""The controllers an analysis can be for, as an editor offers them: the setting's value, the
kind of machine and the series name FANUC gives it; and the machine one document was read as
(:func:`document_machine`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

from ..config import BY_PROGRAM, CONTROLLERS, Config

if TYPE_CHECKING:
    from .view import View

__all__ = (
    "DEFAULT_CONTROLLER",
    "Controller",
    "DocumentMachine",
    "controller_choices",
    "document_machine",
)

# "lathe or mill": each document is read as the machine its codes show (program.machine_kind).
MachineKind = Literal["lathe", "mill", "lathe and mill", "lathe or mill"]

DEFAULT_CONTROLLER = Config().controller


@dataclass(frozen=True)
class Controller:
    id: str
    kind: MachineKind
    series: str


def _kind(config: Config) -> MachineKind:
    if config.machine_by_program:
        return "lathe or mill"
    if config.is_lathe:
        return "lathe"
    return "mill" if config.controller.endswith(("M", "MF")) else "lathe and mill"


def _series(controller: str) -> str:
    # The 30i setting stands for the 30i, 31i and 32i, which share the macro language.
    if controller == BY_PROGRAM:
        return "FANUC Series 0i-F (0i-TF or 0i-MF, as each program's codes show)"
    return "FANUC Series 30i/31i/32i" if controller == "30i" else f"FANUC Series {controller}"


def controller_choices() -> tuple[Controller, ...]:
    """Every controller of the ``controller`` setting, in the order of its choices."""
    return tuple(
        Controller(name, _kind(Config(controller=name)), _series(name)) for name in CONTROLLERS
    )


# "unknown": the codes show neither machine (or both); read as a lathe, with only the verdicts
# a mill's reading gives too.
DocumentMachineKind = Literal["lathe", "mill", "unknown"]


@dataclass(frozen=True)
class DocumentMachine:
    """The machine one analysis read its document as: the controller it was read for (0i-F
    resolved to 0i-TF or 0i-MF), the kind, and the sentence that says which and why."""

    controller: str
    kind: DocumentMachineKind
    text: str


def document_machine(view: View) -> DocumentMachine:
    """The machine ``view``'s analysis read the document as (its resolved settings)."""
    from ..program.machine_kind import machine_text  # the parser: not at start-up

    config = view.config
    if config.machine_by_program:  # not resolved for the document: no analysis said
        return DocumentMachine(config.controller, "unknown", "Machine: not read yet.")
    if not config.machine_known:
        kind: DocumentMachineKind = "unknown"
    else:
        kind = "lathe" if config.is_lathe else "mill"
    return DocumentMachine(config.controller, kind, machine_text(config))


def machine_text(config: Config) -> str:
    """Which machine an analysis read its document as, and why (``config``: the analysis's)."""
    from ..program import machine_kind  # the parser: not at start-up

    return machine_kind.machine_text(config)
