"""The generators' input boxes in an editor: what the server reads and checks while the user
types, so that the editor keeps only its boxes.

- :func:`read_designation`: a thread designation as the thread module's first box reads it
  (its kind, pitch and diameters), or the refusal the command line gives;
- :func:`check_answers`: the answers of a form's boxes read into the generator's parameters,
  and checked by the generator itself;
- :func:`form_defaults`: the text each box opens with, the generator's defaults (the papers').

Every refusal is the generator's own message, the one ``fanuc-macro thread``, ``arc-thread``
and ``drum-groove`` print.  The generators are imported when a box asks, not before.
"""

from __future__ import annotations

import dataclasses
import inspect
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Literal, TypedDict, final

from ..threads.designation import SideUndecided, ThreadDesignation, parse_designation
from ..threads.geometry import basic_minor_diameter, basic_pitch_diameter
from ..threads.iso965 import tolerances
from .generator_requests import (
    ARC_THREAD_PARAMETERS,
    DRUM_GROOVE_PARAMETERS,
    ArcThreadAnswer,
    DrumGrooveAnswer,
    GeneratorKeywords,
    GeneratorRefusal,
    arc_thread_request,
    drum_groove_request,
)

__all__ = (
    "GENERATORS",
    "BoxAnswer",
    "CheckedAnswers",
    "DesignationReading",
    "FormRefusal",
    "Generator",
    "check_answers",
    "form_defaults",
    "read_designation",
    "read_taper",
)

Generator = Literal["threadModule", "arcThread", "drumGroove"]
GENERATORS: tuple[Generator, ...] = ("threadModule", "arcThread", "drumGroove")

Side = Literal["external", "internal", "undecided"]
Reader = Callable[[str, Any], Any]


@dataclass(frozen=True)
class FormRefusal:
    """What is wrong with an answer: the generator's message."""

    message: str


@dataclass(frozen=True)
class DesignationReading:
    """A thread designation as read.  ``side`` is "undecided" when the text fits both kinds
    (an all-capital class both have, or no class): ``question`` asks which, and ``readings``
    writes each kind the ISO way.  Lengths in mm, the basic diameters to 0.001."""

    text: str
    canonical: str
    side: Side
    nominal_diameter: float
    pitch: float
    lead: float
    starts: int
    left_hand: bool
    tolerance: str | None
    pitch_diameter: float
    minor_diameter: float
    question: str | None = None
    readings: tuple[str, str] | None = None  # (external, internal)


def _basic(designation: ThreadDesignation) -> tuple[float, float]:
    d, p = designation.nominal_diameter, designation.pitch
    return round(basic_pitch_diameter(d, p), 3), round(basic_minor_diameter(d, p), 3)


def _reading(
    text: str, des: ThreadDesignation, side: Side, tolerance: str | None
) -> DesignationReading:
    pitch_diameter, minor_diameter = _basic(des)
    return DesignationReading(
        text=text,
        canonical=des.canonical(),
        side=side,
        nominal_diameter=des.nominal_diameter,
        pitch=des.pitch,
        lead=des.thread_lead,
        starts=des.starts,
        left_hand=des.left_hand,
        tolerance=tolerance,
        pitch_diameter=pitch_diameter,
        minor_diameter=minor_diameter,
    )


def _written_class(des: ThreadDesignation) -> str | None:
    return None if des.class_omitted else des.class_text()


def read_designation(text: str) -> DesignationReading | FormRefusal:
    """``text`` read as the thread module reads it; a class the ISO 965-1 tables lack is
    refused here, as the generator would refuse it."""
    compact = "".join(text.split())
    try:
        des = parse_designation(compact)
    except SideUndecided as undecided:
        external = undecided.external
        reading = _reading(compact, external, "undecided", undecided.written_class)
        return dataclasses.replace(
            reading,
            question=f"{undecided.what()}: which is it?",
            readings=(external.canonical(), undecided.internal.canonical()),
        )
    except ValueError as err:
        return FormRefusal(str(err))
    try:
        tolerances(des)
    except ValueError as err:
        return FormRefusal(str(err))
    side: Side = "internal" if des.internal else "external"
    return _reading(compact, des, side, _written_class(des))


