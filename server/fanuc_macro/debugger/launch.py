"""A launch of the debugger: the program file, where to start, the arguments and common
variables set before the first block, and the settings the run takes."""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..config import CONTROLLERS, Config
from ..program.variables import ARGUMENT_VARIABLES, classify
from .answers import DebugError

_ARGUMENT_WORD = re.compile(r"\s*(?:#(\d+)|([A-Z]))\s*=?\s*([-+]?(?:\d+\.?\d*|\.\d+))\s*", re.I)


@dataclass(frozen=True)
class Launch:
    """A launch, checked: the file, where to start and what is set before the first block."""

    program: Path
    entry: int | None = None
    preset: Mapping[int, float] = field(default_factory=dict)
    config: Config = field(default_factory=Config)
    stop_on_entry: bool = False
    full_precision: bool = False
    gave_arguments: bool = False


def read_launch(args: Mapping[str, Any], base: Config | None = None) -> Launch:
    """The launch request's arguments, checked; DebugError names the one that is wrong."""
    # ``args`` is the client's JSON as it came: each value is checked here, where it is read.
    program = args.get("program")
    if not isinstance(program, str) or not program.strip():
        raise DebugError("launch: 'program' must be the path of a program file")
    path = Path(program).expanduser()
    if not path.is_file():
        raise DebugError(f"launch: program {program!r} is not a file")
    entry = args.get("entry")
    entry_number: int | None = None
    if entry not in (None, ""):
        text = str(entry).strip().upper().removeprefix("O")
        if not text.isdigit() or not 1 <= int(text) <= 99999999:
            raise DebugError(
                f"launch: 'entry' must be a program number such as 3331, not {entry!r}"
            )
        entry_number = int(text)
    preset: dict[int, float] = {}
    arguments = args.get("arguments")
    gave = bool(arguments)
    preset.update(_arguments(arguments))
    preset.update(_commons(args.get("commons")))
    if base is None:
        base = Config()
    controller = base.controller
    step_budget = base.step_budget
    given = args.get("controller")
    if given not in (None, ""):
        if given not in CONTROLLERS:
            raise DebugError(
                f"launch: 'controller' {given!r} is not one of {', '.join(CONTROLLERS)}"
            )
        controller = given
    budget = args.get("stepBudget")
    if budget is not None:
        if not isinstance(budget, int) or isinstance(budget, bool) or budget < 1:
            raise DebugError(
                f"launch: 'stepBudget' must be a whole number of blocks, not {budget!r}"
            )
        step_budget = budget
    config = base
    if controller != base.controller or step_budget != base.step_budget:
        from dataclasses import replace

        config = replace(base, controller=controller, step_budget=step_budget)
    return Launch(
        path,
        entry_number,
        preset,
        config,
        stop_on_entry=args.get("stopOnEntry") is True,
        full_precision=args.get("fullPrecision") is True or config.hover_full_precision,
        gave_arguments=gave,
    )


def _arguments(value: object) -> dict[int, float]:
    """G65 words ("A1. F0.3", or {"A": 1, "#9": 0.3}) as local variable numbers."""
    words: list[tuple[str, object]] = []
    if value in (None, "", {}):
        return {}
    if isinstance(value, str):
        at = 0
        text = value.strip()
        while at < len(text):
            found = _ARGUMENT_WORD.match(text, at)
            if found is None or found.end() == at:
                raise DebugError(
                    f"launch: 'arguments' {value!r}: cannot read {text[at:]!r} "
                    "(write G65 words such as 'A1. F0.3' or '#9=0.3')"
                )
            number, letter, num = found.groups()
            words.append((f"#{number}" if number else letter, num))
            at = found.end()
    elif isinstance(value, Mapping):
        words = [(str(k), v) for k, v in value.items()]
    else:
        raise DebugError("launch: 'arguments' must be G65 words or an object of letters and values")
    out: dict[int, float] = {}
    for name, raw in words:
        n = _argument_number(name)
        out[n] = _number_of(f"arguments {name}", raw)
    return out


def _argument_number(name: str) -> int:
    key = name.strip().upper()
    if key.startswith("#") and key[1:].isdigit() and 1 <= int(key[1:]) <= 33:
        return int(key[1:])
    if key in ARGUMENT_VARIABLES:
        return ARGUMENT_VARIABLES[key]
    raise DebugError(
        f"launch: argument {name!r} is not a G65 letter (A-Z but G, L, N, O, P) nor #1-#33"
    )


def _commons(value: object) -> dict[int, float]:
    if value in (None, "", {}):
        return {}
    if not isinstance(value, Mapping):
        raise DebugError("launch: 'commons' must be an object such as {\"#100\": 50}")
    out: dict[int, float] = {}
    for name, raw in value.items():
        key = str(name).strip().lstrip("#")
        if not key.isdigit():
            raise DebugError(f"launch: commons {name!r} is not a variable number such as #100")
        n = int(key)
        kind = classify(n)
        if kind.kind in ("none", "null", "local"):
            raise DebugError(
                f"launch: commons #{n} is not a common or system variable (locals go in "
                "'arguments')"
            )
        out[n] = _number_of(f"commons #{n}", raw)
    return out


def _number_of(what: str, raw: object) -> float:
    try:
        number = float(raw)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise DebugError(f"launch: {what} = {raw!r} is not a number") from None
    if not math.isfinite(number):
        raise DebugError(f"launch: {what} = {raw!r} is not a number")
    return number
