"""The server's commands (workspace/executeCommand): the trace and the toolpath of a program,
thread modules, and the arc-thread and drum-groove programs.

:data:`EDITOR_COMMANDS` answer what an editor would otherwise compute itself: a thread
designation read, a generator's boxes read and checked, their defaults, the trace view's text,
the controllers, the machine a document was read as and the variable under the debugger's
hover.  Their answers are typed here and sent as JSON objects, ``{"error"}`` for a refusal (the
command line's message)."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable, Collection, Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Literal, TypedDict, TypeVar, cast, final

from .engine import Engine, key_of

if TYPE_CHECKING:
    from ..generators import (
        ArcThreadAnswer,
        BoxAnswer,
        DesignationReading,
        DrumGrooveAnswer,
        GeneratorRefusal,
    )
    from ..ide import DocumentMachine, NoToolpathView, ToolpathViewData, Trace, TraceView

log = logging.getLogger(__name__)

# The commands' arguments are the client's JSON (``tuple[Any, ...]``): each command checks
# them where it reads them.  Their answers are TypedDicts, sent as they are.


@final
class CommandRefusal(TypedDict):
    """A command that cannot answer: the message the editor shows."""

    error: str


class _ModuleText(TypedDict):
    text: str


@final
class ThreadModuleText(_ModuleText, total=False):
    # The programs the module takes in the target document when it had the paper's numbers.
    note: str


class _Link(TypedDict):
    start: int
    end: int


class _TraceViewRowRequired(TypedDict):
    line: int
    sourceLine: int


class TraceViewRow(_TraceViewRowRequired, total=False):
    path: str
    link: _Link
    label: str  # always sent, after path and link


class TraceViewAnswer(TypedDict):
    text: str
    rows: list[TraceViewRow]


class _DesignationRequired(TypedDict):
    text: str
    canonical: str
    side: Literal["external", "internal", "undecided"]
    nominalDiameter: float
    pitch: float
    lead: float
    starts: int
    leftHand: bool
    tolerance: str | None
    pitchDiameter: float
    minorDiameter: float


class _Readings(TypedDict):
    external: str
    internal: str


class DesignationAnswer(_DesignationRequired, total=False):
    """An undecided designation adds the question and both readings."""

    question: str
    readings: _Readings


class _CheckedRequired(TypedDict):
    # The generator's parameters as read: numbers, texts, lists of numbers or points.
    parameters: dict[str, object]


class CheckedParameters(_CheckedRequired, total=False):
    warning: str


class ParameterDefaults(TypedDict):
    defaults: dict[str, str]


class ControllerChoice(TypedDict):
    id: str
    kind: str
    series: str


class ControllersAnswer(TypedDict):
    controllers: list[ControllerChoice]
    default: str


class MachineAnswer(TypedDict):
    """The machine a document was read as: the controller resolved (0i-F as 0i-TF or 0i-MF),
    ``kind`` lathe, mill or unknown (neither shown: read as a lathe), and why in a sentence."""

    controller: str
    kind: Literal["lathe", "mill", "unknown"]
    text: str


class VariableSpan(TypedDict, total=False):
    """Empty off a variable."""

    start: int
    end: int


EditorAnswer = (
    DesignationAnswer
    | CheckedParameters
    | ParameterDefaults
    | TraceViewAnswer
    | ControllersAnswer
    | MachineAnswer
    | VariableSpan
    | CommandRefusal
)

TRACE = "fanuc-macro.trace"
TOOLPATH = "fanuc-macro.toolpath"
THREAD_MODULE = "fanuc-macro.threadModule"
ARC_THREAD = "fanuc-macro.arcThread"
DRUM_GROOVE = "fanuc-macro.drumGroove"
READ_DESIGNATION = "fanuc-macro.readDesignation"
CHECK_PARAMETERS = "fanuc-macro.checkParameters"
PARAMETER_DEFAULTS = "fanuc-macro.parameterDefaults"
TRACE_VIEW = "fanuc-macro.traceView"
CONTROLLERS = "fanuc-macro.controllers"
MACHINE = "fanuc-macro.machine"
VARIABLE_AT = "fanuc-macro.variableAt"


def _uri_argument(args: tuple[Any, ...]) -> str | None:
    if not args:
        return None
    first = args[0]
    if isinstance(first, dict):
        first = first.get("uri")
    return first if isinstance(first, str) and first else None


# What an ide function answers for one document: a TypedDict sent as it is.
AnswerT = TypeVar("AnswerT", bound=Mapping[str, object])

# An ide function answering for one document: (key, doc, index, others, config) -> JSON.
Answer = Callable[..., AnswerT]


def _trace() -> Answer[Trace]:
    from ..ide import trace  # the evaluator: loaded by the worker after start-up

    return trace


def _toolpath_view() -> Answer[ToolpathViewData | NoToolpathView]:
    from ..ide import toolpath_view

    return toolpath_view


async def _on_document(
    engine: Engine, command: str, args: tuple[Any, ...], load: Callable[[], Answer[AnswerT]]
) -> AnswerT | CommandRefusal:
    """``[uri]`` -> what the function ``load`` gives answers for that document, with the
    workspace's documents for its calls, computed in the engine's worker."""
    uri = _uri_argument(args)
    if uri is None:
        return {"error": f"{command} takes the document's URI as its argument"}
    key = key_of(uri)
    config = engine.config_for(key)

    def job() -> AnswerT | CommandRefusal:
        if not engine.load(key):
            return {"error": f"{uri} is neither open nor a readable program file"}
        documents = engine.trace_documents(key)
        if documents is None:
            return {"error": f"{uri} is not in the workspace"}
        (_, doc, index), *others = documents
        return load()(key, doc, index, others, config)

    try:
        return await engine.in_worker(job)
    except Exception as err:  # the client shows the message
        log.exception("%s of %s failed", command, uri)
        return {"error": f"{command} failed: {err!r}"}


async def run_trace(engine: Engine, args: tuple[Any, ...]) -> Trace | CommandRefusal:
    """``[uri]`` -> the trace of that document."""
    return await _on_document(engine, TRACE, args, _trace)


async def run_toolpath(
    engine: Engine, args: tuple[Any, ...]
) -> ToolpathViewData | NoToolpathView | CommandRefusal:
    """``[uri]`` -> the Toolpath view's data of that document (ide/toolpath_view.py), its
    words in the editor's language."""
    answer = await _on_document(engine, TOOLPATH, args, _toolpath_view)
    return _toolpath_said(answer, engine.catalogue.locale)


