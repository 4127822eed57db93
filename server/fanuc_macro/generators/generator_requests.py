"""The editor's requests for the arc-thread and drum-groove programs: an untyped JSON object of
parameters, checked and converted into a call of ``build_arc_thread`` or ``build_drum_groove``,
and the answer ``{"text", "summary"}`` or ``{"error"}``.

The keys are the generators' keyword names; a key left out takes the generator's default (the
seed papers' part), except the drum groove's ``pitch``, which the paper does not give.  Given
the program numbers of the file the program goes into (``taken``), a program number left out
is the paper's or the first free one after it, and the answer's ``note`` says which.  The
generators are imported only when a request comes: a start of the server loads neither."""

from __future__ import annotations

import json
import math
import re
from collections.abc import Callable, Collection, Mapping, Sequence
from types import MappingProxyType
from typing import Any, TypedDict, final

from .generated_program import free_programs

__all__ = (
    "ARC_PROGRAMS",
    "ARC_THREAD_PARAMETERS",
    "DRUM_GROOVE_PARAMETERS",
    "DRUM_PROGRAMS",
    "ArcThreadAnswer",
    "ArcThreadSummary",
    "DrumGrooveAnswer",
    "DrumGrooveSummary",
    "GeneratorKeywords",
    "GeneratorRefusal",
    "arc_thread_request",
    "drum_groove_request",
)


# A generator's keyword arguments as read from the client's JSON: each value is what its
# name's reader gives (a number, a text, a list of points), so its type follows the name only.
GeneratorKeywords = dict[str, Any]

# The answers go to the editor as they are: TypedDicts, their keys in the order they are sent;
# final (closed), so that the key an answer lacks tells which answer it is.


@final
class GeneratorRefusal(TypedDict):
    """A parameter the generator cannot take, or a part it cannot cut: its message."""

    error: str


class ArcThreadSummary(TypedDict):
    layer_cuts: list[int]  # G32 cuts of each roughing layer
    layer_angles: list[list[float]]  # each layer's first and last tool-centre angle
    finishing_cuts: int
    finishing_angles: list[float]
    g32_cuts: int


class _ArcThreadText(TypedDict):
    text: str
    summary: ArcThreadSummary


@final
class ArcThreadAnswer(_ArcThreadText, total=False):
    note: str  # the program numbers taken instead of the paper's, which the file has


class DrumGrooveSummary(TypedDict):
    passes: int
    segments_per_pass: int
    g32_cuts: int


class _DrumGrooveText(TypedDict):
    text: str
    summary: DrumGrooveSummary


@final
class DrumGrooveAnswer(_DrumGrooveText, total=False):
    note: str  # the program numbers taken instead of the paper's, which the file has


class _Refused(ValueError):
    """A parameter that cannot be read; its message names it and its value."""


def _shown(value: Any) -> str:
    """A value as the client wrote it: JSON (``"x"``, ``true``, ``null``), cut short."""
    try:
        text = json.dumps(value, ensure_ascii=False)
    except (TypeError, ValueError):
        text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _number(name: str, value: Any) -> float:
    """A finite number, or a text of one (an input box's answer)."""
    if isinstance(value, str):
        try:
            read = float(value.strip())
        except ValueError:
            raise _Refused(f"{name}: {_shown(value)} is not a number") from None
    elif isinstance(value, bool) or not isinstance(value, int | float):
        raise _Refused(f"{name}: {_shown(value)} is not a number")
    else:
        read = float(value)
    if not math.isfinite(read):
        raise _Refused(f"{name}: {_shown(value)} is not a finite number")
    return read


def _whole(name: str, value: Any) -> int:
    read = _number(name, value)
    if read != int(read):
        raise _Refused(f"{name}: {_shown(value)} is not a whole number")
    return int(read)


def _optional_number(name: str, value: Any) -> float | None:
    return None if value is None else _number(name, value)


_LIST_SEPARATOR = re.compile(r"[,;\s]+")


def _diameters(name: str, value: Any) -> tuple[float, ...]:
    """``[108, 103]`` or the text ``"108,103"`` (commas, semicolons or spaces between)."""
    if isinstance(value, str):
        items: list[Any] = [part for part in _LIST_SEPARATOR.split(value.strip()) if part]
    elif isinstance(value, list | tuple):
        items = list(value)
    else:
        raise _Refused(f"{name}: {_shown(value)} is not a list of diameters (write 108,103)")
    return tuple(_number(f"{name}[{i}]", item) for i, item in enumerate(items, 1))


def _point(name: str, value: Any) -> tuple[float, float]:
    given = value
    if isinstance(value, str):
        value = [part for part in re.split(r"[,\s]+", value.strip()) if part]
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise _Refused(f"{name}: {_shown(given)} is not a point X,Z")
    return _number(f"{name} X", value[0]), _number(f"{name} Z", value[1])


def _points(name: str, value: Any) -> tuple[tuple[float, float], ...] | None:
    """``[[x, z], ...]``, the text ``"x,z;x,z"`` (points apart by ``;`` or new lines), or None
    (the paper's profile)."""
    if value is None:
        return None
    if isinstance(value, str):
        items: list[Any] = [part for part in re.split(r"[;\n]+", value.strip()) if part.strip()]
        if not items:
            return None  # an empty text: the paper's profile, as no value
    elif isinstance(value, list | tuple):
        items = list(value)
    else:
        raise _Refused(f"{name}: {_shown(value)} is not a list of points [[X, Z], ...]")
    return tuple(_point(f"{name} point {i}", item) for i, item in enumerate(items, 1))


