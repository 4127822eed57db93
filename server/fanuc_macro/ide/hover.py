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
from ..translation import Text, joined, tr
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
    text = joined("\n\n", (p for p in lead if p))
    rest = joined("\n\n", (p for p in more if p))
    return joined("\n\n---\n\n", (text, rest)) if rest else text


def _source(table: TableMeaning) -> str:
    """The module and a short link to the paper's citation."""
    paper = table.table.paper
    module = table.table.module
    where = tr(
        "[{authors}, {where}]({link})",
        authors=paper.authors_short,
        where=table.table.where,
        link=paper.link,
    )
    return tr("{module}: {where}.", module=_capital(module), where=where)


def hover_variable(view: View, block: Block, hit: Hit) -> str:
    """The value at this block first, then the variable's meaning in a line, then where it is
    set; the kind of variable, the module's formula and the paper after the rule."""
    var = hit.var
    assert var is not None
    n = number_of(var)
    line = block.line
    if n is None:
        return tr(
            "**{variable_text}** — indirect variable: its number is computed when the block runs.",
            variable_text=block.source(var.span).strip(),
        )
    kind = classify(n)
    program = view.index.program_at(line)
    tag = ""
    letter = ARGUMENT_LETTER.get(n)
    if letter is not None and program is not None and _takes_arguments(view, program):
        tag = tr(" · G65 argument **{letter}**", letter=letter)
    kind_text = (
        kind.meaning if kind.verified else tr("{meaning} (unverified)", meaning=kind.meaning)
    )
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
        more.append(tr("*{detail}*", detail=detail))
    about = tr("{kind}.", kind=_capital(kind_text)) if kind_text else ""
    more.append(joined(" ", (t for t in (about, source) if t)))
    head, body = _variable_value(view, block, hit, n, found)
    lead.append(tr("**#{number}**{value}{argument}", number=n, value=head, argument=tag))
    lead.append(joined(" — ", meaning))
    lead.extend(body)
    return with_more(lead, more)


def _capital(text: str) -> str:
    """``text`` with a capital first letter (a translated text's template and parameters
    kept: its English is said capitalised the same way)."""
    capital = text[:1].upper() + text[1:]
    if not isinstance(text, Text):
        return capital
    made = str.__new__(Text, capital)
    made.template, made.params, made.plural, made.number = (
        text.template,
        text.params,
        text.plural,
        text.number,
    )
    return made


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
            tr(
                "Set at line {line}: {program_text}",
                line=a_line + 1,
                program_text=code(view.doc.blocks[a_line].source(a_assign.span)),
            )
        )
    if facts is None:
        body.append(tr("No values: the evaluator did not run on this document."))
        return "", body
    if own is not None:
        write = facts.writes.get(line)
        if write is not None and write[0] == n:
            written = write[1]
            formula = substituted(block, own, facts, precision.show)
            if formula is not None:
                body.insert(0, f"```\n= {formula}\n```")
            return tr(" = **{value}**", value=precision.summary(written)), body
        if not facts.runs.get(line):
            body.append(_not_run(view, line))
        else:
            body.append(tr("The assignment did not run (its condition was false)."))
        return "", body
    summary = facts.reads.get((line, n))
    if summary is not None:
        return tr(" here: **{value}**", value=precision.summary(summary)), body
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
            module_text = tr(
                "Thread module {program}, recognised by its formulas.", program=thread.job.program
            )
            return name, detail, module_text
    return None


