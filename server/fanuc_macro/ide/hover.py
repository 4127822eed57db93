"""Hover: what a variable, word, label, jump, loop, program or keyword is, and what the
analysed runs did with it."""

from __future__ import annotations

from collections.abc import Sequence

from ..config import on_control
from ..evaluator.facts import ValueSummary
from ..program import knowledge
from ..program.arguments import ARGUMENT_LETTER, local_name
from ..program.index import Program
from ..program.machine_kind import machine_text
from ..program.meanings import TableMeaning, table_meaning
from ..program.variables import ARGUMENT_VARIABLES, classify
from ..program.vendor_cycles import VendorCycle, known_cycle, manual_of
from ..syntax.lines import cut_comments
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import Assign, Block, Num, ProgramStart, Span, Word
from ..threads.cross_section import NO_CHAIN, describe_cut, thread_chains
from ..threads.identify import describe as describe_thread
from ..threads.identify import module_meanings
from .cycle_times import MODEL_NOTE, program_time
from .data import Hover, Range
from .locate import Hit, assignments_in, goto_target, number_of
from .navigation import block_call
from .values import Precision, code, inch_at, substituted, times
from .view import View, comment_of, first_comment


def find_assignment(
    view: View, program: Program | None, number: int, line: int
) -> tuple[int, Assign] | None:
    """The assignment of ``#number`` that explains it at ``line``: the last one before it in
    the same program, else the first one after it."""
    blocks = view.doc.blocks
    first, end = (program.first_line, program.end_line) if program else (0, len(blocks))
    stop = min(end, len(blocks))
    # From the hovered line outwards: a long program is read only up to the nearest one.
    for ln in range(min(line, stop - 1), first - 1, -1):
        found = _assignments_of(blocks[ln], number)
        if found:
            return ln, found[-1]
    for ln in range(max(line + 1, first), stop):
        found = _assignments_of(blocks[ln], number)
        if found:
            return ln, found[0]
    return None


def _assignments_of(block: Block, number: int) -> list[Assign]:
    return [
        assign
        for statement in statements_of(block.statement)
        for assign in assignments_in(statement)
        if number_of(assign.target) == number
    ]


def precision_at(view: View, line: int) -> Precision:
    """How values are shown at ``line``: in the unit G20 / G21 leaves there, at the control's
    increment unless the settings ask for every digit."""
    return Precision(inch_at(view.doc.blocks, line), view.config.hover_full_precision)


def with_more(lead: Sequence[str], more: Sequence[str]) -> str:
    """A hover: what was asked, then the rest after a rule (a plain markdown reader shows the
    rule as a line too)."""
    text = "\n\n".join(p for p in lead if p)
    rest = "\n\n".join(p for p in more if p)
    return f"{text}\n\n---\n\n{rest}" if rest else text


def _source(table: TableMeaning) -> str:
    """The module and a short link to the paper's citation."""
    paper = table.table.paper
    module = table.table.module
    where = f"[{paper.authors_short}, {table.table.where}]({paper.link})"
    return f"{module[0].upper()}{module[1:]}: {where}."


def hover_variable(view: View, block: Block, hit: Hit) -> str:
    """The value at this block first, then the variable's meaning in a line, then where it is
    set; the kind of variable, the module's formula and the paper after the rule."""
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
    program = view.index.program_at(line)
    tag = ""
    letter = ARGUMENT_LETTER.get(n)
    if letter is not None and program is not None and _takes_arguments(view, program):
        tag = f" · G65 argument **{letter}**"
    kind_text = kind.meaning + ("" if kind.verified else " (unverified)")
    lead: list[str] = []
    more: list[str] = []
    table = table_meaning(view.index, program.number if program else None, n)
    own = hit.assign
    found = (line, own) if own is not None else find_assignment(view, program, n, line)
    comment = comment_of(view.doc.blocks[found[0]]) if found is not None else ""
    meaning: list[str] = []
    detail = source = ""
    if table is not None:
        meaning.append(table.name)
        detail, source = table.detail, _source(table)
    elif program is not None and (module := _module_meaning(view, program, n)) is not None:
        meaning.append(module[0])
        detail, source = module[1], module[2]
    if comment:
        meaning.append(f"*{comment}*")
    if kind.kind in ("null", "system", "none") or not meaning:
        meaning.insert(0, kind_text)
        kind_text = ""
    if detail:
        more.append(f"*{detail}*")
    about = kind_text[:1].upper() + kind_text[1:] + "." if kind_text else ""
    more.append(" ".join(t for t in (about, source) if t))
    head, body = _variable_value(view, block, hit, n, found)
    lead.append(f"**#{n}**{head}{tag}")
    lead.append(" — ".join(meaning))
    lead.extend(body)
    return with_more(lead, more)