_TAPER_RATIO = re.compile(r"\s*(-?)\s*1\s*:\s*(\d+(?:\.\d*)?)\s*")


def read_taper(text: str) -> float:
    """``1:16`` (a diametral taper as pipe threads give it), ``-1:16`` or ``0.0625``; ValueError
    with the command line's message otherwise."""
    match = _TAPER_RATIO.fullmatch(text)
    try:
        if match is not None:
            value = 1.0 / float(match.group(2))
            return -value if match.group(1) else value
        return float(text)
    except (ValueError, ZeroDivisionError):
        pass
    raise ValueError(
        f"the taper is a ratio or a number (e.g. 1:16, or 0.0625 mm of diameter per mm of "
        f"length), not {text}"
    )


def _designation(name: str, value: Any) -> str:
    if not isinstance(value, str) or not value.strip():
        raise ValueError("the thread designation is missing (for example M50x3-5g6g)")
    return "".join(value.split())


# generator_requests' reader of a number (a number, or the text of one), for the module's.
_number: Reader = ARC_THREAD_PARAMETERS["length"]


def _side(name: str, value: Any) -> bool | None:
    if value is None or isinstance(value, bool):
        return value
    raise ValueError("internal must be true, false or null")


def _infeed(name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise ValueError("infeed must be symmetric, alternate, left or right")
    return value  # the generator refuses a name it does not know


def _taper(name: str, value: Any) -> float:
    if isinstance(value, str):
        return read_taper(value) if value.strip() else 0.0  # an empty box: a parallel thread
    return float(_number(name, value))


THREAD_MODULE_PARAMETERS: Mapping[str, Reader] = MappingProxyType(
    {
        "designation": _designation,
        "length": _number,
        "internal": _side,
        "infeed": _infeed,
        "taper": _taper,
    }
)


@final
class _ModuleText(TypedDict):
    text: str


@final
class _ModuleRefusal(TypedDict):
    error: str
    undecided: bool  # the designation does not say the side: its box asks it


# What running a form's generator gives: its program, or its refusal (final TypedDicts, told
# apart by their keys).
_FormRun = ArcThreadAnswer | DrumGrooveAnswer | _ModuleText | GeneratorRefusal | _ModuleRefusal


def _thread_module_request(parameters: Mapping[str, Any]) -> _ModuleText | _ModuleRefusal:
    """The module for read parameters: ``{"text"}`` or ``{"error"}``, as the command line
    refuses it."""
    from .thread_generator import generate_module

    keywords = dict(parameters)
    designation = keywords.pop("designation", None)
    if designation is None:
        return {
            "error": "the thread designation is missing (for example M50x3-5g6g)",
            "undecided": False,
        }
    length = keywords.pop("length", 40.0)  # a box not answered yet: any length the tables take
    internal = keywords.pop("internal", None)
    try:
        return {"text": generate_module(designation, length, internal, **keywords)}
    except ValueError as err:
        return {"error": str(err), "undecided": isinstance(err, SideUndecided)}


@dataclass(frozen=True)
class _Form:
    readers: Mapping[str, Reader]
    request: Callable[[Mapping[str, Any]], _FormRun]
    required: tuple[str, ...]


def _form(generator: str) -> _Form | None:
    if generator == "threadModule":
        return _Form(THREAD_MODULE_PARAMETERS, _thread_module_request, ("designation",))
    if generator == "arcThread":
        return _Form(ARC_THREAD_PARAMETERS, arc_thread_request, ())
    if generator == "drumGroove":
        return _Form(DRUM_GROOVE_PARAMETERS, drum_groove_request, ("pitch",))
    return None


@dataclass(frozen=True)
class BoxAnswer:
    """One box's answer for the parameters ``names``: one name, ``value`` is its value (the
    text typed, or what was picked); several, the text of as many numbers apart by commas or
    spaces."""

    names: tuple[str, ...]
    value: Any


@dataclass(frozen=True)
class CheckedAnswers:
    """The answers read into the generator's parameters.  ``warning``: a form not finished
    that the generator refuses with its other boxes at their defaults (the user may change
    them yet)."""

    parameters: Mapping[str, Any]
    warning: str | None = None


_WORDS = re.compile(r"[,;\s]+")


def _read_answer(answer: BoxAnswer, readers: Mapping[str, Reader]) -> GeneratorKeywords:
    unknown = [name for name in answer.names if name not in readers]
    if unknown or not answer.names:
        raise ValueError(
            f"unknown parameter {unknown[0] if unknown else '(none)'}; the parameters are "
            + ", ".join(readers)
        )
    if len(answer.names) == 1:
        name = answer.names[0]
        if isinstance(answer.value, str) and not answer.value.strip() and name != "taper":
            return {}  # an empty box: the generator's default, or its refusal of none
        return {name: readers[name](name, answer.value)}
    text = answer.value if isinstance(answer.value, str) else ""
    words = [word for word in _WORDS.split(text.strip()) if word]
    if len(words) != len(answer.names):
        raise ValueError(
            f"give {len(answer.names)} numbers apart by commas: " + ", ".join(answer.names)
        )
    return {name: readers[name](name, word) for name, word in zip(answer.names, words, strict=True)}


def check_answers(
    generator: str, answers: Sequence[BoxAnswer], complete: bool
) -> CheckedAnswers | FormRefusal:
    """The answers read in turn; a ``complete`` form is checked by running its generator, an
    unfinished one too, its refusal then a warning (the later boxes may change what it says)."""
    form = _form(generator)
    if form is None:
        return FormRefusal(f"no generator {generator}; the generators are " + ", ".join(GENERATORS))
    parameters: GeneratorKeywords = {}
    try:
        for answer in answers:
            parameters.update(_read_answer(answer, form.readers))
    except ValueError as err:
        return FormRefusal(str(err))
    answered = {name for answer in answers for name in answer.names}
    missing = [name for name in form.required if name not in parameters]
    if not complete and missing:
        if not answered & set(missing):
            return CheckedAnswers(parameters)  # asked in a later box
        complete = True  # a box left empty that must be answered: the generator's refusal
    ran = form.request(parameters)
    if "error" not in ran:
        return CheckedAnswers(parameters)
    error = ran["error"]
    if complete:
        return FormRefusal(error)
    # A side the designation does not say is asked in a box of its own.
    undecided = "undecided" in ran and ran["undecided"]
    return CheckedAnswers(parameters, None if undecided else error)


def _text(value: Any) -> str:
    if isinstance(value, float | int) and not isinstance(value, bool):
        return f"{value:g}"
    if isinstance(value, tuple | list):
        if value and all(isinstance(item, tuple | list) for item in value):
            return "; ".join(",".join(_text(v) for v in point) for point in value)
        return ", ".join(_text(item) for item in value)
    return str(value)


def form_defaults(
    generator: str, designation: str | None = None
) -> Mapping[str, str] | FormRefusal:
    """Each parameter's default as a box opens with it, a text its Enter accepts: ``"93.82"``,
    ``"108, 103"``, the drum's ``"298.91,205; ..."``; a parameter without one (the drum's
    pitch) is left out.  The thread module's length is one nominal diameter of
    ``designation`` (the paper's M50x3 is 50 long); its taper is empty, a parallel thread."""
    form = _form(generator)
    if form is None:
        return FormRefusal(f"no generator {generator}; the generators are " + ", ".join(GENERATORS))
    if generator == "threadModule":
        module = {"infeed": "symmetric", "taper": ""}
        reading = read_designation(designation) if designation is not None else None
        if isinstance(reading, DesignationReading):
            module["length"] = _text(reading.nominal_diameter)
        return module
    from .drum_groove_generator import DRUM_PROFILE, build_drum_groove

    if generator == "arcThread":
        from .arc_thread_generator import build_arc_thread

        build: Callable[..., object] = build_arc_thread
    else:
        build = build_drum_groove
    defaults: dict[str, str] = {}
    for name, parameter in inspect.signature(build).parameters.items():
        if name not in form.readers:
            continue
        if name == "points":
            defaults[name] = _text(DRUM_PROFILE)
        elif parameter.default is not inspect.Parameter.empty and parameter.default is not None:
            defaults[name] = _text(parameter.default)
    return defaults