def _not_run(view: View, line: int) -> str:
    program = view.index.program_at(line)
    facts = view.facts
    if (
        program is not None
        and facts is not None
        and program.first_line in (facts.analysed_programs)
    ):
        return tr("This block never ran in the analysed runs.")
    return tr("The analysis did not run this program.")


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
        return tr(
            "**O{number:04d}** — kept on the control (setting machine.programsOnControl).",
            number=number,
        )
    if entry is None:
        if diagnosed:
            return tr("**O{number:04d}** — not in the workspace.", number=number)
        return tr(
            "**O{number:04d}** — not in the workspace: a call to it stops with alarm "
            "PS0076 (PROGRAM NOT FOUND).",
            number=number,
        )
    key, doc, program = entry
    comment = first_comment(doc, program)
    header = program.header_line if program.header_line is not None else program.first_line
    where = (
        tr("line {line}", line=header + 1)
        if key == view.key
        else tr("{file}, line {line}", file=_file_name(key), line=header + 1)
    )
    title = f"**{program.display_name}**"
    parts = [tr("{title} — {comment}", title=title, comment=comment) if comment else title, where]
    kind = tr("subprogram (ends with M99)") if program.returns else tr("main program")
    parts[-1] = tr("{where} · {kind}", where=parts[-1], kind=kind)
    if program.named_by_file is not None:
        parts[-1] = tr("{where} · no O line: the number is the file name's", where=parts[-1])
    if key == view.key and line == header:
        parts.append(machine_text(view.config))
        timed = program_time(view, program)
        if timed is not None:
            title, lines = timed
            parts.append(_time_text(title, lines))
    callers: list[str] = []
    for c_key, (_, c_index) in {**view.workspace, view.key: (view.doc, view.index)}.items():
        for c_program in c_index.programs:
            for call in c_program.calls:
                if call.program == number and (c_key != view.key or call.line != line):
                    place = (
                        tr("line {line}", line=call.line + 1)
                        if c_key == view.key
                        else (f"{_file_name(c_key)}:{call.line + 1}")
                    )
                    callers.append(
                        tr(
                            "{call} in {program} ({place})",
                            call=call.kind,
                            program=c_program.display_name,
                            place=place,
                        )
                    )
    if callers:
        shown = joined(", ", callers[:5])
        if len(callers) > 5:
            shown = tr("{callers} and {more} more", callers=shown, more=len(callers) - 5)
        parts.append(tr("Called by {callers}.", callers=shown))
    codes = [c.code for c in view.config.custom_calls if c.program == number]
    if codes:  # the blocks of such a code are not in the index: the code is named
        parts.append(
            tr("Called by every {code} block (setting machine.customCalls).", code=codes[0])
        )
    facts = view.analysis.facts
    if facts is not None:
        runs = facts.by_uri.get(key)
        if runs is not None and header in runs.runs:
            parts.append(
                tr("Entered {times} in the analysed runs.", times=times(runs.runs[header]))
            )
        assumed = runs.assumed_arguments.get(program.first_line) if runs is not None else None
        if assumed:
            names = ", ".join(local_name(n) for n, _ in assumed)
            parts.append(
                tr(
                    "Analysed as a macro with unknown arguments: it ends with M30 or M02 but "
                    "reads {names} before setting them.",
                    names=names,
                )
            )
        stopped = facts.stop_message()
        if stopped is not None:
            parts.append(tr("{stop}.", stop=_capital(stopped)))
    return joined("\n\n", parts)


def _time_text(title: str, lines: str) -> str:
    """The O line's cycle time in a sentence: the time, its parts in brackets, the model."""
    if not lines:
        return tr("{time}. {note}", time=_capital(title), note=MODEL_NOTE)
    # The parts, one a line: said one after another (each translated when it is a Text).
    items = (
        [str(p) if not isinstance(p, str) else p for p in lines.params.values()]
        if isinstance(lines, Text)
        else lines.split("\n")
    )
    return tr(
        "{time} ({parts}). {note}", time=_capital(title), parts=joined(", ", items), note=MODEL_NOTE
    )