def _variable_value(
    view: View, block: Block, hit: Hit, n: int, found: tuple[int, Assign] | None
) -> tuple[str, list[str]]:
    """What the head says of the value (`` = **1.907**``, `` here: **2.5**``), and the lines
    under the meaning: the formula with the values read, where it is set, why no value."""
    line = block.line
    facts = view.facts
    precision = precision_at(view, line)
    body: list[str] = []
    own = hit.assign
    if found is not None and found[0] != line:
        a_line, a_assign = found
        body.append(
            f"Set at line {a_line + 1}: {code(view.doc.blocks[a_line].source(a_assign.span))}"
        )
    if facts is None:
        body.append("No values: the evaluator did not run on this document.")
        return "", body
    if own is not None:
        write = facts.writes.get(line)
        if write is not None and write[0] == n:
            written = write[1]
            formula = substituted(block, own, facts, precision.show)
            if formula is not None:
                body.insert(0, f"```\n= {formula}\n```")
            return f" = **{precision.summary(written)}**", body
        if not facts.runs.get(line):
            body.append(_not_run(view, line))
        else:
            body.append("The assignment did not run (its condition was false).")
        return "", body
    summary = facts.reads.get((line, n))
    if summary is not None:
        return f" here: **{precision.summary(summary)}**", body
    if not facts.runs.get(line):
        body.append(_not_run(view, line))
    return "", body


def _takes_arguments(view: View, program: Program) -> bool:
    """Whether the locals of ``program`` may hold G65 / G66 arguments: it is called so in the
    workspace, or, with no call of it known, it is a sub program (ends with M99) or was
    analysed as a macro. A program only M98 calls gets no arguments: its locals are the
    caller's (FANUC: M98 does not open a new local level)."""
    if program.number is None:
        return False
    kinds = {
        call.kind
        for _, index in (*view.workspace.values(), (view.doc, view.index))
        for caller in index.programs
        for call in caller.calls
        if call.program == program.number
    }
    if kinds:
        return bool(kinds & {"G65", "G66", "G66.1"})
    if program.returns:
        return True
    facts = view.facts
    return facts is not None and bool(facts.assumed_arguments.get(program.first_line))


def _module_meaning(view: View, program: Program, number: int) -> tuple[str, str, str] | None:
    """The meaning of ``#number`` in a thread module recognised by its formulas (in the
    module itself, or in the program whose values it was called with): its name, what the
    module adds after a colon, and which module it is."""
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
            name, _, detail = meaning.partition(": ")
            return name, detail, f"Thread module {thread.job.program}, recognised by its formulas."
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


def _file_name(key: str) -> str:
    return key.rstrip("/").rsplit("/", 1)[-1]


def hover_program(view: View, number: int, line: int | None = None, diagnosed: bool = False) -> str:
    """What O``number`` is; ``diagnosed``: the hovered call has a diagnostic, which the editor
    shows with the hover, so a missing program is not explained twice."""
    entry = view.program_entry(number)
    cycle = known_cycle(number) if entry is None else None
    if cycle is not None:
        return _cycle_text(cycle)
    if entry is None and on_control(view.config, number):
        return f"**O{number:04d}** — kept on the control (setting machine.programsOnControl)."
    if entry is None:
        if diagnosed:
            return f"**O{number:04d}** — not in the workspace."
        return (
            f"**O{number:04d}** — not in the workspace: a call to it stops with alarm "
            "PS0076 (PROGRAM NOT FOUND)."
        )
    key, doc, program = entry
    comment = first_comment(doc, program)
    header = program.header_line if program.header_line is not None else program.first_line
    where = f"line {header + 1}" if key == view.key else f"{_file_name(key)}, line {header + 1}"
    parts = [f"**{program.display_name}**" + (f" — {comment}" if comment else ""), where]
    kind = "subprogram (ends with M99)" if program.returns else "main program"
    parts[-1] += f" · {kind}"
    if program.named_by_file is not None:
        parts[-1] += " · no O line: the number is the file name's"
    if key == view.key and line == header:
        parts.append(machine_text(view.config))
        timed = program_time(view, program)
        if timed is not None:
            title, lines = timed
            more = f" ({lines.replace(chr(10), ', ')})" if lines else ""
            parts.append(f"{title[0].upper()}{title[1:]}{more}. {MODEL_NOTE}")
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
    codes = [c.code for c in view.config.custom_calls if c.program == number]
    if codes:  # the blocks of such a code are not in the index: the code is named
        parts.append(f"Called by every {codes[0]} block (setting machine.customCalls).")
    facts = view.analysis.facts
    if facts is not None:
        runs = facts.by_uri.get(key)
        if runs is not None and header in runs.runs:
            parts.append(f"Entered {times(runs.runs[header])} in the analysed runs.")
        assumed = runs.assumed_arguments.get(program.first_line) if runs is not None else None
        if assumed:
            names = ", ".join(local_name(n) for n, _ in assumed)
            parts.append(
                f"Analysed as a macro with unknown arguments: it ends with M30 or M02 but "
                f"reads {names} before setting them."
            )
        stopped = facts.stop_message()
        if stopped is not None:
            parts.append(stopped[0].upper() + stopped[1:] + ".")
    return "\n\n".join(parts)


