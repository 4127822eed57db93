"""Inputs for fuzzing the analysis, and the properties each analysis must keep.

The inputs are mutations of real programs: the test fixtures and the corpus beside the
project (``../shared/corpus``, read from there), at three levels:

- bytes: flipped, inserted, deleted and repeated bytes, line ends and control characters,
  decoded as the command line decodes a file (so also as GB18030, Shift-JIS or Latin-1);
- tokens: the words of a block (addresses, numbers, keywords, brackets, operators) deleted,
  repeated, swapped or replaced by others;
- grammar: generated blocks (expressions, conditions, loops, jumps, calls), some of them
  extreme (long chains, deep nesting, long numbers), put into a program; and the level
  "extreme", whose blocks are all around the limits of what the analysis reads.

Every choice is drawn from a :class:`Draw`: a seeded ``random.Random`` for the long campaign
(``bench/fuzz_campaign.py``), Hypothesis' data for the test suite (``tests/test_fuzz.py``),
which then shrinks a failing input to a small one.
"""

from __future__ import annotations

import hashlib
import json
import random
import re
import time
import traceback
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any, Protocol, TypeVar

from fanuc_macro.analysis import Analysis
from fanuc_macro.config import Config
from fanuc_macro.database import Database
from fanuc_macro.ide.trace import trace
from fanuc_macro.syntax.lines import decode_bytes, split_lines
from fanuc_macro.syntax.parser import BlockParser, parse_text
from fanuc_macro.workspace import Workspace

ROOT = Path(__file__).resolve().parents[1]
FIXTURES = ROOT / "tests" / "fixtures"
CORPUS = ROOT.parent / "shared" / "corpus"

T = TypeVar("T")

# The evaluator stops on its step budget, well before its safety-net time limit: the same input
# then gives the same result whatever the load of the machine.
CONFIG = Config.from_settings({"analysis": {"stepBudget": 20_000, "timeLimit": 60.0}})
URI = "fuzz.nc"
SECONDS = 10.0  # an analysis that takes longer is a finding (most take milliseconds)


class Draw(Protocol):
    def integer(self, low: int, high: int) -> int:
        """An integer from ``low`` to ``high``, both included."""

    def choice(self, options: Sequence[T]) -> T: ...


class RandomDraw:
    def __init__(self, rng: random.Random) -> None:
        self.rng = rng

    def integer(self, low: int, high: int) -> int:
        return self.rng.randint(low, high)

    def choice(self, options: Sequence[T]) -> T:
        return options[self.rng.randrange(len(options))]


# ---- seeds -------------------------------------------------------------------------------------


@cache
def seeds() -> tuple[tuple[str, bytes], ...]:
    """(name, bytes) of every fixture program and of every corpus file."""
    found = [(str(p.relative_to(ROOT)), p.read_bytes()) for p in sorted(FIXTURES.rglob("*.nc"))]
    if CORPUS.is_dir():
        found += [
            (f"corpus/{p.name}", p.read_bytes())
            for p in sorted(CORPUS.iterdir())
            if p.is_file() and p.suffix not in (".md", ".tsv")
        ]
    return tuple(found)


# ---- byte level --------------------------------------------------------------------------------

NASTY_BYTES = (
    b"\x00", b"\r", b"\n", b"\r\n", b"\x0c", b"\x85", b"\xe2\x80\xa8", b"\xff", b"\xef\xbb\xbf",
    b"(", b")", b";", b"%", b"[", b"]", b"#", b"=", b"\t", b" ", b"\x1b", b"\xa3",
)  # fmt: skip


def mutate_bytes(draw: Draw, data: bytes) -> bytes:
    out = bytearray(data)
    for _ in range(draw.integer(1, 6)):
        at = draw.integer(0, len(out))
        kind = draw.integer(0, 6)
        if kind == 0 and out:  # flip a byte
            at = min(at, len(out) - 1)
            out[at] ^= 1 << draw.integer(0, 7)
        elif kind == 1:  # insert bytes
            out[at:at] = bytes(draw.integer(0, 255) for _ in range(draw.integer(1, 8)))
        elif kind == 2:  # delete a range
            del out[at : at + draw.integer(1, 64)]
        elif kind == 3:  # repeat a range: long runs of anything
            piece = bytes(out[at : at + draw.integer(1, 12)]) or b"1"
            out[at:at] = piece * draw.integer(2, 400)
        elif kind == 4:
            out[at:at] = draw.choice(NASTY_BYTES)
        elif kind == 5:  # cut the file short
            del out[at:]
        else:  # a line of another seed
            _, other = draw.choice(seeds())
            lines = other.split(b"\n")
            out[at:at] = draw.choice(lines) + b"\n"
    return bytes(out)