def _toolpath_said(answer: AnswerT, locale: str) -> AnswerT:
    """The Toolpath view's texts (why nothing is drawn, the unit's note, why the run
    stopped, where the stock and the tool come from, why the path is lost) in ``locale``."""
    if locale == "en":
        return answer
    from ..translation import render

    said: dict[str, Any] = dict(answer)
    for key in ("error", "units_note", "stopped"):
        if isinstance(said.get(key), str):
            said[key] = render(said[key], locale)
    for key in ("stock", "tool"):
        part = said.get(key)
        if isinstance(part, dict) and isinstance(part.get("source"), str):
            said[key] = {**part, "source": render(part["source"], locale)}
    if isinstance(said.get("lost"), list):
        said["lost"] = [
            {**lost, "reason": render(lost["reason"], locale)}
            if isinstance(lost, dict) and isinstance(lost.get("reason"), str)
            else lost
            for lost in said["lost"]
        ]
    return cast(AnswerT, said)


class ThreadOptions(TypedDict, total=False):
    """The module's options the command passes on as keywords (its defaults otherwise)."""

    infeed: str
    taper: float
    main_number: int
    sub_number: int


ThreadArguments = tuple[str, float, bool | None, ThreadOptions, str | None]


def _thread_arguments(args: tuple[Any, ...]) -> ThreadArguments | str:
    """(designation, length, internal, the module's options) or what is wrong."""
    if not args or not isinstance(args[0], dict):
        return 'expected one argument {"designation": str, "length": number, "internal": ...}'
    spec = args[0]
    designation = spec.get("designation")
    length = spec.get("length")
    internal = spec.get("internal")
    options: ThreadOptions = {}
    infeed = spec.get("infeed")
    if infeed is not None:
        if not isinstance(infeed, str):
            return "infeed must be symmetric, alternate, left or right"
        options["infeed"] = infeed  # the generator refuses a name it does not know
    taper = spec.get("taper")
    if taper is not None:
        if isinstance(taper, bool) or not isinstance(taper, int | float):
            return "the taper must be a number: the diameter change per mm (0.0625 for 1:16)"
        options["taper"] = float(taper)
    if not isinstance(designation, str) or not designation.strip():
        return "the thread designation is missing (for example M50x3-5g6g)"
    if isinstance(length, bool) or not isinstance(length, int | float) or length <= 0:
        return "the thread length must be a positive number of millimetres"
    if internal is not None and not isinstance(internal, bool):
        return "internal must be true, false or null"
    into = spec.get("uri")
    if into is not None and not isinstance(into, str):
        return "uri must be the URI of the document the module goes into"
    return designation.strip(), float(length), internal, options, into