def _cycle_text(cycle: VendorCycle) -> str:
    """A vendor's cycle kept on the control: its name, its arguments, the manual."""
    parts = [
        f"**O{cycle.number}** — {cycle.package}: {cycle.name}. A cycle kept on the control, "
        "not in the workspace: the analysis does not follow it."
    ]
    if cycle.arguments:
        parts.append(
            "Arguments: " + "; ".join(f"**{letter}** {what}" for letter, what in cycle.arguments)
        )
    parts.append(
        f"Source: {manual_of(cycle)}; the meanings are not checked against its pages "
        f"(the cycle is named by: {cycle.verified})."
    )
    return "\n\n".join(parts)


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
    call = block_call(view, program, block.line)
    value = constant_value(word.value)
    lathe = view.config.is_lathe
    system = view.config.g_code_system
    known = view.config.machine_known
    if (
        call is not None
        and call.program is not None
        and ((word.address == "P" and call.code is None) or word.span == call.span)
    ):
        head = ""
        rest: list[str] = []
        if call.code is not None:
            how = "a macro, like G65" if call.kind == "G65" else "a subprogram, like M98"
            head = (
                f"**{call.code}** — calls O{call.program:04d} as {how} (setting "
                "machine.customCalls, as the control's parameter sets it up)"
            )
        elif word.span == call.span and value is not None:
            head, *rest = knowledge.code_parts(word.address, value, lathe, system, known)
        diagnosed = _diagnosed(view, block.line, word.span)
        return with_more((head, hover_program(view, call.program, block.line, diagnosed)), rest)
    thread = _thread_hover(view, block.line)
    if word.address in ("G", "M") and value is not None:
        # The code's meaning on this machine in a line, the thread its block cuts, then the
        # code's form and use.
        head, *rest = knowledge.code_parts(word.address, value, lathe, system, known)
        return with_more((head, thread or ""), rest)
    parts: list[str] = []
    if call is not None and any(arg is word for arg in call.arguments):
        target = f"O{call.program:04d}" if call.program is not None else "the macro"
        number = _argument_variable(call.arguments, word)
        kind = call.code or call.kind
        if number is None:
            article = "an" if kind[0] in "MS" else "a"  # an M165, a G65
            return f"**{word.address}** cannot be {article} {kind} argument"
        text = f"{kind} argument **{word.address}** → **#{number}** in {target}"
        cycle = known_cycle(call.program)
        if cycle is None or view.program_entry(cycle.number) is not None:
            return text
        meaning = dict(cycle.arguments).get(word.address)
        return text if meaning is None else f"{text}: {meaning} ({manual_of(cycle)})"
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
            shown = summary.describe(precision_at(view, block.line).show)
            parts.append(f"Value in the motions: **{shown}**")
    if thread is not None:
        parts.append(thread)
    return "\n\n".join(parts) or None


def _thread_hover(view: View, line: int) -> str | None:
    """What is known of the thread a threading pass at ``line`` cuts."""
    threads = view.analysis.threads
    chains = thread_chains(threads, view.index)
    texts = [
        "\n".join(
            filter(
                None,
                (describe_thread(t), describe_cut(t, chains.get(id(t), NO_CHAIN).before)),
            )
        )
        for t in threads
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
        text = f"{code(view.doc.blocks[jump.line].source(jump.span))} at line {jump.line + 1}"
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
        parts.append(f"The block ran {times(facts.runs[block.line])}.")
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
        # The editor shows the diagnostic that says so (MB101) above the hover: say it only
        # where no diagnostic does (the rule disabled or suppressed).
        if not _diagnosed(view, block.line, hit.span):
            parts.append(
                f"No N{target} in {program.display_name}: the jump stops with alarm "
                "PS0128 (ILLEGAL MACRO SEQUENCE NUMBER)."
            )
    else:
        target_block = view.doc.blocks[line]
        parts.append(
            f"→ line {line + 1}: {code(cut_comments(target_block.text).code)}"
            + (f" ({comment_of(target_block)})" if comment_of(target_block) else "")
        )
    facts = view.facts
    if facts is not None:
        jc = facts.jumps.get(block.line)
        if jc is not None:
            text = f"Taken {times(jc.taken)}, not taken {times(jc.not_taken)}"
            if jc.undecided:
                text += f", undecided {times(jc.undecided)}"
            parts.append(text + ".")
        elif block.line in facts.runs:
            parts.append(f"Taken {times(facts.runs[block.line])}.")
    return "\n\n".join(parts)


def _diagnosed(view: View, line: int, span: Span) -> bool:
    """Whether a diagnostic of the document overlaps ``span`` of ``line`` (the editor shows
    it with the hover)."""
    return any(
        d.line <= line <= d.end_line
        and (d.line < line or d.column < span.end)
        and (d.end_line > line or d.end_column > span.start)
        for d in view.analysis.diagnostics
    )


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
                f"The body ran {times(jc.taken)}; the condition ended the loop "
                f"{times(jc.not_taken)}."
            )
    return "\n\n".join(parts)


def hover(view: View, line: int, column: int) -> Hover | None:
    """The markdown about what is at ``line``, ``column`` (code points)."""
    found = view.hit_at(line, column)
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
    return Hover(text, Range.of(block.line, hit.span.start, block.line, hit.span.end))
