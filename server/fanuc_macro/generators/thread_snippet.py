"""The symmetric thread module for a document that enters the thread in ``#100``-``#104``.

A main program in the shape of the paper's O4009 / O4010 assigns ``#100`` D, ``#101`` P,
``#102`` L, ``#103`` es/EI (a magnitude) and ``#104`` Td2/TD2, then calls the sub-program.
:func:`module_from_document` reads those values by running the document with the evaluator
(so ``#102=2*#101`` works too), fills what is missing from a designation written in a
comment (``(M50x3-5g6g)``), and returns the module generated for them: the language server
offers it as a completion item.  Pure: text in, text out, no LSP types.

The side comes from the designation's class (its case, or a class only one kind has), else
the program's words (INTERNAL, NUT ...), the paper's sub-program numbers, or the ISO 965-1
class that has the entered es/EI and Td2/TD2.  When none of these tells, the side is not
guessed: :func:`thread_inputs` gives both readings, and the completion offers both modules.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..evaluator import DocumentFacts, evaluate
from ..program.index import ProgramIndex, build_index
from ..syntax.parser import default_parser, parse_text
from ..syntax.tree import Assign, Document, IfThen
from ..threads.designation import SideUndecided, ThreadDesignation, parse_designation
from ..threads.identify import thread_words
from ..threads.iso965 import pitch_classes, tolerances
from .thread_generator import ThreadModule, build_module_from_values, default_program_numbers

__all__ = ("ThreadInputs", "module_from_analysis", "module_from_document", "thread_inputs")

_URI = "snippet:thread-module.nc"
_VARIABLES = range(100, 105)

_INTERNAL_WORDS = ("INTERNAL", "内螺纹", "內螺紋", "NUT")
_EXTERNAL_WORDS = ("EXTERNAL", "外螺纹", "外螺紋", "BOLT")


def _assigned_lines(doc: Document) -> dict[int, list[int]]:
    """Lines that assign #100-#104, by variable."""
    found: dict[int, list[int]] = {}
    for block in doc.blocks:
        statement = block.statement
        target = statement.then if isinstance(statement, IfThen) else statement
        if isinstance(target, Assign) and target.target.number is not None:
            number = int(target.target.number)
            if number in _VARIABLES and number == target.target.number:
                found.setdefault(number, []).append(block.line)
    return found


def _comments(doc: Document) -> list[str]:
    return [c.text for block in doc.blocks for c in block.parsed.comments]


def _designation_texts(doc: Document) -> list[str]:
    return [
        form
        for block in doc.blocks
        if block.parsed.comments
        for _written, form in thread_words(block.parsed).designations
    ]


def _side_from_words(comments: list[str]) -> bool | None:
    text = " ".join(comments).upper()
    internal = any(w in text for w in _INTERNAL_WORDS)
    external = any(w in text for w in _EXTERNAL_WORDS)
    if internal != external:
        return internal
    return None


def _side_from_programs(index: ProgramIndex) -> bool | None:
    """The paper's numbering: O3330 is the internal sub-program, O3331 the external one."""
    numbers = {p.number for p in index.programs if p.number is not None}
    numbers |= {c.program for p in index.programs for c in p.calls if c.program is not None}
    internal_sub = default_program_numbers(True)[1] in numbers
    external_sub = default_program_numbers(False)[1] in numbers
    if internal_sub != external_sub:
        return internal_sub
    return None


def _side_from_tables(
    diameter: float, pitch: float, deviation: float, pitch_tolerance: float
) -> bool | None:
    """Which side's ISO 965-1 cells give these |es|/EI and Td2/TD2, if only one does."""
    matches: set[bool] = set()
    for internal in (False, True):
        # The pitch-diameter classes alone: a class such as 5g (crest grade 5, which Td does not
        # have) still names its es and Td2.
        for c in pitch_classes(diameter, pitch, internal=internal):
            if (
                abs(abs(c.deviation) - deviation) < 5e-4
                and abs(c.tolerance - pitch_tolerance) < 5e-4
            ):
                matches.add(internal)
    return matches.pop() if len(matches) == 1 else None


def _readings(text: str) -> tuple[ThreadDesignation, ...]:
    """The designation as its text reads; both readings (external, internal) when the text
    does not say its side; none when it cannot be read."""
    try:
        return (parse_designation(text),)
    except SideUndecided as err:
        return (err.external, err.internal)
    except ValueError:
        return ()


def _numbers(doc: Document, index: ProgramIndex, first_line: int) -> tuple[int | None, int | None]:
    """The number of the program that enters the values, and the program it calls first."""
    program = index.program_at(first_line)
    if program is None or program.number is None:
        return None, None
    call = next((c for c in program.calls if c.kind == "M98" and c.program is not None), None)
    return program.number, None if call is None else call.program