async def run_thread_module(
    engine: Engine, args: tuple[Any, ...]
) -> ThreadModuleText | CommandRefusal:
    """``[{designation, length, internal, infeed?, taper?, uri?}]`` -> ``{"text"[, "note"]}``
    or ``{"error": ...}``.  ``internal`` (true, false or null) says the kind of thread when the
    designation does not (all capitals with a class both kinds have, or no class): such a
    designation with ``internal`` null, or one whose class contradicts ``internal``, is refused,
    never guessed.  ``uri``: the open document the module goes into; where it has the paper's
    program numbers, the module takes free ones, and ``note`` says which."""
    parsed = _thread_arguments(args)
    if isinstance(parsed, str):
        return {"error": parsed}
    designation, length, internal, options, into = parsed
    target = engine.document(into) if into is not None else None
    from ..generators import NoGenerator, SideConflict, SideUndecided, load_generator

    try:
        generate = load_generator()
    except NoGenerator as err:
        return {"error": str(err)}
    except ModuleNotFoundError as err:
        log.exception("the thread module generator cannot be imported")
        return {"error": f"the thread module generator cannot be loaded: {err}"}
    except Exception as err:
        log.exception("the thread module generator cannot be imported")
        return {"error": f"the thread module generator cannot be loaded: {err}"}
    note: str | None = None
    try:
        if target is not None:
            from ..generators import module_numbers, programs_in

            taken = await asyncio.to_thread(programs_in, target.text)
            numbers = module_numbers(designation, internal, taken)
            options["main_number"], options["sub_number"] = numbers.numbers
            note = numbers.note
        text = await asyncio.to_thread(generate, designation, length, internal, **options)
    except SideUndecided as err:
        return {"error": err.question('with "internal": false (external) or true (internal)')}
    except SideConflict as err:
        return {"error": err.refusal(f'"internal": {"true" if internal else "false"} was sent')}
    except ValueError as err:  # a designation the generator does not accept: its message
        return {"error": str(err)}
    except Exception as err:
        log.exception("thread module %s failed", designation)
        return {"error": f"the thread module generator failed ({err}); the server's log has more"}
    if not isinstance(text, str):
        return {"error": "the thread module generator returned no text"}
    answer: ThreadModuleText = {"text": text}
    if note is not None:
        answer["note"] = note
    return answer


async def _generated(
    engine: Engine,
    command: str,
    args: tuple[Any, ...],
    request: Callable[[Any, Collection[int] | None], AnswerT],
) -> AnswerT | CommandRefusal:
    """The generator's answer to its parameters; ``uri`` among them is the open document the
    program goes into, whose program numbers it does not take."""
    if len(args) > 1:
        return {"error": f"{command} takes one argument, the object of its parameters"}
    parameters = args[0] if args else None
    into = parameters.pop("uri", None) if isinstance(parameters, dict) else None
    if into is not None and not isinstance(into, str):
        return {"error": "uri must be the URI of the document the program goes into"}
    target = engine.document(into) if into is not None else None
    # A generator runs its program on the evaluator: off the event loop, as the thread module.
    try:
        if target is None:
            return await asyncio.to_thread(request, parameters, None)
        from ..generators import programs_in

        taken = await asyncio.to_thread(programs_in, target.text)
        return await asyncio.to_thread(request, parameters, taken)
    except Exception as err:
        log.exception("%s failed", command)
        return {"error": f"{command} failed: {err!r}"}


