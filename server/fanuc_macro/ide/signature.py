"""Signature help: the arguments of a macro call (G65/G66 P<n>: which local each argument
letter fills and what the called program does with it) and the parameters of a function.

It reads the line as typed, which the newest analysis may not have seen yet: the callee is
looked up in the analysis (this document, then the workspace).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ..program import knowledge
from ..program.index import Program
from ..program.meanings import ROLE_TITLES, variable_roles
from ..program.variables import ARGUMENT_VARIABLES
from ..syntax.lines import cut_comments
from ..syntax.tree import Document
from .locate import uses
from .view import View, comment_of, first_comment


@dataclass(frozen=True)
class Parameter:
    start: int  # where the parameter is in its signature's label (code points)
    end: int
    documentation: str = ""  # markdown


@dataclass(frozen=True)
class Signature:
    label: str
    documentation: str  # markdown
    parameters: tuple[Parameter, ...]
    active: int | None  # the parameter at the cursor; None: none of them


# Argument specification I, the order the manual lists the letters in (FANUC Custom Macro B:
# "Argument specification I"); ``ARGUMENT_VARIABLES`` gives each letter's local.
LETTER_ORDER = "ABCIJKDEFHMQRSTUVWXYZ"
_CALL = re.compile(r"G0*(65|66(?:\.1)?)(?![.\d])", re.I)
_PROGRAM = re.compile(r"P\s*(\d+)", re.I)
_WORD_START = re.compile(r"[A-Z]", re.I)

# What each parameter of a function is, where its name alone does not say.
_FUNCTION_PARAMETERS: dict[str, tuple[str, ...]] = {
    "SIN": ("an angle in degrees",),
    "COS": ("an angle in degrees",),
    "TAN": ("an angle in degrees",),
    "ASIN": ("a value from -1 to 1",),
    "ACOS": ("a value from -1 to 1",),
    "ATAN": ("the ordinate (the sine side)", "the abscissa (the cosine side)"),
    "POW": ("the base", "the exponent"),
    "ADP": ("a local #1-#33 given as an argument",),
}


def argument_numbers(letters: list[str]) -> list[int | None]:
    """The local each argument letter of a call fills, in order: specification I, and for an
    I, J or K that repeats or comes out of order, specification II (sets of three from #4)."""
    out: list[int | None] = []
    ijk_set = -1
    seen: set[str] = set()
    for letter in letters:
        if letter in "IJK":
            order = "IJK".index(letter)
            if ijk_set < 0 or letter in seen or any(order < "IJK".index(s) for s in seen):
                ijk_set += 1
                seen = set()
            seen.add(letter)
            number = 4 + 3 * ijk_set + order
            out.append(number if number <= 33 else None)
        else:
            out.append(ARGUMENT_VARIABLES.get(letter))
    return out


def _top_level_words(code: str, end: int) -> list[tuple[str, int]]:
    """The address letters of the block's words before ``end``, outside brackets, with where
    each starts."""
    words: list[tuple[str, int]] = []
    depth = 0
    previous_letter = False
    for i, ch in enumerate(code[:end]):
        if ch == "[":
            depth += 1
        elif ch == "]":
            depth = max(0, depth - 1)
        letter = ch.isascii() and ch.isalpha()
        if depth == 0 and letter and not previous_letter:
            words.append((ch.upper(), i))
        previous_letter = letter and depth == 0
    return words


def _callee_reads(doc: Document, program: Program) -> dict[int, int]:
    """The argument locals the called program reads, each with the first line reading it."""
    reads: dict[int, int] = {}
    for use in uses(doc.blocks, program.first_line, program.end_line):
        number = use.var.number
        if use.assign is None and number is not None and number == int(number):
            reads.setdefault(int(number), use.line)
    return reads


def _argument_documentation(
    view: View, letter: str, number: int | None, callee: tuple[str, Document, Program] | None
) -> str:
    if number is None:
        return f"**{letter}** is not an argument letter: G, L, N, O and P are the call's own."
    head = f"**{letter}** → **#{number}**"
    if callee is None:
        return head
    key, doc, program = callee
    reads = _callee_reads(doc, program)
    if number not in reads:
        return f"{head} — {program.display_name} does not read #{number}"
    parts = [f"{head} — read by {program.display_name} at line {reads[number] + 1}"]
    index = view.index if key == view.key else view.workspace[key][1]
    role = variable_roles(doc, index).get((program.first_line, number))
    if role is not None:
        parts.append(ROLE_TITLES.get(role.role, role.role))
    comment = comment_of(doc.blocks[reads[number]])
    if comment:
        parts.append(f"({comment})")
    return " ".join(parts[:1]) + ("\n\n" + " ".join(parts[1:]) if len(parts) > 1 else "")


def call_signature(view: View | None, line_text: str, column: int) -> Signature | None:
    """The arguments of the G65/G66 call on ``line_text``, with the one at ``column``."""
    code = cut_comments(line_text).code
    column = min(column, len(code))
    call = _CALL.search(code)
    if call is None or call.end() > column:
        return None
    words = _top_level_words(code, column)
    letters = [w for w, start in words if start >= call.end() and w != "P"]
    program = _PROGRAM.search(code, call.end())
    number = int(program.group(1)) if program is not None else None
    callee = view.program_entry(number) if view is not None and number is not None else None
    # The letter being typed: the last word's, when the cursor is still in it.
    current: str | None = None
    if words and words[-1][1] >= call.end():
        letter, start = words[-1]
        typed = code[start:column]
        if letter != "P" and not typed.endswith(" "):
            current = letter
    numbers = argument_numbers(letters)
    shown: list[tuple[str, int | None]] = []
    if callee is not None:
        reads = _callee_reads(callee[1], callee[2])
        for letter in LETTER_ORDER:
            if ARGUMENT_VARIABLES[letter] in reads:
                shown.append((letter, ARGUMENT_VARIABLES[letter]))
    # The letters written too (in their places by the order of their locals).
    for letter, n in zip(letters, numbers, strict=True):
        if (letter, n) not in shown:
            shown.append((letter, n))
    shown.sort(key=lambda item: (item[1] is None, item[1] or 0))
    target = f"P{number}" if number is not None else "P…"
    label = f"{call.group(0).upper()} {target}"
    parameters: list[Parameter] = []
    active: int | None = None
    current_number = numbers[-1] if current is not None and numbers else None
    for letter, n in shown:
        text = f"{letter}=#{n}" if n is not None else f"{letter}=?"
        start = len(label) + 1
        label += " " + text
        if current is not None and letter == current and n == current_number:
            active = len(parameters)
        parameters.append(
            Parameter(start, start + len(text), _argument_documentation(view, letter, n, callee))
            if view is not None
            else Parameter(start, start + len(text), f"**{letter}** → **#{n}**")
        )
    if callee is not None:
        _, doc, called = callee
        comment = first_comment(doc, called)
        documentation = f"**{called.display_name}**" + (f" — {comment}" if comment else "")
    elif number is not None:
        documentation = f"O{number:04d} is not in the workspace."
    else:
        documentation = "The program to call: P<number>."
    return Signature(label, documentation, tuple(parameters), active)


def _open_bracket(code: str, column: int) -> tuple[int, int] | None:
    """The innermost ``[`` still open at ``column`` and the commas before the cursor in it."""
    opens: list[list[int]] = []  # [position, commas]
    for i, ch in enumerate(code[:column]):
        if ch == "[":
            opens.append([i, 0])
        elif ch == "]" and opens:
            opens.pop()
        elif ch == "," and opens:
            opens[-1][1] += 1
    if not opens:
        return None
    return opens[-1][0], opens[-1][1]


_BRACKETED = re.compile(r"\[([^\[\]]+)\]")
_NAME_BEFORE = re.compile(r"([A-Za-z]+)\s*$")
_ATAN_FIRST = re.compile(r"ATAN\s*\[[^\[\]]*(?:\[[^\[\]]*\][^\[\]]*)*\]\s*/\s*$", re.I)


def function_signature(line_text: str, column: int) -> Signature | None:
    """The parameters of the function whose brackets hold ``column``."""
    code = cut_comments(line_text).code
    column = min(column, len(code))
    found = _open_bracket(code, column)
    while found is not None:
        bracket, commas = found
        before = code[:bracket]
        name_match = _NAME_BEFORE.search(before)
        if _ATAN_FIRST.search(before):
            name, active = "ATAN", 1  # the second bracket of ATAN[a]/[b]
        elif name_match is not None and name_match.group(1).upper() in knowledge.FUNCTIONS:
            name, active = name_match.group(1).upper(), commas
        else:
            found = _open_bracket(code, bracket)  # a bracket of an expression: look outside
            continue
        return _function(name, active)
    return None


def _function(name: str, active: int) -> Signature:
    info = knowledge.FUNCTIONS[name]
    label = info.signature
    notes = _FUNCTION_PARAMETERS.get(name, ())
    parameters: list[Parameter] = []
    for m in _BRACKETED.finditer(label):  # "[a]/[b]" or "[a,b]": each name between commas
        offset = m.start(1)
        for part in m.group(1).split(","):
            at = len(parameters)
            note = notes[at] if at < len(notes) else ""
            parameters.append(Parameter(offset, offset + len(part), note))
            offset += len(part) + 1
    documentation = f"{info.title}" + (f"\n\n{info.text}" if info.text else "")
    shown = active if active < len(parameters) else None
    return Signature(label, documentation, tuple(parameters), shown)


def signature_help(line_text: str, column: int, view: View | None) -> Signature | None:
    """What to show at ``column`` (code points) of ``line_text``: a function's parameters inside
    its brackets, else a macro call's arguments."""
    return function_signature(line_text, column) or call_signature(view, line_text, column)


__all__ = [
    "LETTER_ORDER",
    "Parameter",
    "Signature",
    "argument_numbers",
    "call_signature",
    "function_signature",
    "signature_help",
]
