"""The symmetric thread module completed into the user's own program.

A main program that enters a thread in ``#100``-``#104`` (as the paper's O4009 / O4010 do) gets,
at the cursor, the M98 call of the module (and the assignments of whichever of ``#100``-``#104``
it leaves to a designation comment), and after the program the module's sub-program under the
first free O number from the paper's (O3331 external, O3330 internal). The user's values are
used, never entered twice; a call the program already has to a missing program gets that
program. When nothing in the document tells an external thread from an internal one (an
all-capital designation such as ``M50X3-5G6G`` and no other sign), both modules are offered,
never one guessed. Pure: the analysis in, text and edits out.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..translation import tr
from .data import Position, Range, TextEdit
from .view import View

if TYPE_CHECKING:
    from ..generators import ThreadInputs
    from ..program.index import Program

# The words that find the item: what a machinist types for it.
TRIGGERS = ("thread", "M98", "螺纹")
_VALUES = (100, 101, 102, 103, 104)
_LARGEST_PROGRAM = 9999  # O1-O9999: four digits on 0i / 16i (FANUC 0i-F manual, "Program number")


@dataclass(frozen=True)
class ThreadInsertion:
    """What the completion inserts: ``at_cursor`` in place of the typed word, ``sub_program``
    after the user's program."""

    at_cursor: str
    sub_program: TextEdit
    sub_number: int
    title: str  # "M50x3-5g6g external, O3332: 44 passes, 186 G92 cuts, final X46.186"
    preview: str  # the text of both, for the item's documentation


def _used_numbers(view: View) -> set[int]:
    used: set[int] = set()
    for _, index in (*view.workspace.values(), (view.doc, view.index)):
        for program in index.programs:
            if program.number is not None:
                used.add(program.number)
    return used


def _free_number(first: int, used: set[int]) -> int | None:
    for number in range(first, _LARGEST_PROGRAM + 1):
        if number not in used:
            return number
    for number in range(first - 1, 0, -1):
        if number not in used:
            return number
    return None


def _insertion_point(view: View, first_line: int, end_line: int) -> tuple[Position, bool]:
    """Where the sub-program goes: after the program's last block, before the ``%`` and blank
    lines that close it; True when that is past the document's last line."""
    blocks = view.doc.blocks
    at = min(end_line, len(blocks))
    while at - 1 > first_line and blocks[at - 1].text.strip() in ("", "%"):
        at -= 1
    if at < len(blocks):
        return Position(at, 0), False
    last = len(blocks) - 1
    return Position(last, len(blocks[last].text)), True


def thread_insertions(view: View, line: int, eol: str = "\n") -> list[ThreadInsertion]:
    """The module for the thread the program at ``line`` enters: the external and the internal
    one when nothing in the document tells which it is; none when that program enters none,
    when its thread is not complete, or when the module it calls is there already."""
    facts = view.facts
    program = view.index.program_at(line)
    if facts is None or program is None:
        return []
    # The generator is imported on the first thread completion, not before initialize.
    from ..generators import thread_inputs

    found = []
    for inputs in thread_inputs(view.doc, view.index, facts):
        if program.contains(inputs.first_line):
            insertion = _insertion(view, program, inputs, eol)
            if insertion is not None:
                found.append(insertion)
    return found


def _insertion(
    view: View, program: Program, inputs: ThreadInputs, eol: str
) -> ThreadInsertion | None:
    from ..generators import default_program_numbers

    used = _used_numbers(view)
    called = next((c for c in program.calls if c.kind == "M98" and c.program is not None), None)
    if called is not None and called.program in used:
        return None  # the program calls a sub-program it has: the module is written
    if called is not None and called.program is not None:
        sub: int | None = called.program
    else:
        sub = _free_number(default_program_numbers(inputs.internal)[1], used - {program.number})
    if sub is None or sub == program.number:
        return None
    main = program.number if program.number is not None and program.number != sub else None
    module = inputs.module(main, sub)
    if module is None:
        return None
    at_cursor = [module.value_line(n) for n in _VALUES if n not in inputs.assigned]
    if called is None:
        at_cursor.append(module.call_line())
    cursor_text = eol.join(at_cursor)
    sub_lines = module.sub_program_lines()
    position, at_end = _insertion_point(view, program.first_line, program.end_line)
    sub_text = eol + eol.join(sub_lines) if at_end else eol.join(sub_lines) + eol
    side = tr("internal") if inputs.internal else tr("external")
    thread = (
        inputs.designation.canonical()
        if inputs.designation is not None
        else f"M{inputs.diameter:g}x{inputs.pitch:g}"
    )
    title = tr(
        "{thread} {side}, O{sub:04d}: {passes} passes, {cuts} G92 cuts, final X{final_x:.3f}",
        thread=thread,
        side=side,
        sub=sub,
        passes=module.rough_passes,
        cuts=module.g92_cuts,
        final_x=module.final_x,
    )
    where = program.display_name if program.number is not None else tr("the program")
    after = tr(
        "After {program}:\n```\n{program_text}\n```",
        program=where,
        program_text="\n".join(sub_lines),
    )
    preview = (
        tr(
            "At the cursor:\n```\n{program_text}\n```\n\n{after}",
            program_text="\n".join(at_cursor),
            after=after,
        )
        if at_cursor
        else after
    )
    return ThreadInsertion(
        at_cursor=cursor_text,
        sub_program=TextEdit(Range(position, position), sub_text),
        sub_number=sub,
        title=title,
        preview=preview,
    )


def trigger_for(word: str) -> str | None:
    """The trigger word ``word`` begins (case-insensitive), or None: the item's filter text,
    so that the client keeps it while the user types on."""
    if not word:
        return TRIGGERS[0]
    for trigger in TRIGGERS:
        if trigger.upper().startswith(word.upper()):
            return trigger
    return None