async def run_arc_thread(
    engine: Engine, args: tuple[Any, ...]
) -> ArcThreadAnswer | GeneratorRefusal | CommandRefusal:
    """``[{parameter: value[, uri]}]`` -> ``{"text", "summary"[, "note"]}`` or ``{"error"}``
    (generators/generator_requests.py)."""
    from ..generators import arc_thread_request

    return await _generated(engine, ARC_THREAD, args, arc_thread_request)


async def run_drum_groove(
    engine: Engine, args: tuple[Any, ...]
) -> DrumGrooveAnswer | GeneratorRefusal | CommandRefusal:
    """``[{parameter: value[, uri]}]`` (``pitch`` required) -> ``{"text", "summary"[,
    "note"]}`` or ``{"error"}``."""
    from ..generators import drum_groove_request

    return await _generated(engine, DRUM_GROOVE, args, drum_groove_request)


# ---- what the editor asks instead of computing it ------------------------------------------


def _designation_json(reading: DesignationReading) -> DesignationAnswer:
    answer: DesignationAnswer = {
        "text": reading.text,
        "canonical": reading.canonical,
        "side": reading.side,
        "nominalDiameter": reading.nominal_diameter,
        "pitch": reading.pitch,
        "lead": reading.lead,
        "starts": reading.starts,
        "leftHand": reading.left_hand,
        "tolerance": reading.tolerance,
        "pitchDiameter": reading.pitch_diameter,
        "minorDiameter": reading.minor_diameter,
    }
    if reading.question is not None and reading.readings is not None:
        answer["question"] = reading.question
        answer["readings"] = {"external": reading.readings[0], "internal": reading.readings[1]}
    return answer


async def run_read_designation(
    engine: Engine, args: tuple[Any, ...]
) -> DesignationAnswer | CommandRefusal:
    """``[text]`` -> the designation read (``side`` external, internal or undecided, with the
    ``question`` and both ``readings`` when undecided) or ``{"error"}``."""
    from ..generators import FormRefusal, read_designation

    if not args or not isinstance(args[0], str):
        return {"error": f"{READ_DESIGNATION} takes the designation's text as its argument"}
    reading = read_designation(args[0])
    if isinstance(reading, FormRefusal):
        return {"error": reading.message}
    return _designation_json(reading)


def _answers(value: Any) -> list[BoxAnswer] | str:
    """``[{"names": [...], "value": ...}, ...]`` or what is wrong with it."""
    from ..generators import BoxAnswer

    if not isinstance(value, list):
        return "answers must be a list of {names, value}"
    answers: list[BoxAnswer] = []
    for item in value:
        names = item.get("names") if isinstance(item, dict) else None
        if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
            return "each answer must be {names: [parameter names], value}"
        answers.append(BoxAnswer(tuple(names), item.get("value")))
    return answers


async def run_check_parameters(
    engine: Engine, args: tuple[Any, ...]
) -> CheckedParameters | CommandRefusal:
    """``[{generator, answers: [{names, value}], complete}]`` -> ``{"parameters"[, "warning"]}``
    (the parameters to send to the generator's command) or ``{"error"}``."""
    from ..generators import FormRefusal, check_answers

    spec = args[0] if len(args) == 1 and isinstance(args[0], dict) else None
    if spec is None:
        return {"error": f"{CHECK_PARAMETERS} takes one object {{generator, answers, complete}}"}
    answers = _answers(spec.get("answers", []))
    if isinstance(answers, str):
        return {"error": answers}
    generator = spec.get("generator")
    complete = spec.get("complete") is True
    checked = await asyncio.to_thread(check_answers, str(generator), answers, complete)
    if isinstance(checked, FormRefusal):
        return {"error": checked.message}
    answer: CheckedParameters = {"parameters": dict(checked.parameters)}
    if checked.warning is not None:
        answer["warning"] = checked.warning
    return answer


async def run_parameter_defaults(
    engine: Engine, args: tuple[Any, ...]
) -> ParameterDefaults | CommandRefusal:
    """``[generator, designation?]`` -> ``{"defaults": {name: text a box opens with}}`` or
    ``{"error"}``; the thread module's length follows its designation."""
    from ..generators import FormRefusal, form_defaults

    designation = args[1] if len(args) > 1 and isinstance(args[1], str) else None
    defaults = form_defaults(str(args[0]) if args else "", designation)
    if isinstance(defaults, FormRefusal):
        return {"error": defaults.message}
    return {"defaults": dict(defaults)}


