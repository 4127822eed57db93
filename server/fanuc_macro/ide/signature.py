"""Signature help: the arguments of a macro call (G65/G66 P<n>: which local each argument
letter fills and what the called program does with it) and the parameters of a function.

It reads the line as typed, which the newest analysis may not have seen yet: the callee is
looked up in the analysis (this document, then the workspace).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..program import knowledge
from ..program.arguments import argument_numbers
from ..program.index import Program
from ..program.variables import ARGUMENT_VARIABLES, FORBIDDEN_ARGUMENTS
from ..syntax.lines import cut_comments
from ..syntax.tree import Document
from ..translation import tr
from .locate import locals_read_before_set
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


# The letters of argument specification I in the order of the locals they fill (A #1 ... Z #26;
# ``ARGUMENT_VARIABLES`` has the table: FANUC Custom Macro B, as the shared reference macro-b.md
# §5.2 gives it, with specification II's sets of I, J, K).
LETTER_ORDER = "ABCIJKDEFHMQRSTUVWXYZ"
_CALL = re.compile(r"G0*(65|66(?:\.1)?)(?![.\d])", re.I)
_PROGRAM = re.compile(r"P\s*(\d+)", re.I)

# What each parameter of a function is, where its name alone does not say.
_FUNCTION_PARAMETERS: Mapping[str, tuple[str, ...]] = MappingProxyType(
    {
        "SIN": (tr("an angle in degrees"),),
        "COS": (tr("an angle in degrees"),),
        "TAN": (tr("an angle in degrees"),),
        "ASIN": (tr("a value from -1 to 1"),),
        "ACOS": (tr("a value from -1 to 1"),),
        "ATAN": (tr("the ordinate (the sine side)"), tr("the abscissa (the cosine side)")),
        "POW": (tr("the base"), tr("the exponent")),
        "ADP": (tr("a local #1-#33 given as an argument"),),
    }
)


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


@dataclass(frozen=True)
class _Callee:
    """The called program, what it reads of its arguments and what its comments say of them."""

    name: str
    reads: dict[int, int]  # argument local -> the first line reading it
    comments: dict[int, str]  # argument local -> the comment of the line first reading it

    @staticmethod
    def of(doc: Document, program: Program) -> _Callee:
        reads = locals_read_before_set(doc.blocks, program.first_line, program.end_line)
        comments = {n: comment_of(doc.blocks[line]) for n, line in reads.items()}
        return _Callee(program.display_name, reads, comments)


def _argument_documentation(letter: str, number: int | None, callee: _Callee | None) -> str:
    if number is None:
        return tr("**{letter}** fills no local: past #33", letter=letter)
    head = f"**{letter}** → **#{number}**"
    if callee is None:
        return head
    if number not in callee.reads:
        return tr(
            "{argument} — unused: {program} does not read #{number} before it sets it",
            argument=head,
            program=callee.name,
            number=number,
        )
    read = tr(
        "{argument} — read by {program} at line {line}",
        argument=head,
        program=callee.name,
        line=callee.reads[number] + 1,
    )
    comment = callee.comments.get(number)
    return tr("{argument}\n\n({comment})", argument=read, comment=comment) if comment else read


def call_signature(view: View | None, line_text: str, column: int) -> Signature | None:
    """The arguments of the G65/G66 call on ``line_text``, with the one at ``column``."""
    code = cut_comments(line_text).code
    column = min(column, len(code))
    call = _CALL.search(code)
    if call is None or call.end() > column:
        return None
    words = _top_level_words(code, column)
    # The call's own words (P the program, L the repeat count) are no arguments.
    letters = [w for w, start in words if start >= call.end() and w not in FORBIDDEN_ARGUMENTS]
    program = _PROGRAM.search(code, call.end())
    number = int(program.group(1)) if program is not None else None
    entry = view.program_entry(number) if view is not None and number is not None else None
    callee = _Callee.of(entry[1], entry[2]) if entry is not None else None
    # The letter being typed: the last word's, when the cursor is still in it.
    current: str | None = None
    if words and words[-1][1] >= call.end():
        letter, start = words[-1]
        typed = code[start:column]
        if letter not in FORBIDDEN_ARGUMENTS and not typed.endswith(" "):
            current = letter
    numbers = argument_numbers(letters)
    shown: list[tuple[str, int | None]] = []
    if callee is not None:
        for letter in LETTER_ORDER:
            if ARGUMENT_VARIABLES[letter] in callee.reads:
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
        documentation = _argument_documentation(letter, n, callee)
        parameters.append(Parameter(start, start + len(text), documentation))
    if entry is not None:
        _, doc, called = entry
        comment = first_comment(doc, called)
        title = f"**{called.display_name}**"
        documentation = (
            tr("{title} — {comment}", title=title, comment=comment) if comment else title
        )
    elif number is not None:
        documentation = tr("O{number:04d} is not in the workspace.", number=number)
    else:
        documentation = tr("The program to call: P<number>.")
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
    documentation = (
        tr("{title}\n\n{text}", title=info.title, text=info.text) if info.text else info.title
    )
    shown = active if active < len(parameters) else None
    return Signature(label, documentation, tuple(parameters), shown)


def signature_help(line_text: str, column: int, view: View | None) -> Signature | None:
    """What to show at ``column`` (code points) of ``line_text``: a function's parameters inside
    its brackets, else a macro call's arguments; nothing in a comment."""
    for comment in cut_comments(line_text).comments:
        if comment.span.start < column and (column < comment.span.end or not comment.closed):
            return None
    return function_signature(line_text, column) or call_signature(view, line_text, column)


__all__ = (
    "LETTER_ORDER",
    "Parameter",
    "Signature",
    "call_signature",
    "function_signature",
    "signature_help",
)
