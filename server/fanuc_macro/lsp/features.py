"""The editor features, from one analysis to protocol types: hover, inlay hints, definitions,
references, symbols, completion and code actions.

Nothing here analyses: it reads the parsed blocks, the program index and the evaluator's facts
of a finished :class:`~fanuc_macro.analysis.Analysis` and words them for the editor. Every
function is pure and may run in a thread.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import resources

from lsprotocol import types

from ..analysis import Analysis
from ..config import Config
from ..evaluator.compiler import compile_expr
from ..evaluator.facts import DocumentFacts, ValueSummary
from ..evaluator.values import MacroAlarm, Unknown, Value, fmt
from ..program import knowledge
from ..program.index import Call as IndexCall
from ..program.index import Program, ProgramIndex, constant_value
from ..program.meanings import table_meaning
from ..program.variables import ARGUMENT_VARIABLES, classify
from ..rules import expressions
from ..rules.expressions import logic_fixes, logic_operands
from ..syntax.lines import cut_comments
from ..syntax.parser import default_parser, statements_of
from ..syntax.tree import (
    Assign,
    Binary,
    Block,
    Bracket,
    Document,
    Expr,
    NcStatement,
    Num,
    ParsedLine,
    ProgramStart,
    Span,
    Unary,
    Var,
    While,
    Word,
)
from ..syntax.walk import subexpressions
from ..threads.identify import describe as describe_thread
from ..threads.identify import module_meanings
from .client import CompletionSupport
from .convert import Codec, Lines
from .locate import (
    Hit,
    assignments_in,
    find,
    goto_target,
    number_of,
    uses,
)

ARGUMENT_LETTER = {n: letter for letter, n in ARGUMENT_VARIABLES.items()}


@dataclass
class View:
    """One analysed document and what the features need around it."""

    key: str
    uri: str  # as the client names it
    analysis: Analysis
    lines: Lines
    config: Config
    # Every workspace document by key: (document, index), for calls across files.
    workspace: dict[str, tuple[Document, ProgramIndex]] = field(default_factory=dict)
    client_uri: Callable[[str], str] = lambda key: key
    markdown: bool = True

    @property
    def doc(self) -> Document:
        return self.analysis.doc

    @property
    def index(self) -> ProgramIndex:
        return self.analysis.index

    @property
    def facts(self) -> DocumentFacts | None:
        facts = self.analysis.facts
        return None if facts is None else facts.by_uri.get(self.key)

    def block(self, line: int) -> Block | None:
        blocks = self.doc.blocks
        return blocks[line] if 0 <= line < len(blocks) else None

    def hit_at(self, position: types.Position) -> tuple[Block, Hit] | None:
        block = self.block(position.line)
        if block is None:
            return None
        hit = find(block, self.lines.column(position))
        return None if hit is None else (block, hit)

    def lines_of(self, key: str) -> Lines:
        if key == self.key:
            return self.lines
        entry = self.workspace.get(key)
        texts = [b.text for b in entry[0].blocks] if entry is not None else []
        return Lines(texts, self.lines.codec)

    def location(
        self, key: str, line: int, start: int = 0, end: int | None = None
    ) -> types.Location:
        lines = self.lines_of(key)
        stop = len(lines.text(line)) if end is None else end
        return types.Location(uri=self.client_uri(key), range=lines.range(line, start, line, stop))


# ---- values ----------------------------------------------------------------------------------


def short(value: Value) -> str:
    """A value for an inlay hint: three decimals, as a machinist reads a drawing."""
    if value is None:
        return "<vacant>"
    if isinstance(value, Unknown):
        return "?"
    if value != value or value in (float("inf"), float("-inf")):
        return fmt(value)
    if value == int(value) and abs(value) < 1e9:
        return f"{int(value)}."
    if abs(value) < 0.001:
        return f"{value:.3g}"
    text = f"{value:.3f}".rstrip("0")
    return text + "0" if text.endswith(".") else text


def short_summary(summary: ValueSummary) -> str | None:
    if summary.count == 0:
        return None
    if summary.count == 1 or summary.constant:
        if isinstance(summary.first, Unknown):
            return None
        return short(summary.first)
    if not summary.numeric:
        return None
    return f"{short(summary.first)} → {short(summary.last)} ×{summary.count}"


def _value_text(value: Value) -> str:
    text = fmt(value)
    return f"[{text}]" if text.startswith("-") else text


def _literal(expr: Expr) -> bool:
    """Numbers and arithmetic only, with at least one operation (``7./8.``, not ``7.``)."""
    operation = False
    for node in subexpressions(expr):
        if isinstance(node, Binary):
            if node.op not in ("+", "-", "*", "/"):
                return False
            operation = True
        elif isinstance(node, Unary):
            operation = True
        elif not isinstance(node, Num | Bracket):
            return False
    return operation


class _NoFrame:
    """A frame for constant expressions: they read no variable."""

    signed_atan = False
    length_increment = 0.001

    def __init__(self) -> None:
        self.locals: list[Value] = []
        self.store: dict[int, Value] = {}

    def note_rounding(self, name: str, argument: float, result: float) -> None:
        pass

    def read_global(self, number: int) -> Value:
        raise LookupError(number)

    def read_indirect(self, number: Value, node: Var) -> Value:
        raise LookupError(number)


def _fold(expr: Expr) -> Value:
    try:
        return compile_expr(expr)(_NoFrame())
    except (MacroAlarm, LookupError, ArithmeticError):
        return None


def substituted(block: Block, assign: Assign, facts: DocumentFacts) -> str | None:
    """The right-hand side with the constant values read at this block put in for variables
    (and written constants such as ``[7./8.]`` folded); None when nothing changes."""
    line = block.line
    base = assign.value.span.start
    replacements: list[tuple[Span, str]] = []

    def visit(node: Expr) -> None:
        if isinstance(node, Var):
            n = number_of(node)
            if n is not None:
                summary = facts.reads.get((line, n))
                if summary is not None and summary.constant:
                    replacements.append((node.span, _value_text(summary.first)))
            return
        if isinstance(node, Bracket) and _literal(node.inner):
            value = _fold(node.inner)
            if isinstance(value, float):
                replacements.append((node.inner.span, fmt(value)))
                return
        if isinstance(node, Binary):
            visit(node.left)
            visit(node.right)
        elif isinstance(node, Unary):
            visit(node.operand)
        elif isinstance(node, Bracket):
            visit(node.inner)
        elif not isinstance(node, Num):
            for arg in node.args:
                visit(arg)

    visit(assign.value)
    if not replacements:
        return None
    text = block.source(assign.value.span)
    for span, new in sorted(replacements, key=lambda r: -r[0].start):
        text = text[: span.start - base] + new + text[span.end - base :]
    return text.strip()


# ---- hover -----------------------------------------------------------------------------------


def _comment(block: Block) -> str:
    return " ".join(c.text.strip() for c in block.parsed.comments if c.text.strip())


def _code(text: str) -> str:
    text = text.strip()
    ticks = "``" if "`" in text else "`"
    return f"{ticks}{text}{ticks}"


def _times(n: int) -> str:
    return "once" if n == 1 else f"{n} times"


def find_assignment(
    view: View, program: Program | None, number: int, line: int
) -> tuple[int, Assign] | None:
    """The assignment of ``#number`` that explains it at ``line``: the last one before it in
    the same program, else the first one after it."""
    first, end = (program.first_line, program.end_line) if program else (0, len(view.doc.blocks))
    before: tuple[int, Assign] | None = None
    after: tuple[int, Assign] | None = None
    for ln in range(first, min(end, len(view.doc.blocks))):
        for statement in statements_of(view.doc.blocks[ln].statement):
            for assign in assignments_in(statement):
                if number_of(assign.target) != number:
                    continue
                if ln <= line:
                    before = (ln, assign)
                elif after is None:
                    after = (ln, assign)
    return before or after


def _variable_kind(number: int) -> str:
    kind = classify(number)
    label = {
        "null": "null variable",
        "local": "local variable",
        "common": "common variable",
        "retained": "common variable (retained)",
        "extended-common": "common variable (extended range)",
        "system": "system variable",
        "none": "not a FANUC variable",
    }.get(kind.kind, kind.kind)
    return label


def hover_variable(view: View, block: Block, hit: Hit) -> str:
    var = hit.var
    assert var is not None
    n = number_of(var)
    line = block.line
    if n is None:
        return (
            f"**{block.source(var.span).strip()}** — indirect variable: its number is "
            "computed when the block runs."
        )
    kind = classify(n)
    head = f"**#{n}** — {_variable_kind(n)}"
    letter = ARGUMENT_LETTER.get(n)
    if letter is not None:
        head += f" · G65 argument **{letter}**"
    parts = [head]
    meaning = kind.meaning + ("" if kind.verified else " (unverified)")
    parts.append(f"*{meaning}*")
    program = view.index.program_at(line)
    table = table_meaning(view.index, program.number if program else None, n)
    if table is None and program is not None:
        table = _module_meaning(view, program, n)
    if table is not None:
        parts.append(table)
    facts = view.facts
    own = hit.assign
    found = (line, own) if own is not None else find_assignment(view, program, n, line)
    if found is not None:
        a_line, a_assign = found
        a_block = view.doc.blocks[a_line]
        comment = _comment(a_block)
        where = "set here" if a_line == line else f"set at line {a_line + 1}"
        text = f"{where}: {_code(a_block.source(a_assign.span))}"
        if comment:
            text = f"**{comment}** — {text}"
        parts.append(text)
    if facts is None:
        parts.append("No values: the evaluator did not run on this document.")
        return "\n\n".join(parts)
    if own is not None:
        write = facts.writes.get(line)
        if write is not None and write[0] == n:
            written = write[1]
            value = written.describe()
            approx = short_summary(written)
            shown = f"Value assigned: **{value}**"
            if approx is not None and approx != value and written.count == 1:
                shown += f" (≈ {approx})"
            parts.append(shown)
            formula = substituted(block, own, facts)
            if formula is not None:
                if written.count == 1 or written.constant:
                    parts.append(f"```\n= {formula}\n= {fmt(written.first)}\n```")
                else:
                    parts.append(f"```\n= {formula}\n```")
        elif not facts.runs.get(line):
            parts.append(_not_run(view, line))
        else:
            parts.append("The assignment did not run (its condition was false).")
        return "\n\n".join(parts)
    summary = facts.reads.get((line, n))
    if summary is not None:
        value = summary.describe()
        approx = short_summary(summary)
        shown = f"Value here: **{value}**"
        if approx is not None and approx != value and summary.count == 1:
            shown += f" (≈ {approx})"
        parts.append(shown)
    elif not facts.runs.get(line):
        parts.append(_not_run(view, line))
    return "\n\n".join(parts)


def _module_meaning(view: View, program: Program, number: int) -> str | None:
    """The meaning of ``#number`` in a thread module recognised by its formulas (in the
    module itself, or in the program whose values it was called with)."""
    for thread in view.analysis.threads:
        if thread.job.uri != view.key or thread.module is None:
            continue
        meaning = module_meanings(thread).get(number)
        if meaning is None:
            continue
        inside = thread.job.program_line == program.first_line
        module = view.index.program_at(thread.job.program_line)
        number_of_module = module.number if module is not None else None
        caller = number_of_module is not None and any(
            c.program == number_of_module for c in program.calls
        )
        if inside or (caller and number >= 100):  # a caller sets the module's commons
            return f"{meaning} — thread module {thread.job.program}, recognised by its formulas"
    return None


def _not_run(view: View, line: int) -> str:
    program = view.index.program_at(line)
    facts = view.facts
    if (
        program is not None
        and facts is not None
        and program.first_line in (facts.analysed_programs)
    ):
        return "This block never ran in the analysed runs."
    return "The analysis did not run this program."


def _program_entry(view: View, number: int) -> tuple[str, Document, Program] | None:
    """Where O``number`` is: this document first, then the workspace (as the evaluator)."""
    own = view.index.by_number(number)
    if own is not None:
        return view.key, view.doc, own
    for key, (doc, index) in view.workspace.items():
        if key == view.key:
            continue
        program = index.by_number(number)
        if program is not None:
            return key, doc, program
    return None


def _first_comment(doc: Document, program: Program) -> str:
    for line in range(program.first_line, min(program.end_line, len(doc.blocks))):
        text = _comment(doc.blocks[line])
        if text:
            return text
    return ""


def _file_name(key: str) -> str:
    return key.rstrip("/").rsplit("/", 1)[-1]


def hover_program(view: View, number: int, line: int | None = None) -> str:
    entry = _program_entry(view, number)
    if entry is None:
        return (
            f"**O{number:04d}** — not in the workspace: a call to it stops with alarm "
            "PS0076 (PROGRAM NOT FOUND)."
        )
    key, doc, program = entry
    comment = _first_comment(doc, program)
    header = program.header_line if program.header_line is not None else program.first_line
    where = f"line {header + 1}" if key == view.key else f"{_file_name(key)}, line {header + 1}"
    parts = [f"**{program.display_name}**" + (f" — {comment}" if comment else ""), where]
    kind = "subprogram (ends with M99)" if program.returns else "main program"
    parts[-1] += f" · {kind}"
    if program.named_by_file is not None:
        parts[-1] += " · no O line: the number is the file name's"
    callers: list[str] = []
    for c_key, (_, c_index) in {**view.workspace, view.key: (view.doc, view.index)}.items():
        for c_program in c_index.programs:
            for call in c_program.calls:
                if call.program == number and (c_key != view.key or call.line != line):
                    place = (
                        f"line {call.line + 1}"
                        if c_key == view.key
                        else (f"{_file_name(c_key)}:{call.line + 1}")
                    )
                    callers.append(f"{call.kind} in {c_program.display_name} ({place})")
    if callers:
        shown = ", ".join(callers[:5]) + (
            f" and {len(callers) - 5} more" if len(callers) > 5 else ""
        )
        parts.append(f"Called by {shown}.")
    facts = view.analysis.facts
    if facts is not None:
        runs = facts.by_uri.get(key)
        if runs is not None and header in runs.runs:
            parts.append(f"Entered {_times(runs.runs[header])} in the analysed runs.")
        assumed = runs.assumed_arguments.get(program.first_line) if runs is not None else None
        if assumed:
            names = ", ".join(
                f"#{n} ({ARGUMENT_LETTER[n]})" if n in ARGUMENT_LETTER else f"#{n}"
                for n, _ in assumed
            )
            parts.append(
                f"Analysed as a macro with unknown arguments: it ends with M30 or M02 but "
                f"reads {names} before setting them."
            )
        stopped = facts.stop_message()
        if stopped is not None:
            parts.append(stopped[0].upper() + stopped[1:] + ".")
    return "\n\n".join(parts)


def _call_at(program: Program | None, line: int) -> IndexCall | None:
    if program is None:
        return None
    return next((c for c in program.calls if c.line == line), None)


def _argument_variable(arguments: Sequence[Word], word: Word) -> int | None:
    """The local an argument fills: specification I, or II for a repeated I/J/K (sets of
    three from #4)."""
    ijk_set = -1
    seen: set[str] = set()
    for arg in arguments:
        number: int | None
        if arg.address in ("I", "J", "K"):
            order = "IJK".index(arg.address)
            if ijk_set < 0 or arg.address in seen or order < max("IJK".index(a) for a in seen):
                ijk_set += 1
                seen = set()
            seen.add(arg.address)
            number = 4 + 3 * ijk_set + order
        else:
            number = ARGUMENT_VARIABLES.get(arg.address)
        if arg is word:
            return number if number is not None and number <= 33 else None
    return None


def hover_word(view: View, block: Block, hit: Hit) -> str | None:
    word = hit.word
    assert word is not None
    program = view.index.program_at(block.line)
    call = _call_at(program, block.line)
    value = constant_value(word.value)
    lathe = view.config.is_lathe
    if (
        call is not None
        and call.program is not None
        and (word.address == "P" or word.span == call.span)
    ):
        head = ""
        if word.span == call.span and value is not None:
            head = (knowledge.code_markdown(word.address, value, lathe) or "") + "\n\n---\n\n"
        return head + hover_program(view, call.program, block.line)
    thread = _thread_hover(view, block.line)
    if word.address in ("G", "M") and value is not None:
        code = knowledge.code_markdown(word.address, value, lathe)
        return "\n\n---\n\n".join(t for t in (code, thread) if t) or None
    parts: list[str] = []
    if call is not None and any(arg is word for arg in call.arguments):
        target = f"O{call.program:04d}" if call.program is not None else "the macro"
        number = _argument_variable(call.arguments, word)
        if number is None:
            return f"**{word.address}** cannot be a {call.kind} argument"
        return f"{call.kind} argument **{word.address}** → **#{number}** in {target}"
    address = knowledge.address_markdown(word.address, lathe)
    if address is not None:
        parts.append(address)
    if not isinstance(word.value, Num):
        summary = ValueSummary()
        facts = view.analysis.facts
        if facts is not None:
            for motion in facts.motions:
                if motion.line == block.line and motion.uri == view.key:
                    got = motion.words.get(word.address)
                    if got is not None:
                        summary.add(got)
        if summary.count:
            parts.append(f"Value in the motions: **{summary.describe()}**")
    if thread is not None:
        parts.append(thread)
    return "\n\n".join(parts) or None


def _thread_hover(view: View, line: int) -> str | None:
    """What is known of the thread a threading pass at ``line`` cuts."""
    texts = [
        describe_thread(t)
        for t in view.analysis.threads
        if t.job.uri == view.key and any(m.line == line for m in t.job.passes)
    ]
    return "\n\n".join(dict.fromkeys(texts)) or None


def hover_label(view: View, block: Block) -> str:
    seq = block.parsed.seq
    program = view.index.program_at(block.line)
    if seq is None or program is None:
        return ""
    parts = [f"**N{seq}** — sequence number in {program.display_name}"]
    facts = view.facts
    jumps = [j for j in program.jumps if j.target == seq]
    for jump in jumps[:8]:
        text = f"{_code(view.doc.blocks[jump.line].source(jump.span))} at line {jump.line + 1}"
        reaches = program.label_line(seq, jump.line) == block.line
        if facts is not None:
            if jump.conditional:
                jc = facts.jumps.get(jump.line)
                if jc is not None:
                    total = jc.taken + jc.not_taken + jc.undecided
                    text += f": taken {jc.taken} of {total}"
                else:
                    text += ": never reached"
            else:
                text += f": taken {facts.runs.get(jump.line, 0)}"
        if not reaches:
            text += f" (reaches the other N{seq})"
        parts.append("- " + text)
    if not jumps:
        parts.append("No GOTO jumps here.")
    elif len(jumps) > 8:
        parts.append(f"- and {len(jumps) - 8} more")
    duplicates = program.labels.get(seq, [])
    if len(duplicates) > 1:
        where = ", ".join(str(ln + 1) for ln in duplicates)
        parts.append(
            f"N{seq} appears on lines {where}: GOTO searches forward from the jump, "
            "then from the program head."
        )
    if facts is not None and block.line in facts.runs:
        parts.append(f"The block ran {_times(facts.runs[block.line])}.")
    return "\n\n".join(parts)


def hover_goto(view: View, block: Block, hit: Hit) -> str | None:
    assert hit.goto is not None
    target = goto_target(hit.goto)
    program = view.index.program_at(block.line)
    if target is None or program is None:
        return knowledge.keyword_markdown("GOTO")
    parts = [f"**GOTO {target}**"]
    line = program.label_line(target, block.line)
    if line is None:
        parts.append(
            f"No N{target} in {program.display_name}: the jump stops with alarm "
            "PS0128 (ILLEGAL MACRO SEQUENCE NUMBER)."
        )
    else:
        target_block = view.doc.blocks[line]
        parts.append(
            f"→ line {line + 1}: {_code(cut_comments(target_block.text).code)}"
            + (f" ({_comment(target_block)})" if _comment(target_block) else "")
        )
    facts = view.facts
    if facts is not None:
        jc = facts.jumps.get(block.line)
        if jc is not None:
            text = f"Taken {_times(jc.taken)}, not taken {_times(jc.not_taken)}"
            if jc.undecided:
                text += f", undecided {_times(jc.undecided)}"
            parts.append(text + ".")
        elif block.line in facts.runs:
            parts.append(f"Taken {_times(facts.runs[block.line])}.")
    return "\n\n".join(parts)


def hover_loop(view: View, block: Block, hit: Hit) -> str | None:
    program = view.index.program_at(block.line)
    if program is None:
        return None
    loop = next(
        (lp for lp in program.loops if lp.do_line == block.line or lp.end_line == block.line), None
    )
    n = f"{hit.loop_id:g}" if hit.loop_id is not None else "?"
    if loop is None:
        return f"**DO{n} / END{n}** — unpaired (see the diagnostics)"
    end = "no END" if loop.end_line is None else f"END{n} at line {loop.end_line + 1}"
    parts = [f"**WHILE … DO{n}** at line {loop.do_line + 1}, {end} — nesting level {loop.depth}"]
    facts = view.facts
    if facts is not None:
        jc = facts.jumps.get(loop.do_line)
        if jc is not None:
            parts.append(
                f"The body ran {_times(jc.taken)}; the condition ended the loop "
                f"{_times(jc.not_taken)}."
            )
    return "\n\n".join(parts)


def hover(view: View, position: types.Position) -> types.Hover | None:
    found = view.hit_at(position)
    if found is None:
        return None
    block, hit = found
    text: str | None = None
    if hit.kind == "var":
        text = hover_variable(view, block, hit)
    elif hit.kind == "function" and hit.call is not None:
        text = knowledge.function_markdown(hit.call.name)
    elif hit.kind == "word":
        text = hover_word(view, block, hit)
    elif hit.kind == "label":
        text = hover_label(view, block)
    elif hit.kind == "program":
        statement = block.statement
        if isinstance(statement, ProgramStart) and statement.number is not None:
            text = hover_program(view, statement.number, block.line)
    elif hit.kind == "goto":
        text = hover_goto(view, block, hit)
    elif hit.kind == "loop":
        text = hover_loop(view, block, hit)
    elif hit.kind == "keyword":
        text = knowledge.keyword_markdown(hit.keyword) or knowledge.function_markdown(hit.keyword)
    if not text:
        return None
    kind = types.MarkupKind.Markdown if view.markdown else types.MarkupKind.PlainText
    return types.Hover(
        contents=types.MarkupContent(kind=kind, value=text),
        range=view.lines.range(block.line, hit.span.start, block.line, hit.span.end),
    )


# ---- inlay hints -----------------------------------------------------------------------------


def inlay_hints(view: View, first: int, last: int) -> list[types.InlayHint]:
    """``= value`` after every assignment the analysis ran, in the lines ``first``..``last``."""
    facts = view.facts
    if facts is None:
        return []
    hints: list[types.InlayHint] = []
    for line in sorted(ln for ln in facts.writes if first <= ln <= last):
        if not facts.runs.get(line):
            continue
        block = view.block(line)
        if block is None:
            continue
        number, summary = facts.writes[line]
        label = short_summary(summary)
        if label is None:
            continue
        assign = next((a for s in statements_of(block.statement) for a in assignments_in(s)), None)
        if assign is None:
            continue
        hints.append(
            types.InlayHint(
                position=view.lines.position(line, assign.span.end),
                label=f"= {label}",
                padding_left=True,
                tooltip=f"#{number} = {summary.describe()}",
            )
        )
    return hints


# ---- definitions and references --------------------------------------------------------------


def definition(view: View, position: types.Position) -> list[types.Location] | None:
    found = view.hit_at(position)
    if found is None:
        return None
    block, hit = found
    program = view.index.program_at(block.line)
    if hit.kind == "goto" and hit.goto is not None and program is not None:
        target = goto_target(hit.goto)
        line = program.label_line(target, block.line) if target is not None else None
        if line is None:
            return None
        seq_span = view.doc.blocks[line].parsed.seq_span
        if seq_span is None:
            return [view.location(view.key, line)]
        return [view.location(view.key, line, seq_span.start, seq_span.end)]
    if hit.kind == "word" and hit.word is not None:
        call = _call_at(program, block.line)
        if (
            call is not None
            and call.program is not None
            and (hit.word.address == "P" or hit.word.span == call.span)
        ):
            entry = _program_entry(view, call.program)
            if entry is None:
                return None
            key, _, callee = entry
            header = callee.header_line if callee.header_line is not None else callee.first_line
            return [view.location(key, header)]
        return None
    if hit.kind == "var" and hit.var is not None:
        n = number_of(hit.var)
        if n is None:
            return None
        first, end = (
            (program.first_line, program.end_line) if program else (0, len(view.doc.blocks))
        )
        return [
            view.location(view.key, use.line, use.var.span.start, use.var.span.end)
            for use in uses(view.doc.blocks, first, end)
            if use.assign is not None and number_of(use.var) == n
        ] or None
    return None


def references(
    view: View,
    position: types.Position,
    include_declaration: bool,
    open_views: Sequence[View] = (),
) -> list[types.Location] | None:
    """Every read and write of a variable: in its program for locals, in every open document
    for common and system variables (they are shared by all programs)."""
    found = view.hit_at(position)
    if found is None or found[1].kind != "var" or found[1].var is None:
        return None
    block, hit = found
    assert hit.var is not None
    n = number_of(hit.var)
    if n is None:
        return None
    local = 1 <= n <= 33
    targets: list[tuple[View, int, int]] = []
    if local:
        program = view.index.program_at(block.line)
        first, end = (
            (program.first_line, program.end_line) if program else (0, len(view.doc.blocks))
        )
        targets.append((view, first, end))
    else:
        targets.append((view, 0, len(view.doc.blocks)))
        for other in open_views:
            if other.key != view.key:
                targets.append((other, 0, len(other.doc.blocks)))
    out: list[types.Location] = []
    for target, first, end in targets:
        for use in uses(target.doc.blocks, first, end):
            if number_of(use.var) != n:
                continue
            if use.assign is not None and not include_declaration:
                continue
            out.append(target.location(target.key, use.line, use.var.span.start, use.var.span.end))
    return out


# ---- symbols ---------------------------------------------------------------------------------


def document_symbols(view: View) -> list[types.DocumentSymbol]:
    out: list[types.DocumentSymbol] = []
    lines = view.lines
    blocks = view.doc.blocks
    for program in view.index.programs:
        last = max(program.first_line, min(program.end_line, len(blocks)) - 1)
        header = program.header_line if program.header_line is not None else program.first_line
        head_block = blocks[header]
        statement = head_block.statement
        selection = (
            statement.span if isinstance(statement, ProgramStart) else Span(0, len(head_block.text))
        )
        children: list[_Node] = []
        targets = {j.target for j in program.jumps if j.target is not None}
        for seq, seq_lines in program.labels.items():
            if seq not in targets:
                continue
            for ln in seq_lines:
                span = blocks[ln].parsed.seq_span or Span(0, 0)
                children.append(
                    _Node(
                        ln,
                        ln,
                        types.DocumentSymbol(
                            name=f"N{seq}",
                            detail=_comment(blocks[ln]) or None,
                            kind=types.SymbolKind.Key,
                            range=lines.range(ln, 0, ln, len(lines.text(ln))),
                            selection_range=lines.range(ln, span.start, ln, span.end),
                        ),
                        is_loop=False,
                    )
                )
        for loop in program.loops:
            end = loop.end_line if loop.end_line is not None else loop.do_line
            do_block = blocks[loop.do_line]
            do_statement = next(
                (s for s in statements_of(do_block.statement) if isinstance(s, While)), None
            )
            span = do_statement.span if do_statement is not None else Span(0, len(do_block.text))
            children.append(
                _Node(
                    loop.do_line,
                    end,
                    types.DocumentSymbol(
                        name=" ".join(do_block.source(span).split()),
                        detail=f"lines {loop.do_line + 1}-{end + 1}",
                        kind=types.SymbolKind.Array,
                        range=lines.range(loop.do_line, 0, end, len(lines.text(end))),
                        selection_range=lines.range(
                            loop.do_line, span.start, loop.do_line, span.end
                        ),
                    ),
                    is_loop=True,
                )
            )
        name = program.display_name
        if program.number is not None and program.name:
            name += f" <{program.name}>"
        out.append(
            types.DocumentSymbol(
                name=name,
                detail=_first_comment(view.doc, program) or None,
                kind=types.SymbolKind.Function if program.returns else types.SymbolKind.Module,
                range=lines.range(program.first_line, 0, last, len(lines.text(last))),
                selection_range=lines.range(header, selection.start, header, selection.end),
                children=_nest(children),
            )
        )
    return out


@dataclass
class _Node:
    start: int
    end: int
    symbol: types.DocumentSymbol
    is_loop: bool
    children: list[_Node] = field(default_factory=list)

    def build(self) -> types.DocumentSymbol:
        if self.children:
            self.symbol.children = [child.build() for child in self.children]
        return self.symbol


def _nest(nodes: list[_Node]) -> list[types.DocumentSymbol]:
    """Labels and loops as a tree: each inside the innermost loop whose lines hold it."""
    nodes.sort(key=lambda node: (node.start, -node.end))
    roots: list[_Node] = []
    stack: list[_Node] = []  # open loops
    for node in nodes:
        while stack and node.start > stack[-1].end:
            stack.pop()
        (stack[-1].children if stack else roots).append(node)
        if node.is_loop:
            stack.append(node)
    return [node.build() for node in roots]


# ---- completion ------------------------------------------------------------------------------

# What is being typed: a variable (#51), or letters with the digits after them (SQ, G9, GOTO1).
_PREFIX = re.compile(r"#\d*$|[A-Za-z]+\d*\.?\d*$")
_CODE_PREFIX = re.compile(r"([GgMm])(\d*\.?\d*)$")


@lru_cache(maxsize=1)
def snippets() -> tuple[tuple[str, str, str, str], ...]:
    """(prefix, name, description, body) of the extension's snippets, shipped with the package."""
    try:
        raw = (resources.files("fanuc_macro") / "data" / "fanuc-macro.code-snippets").read_text(
            "utf-8"
        )
        data = json.loads(raw)
    except (OSError, ValueError):
        return ()
    out: list[tuple[str, str, str, str]] = []
    if not isinstance(data, dict):
        return ()
    for name, entry in data.items():
        if not isinstance(entry, dict):
            continue
        prefixes = entry.get("prefix")
        body = entry.get("body")
        if isinstance(prefixes, str):
            prefixes = [prefixes]
        if isinstance(body, list):
            body = "\n".join(str(b) for b in body)
        if not isinstance(prefixes, list) or not isinstance(body, str):
            continue
        for prefix in prefixes:
            out.append((str(prefix), str(name), str(entry.get("description", "")), body))
    return tuple(out)


def _doc(text: str, support: CompletionSupport) -> types.MarkupContent | str:
    if support.markdown:
        return types.MarkupContent(kind=types.MarkupKind.Markdown, value=text)
    return text


def completion(
    line_text: str,
    line: int,
    column: int,
    codec: Codec,
    config: Config,
    support: CompletionSupport,
    view: View | None = None,
) -> types.CompletionList:
    before = line_text[:column]
    for comment in cut_comments(line_text).comments:
        if comment.span.start < column and (column < comment.span.end or not comment.closed):
            return types.CompletionList(is_incomplete=False, items=[])  # typing a comment
    prefix = _PREFIX.search(before)
    start = prefix.start() if prefix is not None else column
    word = before[start:]
    edit_range = types.Range(
        start=types.Position(line=line, character=codec.to_client(line_text, start)),
        end=types.Position(line=line, character=codec.to_client(line_text, column)),
    )
    items: list[types.CompletionItem] = []

    def add(
        label: str,
        kind: types.CompletionItemKind,
        detail: str,
        new_text: str,
        documentation: str = "",
        sort: str = "5",
        snippet: bool = False,
    ) -> None:
        items.append(
            types.CompletionItem(
                label=label,
                kind=kind,
                detail=detail or None,
                documentation=_doc(documentation, support) if documentation else None,
                sort_text=f"{sort}{label}",
                filter_text=label,
                text_edit=types.TextEdit(range=edit_range, new_text=new_text),
                insert_text_format=(
                    types.InsertTextFormat.Snippet if snippet else types.InsertTextFormat.PlainText
                ),
            )
        )

    if word.startswith("#"):
        if view is not None:
            for number, note in _program_variables(view, line):
                add(
                    f"#{number}",
                    types.CompletionItemKind.Variable,
                    note or _variable_kind(number),
                    f"#{number}",
                    sort="0",
                )
        for number in knowledge.SYSTEM_VARIABLES:
            kind = classify(number)
            add(
                f"#{number}",
                types.CompletionItemKind.Variable,
                kind.meaning,
                f"#{number}",
                sort="1",
            )
        return types.CompletionList(is_incomplete=False, items=_unique(items))
    code_prefix = _CODE_PREFIX.fullmatch(word)
    lathe = config.is_lathe
    codes = knowledge.completion_codes(lathe)
    if code_prefix is not None:
        letter = code_prefix.group(1).upper()
        for name, title in codes:
            if name.startswith(letter):
                value = float(name[1:])
                add(
                    name,
                    types.CompletionItemKind.Value,
                    title,
                    name,
                    knowledge.code_markdown(letter, value, lathe) or "",
                    sort="0",
                )
        return types.CompletionList(is_incomplete=False, items=items)
    for info in knowledge.FUNCTIONS.values():
        add(
            info.name,
            types.CompletionItemKind.Function,
            f"{info.signature} — {info.title}",
            info.snippet if support.snippets else f"{info.name}[]",
            knowledge.function_markdown(info.name) or "",
            sort="1",
            snippet=support.snippets,
        )
    for name, (title, text) in knowledge.KEYWORDS.items():
        add(name, types.CompletionItemKind.Keyword, title, name, text, sort="2")
    if support.snippets and not support.builtin_snippets:
        for prefix_text, name, description, body in snippets():
            add(
                prefix_text,
                types.CompletionItemKind.Snippet,
                f"{name} — {description}",
                body,
                f"```\n{body}\n```",
                sort="3",
                snippet=True,
            )
    if not word or word[:1].upper() in ("G", "M"):
        for name, title in codes:
            add(name, types.CompletionItemKind.Value, title, name, sort="4")
    module = _thread_module(view) if not word.startswith("#") else None
    if module is not None:
        item = types.CompletionItem(
            label="thread module for this program's thread",
            kind=types.CompletionItemKind.Snippet,
            detail="symmetric thread module (G92, left-right) computed from #100-#104",
            documentation=types.MarkupContent(
                kind=types.MarkupKind.Markdown, value=f"```\n{module}\n```"
            ),
            insert_text=module,
            insert_text_format=types.InsertTextFormat.PlainText,
            filter_text="thread",
            sort_text="0",
        )
        items.append(item)
    return types.CompletionList(is_incomplete=False, items=items)


def _thread_module(view: View | None) -> str | None:
    """The symmetric thread module for the thread the document enters in #100-#104 (or names
    in a comment such as ``(M50X3-5G6G)``), from the analysis the server already has."""
    if view is None or view.facts is None:
        return None
    # The generator is imported on the first thread completion, not before initialize.
    from ..threads.snippet import module_from_analysis

    try:
        return module_from_analysis(view.doc, view.index, view.facts)
    except ValueError:
        return None


def _unique(items: list[types.CompletionItem]) -> list[types.CompletionItem]:
    seen: set[str] = set()
    out: list[types.CompletionItem] = []
    for item in items:
        if item.label not in seen:
            seen.add(item.label)
            out.append(item)
    return out


def _program_variables(view: View, line: int) -> list[tuple[int, str]]:
    """Variables the program at ``line`` uses, with the comment of an assignment."""
    program = view.index.program_at(min(line, max(0, len(view.doc.blocks) - 1)))
    first, end = (program.first_line, program.end_line) if program else (0, len(view.doc.blocks))
    found: dict[int, str] = {}
    for use in uses(view.doc.blocks, first, end):
        n = number_of(use.var)
        if n is None:
            continue
        comment = _comment(view.doc.blocks[use.line]) if use.assign is not None else ""
        if n not in found or (comment and not found[n]):
            found[n] = comment
    return sorted(found.items())


# ---- code actions ----------------------------------------------------------------------------

_SUPPRESS = re.compile(r"\(\s*fanuc-macro\s*:\s*ignore\b[^)]*\)", re.I)


def _ends_program(block: Block) -> bool:
    for statement in statements_of(block.statement):
        nc = statement if isinstance(statement, NcStatement) else None
        if nc is not None and any(
            w.address == "M" and constant_value(w.value) in (2.0, 30.0, 99.0) for w in nc.words
        ):
            return True
    return False


def _edit(uri: str, edit_range: types.Range, text: str) -> types.WorkspaceEdit:
    return types.WorkspaceEdit(changes={uri: [types.TextEdit(range=edit_range, new_text=text)]})


def insert_end(view: View, line: int, eol: str) -> types.CodeAction | None:
    """MB201: close the DO with END<m> before the program's M99/M30 (or after its last block)."""
    program = view.index.program_at(line)
    if program is None:
        return None
    problem = next(
        (p for p in program.loop_problems if p.kind == "no-end" and p.line == line), None
    )
    if problem is None:
        return None
    n = f"{problem.loop_id:g}"
    blocks = view.doc.blocks
    end = min(program.end_line, len(blocks))
    target = next((ln for ln in range(line + 1, end) if _ends_program(blocks[ln])), None)
    if target is not None:
        position = types.Position(line=target, character=0)
        text = f"END{n}{eol}"
    else:
        last = max(
            (ln for ln in range(line, end) if blocks[ln].statement is not None), default=line
        )
        position = view.lines.position(last, len(blocks[last].text))
        text = f"{eol}END{n}"
    return types.CodeAction(
        title=f"Insert END{n} to close DO{n}",
        kind=types.CodeActionKind.QuickFix,
        edit=_edit(view.uri, types.Range(start=position, end=position), text),
        is_preferred=True,
    )


def bracket_logic(view: View, line: int, column: int) -> list[types.CodeAction]:
    """MB305: the comparison rewritten with brackets, the likely intent first (each operand
    compared on its own, preferred), then the control's own reading made explicit. A rewrite
    is offered only when the line it gives parses, keeps within five brackets and no longer
    has that comparison's problem."""
    block = view.block(line)
    if block is None:
        return []
    text = block.text
    actions: list[types.CodeAction] = []
    for statement in statements_of(block.statement):
        for found in logic_operands(statement):
            compare = found.compare
            if compare.span.start != column:
                continue
            before = _logic_count(block.parsed)
            for i, (what, rewritten) in enumerate(logic_fixes(text, found)):
                fixed = text[: compare.span.start] + rewritten + text[compare.span.end :]
                if not _acceptable_fix(fixed, before):
                    continue
                edit_range = view.lines.range(line, compare.span.start, line, compare.span.end)
                actions.append(
                    types.CodeAction(
                        title=f"Bracket the condition: {rewritten} ({what})",
                        kind=types.CodeActionKind.QuickFix,
                        edit=_edit(view.uri, edit_range, rewritten),
                        is_preferred=i == 0 or None,
                    )
                )
            return actions
    return actions


def _logic_count(parsed: ParsedLine) -> int:
    return sum(len(logic_operands(s)) for s in statements_of(parsed.statement))


def _acceptable_fix(fixed: str, before: int) -> bool:
    """The rewritten line parses, nests no bracket more than five deep (the IF's own and the
    conditions' brackets counted too, to be safe: PS0118), and has fewer MB305 findings."""
    parsed = default_parser().parse_line(fixed)
    if parsed.problem is not None or parsed.statement is None:
        return False
    depth = deepest = 0
    for i, ch in enumerate(fixed):
        if any(c.span.start <= i < c.span.end for c in parsed.comments):
            continue
        if ch == "[":
            depth += 1
            deepest = max(deepest, depth)
        elif ch == "]":
            depth -= 1
    if deepest > expressions.MAX_BRACKET_NESTING:
        return False
    return _logic_count(parsed) < before


def suppress(view: View, line: int, code: str) -> types.CodeAction:
    text = view.lines.text(line)
    existing = _SUPPRESS.search(text)
    if existing is not None:
        at = existing.end() - 1  # before its ")"
        position = view.lines.position(line, at)
        new = f" {code}"
    else:
        position = view.lines.position(line, len(text))
        new = f" (fanuc-macro: ignore {code})"
    return types.CodeAction(
        title=f"Suppress {code} on this line",
        kind=types.CodeActionKind.QuickFix,
        edit=_edit(view.uri, types.Range(start=position, end=position), new),
    )


def code_actions(
    view: View, diagnostics: Iterable[types.Diagnostic], eol: str
) -> list[types.CodeAction]:
    actions: list[types.CodeAction] = []
    seen: set[tuple[str, int]] = set()
    for diag in diagnostics:
        if diag.source not in (None, "fanuc-macro") or not isinstance(diag.code, str):
            continue
        code = diag.code
        line = diag.range.start.line
        if code == "MB201":
            fix = insert_end(view, line, eol)
            if fix is not None:
                fix.diagnostics = [diag]
                actions.append(fix)
        if code == "MB305":
            column = view.lines.column(diag.range.start)
            for fix in bracket_logic(view, line, column):
                fix.diagnostics = [diag]
                actions.append(fix)
        if (code, line) in seen or not re.fullmatch(r"MB\d{3}", code):
            continue
        seen.add((code, line))
        action = suppress(view, line, code)
        action.diagnostics = [diag]
        actions.append(action)
    return actions


__all__ = [
    "CompletionSupport",
    "View",
    "code_actions",
    "completion",
    "definition",
    "document_symbols",
    "hover",
    "inlay_hints",
    "references",
    "short",
    "short_summary",
    "substituted",
]