# ---- token level -------------------------------------------------------------------------------

TOKEN = re.compile(
    r"[A-Za-z]+|#|\d+\.?\d*|\.\d+|<[^>]*>|\([^)]*\)?|[\[\]=+\-*/,;%<>:]|[ \t]+|.", re.S
)
TOKENS = (
    "G65", "G66", "G67", "M98", "M99", "M30", "P9010", "L3", "O1000", "N10", "GOTO", "GOTO10",
    "IF", "THEN", "WHILE", "DO1", "DO4", "END1", "END2", "EQ", "NE", "GT", "LT", "GE", "LE",
    "AND", "OR", "XOR", "MOD", "SIN", "COS", "TAN", "ATAN", "ASIN", "SQRT", "ABS", "ROUND", "FIX",
    "FUP", "LN", "EXP", "POW", "BIN", "BCD", "ADP", "DPRNT", "POPEN", "PCLOS", "#", "#0", "#1",
    "#33", "#100", "#3000", "#4001", "#5021", "#[", "[", "]", "=", "+", "-", "*", "/", ",", "(",
    ")", ";", "%", "0", "1", "-1", "0.", ".5", "90.", "1000", "999999999999", "1234567890123",
    "1e5", "X", "Z", "F", "S", "T0101", "G76", "G92", "G32", "G01", "G00", "/", "/1", " ", "\t",
)  # fmt: skip


def mutate_tokens(draw: Draw, text: str) -> str:
    lines = split_lines(text) or [""]
    for _ in range(draw.integer(1, 4)):
        at = draw.integer(0, len(lines) - 1)
        tokens = TOKEN.findall(lines[at]) or [""]
        where = draw.integer(0, len(tokens) - 1)
        kind = draw.integer(0, 5)
        if kind == 0:
            del tokens[where]
        elif kind == 1:  # the same word many times: long blocks
            tokens[where:where] = [tokens[where]] * draw.integer(2, 300)
        elif kind == 2:
            tokens[where] = draw.choice(TOKENS)
        elif kind == 3:
            tokens.insert(where, draw.choice(TOKENS))
        elif kind == 4:
            other = draw.integer(0, len(tokens) - 1)
            tokens[where], tokens[other] = tokens[other], tokens[where]
        else:  # a whole line moved elsewhere
            lines.insert(draw.integer(0, len(lines)), lines[at])
            continue
        lines[at] = "".join(tokens)
    return "\n".join(lines) + "\n"


# ---- grammar level -----------------------------------------------------------------------------

FUNCTIONS = ("SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SQRT", "ABS", "ROUND", "FIX", "FUP",
             "LN", "EXP", "BIN", "BCD", "ADP")  # fmt: skip
OPERATORS = ("+", "-", "*", "/", "MOD", "AND", "OR", "XOR")
RELATIONS = ("EQ", "NE", "GT", "GE", "LT", "LE")


