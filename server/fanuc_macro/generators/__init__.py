"""Program generators: the symmetric thread module (seed 000), the arc thread (seed 002) and the
drum groove (seed 003), and the editor's requests for them. Each writes Macro B text and checks
it by running it with the evaluator. :mod:`.generated_program` is what they share;
:mod:`.generator_requests` reads an editor's parameters, and :mod:`.editor_forms` reads and
checks the boxes of an editor's forms with the generators themselves.

The front ends import this package, never its modules: the names below are its public API.
Each name loads its module when first read, so that a start of the language server or a check
loads no generator.
"""

from __future__ import annotations

import importlib
from types import MappingProxyType
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .arc_thread_generator import ArcThreadProgram as ArcThreadProgram
    from .arc_thread_generator import build_arc_thread as build_arc_thread
    from .arc_thread_generator import generate_arc_thread as generate_arc_thread
    from .drum_groove_generator import DRUM_PROFILE as DRUM_PROFILE
    from .drum_groove_generator import DrumGrooveProgram as DrumGrooveProgram
    from .drum_groove_generator import build_drum_groove as build_drum_groove
    from .drum_groove_generator import generate_drum_groove as generate_drum_groove
    from .editor_forms import BoxAnswer as BoxAnswer
    from .editor_forms import DesignationReading as DesignationReading
    from .editor_forms import FormRefusal as FormRefusal
    from .editor_forms import check_answers as check_answers
    from .editor_forms import form_defaults as form_defaults
    from .editor_forms import read_designation as read_designation
    from .editor_forms import read_taper as read_taper
    from .generated_program import FreeNumbers as FreeNumbers
    from .generated_program import free_numbers as free_numbers
    from .generated_program import free_programs as free_programs
    from .generated_program import programs_in as programs_in
    from .generator_requests import ARC_PROGRAMS as ARC_PROGRAMS
    from .generator_requests import ARC_THREAD_PARAMETERS as ARC_THREAD_PARAMETERS
    from .generator_requests import DRUM_GROOVE_PARAMETERS as DRUM_GROOVE_PARAMETERS
    from .generator_requests import DRUM_PROGRAMS as DRUM_PROGRAMS
    from .generator_requests import ArcThreadAnswer as ArcThreadAnswer
    from .generator_requests import DrumGrooveAnswer as DrumGrooveAnswer
    from .generator_requests import GeneratorRefusal as GeneratorRefusal
    from .generator_requests import arc_thread_request as arc_thread_request
    from .generator_requests import drum_groove_request as drum_groove_request
    from .thread_generator import INFEEDS as INFEEDS
    from .thread_generator import MATERIAL_COEFFICIENTS as MATERIAL_COEFFICIENTS
    from .thread_generator import ThreadModule as ThreadModule
    from .thread_generator import build_module as build_module
    from .thread_generator import default_program_numbers as default_program_numbers
    from .thread_generator import generate_module as generate_module
    from .thread_generator import module_numbers as module_numbers
    from .thread_module import NoGenerator as NoGenerator
    from .thread_module import SideConflict as SideConflict
    from .thread_module import SideUndecided as SideUndecided
    from .thread_module import load_generator as load_generator
    from .thread_snippet import ThreadInputs as ThreadInputs
    from .thread_snippet import module_from_analysis as module_from_analysis
    from .thread_snippet import module_from_document as module_from_document
    from .thread_snippet import thread_inputs as thread_inputs

# The public API: each name and the module that defines it (the imports above, for the type
# checker; a test keeps the two the same).
PUBLIC: MappingProxyType[str, str] = MappingProxyType(
    {
        "ArcThreadProgram": "arc_thread_generator",
        "build_arc_thread": "arc_thread_generator",
        "generate_arc_thread": "arc_thread_generator",
        "DRUM_PROFILE": "drum_groove_generator",
        "DrumGrooveProgram": "drum_groove_generator",
        "build_drum_groove": "drum_groove_generator",
        "generate_drum_groove": "drum_groove_generator",
        "FreeNumbers": "generated_program",
        "free_numbers": "generated_program",
        "free_programs": "generated_program",
        "programs_in": "generated_program",
        "ARC_PROGRAMS": "generator_requests",
        "ARC_THREAD_PARAMETERS": "generator_requests",
        "DRUM_PROGRAMS": "generator_requests",
        "DRUM_GROOVE_PARAMETERS": "generator_requests",
        "ArcThreadAnswer": "generator_requests",
        "DrumGrooveAnswer": "generator_requests",
        "GeneratorRefusal": "generator_requests",
        "arc_thread_request": "generator_requests",
        "drum_groove_request": "generator_requests",
        "INFEEDS": "thread_generator",
        "MATERIAL_COEFFICIENTS": "thread_generator",
        "ThreadModule": "thread_generator",
        "build_module": "thread_generator",
        "default_program_numbers": "thread_generator",
        "generate_module": "thread_generator",
        "module_numbers": "thread_generator",
        "NoGenerator": "thread_module",
        "SideConflict": "thread_module",
        "SideUndecided": "thread_module",
        "load_generator": "thread_module",
        "ThreadInputs": "thread_snippet",
        "module_from_analysis": "thread_snippet",
        "module_from_document": "thread_snippet",
        "thread_inputs": "thread_snippet",
        "BoxAnswer": "editor_forms",
        "DesignationReading": "editor_forms",
        "FormRefusal": "editor_forms",
        "check_answers": "editor_forms",
        "form_defaults": "editor_forms",
        "read_designation": "editor_forms",
        "read_taper": "editor_forms",
    }
)


def __getattr__(name: str) -> object:
    """A public name, its module loaded on first read (no public name is a module's name, so
    the import system's binding of a module to this package never hides one)."""
    module = PUBLIC.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value: object = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value
