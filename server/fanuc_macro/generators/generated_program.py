"""What the program generators share: FANUC number and comment text, a program text under
construction, and executing a generated program with the project's evaluator (the numbers a
generated comment states are read from that run, not from the formulas)."""

from __future__ import annotations

import inspect
from collections.abc import Callable, Collection, Sequence
from dataclasses import dataclass
from itertools import chain

from ..analysis import Analysis, analyse
from ..program.index import build_index
from ..syntax.lines import decode_bytes
from ..syntax.parser import default_parser, parse_text

__all__ = (
    "GENERATED_URI",
    "FreeNumbers",
    "Lines",
    "clean_comment",
    "count_of",
    "entered",
    "execute",
    "free_numbers",
    "free_programs",
    "mm",
    "num",
    "program_number",
    "programs_in",
)

GENERATED_URI = "generated:thread-program.nc"


def num(value: float, places: int = 4) -> str:
    """A FANUC number with a decimal point: ``50.``, ``0.048``, ``-0.5``."""
    text = f"{value:.{places}f}".rstrip("0")
    if text in ("-0.", "0.", "-."):
        return "0."
    return text


def entered(what: str, value: float, places: int = 4) -> None:
    """Refuse a value the program's ``places`` decimals would change: 1e-05 would be entered
    as ``0.``, 25.00004 as ``25.``, and the program would cut something else than asked."""
    text = num(value, places)
    if abs(float(text) - value) > 1e-12 * max(1.0, abs(value)):
        raise ValueError(
            f"{what} {value!r} has more than {places} decimals: the program would enter {text}"
        )


def mm(value: float) -> str:
    """A measured length for a comment, to the least input increment (0.001 mm)."""
    text = f"{value:.3f}"
    return "0.000" if text == "-0.000" else text


def count_of(n: int, word: str) -> str:
    """``1 SPRING PASS``, ``8 SPRING PASSES``."""
    plural = word + ("ES" if word.endswith("S") else "S")
    return f"{n} {word if n == 1 else plural}"


def clean_comment(text: str, keep_case: str = "") -> str:
    """``text`` in upper case, but for ``keep_case``: a word whose case carries meaning (a thread
    designation's class, ``5g6g`` external, ``5G6G`` internal)."""
    # Old controls read only upper-case ASCII in comments, and a ')' would end the comment.
    cleaned = text.upper().replace("(", "").replace(")", "").replace("%", " PCT")
    if not cleaned.isascii():
        raise ValueError(f"the comment {text} must be ASCII for old controls")
    # A control shows lower case in a comment as it is (MB006 reports it outside comments only).
    if keep_case and keep_case.isascii() and not set(keep_case) & set("()% "):
        cleaned = cleaned.replace(keep_case.upper(), keep_case)
    return " ".join(cleaned.split())


class Lines:
    """A program text under construction; ``key`` remembers where a block landed."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.at: dict[str, int] = {}

    def add(
        self, code: str, comment: str = "", key: str | None = None, keep_case: str = ""
    ) -> None:
        if key is not None:
            self.at[key] = len(self.lines)
        note = clean_comment(comment, keep_case)
        if code and note:
            self.lines.append(f"{code} ({note})")
        elif note:
            self.lines.append(f"({note})")
        else:
            self.lines.append(code)

    def text(self) -> str:
        return "\n".join(self.lines) + "\n"


def program_number(value: int, what: str) -> int:
    if not 1 <= value <= 9999:
        raise ValueError(f"{what} program number O{value} is outside O0001-O9999")
    return value


def programs_in(text: str | bytes) -> frozenset[int]:
    """The O numbers of the programs ``text`` holds (a file's bytes in any of its encodings):
    a file a generated program goes into."""
    if isinstance(text, bytes):
        text = decode_bytes(text).text
    doc = parse_text(text, "generated:target.nc", default_parser())
    return frozenset(p.number for p in build_index(doc).programs if p.number is not None)


@dataclass(frozen=True)
class FreeNumbers:
    """The numbers a generated program's parts take, in the order asked; ``note`` says which
    numbers the file had and which the parts take instead (None when none moved)."""

    numbers: tuple[int, ...]
    note: str | None = None


def _free(first: int, taken: Collection[int]) -> int:
    for number in chain(range(first, 10000), range(first - 1, 0, -1)):
        if number not in taken:
            return number
    raise ValueError("the file has every program number O0001-O9999")


def _listed(items: Sequence[str]) -> str:
    return items[0] if len(items) == 1 else f"{', '.join(items[:-1])} and {items[-1]}"


def free_numbers(wanted: Sequence[tuple[str, int]], taken: Collection[int]) -> FreeNumbers:
    """Each (part, number) of ``wanted`` at its number, or when the file has it (``taken``) or
    an earlier part took it, at the first free number after it (else before it).  The parts the
    file leaves free keep their numbers; the program's calls are written with the numbers
    given."""
    used = set(taken)
    kept: list[int | None] = []
    for _, number in wanted:
        free = number not in used
        kept.append(number if free else None)
        used.add(number)
    used = set(taken) | {n for n in kept if n is not None}
    numbers: list[int] = []
    for (_, number), got in zip(wanted, kept, strict=True):
        if got is None:
            got = _free(number, used)
            used.add(got)
        numbers.append(got)
    moved = [
        (part, old, new) for (part, old), new in zip(wanted, numbers, strict=True) if old != new
    ]
    if not moved:
        return FreeNumbers(tuple(numbers))
    had = _listed([f"O{old:04d}" for _, old, _ in moved])
    verb = "is" if len(moved) == 1 else "are"
    takes = _listed([f"the {part} is O{new:04d}" for part, _, new in moved])
    return FreeNumbers(tuple(numbers), f"{had} {verb} in the file already: {takes}.")


def free_programs(
    numbers: dict[str, int],
    build: Callable[..., object],
    parts: Sequence[tuple[str, str]],
    taken: Collection[int],
) -> str | None:
    """Puts in ``numbers`` the program numbers of the ``parts`` (``build``'s keyword, what the
    program is) it lacks: ``build``'s default, or the first free one after it in a file that
    has the programs ``taken``; says what moved.  A number given that the file has is refused
    (ValueError)."""
    for key, _ in parts:
        if key in numbers and numbers[key] in taken:
            raise ValueError(f"the file has O{numbers[key]:04d} already")
    defaults = inspect.signature(build).parameters
    left = [(key, what) for key, what in parts if key not in numbers]
    given = {numbers[key] for key, _ in parts if key in numbers}
    free = free_numbers([(what, defaults[key].default) for key, what in left], {*taken, *given})
    numbers.update((key, number) for (key, _), number in zip(left, free.numbers, strict=True))
    return free.note


def execute(text: str) -> Analysis:
    """Analyse (parse, evaluate, check) a generated program; fail loudly if it did not run."""
    analysis = analyse(text, GENERATED_URI)
    facts = analysis.facts
    if facts is None:
        raise RuntimeError("the evaluator failed on the generated program")
    if facts.stopped == "budget":
        raise RuntimeError(
            f"the generated program did not end within the evaluator's budget ({facts.steps} "
            "executed blocks): it cuts too much for one run"
        )
    if facts.stopped is not None:
        raise RuntimeError(f"the evaluator stopped early on the generated program: {facts.stopped}")
    alarms = [
        f.message for f in facts.document(GENERATED_URI).findings if f.kind.startswith("alarm:")
    ]
    if alarms:
        raise RuntimeError(f"the generated program raises an alarm: {alarms[0]}")
    return analysis