def number(draw: Draw) -> str:
    digits = str(draw.integer(0, 10 ** draw.integer(1, 13)))
    form = draw.integer(0, 4)
    if form == 0:
        return digits + "."
    if form == 1:
        return "." + digits
    if form == 2:
        return digits[: len(digits) // 2] + "." + digits[len(digits) // 2 :]
    return digits


def variable(draw: Draw) -> str:
    return "#" + str(draw.choice((0, 1, 2, 3, 9, 24, 26, 33, 100, 149, 500, 3000, 4001, 5021)))


def expression(draw: Draw, depth: int = 0) -> str:
    kind = draw.integer(0, 9 if depth < 5 else 1)
    if kind == 0:
        return number(draw)
    if kind == 1:
        return variable(draw)
    if kind == 2:
        return "[" + expression(draw, depth + 1) + "]"
    if kind == 3:
        return draw.choice(FUNCTIONS) + "[" + expression(draw, depth + 1) + "]"
    if kind == 4:
        return "ATAN[" + expression(draw, depth + 1) + "]/[" + expression(draw, depth + 1) + "]"
    if kind == 5:
        return "POW[" + expression(draw, depth + 1) + "," + expression(draw, depth + 1) + "]"
    if kind == 6:
        return "-" + expression(draw, depth + 1)
    if kind == 7:
        return "#[" + expression(draw, depth + 1) + "]"
    if kind == 8:  # a chain of one operator, deep on the left: now and then past the limits
        op = draw.choice(OPERATORS)
        return op.join(expression(draw, 5) for _ in range(_count(draw, 400)))
    left, right = expression(draw, depth + 1), expression(draw, depth + 1)
    return left + draw.choice(OPERATORS) + right


def _count(draw: Draw, extreme: int) -> int:
    """Mostly a few; one time in four, from 90 to ``extreme``: around and past the limits on
    depth (100 levels) and line length (1024 characters)."""
    return draw.integer(90, extreme) if draw.integer(0, 3) == 0 else draw.integer(2, 12)


def deep(draw: Draw) -> str:
    """Nesting around and past the limits: brackets, functions, indirect variables."""
    levels = _count(draw, 320)
    opening = draw.choice(("[", "SIN[", "#[", "ABS[", "-["))
    return opening * levels + expression(draw, 5) + "]" * levels


def condition(draw: Draw, depth: int = 0) -> str:
    if depth < 3 and draw.integer(0, 3) == 0:
        parts = [condition(draw, depth + 1) for _ in range(draw.integer(2, 4))]
        return "[" + draw.choice(("AND", "OR", "XOR")).join(parts) + "]"
    return "[" + expression(draw) + draw.choice(RELATIONS) + expression(draw) + "]"


def block(draw: Draw) -> str:
    kind = draw.integer(0, 11)
    if kind == 0:
        return variable(draw) + "=" + expression(draw)
    if kind == 1:
        return f"IF{condition(draw)}GOTO{draw.integer(0, 120)}"
    if kind == 2:
        return f"IF{condition(draw)}THEN{variable(draw)}={expression(draw)}"
    if kind == 3:
        n = draw.integer(0, 5)
        return f"WHILE{condition(draw)}DO{n}\n{variable(draw)}={expression(draw)}\nEND{n}"
    if kind == 4:
        return f"N{draw.integer(0, 120)} G01 X[{expression(draw)}] Z{number(draw)} F#9"
    if kind == 5:
        letters = "ABCDEFHIJKMQRSTUVWXYZ"
        args = "".join(f"{draw.choice(letters)}{expression(draw, 4)}" for _ in range(8))
        return f"G65 P{draw.integer(1, 9999)} {args}"
    if kind == 6:
        return f"M98 P{draw.integer(0, 99999999)} L{draw.integer(0, 9999)}"
    if kind == 7:
        return f"{variable(draw)}={deep(draw)}"
    if kind == 8:
        return f"GOTO{expression(draw)}"
    if kind == 9:
        return f"G76 P{number(draw)} Q{number(draw)} R{number(draw)} X{expression(draw, 4)}"
    if kind == 10:
        return "DPRNT[" + "X#1[53]*" * draw.integer(1, 40) + "]"
    return f"#3000={draw.integer(0, 999)}(ALARM)"


def extreme_block(draw: Draw) -> str:
    """A block around the limits: nesting 90 to 320 deep, chains of 90 to 400 terms, long
    numbers, many words."""
    kind = draw.integer(0, 3)
    count = draw.integer(90, 400)
    if kind == 0:
        opening = draw.choice(("[", "SIN[", "#[", "ABS[", "-[", "ATAN["))
        return f"{variable(draw)}={opening * count}{number(draw)}{']' * count}"
    if kind == 1:
        op = draw.choice(OPERATORS)
        return f"{variable(draw)}=" + op.join(number(draw) for _ in range(count))
    if kind == 2:
        parts = [f"[{variable(draw)}{draw.choice(RELATIONS)}{number(draw)}]" for _ in range(3)]
        cond = "[" * count + draw.choice(("AND", "OR")).join(parts) + "]" * count
        return f"IF{cond}GOTO{draw.integer(0, 9)}"
    return "G01" + "".join(f" X{number(draw)}" for _ in range(count))


def mutate_grammar(draw: Draw, text: str, extreme: bool = False) -> str:
    lines = split_lines(text)
    for _ in range(draw.integer(1, 5)):
        at = draw.integer(0, len(lines))
        new = extreme_block(draw) if extreme else block(draw)
        if lines and draw.integer(0, 2) == 0:
            lines[min(at, len(lines) - 1)] = new
        else:
            lines.insert(at, new)
    return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class FuzzInput:
    seed: str  # the seed's name
    level: str  # one of LEVELS
    before: str  # the seed's text: the document as it was before the edit
    text: str  # the mutated text
    start: str = "seed"  # where the editor's edit path begins: one of STARTS
    # The versions the editor's document goes through, analysed one after the other in one
    # workspace as the language server does (each must give what a fresh analysis gives).
    path: tuple[str, ...] = ()
    opened: bytes = b""  # start "binary": the file's bytes, read before the first version


LEVELS = ("bytes", "tokens", "grammar", "extreme")
# The edit path: from the unmutated program to the mutated one; typing into an empty document;
# a binary file's document turned into text; one-character edits of the mutated text.
STARTS = ("seed", "empty", "binary", "mutated")
# What a one-character edit types: the characters of Macro B, line breaks, and spaces the
# parser must not take for ASCII ones.
TYPED = "#=[]()*/+-.,;%0123456789GXZFIOPNM \n\t\r\xa0\u3000"


def one_char_edit(draw: Draw, text: str) -> str:
    """``text`` with one character deleted, inserted or replaced, as a keystroke does."""
    at = draw.integer(0, len(text))
    kind = draw.integer(0, 2) if text else 1
    if kind == 0:
        at = min(at, len(text) - 1)
        return text[:at] + text[at + 1 :]
    typed = draw.choice(TYPED)
    if kind == 1:
        return text[:at] + typed + text[at:]
    at = min(at, len(text) - 1)
    return text[:at] + typed + text[at + 1 :]


def edit_path(
    draw: Draw, data: bytes, before: str, text: str, start: str | None = None
) -> tuple[str, tuple[str, ...], bytes]:
    """(start, versions, opened bytes) of an edit path that ends at or goes on from ``text``."""
    start = start or draw.choice(STARTS)
    if start == "seed":
        return start, (before, text), b""
    if start == "empty":  # a new file: the first keystrokes, then the whole text pasted
        typed = text[: draw.integer(1, 3)]
        return start, ("", *(typed[:n] for n in range(1, len(typed) + 1)), text), b""
    if start == "binary":
        at = draw.integer(0, len(data))
        return start, (text,), data[:at] + b"\x00" * draw.integer(1, 8) + data[at:]
    versions = [text]
    for _ in range(draw.integer(1, 3)):
        versions.append(one_char_edit(draw, versions[-1]))
    return start, tuple(versions), b""


def make_input(draw: Draw, level: str | None = None, start: str | None = None) -> FuzzInput:
    name, data = draw.choice(seeds())
    level = level or draw.choice(LEVELS)
    before = decode_bytes(data).text
    if level == "bytes":
        text = decode_bytes(mutate_bytes(draw, data)).text
    elif level == "tokens":
        text = mutate_tokens(draw, before)
    else:
        text = mutate_grammar(draw, before, extreme=level == "extreme")
    start, path, opened = edit_path(draw, data, before, text, start)
    return FuzzInput(name, level, before, text, start, path, opened)


# ---- the properties ----------------------------------------------------------------------------


def _summary(diagnostics: Sequence[Any]) -> list[tuple[str, int, int, str]]:
    return [(d.code, d.line, d.column, d.message) for d in diagnostics]


def check(case: FuzzInput, seconds: float = SECONDS) -> str | None:
    """What is wrong with the analysis of ``case`` (None: nothing): see :func:`outcome`."""
    return outcome(case, seconds)[0]


def outcome(case: FuzzInput, seconds: float = SECONDS) -> tuple[str | None, str]:
    """What is wrong with the analysis of ``case`` (None: nothing), and the digest of its
    diagnostics (:func:`digest`), which another process, after other inputs, must find the
    same.

    No exception escapes the analysis and no rule fails inside it (MB000); it ends within
    ``seconds``; an analysis in a database and with a parser of its own gives what one in the
    database of this process's earlier analyses gives (no history dependence); the edit path
    of the parser (the previous version's blocks reused) gives the document a fresh parse
    gives; each version of the case's edit path, analysed one after the
    other in one workspace as the language server does (the evaluation resumed, the facts
    kept, see evaluator/checkpoints.py), gives the diagnostics of a fresh workspace; and the
    trace of the program is JSON.
    """
    uri = URI
    limits = CONFIG.read_limits
    digested = ""
    try:
        started = time.perf_counter()
        first = _after_history(case.text)
        elapsed = time.perf_counter() - started
        digested = _digest_of(first.diagnostics)
        internal = [d.message for d in first.diagnostics if d.code == "MB000"]
        if internal:
            return f"MB000: {internal[0]}", digested
        if elapsed > seconds:
            return f"slow: {elapsed:.1f} s", digested
        if _summary(first.diagnostics) != _summary(_fresh(case.text).diagnostics):
            return "history dependence: after other analyses, not what a fresh one gives", digested
        parser = BlockParser()
        previous = parse_text(case.before, uri, parser, limits=limits)
        edited = parse_text(case.text, uri, parser, previous, limits)
        if edited != parse_text(case.text, uri, BlockParser(), limits=limits):
            return "the edit path's document differs from a fresh parse", digested
        problem = _edit_path_problem(case, first)
        if problem is not None:
            return problem, digested
        # What `fanuc-macro trace --format json` prints.
        json.dumps(trace(uri, first.doc, first.index, (), CONFIG))
    except Exception:  # the finding: what escaped, from where
        lines = traceback.format_exc().splitlines()
        shown = lines if len(lines) <= 24 else [*lines[:13], "  ...", *lines[-8:]]
        return "exception: " + "\n".join(shown), digested
    return None, digested


# The database of every analysis this process has run, as a language server's builds up over a
# day: an analysis in it must give what one in a fresh database gives. Its workspace holds a
# few documents, each input replacing the oldest one's text (as a paste over a whole document
# does), so the caches are those of edits, never dropped by a close.
_HISTORY = Database()
_HISTORY_URIS = ("history-0.nc", "history-1.nc", "history-2.nc")
_history: list[Workspace] = []
_turn = [0]


def _after_history(text: str) -> Analysis:
    """The analysis of ``text`` in the database of this process's earlier analyses, alone
    (the workspace's other documents take no part)."""
    if not _history:
        _history.append(Workspace(CONFIG, db=_HISTORY))
    workspace = _history[0]
    uri = _HISTORY_URIS[_turn[0] % len(_HISTORY_URIS)]
    _turn[0] += 1
    workspace.add_text(uri, text)
    own = frozenset(p.number for p in workspace.index(uri).programs if p.number is not None)
    return workspace.analyse(uri, own, others=[])


def _fresh(text: str) -> Analysis:
    """The analysis of ``text`` alone, in a workspace and database of its own."""
    workspace = Workspace(CONFIG)
    workspace.add_text(URI, text)
    return workspace.analyse(URI)


def _edit_path_problem(case: FuzzInput, fresh_text: Analysis) -> str | None:
    """How the workspace's analysis of a version of the edit path differs from a fresh one."""
    workspace = Workspace(CONFIG)
    if case.opened:
        workspace.add_bytes(URI, case.opened)
        if workspace.not_text(URI) is None:
            workspace.analyse(URI)
    for step, version in enumerate(case.path):
        workspace.add_text(URI, version)
        got = _summary(workspace.analyse(URI).diagnostics)
        internal = [m for code, _, _, m in got if code == "MB000"]
        if internal:
            return f"MB000 on the edit path ({case.start}, version {step}): {internal[0]}"
        want = fresh_text if version == case.text else _fresh(version)
        if got != _summary(want.diagnostics):
            extra = [d for d in got if d not in _summary(want.diagnostics)][:3]
            missing = [d for d in _summary(want.diagnostics) if d not in got][:3]
            return (
                f"the edit path ({case.start}, version {step}) differs from a fresh analysis: "
                f"extra {extra}, missing {missing}"
            )
    return None


def _digest_of(diagnostics: Sequence[Any]) -> str:
    text = json.dumps(_summary(diagnostics), ensure_ascii=False)
    return hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()[:16]


def digest(case: FuzzInput) -> str:
    """A digest of the diagnostics of ``case``'s text: the same in any process."""
    return _digest_of(_after_history(case.text).diagnostics)


def describe(case: FuzzInput, shown: int = 300) -> str:
    text = case.text if len(case.text) <= shown else case.text[:shown] + "..."
    path = f", edit path from {case.start}: {[v[:80] for v in case.path]!r}"
    return f"{case.level} mutation of {case.seed}: {text!r}{path}"


__all__ = [
    "CONFIG",
    "LEVELS",
    "STARTS",
    "Draw",
    "FuzzInput",
    "RandomDraw",
    "check",
    "describe",
    "digest",
    "make_input",
    "one_char_edit",
    "outcome",
    "seeds",
]