def _cycle_text(cycle: VendorCycle) -> str:
    """A vendor's cycle kept on the control: its name, its arguments, the manual."""
    parts: list[str] = [
        tr(
            "**O{number}** — {package}: {name}. A cycle kept on the control, not in the "
            "workspace: the analysis does not follow it.",
            number=cycle.number,
            package=cycle.package,
            name=cycle.name,
        )
    ]
    if cycle.arguments:
        shown = joined(
            "; ",
            (
                tr("**{letter}** {meaning}", letter=letter, meaning=what)
                for letter, what in cycle.arguments
            ),
        )
        parts.append(tr("Arguments: {arguments}", arguments=shown))
    parts.append(
        tr(
            "Source: {manual}; the meanings are not checked against its pages (the cycle is "
            "named by: {named_by}).",
            manual=manual_of(cycle),
            named_by=cycle.verified,
        )
    )
    return joined("\n\n", parts)


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
            how = tr("a macro, like G65") if call.kind == "G65" else tr("a subprogram, like M98")
            head = tr(
                "**{code}** — calls O{program:04d} as {how} (setting machine.customCalls, as "
                "the control's parameter sets it up)",
                code=call.code,
                program=call.program,
                how=how,
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
        target = f"O{call.program:04d}" if call.program is not None else tr("the macro")
        number = _argument_variable(call.arguments, word)
        kind = call.code or call.kind
        if number is None:
            if kind[0] in "MS":  # an M165, a G65
                return tr(
                    "**{address}** cannot be an {kind} argument", address=word.address, kind=kind
                )
            return tr("**{address}** cannot be a {kind} argument", address=word.address, kind=kind)
        text = tr(
            "{kind} argument **{address}** → **#{number}** in {target}",
            kind=kind,
            address=word.address,
            number=number,
            target=target,
        )
        cycle = known_cycle(call.program)
        if cycle is None or view.program_entry(cycle.number) is not None:
            return text
        meaning = dict(cycle.arguments).get(word.address)
        if meaning is None:
            return text
        return tr(
            "{argument}: {meaning} ({manual})",
            argument=text,
            meaning=meaning,
            manual=manual_of(cycle),
        )
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
            parts.append(tr("Value in the motions: **{value}**", value=shown))
    if thread is not None:
        parts.append(thread)
    return joined("\n\n", parts) or None


def _thread_hover(view: View, line: int) -> str | None:
    """What is known of the thread a threading pass at ``line`` cuts."""
    threads = view.analysis.threads
    chains = thread_chains(threads, view.index)
    texts = [
        joined(
            "\n",
            filter(
                None,
                (describe_thread(t), describe_cut(t, chains.get(id(t), NO_CHAIN).before)),
            ),
        )
        for t in threads
        if t.job.uri == view.key and any(m.line == line for m in t.job.passes)
    ]
    return joined("\n\n", dict.fromkeys(texts)) or None


def hover_label(view: View, block: Block) -> str:
    seq = block.parsed.seq
    program = view.index.program_at(block.line)
    if seq is None or program is None:
        return ""
    parts: list[str] = [
        tr("**N{seq}** — sequence number in {program}", seq=seq, program=program.display_name)
    ]
    facts = view.facts
    jumps = [j for j in program.jumps if j.target == seq]
    for jump in jumps[:8]:
        text = tr(
            "{program_text} at line {line}",
            program_text=code(view.doc.blocks[jump.line].source(jump.span)),
            line=jump.line + 1,
        )
        reaches = program.label_line(seq, jump.line) == block.line
        if facts is not None:
            if jump.conditional:
                jc = facts.jumps.get(jump.line)
                if jc is not None:
                    total = jc.taken + jc.not_taken + jc.undecided
                    text = tr(
                        "{jump}: taken {taken} of {total}", jump=text, taken=jc.taken, total=total
                    )
                else:
                    text = tr("{jump}: never reached", jump=text)
            else:
                text = tr("{jump}: taken {taken}", jump=text, taken=facts.runs.get(jump.line, 0))
        if not reaches:
            text = tr("{jump} (reaches the other N{seq})", jump=text, seq=seq)
        parts.append(tr("- {jump}", jump=text))
    if not jumps:
        parts.append(tr("No GOTO jumps here."))
    elif len(jumps) > 8:
        parts.append(tr("- and {more} more", more=len(jumps) - 8))
    duplicates = program.labels.get(seq, [])
    if len(duplicates) > 1:
        where = ", ".join(str(ln + 1) for ln in duplicates)
        parts.append(
            tr(
                "N{seq} appears on lines {lines}: GOTO searches forward from the jump, then "
                "from the program head.",
                seq=seq,
                lines=where,
            )
        )
    if facts is not None and block.line in facts.runs:
        parts.append(tr("The block ran {times}.", times=times(facts.runs[block.line])))
    return joined("\n\n", parts)


def hover_goto(view: View, block: Block, hit: Hit) -> str | None:
    assert hit.goto is not None
    target = goto_target(hit.goto)
    program = view.index.program_at(block.line)
    if target is None or program is None:
        return knowledge.keyword_markdown("GOTO")
    parts: list[str] = [f"**GOTO {target}**"]
    line = program.label_line(target, block.line)
    if line is None:
        # The editor shows the diagnostic that says so (MB101) above the hover: say it only
        # where no diagnostic does (the rule disabled or suppressed).
        if not _diagnosed(view, block.line, hit.span):
            parts.append(
                tr(
                    "No N{target} in {program}: the jump stops with alarm PS0128 (ILLEGAL "
                    "MACRO SEQUENCE NUMBER).",
                    target=target,
                    program=program.display_name,
                )
            )
    else:
        target_block = view.doc.blocks[line]
        comment = comment_of(target_block)
        shown = code(cut_comments(target_block.text).code)
        parts.append(
            tr(
                "→ line {line}: {program_text} ({comment})",
                line=line + 1,
                program_text=shown,
                comment=comment,
            )
            if comment
            else tr("→ line {line}: {program_text}", line=line + 1, program_text=shown)
        )
    facts = view.facts
    if facts is not None:
        jc = facts.jumps.get(block.line)
        if jc is not None:
            taken, not_taken = times(jc.taken), times(jc.not_taken)
            if jc.undecided:
                parts.append(
                    tr(
                        "Taken {taken}, not taken {not_taken}, undecided {undecided}.",
                        taken=taken,
                        not_taken=not_taken,
                        undecided=times(jc.undecided),
                    )
                )
            else:
                parts.append(
                    tr("Taken {taken}, not taken {not_taken}.", taken=taken, not_taken=not_taken)
                )
        elif block.line in facts.runs:
            parts.append(tr("Taken {times}.", times=times(facts.runs[block.line])))
    return joined("\n\n", parts)


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
        return tr("**DO{n} / END{n}** — unpaired (see the diagnostics)", n=n)
    end = (
        tr("no END")
        if loop.end_line is None
        else tr("END{n} at line {line}", n=n, line=loop.end_line + 1)
    )
    parts: list[str] = [
        tr(
            "**WHILE … DO{n}** at line {line}, {end} — nesting level {depth}",
            n=n,
            line=loop.do_line + 1,
            end=end,
            depth=loop.depth,
        )
    ]
    facts = view.facts
    if facts is not None:
        jc = facts.jumps.get(loop.do_line)
        if jc is not None:
            parts.append(
                tr(
                    "The body ran {taken}; the condition ended the loop {ended}.",
                    taken=times(jc.taken),
                    ended=times(jc.not_taken),
                )
            )
    return joined("\n\n", parts)


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