# Each parameter: its reader.  The names are the keyword names of the generators.
Reader = Callable[[str, Any], Any]

ARC_THREAD_PARAMETERS: Mapping[str, Reader] = MappingProxyType(
    {
        "outer_diameter": _number,
        "groove_radius": _number,
        "tool_radius": _number,
        "pitch": _number,
        "length": _number,
        "layers": _diameters,
        "cuts_per_layer": _whole,
        "finishing_diameter": _number,
        "finishing_cuts": _whole,
        "run_in": _number,
        "finishing_tool_radius": _optional_number,
        "rough_speed": _whole,
        "finishing_speed": _whole,
        "spindle_m": _whole,
        "rough_tool": _whole,
        "finishing_tool": _whole,
        "retract_x": _number,
        "start_x": _number,
        "start_z": _number,
        "main_number": _whole,
        "rough_number": _whole,
        "finishing_number": _whole,
    }
)

DRUM_GROOVE_PARAMETERS: Mapping[str, Reader] = MappingProxyType(
    {
        "points": _points,
        "pitch": _number,
        "layers": _whole,
        "radial_step": _number,
        "axial_step": _number,
        "cuts_per_layer": _whole,
        "direction": _whole,
        "run_in": _number,
        "clearance": _number,
        "spindle_speed": _whole,
        "tool": _whole,
        "main_number": _whole,
        "macro_number": _whole,
    }
)


def _read(
    what: str,
    parameters: Any,
    readers: Mapping[str, Reader],
    required: Mapping[str, str] | None = None,
) -> GeneratorKeywords:
    """The generator's keyword arguments: ``parameters`` is the client's JSON, checked here
    name by name, each value by its reader (so a value's type follows from its name only)."""
    if parameters is None:
        parameters = {}
    if not isinstance(parameters, dict):
        raise _Refused(f"the {what} parameters must be an object of names and values")
    unknown = [key for key in parameters if key not in readers]
    if unknown:
        raise _Refused(
            f"unknown {what} parameter {_shown(unknown[0])}; the parameters are "
            + ", ".join(readers)
        )
    for key, why in (required or {}).items():
        if parameters.get(key) is None:
            raise _Refused(f"{key} is missing: {why}")
    return {key: readers[key](key, value) for key, value in parameters.items()}


ARC_PROGRAMS = (
    ("main_number", "main program"),
    ("rough_number", "roughing macro"),
    ("finishing_number", "finishing macro"),
)
DRUM_PROGRAMS = (("main_number", "main program"), ("macro_number", "macro"))


def _numbers(
    keywords: GeneratorKeywords,
    build: Callable[..., object],
    parts: Sequence[tuple[str, str]],
    taken: Collection[int] | None,
) -> str | None:
    """The program numbers left out, free in the target file (``taken``; None: no file)."""
    if taken is None:
        return None
    numbers = {key: keywords[key] for key, _ in parts if key in keywords}
    try:
        note = free_programs(numbers, build, parts, taken)
    except ValueError as err:
        raise _Refused(str(err)) from None
    keywords.update(numbers)
    return note


def arc_thread_request(
    parameters: Any, taken: Collection[int] | None = None
) -> ArcThreadAnswer | GeneratorRefusal:
    """``{name: value}`` of ``build_arc_thread``'s keywords -> ``{"text", "summary"[, "note"]}``
    or ``{"error"}``; ``taken``: the program numbers of the file it goes into."""
    try:
        keywords = _read("arc thread", parameters, ARC_THREAD_PARAMETERS)
        from .arc_thread_generator import build_arc_thread

        note = _numbers(keywords, build_arc_thread, ARC_PROGRAMS, taken)
        built = build_arc_thread(**keywords)
    except ValueError as err:  # _Refused, or what the generator cannot cut
        return {"error": str(err)}
    answer: ArcThreadAnswer = {
        "text": built.text,
        "summary": {
            "layer_cuts": list(built.layer_cuts),
            "layer_angles": [list(pair) for pair in built.layer_angles],
            "finishing_cuts": built.finishing_cuts,
            "finishing_angles": list(built.finishing_angles),
            "g32_cuts": sum(built.layer_cuts) + built.finishing_cuts,
        },
    }
    if note is not None:
        answer["note"] = note
    return answer


DRUM_REQUIRED: Mapping[str, str] = MappingProxyType(
    {
        "pitch": "give the groove's pitch (lead) in mm; the paper's is not known, "
        "its figure 2 is lost"
    }
)


def drum_groove_request(
    parameters: Any, taken: Collection[int] | None = None
) -> DrumGrooveAnswer | GeneratorRefusal:
    """``{name: value}`` of ``build_drum_groove``'s parameters (``pitch`` required, ``points``
    left out or null: the paper's profile) -> ``{"text", "summary"[, "note"]}`` or
    ``{"error"}``; ``taken``: the program numbers of the file it goes into."""
    try:
        keywords = _read("drum groove", parameters, DRUM_GROOVE_PARAMETERS, DRUM_REQUIRED)
        from .drum_groove_generator import build_drum_groove

        note = _numbers(keywords, build_drum_groove, DRUM_PROGRAMS, taken)
        points = keywords.pop("points", None)
        pitch = keywords.pop("pitch")
        built = build_drum_groove(points, pitch, **keywords)
    except ValueError as err:
        return {"error": str(err)}
    answer: DrumGrooveAnswer = {
        "text": built.text,
        "summary": {
            "passes": built.passes,
            "segments_per_pass": built.segments_per_pass,
            "g32_cuts": built.g32_cuts,
        },
    }
    if note is not None:
        answer["note"] = note
    return answer