def _trace_view_json(view: TraceView) -> TraceViewAnswer:
    rows: list[TraceViewRow] = []
    for row in view.rows:
        json_row: TraceViewRow = {"line": row.line, "sourceLine": row.source_line}
        if row.path is not None:
            json_row["path"] = row.path
        if row.link is not None:
            json_row["link"] = {"start": row.link[0], "end": row.link[1]}
        json_row["label"] = row.label
        rows.append(json_row)
    return {"text": view.text, "rows": rows}


async def run_trace_view(engine: Engine, args: tuple[Any, ...]) -> TraceViewAnswer | CommandRefusal:
    """``[uri, source]`` -> ``{"text", "rows": [{line, sourceLine, path?, link?, label}]}``:
    the trace view of that document, headed with ``source`` (its path as the editor shows
    it; the URI when left out), or ``{"error"}``."""
    source = args[1] if len(args) > 1 and isinstance(args[1], str) else _uri_argument(args)
    locale = engine.catalogue.locale

    def load() -> Answer[TraceViewAnswer]:
        from ..ide import trace, view_of_trace

        def answer(*document: Any) -> TraceViewAnswer:
            return _trace_view_json(view_of_trace(trace(*document), source or "", locale))

        return answer

    return await _on_document(engine, TRACE_VIEW, args[:1], load)


async def run_controllers(engine: Engine, args: tuple[Any, ...]) -> ControllersAnswer:
    """``[]`` -> ``{"controllers": [{id, kind, series}], "default"}``."""
    from ..ide import DEFAULT_CONTROLLER, controller_choices

    return {
        "controllers": [
            {"id": c.id, "kind": c.kind, "series": c.series} for c in controller_choices()
        ],
        "default": DEFAULT_CONTROLLER,
    }


def _machine_json(machine: DocumentMachine) -> MachineAnswer:
    return {"controller": machine.controller, "kind": machine.kind, "text": machine.text}


# Seconds the machine of a document waits for the analysis of its current version.
MACHINE_TIMEOUT = 60.0


async def run_machine(engine: Engine, args: tuple[Any, ...]) -> MachineAnswer | CommandRefusal:
    """``[uri]`` -> ``{"controller", "kind", "text"}``: the machine the newest analysis of that
    open document read it as, or ``{"error"}``."""
    from ..ide import View, document_machine

    uri = _uri_argument(args)
    if uri is None:
        return {"error": f"{MACHINE} takes the document's URI as its argument"}
    result = await engine.fresh(uri, MACHINE_TIMEOUT)
    if result is None:
        return {"error": f"{uri} is not open"}
    if result.analysis is None:
        return {"error": f"{uri} has no analysis: {result.error or 'it failed'}"}
    return _machine_json(
        document_machine(View(result.key, result.analysis, engine.config_for(result.key)))
    )


async def run_variable_at(engine: Engine, args: tuple[Any, ...]) -> VariableSpan | CommandRefusal:
    """``[line's text, column]`` -> ``{"start", "end"}`` of the Macro B variable under the
    column (the debugger's hover), ``{}`` off a variable."""
    from ..ide import variable_at

    if len(args) != 2 or not isinstance(args[0], str) or not isinstance(args[1], int):
        return {"error": f"{VARIABLE_AT} takes a line's text and a column"}
    found = variable_at(args[0], args[1])
    return {} if found is None else {"start": found[0], "end": found[1]}


EditorCommand = Callable[[Engine, tuple[Any, ...]], Awaitable[EditorAnswer]]

EDITOR_COMMANDS: Mapping[str, EditorCommand] = MappingProxyType(
    {
        READ_DESIGNATION: run_read_designation,
        CHECK_PARAMETERS: run_check_parameters,
        PARAMETER_DEFAULTS: run_parameter_defaults,
        TRACE_VIEW: run_trace_view,
        CONTROLLERS: run_controllers,
        MACHINE: run_machine,
        VARIABLE_AT: run_variable_at,
    }
)