def module_from_document(text: str) -> str | None:
    """The symmetric thread module for the thread this document enters in #100-#104.

    None when the document assigns none of #100-#104, when D, P, L, es/EI and Td2/TD2
    cannot all be found (from the executed assignments, else from a designation comment),
    when they do not make a thread, or when nothing tells an external from an internal one.
    """
    doc = parse_text(text, _URI, default_parser())
    if not _assigned_lines(doc):
        return None
    index = build_index(doc)
    facts = evaluate([(_URI, doc, index)], only_uri=_URI)
    return module_from_analysis(doc, index, facts.document(_URI))


@dataclass(frozen=True)
class ThreadInputs:
    """What a document enters for the symmetric module: the five values (from its executed
    assignments, else from a designation comment), the side, and its programs' numbers."""

    diameter: float
    pitch: float
    length: float
    deviation: float  # |es| or EI, a magnitude (#103)
    pitch_tolerance: float  # Td2 / TD2 (#104)
    internal: bool
    designation: ThreadDesignation | None
    main: int | None  # the program that enters the values
    sub: int | None  # the program it calls first (M98), if any
    assigned: frozenset[int]  # which of #100-#104 the document assigns a number to
    first_line: int  # the first line that assigns one of them

    def module(self, main: int | None, sub: int | None) -> ThreadModule | None:
        """The module for this thread under these program numbers (the paper's when None);
        None when the values make no thread."""
        try:
            return build_module_from_values(
                self.diameter,
                self.pitch,
                self.length,
                self.deviation,
                self.pitch_tolerance,
                internal=self.internal,
                main_number=main,
                sub_number=sub,
                designation=self.designation,
            )
        except ValueError:
            return None


def thread_inputs(doc: Document, index: ProgramIndex, facts: DocumentFacts) -> list[ThreadInputs]:
    """The thread a document enters in #100-#104: one reading when the document tells its
    side, the external and the internal one when it does not; none when it assigns none of
    #100-#104, or when D, P, L, es/EI and Td2/TD2 cannot all be found."""
    assigned = _assigned_lines(doc)
    if not assigned:
        return []
    writes = facts.writes
    values: dict[int, float] = {}
    for number, lines in assigned.items():
        for line in lines:  # the last assignment in the text that produced a number wins
            write = writes.get(line)
            if write is not None and isinstance(write[1].last, float):
                values[number] = write[1].last

    readings = next((r for r in map(_readings, _designation_texts(doc)) if r), ())
    internal: bool | None = readings[0].internal if len(readings) == 1 else None
    if internal is None:
        internal = _side_from_words(_comments(doc))
    if internal is None:
        internal = _side_from_programs(index)
    if internal is None and all(n in values for n in (100, 101, 103, 104)):
        internal = _side_from_tables(values[100], values[101], values[103], values[104])
    sides = (False, True) if internal is None else (internal,)
    found: list[ThreadInputs] = []
    for side in sides:
        des = next((d for d in readings if d.internal == side), None)
        inputs = _inputs(doc, index, assigned, values, side, des)
        if inputs is not None:
            found.append(inputs)
    return found


def _inputs(
    doc: Document,
    index: ProgramIndex,
    assigned: dict[int, list[int]],
    values: dict[int, float],
    internal: bool,
    des: ThreadDesignation | None,
) -> ThreadInputs | None:
    """The inputs on one side, ``des`` the designation read on that side."""
    deviation = values.get(103)
    pitch_tolerance = values.get(104)
    if des is not None and (deviation is None or pitch_tolerance is None):
        try:
            tol = tolerances(des)
        except ValueError:
            return None
        if deviation is None:
            deviation = abs(tol.fundamental_deviation)
        if pitch_tolerance is None:
            pitch_tolerance = tol.pitch_diameter_tolerance
    diameter = values.get(100, des.nominal_diameter if des is not None else None)
    pitch = values.get(101, des.pitch if des is not None else None)
    length = values.get(102)
    if diameter is None or pitch is None or length is None:
        return None
    if deviation is None or pitch_tolerance is None:
        return None
    if des is not None and (
        abs(des.nominal_diameter - diameter) > 1e-9 or abs(des.pitch - pitch) > 1e-9
    ):
        des = None  # the comment names another thread than the values enter

    first_line = min(line for lines in assigned.values() for line in lines)
    main, sub = _numbers(doc, index, first_line)
    return ThreadInputs(
        diameter,
        pitch,
        length,
        deviation,
        pitch_tolerance,
        internal,
        des,
        main,
        sub,
        frozenset(values),
        first_line,
    )


def module_from_analysis(doc: Document, index: ProgramIndex, facts: DocumentFacts) -> str | None:
    """:func:`module_from_document` for a document already parsed, indexed and evaluated
    (the language server has all three): no second run of the evaluator."""
    found = thread_inputs(doc, index, facts)
    if len(found) != 1:
        return None
    inputs = found[0]
    main, sub = inputs.main, inputs.sub
    default_main, default_sub = default_program_numbers(inputs.internal)
    if main is not None and sub is not None and main == sub:
        main = sub = None
    if main is not None and sub is None and main == default_sub:
        main = None
    if sub is not None and main is None and sub == default_main:
        sub = None
    module = inputs.module(main, sub)
    return None if module is None else module.text
