"""MB4xx: statements and calls: mixed blocks, G65 arguments, call targets, repeat counts."""

from __future__ import annotations

from bisect import bisect_left
from collections.abc import Iterable, Iterator
from typing import NamedTuple, cast

from ..config import on_control
from ..diagnostics import (
    Diagnostic,
    Fix,
    FixEdit,
    Related,
    RuleDoc,
    RuleInfo,
    Severity,
    line_list,
    make,
)
from ..line_maps import LineMap
from ..per_line import PerLine
from ..program.arguments import (
    LocalsNamed,
    LocalUse,
    argument_numbers,
    local_name,
    local_uses,
)
from ..program.custom_calls import unset_m_calls
from ..program.index import Call as IndexCall
from ..program.index import Program
from ..program.variables import ARGUMENT_VARIABLES, FORBIDDEN_ARGUMENTS
from ..program.vendor_cycles import describe, known_cycle
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import (
    Assign,
    Document,
    Goto,
    IfNc,
    Mixed,
    NcStatement,
    Num,
    ParsedLine,
    PlainNc,
    Statement,
    Var,
    Word,
)
from ..translation import Text, tr, tr_n
from .context import LineFinding, RuleContext

FAMILY = "statements"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB401 = RuleInfo("MB401", "nc-and-macro", Severity.ERROR,
                 "An NC statement and a macro statement in one block (alarm PS0127).", FAMILY)
MB402 = RuleInfo("MB402", "g65-argument-letter", Severity.ERROR,
                 "G, L, N, O or P used as a G65/G66 argument (alarm PS0129 for G).", FAMILY)
MB403 = RuleInfo("MB403", "call-target-missing", Severity.WARNING,
                 "M98/G65/G66 calls a program that is in neither the file nor the workspace.",
                 FAMILY)
MB404 = RuleInfo("MB404", "argument-without-decimal-point", Severity.INFORMATION,
                 "A G65 argument written without a decimal point: its value depends on the "
                 "machine's least input increment.", FAMILY)
MB405 = RuleInfo("MB405", "repeat-count", Severity.ERROR,
                 "An L repeat count outside 1-9999, or a call with no P.", FAMILY)
MB406 = RuleInfo("MB406", "modal-call-not-cancelled", Severity.WARNING,
                 "A G66/G66.1 modal call with no G67 after it in the same program.", FAMILY)
MB407 = RuleInfo("MB407", "program-not-ended", Severity.WARNING,
                 "An O program with no M30, M02 or M99: it runs off its end.", FAMILY)
MB408 = RuleInfo("MB408", "vendor-cycle-on-control", Severity.HINT,
                 "A call of a vendor's known probing or tool-setting cycle that is not in the "
                 "workspace: it lives on the control.", FAMILY)
MB409 = RuleInfo("MB409", "m-code-call-not-set-up", Severity.HINT,
                 "An M code with P and argument words, as a macro call through a parameter "
                 "takes, that the settings do not set up as a call.", FAMILY)
MB410 = RuleInfo("MB410", "resident-program-range", Severity.HINT,
                 "A call of a program numbered O8000-O9999, the ranges the control keeps for "
                 "its resident programs, that is not in the workspace.", FAMILY)
MB411 = RuleInfo("MB411", "argument-not-used", Severity.WARNING,
                 "A G65/G66 argument whose local the called program never names: its value is "
                 "lost.", FAMILY)
MB412 = RuleInfo("MB412", "m98-argument", Severity.WARNING,
                 "A word of an M98 block that the subprogram reads as an argument: M98 passes "
                 "none.", FAMILY)
MB413 = RuleInfo("MB413", "m98-sets-callers-local", Severity.WARNING,
                 "A subprogram called by M98 sets a local its caller counts with across the "
                 "call: they share #1-#33.", FAMILY)
# fmt: on


# "The units used for argument data passed without a decimal point correspond to the least
# input increment of each address" (FANUC 16i/18i Operator's Manual B-63684EN, Custom macro,
# "Position of the decimal point"): lengths and angles (0.001 mm or degree on IS-B) are scaled;
# S, T, M, D, H take whole numbers and F is in mm/min (1 mm/min on IS-B), so those are not.
# E has no axis on a mill and its increment is not settled (a lathe's precise lead): left out.
SCALED_ARGUMENTS = frozenset("ABCIJKQRUVWXYZ")

# Parameter 3202 #0 NE8 and #4 NE9 forbid editing the programs O8000-O8999 and O9000-O9999
# (FANUC Series 0i-F Parameter Manual B-64610EN, "Parameters of program"; also the 16i/18i
# B-63530EN): the ranges machine builders, vendors and shops keep their resident programs in,
# and the custom G/M/T code calls' targets (O9000-O9029). Unverified against a copy here.
_RESIDENT_RANGES = ((8000, 8999, "NE8"), (9000, 9999, "NE9"))


def resident_range(number: int) -> Text | None:
    """The protected range ``number`` is in, as a message names it; None outside them."""
    for low, high, bit in _RESIDENT_RANGES:
        if low <= number <= high:
            return tr(
                "O{low}-O{high} holds the control's resident programs (parameter 3202 {bit} "
                "locks their editing)",
                low=low,
                high=high,
                bit=bit,
            )
    return None


MB401_DOC = RuleDoc(
    "MB401",
    reports="""
An NC statement and a macro statement in the same block:
`G01 X#1 #1=#1-2.`, `G00 Z2. GOTO20`, `#2=0 G00 X100.`.
""",
    why="""
FANUC raises PS0127 DUPLICATE NC,MACRO STATEMENT and stops at
the block. Controls that accept it (Haas, LinuxCNC) do not agree on the order in which the two
parts run, so even there the value used by the move is uncertain.
""",
    example="""
```nc
O2008 (FACING PASSES)
N10 G01 X#1 #1=#1-2.
M30
```
""",
    fix="""
Put the macro statement in its own block, before or after the NC block as
intended.
""",
    not_reported="""
A sequence number, a block skip `/` or a comment beside a macro
statement (`N10 #1=5`, `/#2=0 (SKIP)`), `IF [...] THEN` with one assignment, and NC blocks whose
words are variables or expressions (`G01 X#1 Z[#2-1.]`): those are NC statements.
""",
)


def check_line(parsed: ParsedLine) -> Iterable[LineFinding]:
    statement = parsed.statement
    if not isinstance(statement, Mixed):
        return ()
    m = statement.macro.span
    n = statement.nc.span
    return (
        LineFinding(
            "MB401",
            tr(
                "macro statement {macro_text} in the same block as NC words {nc_text}: FANUC "
                "raises PS0127; put them in separate blocks",
                macro_text=repr(parsed.text[m.start : m.end]),
                nc_text=repr(parsed.text[n.start : n.end]),
            ),
            m.start,
            m.end,
        ),
    )


MB402_DOC = RuleDoc(
    "MB402",
    reports="""
`G`, `L`, `N`, `O` or `P` used as an argument of `G65`/`G66`:
`G65 P9010 A10. G01.`. `P` (the program) and `L` (the repeat count) are not arguments; `G` is
allowed only with `G66.1`.
""",
    why="""
These letters cannot pass a value to the macro: `G` raises
PS0129 USE 'G' AS ARGUMENT, and the others are read as the call's own program number, repeat
count or sequence number. The macro never receives the value, and the call stops or runs with
another value than the one written.
""",
    example="""
```nc
O1002 (POCKET CALL)
G65 P9010 A10. B20. G01.
M30
```
""",
    fix="""
Pass the value through another letter (`A`–`Z` except `G L N O P`) and read the
matching local in the macro (`D` → `#7`, `E` → `#8`, ...).
""",
    not_reported="""
`G` in a `G66.1` block (it is a word of the block, passed as an
argument), the call's own `P` and `L`, and `M98`, which takes no arguments.
""",
)


MB404_DOC = RuleDoc(
    "MB404",
    reports="""
A `G65`/`G66` argument of a length or angle address written as a number
without a decimal point: `A10`, `Z-10`, `R5` (the letters A B C I J K Q R U V W X Y Z).
""",
    why="""
Without a decimal point the value passed to the macro is
counted in least input increments: with metric IS-B, `A10` arrives as `0.01`, not `10.`,
unless calculator-type decimal point input (parameter 3401#0) is set. A depth of `Z10` becomes
0.01 mm on one machine and 10 mm on the next: an air cut, or a tool driven 10 mm into the part.
""",
    example="""
```nc
O0001 (DRILL CALL)
G65 P9001 A10 B2.5 Z-10.
M30
```
""",
    fix="""
Write every argument with a decimal point: `A10.`, `Z-10.`, `R5.`. The quick fix in
the editor adds the `.` after the argument's digits.
""",
    not_reported="""
A zero (`X0` is 0 in any increment); `S`, `T`, `M`, `D` and
`H`, which take whole numbers, and `F`, counted in mm/min whatever the increment (FANUC: the
units of an argument without a decimal point are the least input increment of its address);
`E`, whose increment is not settled (`G65 P3001 E41` passes the G code 41 to a `G#8`);
arguments given by variables or expressions (`A#1`, `B[10]`), which carry their value as it
is; the words of `M98` and a `G66.1` block's own G codes, which are not arguments.
""",
)


MB405_DOC = RuleDoc(
    "MB405",
    reports="""
An `L` repeat count outside 1–9999 on `M98`/`G65` (`L0`, `L10000`, also the
leading digits of `M98 P<rrrr><pppp>`), or a call without `P`. An `M98 Q<n>` without `P`
calls the block `N<n>` of its own program (FANUC 0i-F / 30i, "Subprogram call"; unverified
against the manual's text): it is reported when the program has no `N<n>`.
""",
    why="""
The control rejects the block with an alarm, and without `P`
there is no program to call. A repeat count of 0 intended to skip the call does not do so on
every control.
""",
    example="""
```nc
O0010 (BOLT CIRCLE)
M98 P0011 L0
M98 L2
M30
```
""",
    fix="""
Give `P` and a repeat count from 1 to 9999; skip the call with `IF [...] GOTO`
instead of `L0`.
""",
    not_reported="""
A repeat count computed at run time (`L#2`) or not written (one
run; a `G66` without `L` calls the macro after each move). An `M98 Q<n>` whose program has
`N<n>`: the evaluator runs that block as a subprogram, up to its `M99`.
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    local_programs = {p.number for p in ctx.index.programs if p.number is not None}
    known = local_programs | set(ctx.workspace_programs or ())
    # Calls of a program that is not there, by program: one diagnostic each, at the first call.
    missing: dict[int, list[IndexCall]] = {}
    vendor: dict[int, list[IndexCall]] = {}  # known vendor cycles, MB408's
    resident: dict[int, list[IndexCall]] = {}  # O8000-O9999, MB410's
    for program in ctx.index.programs:
        for call in program.calls:
            line = call.line
            span = call.span
            if call.kind == "M97":
                continue  # Haas local subroutine: MB002 says so
            words = _words(ctx, line)
            if call.program_span is None:
                if call.kind == "M98" and any(w.address == "H" for w in words):
                    continue  # Citizen's M98 H<n>: MB002 says so
                q_word = next((w for w in words if w.address == "Q"), None)
                if call.kind == "M98" and q_word is not None:
                    yield from _internal_call(program, call, q_word)
                    continue
                yield make(
                    MB405,
                    tr("{call} without P: no program to call", call=call.kind),
                    line,
                    span.start,
                    span.end,
                )
                continue
            number = call.program
            if number is not None and number not in known and not on_control(ctx.config, number):
                kept = (
                    vendor
                    if known_cycle(number)
                    else resident
                    if resident_range(number)
                    else missing
                )
                kept.setdefault(number, []).append(call)
            if call.repeat is not None and not 1 <= call.repeat <= 9999:
                l_word = next((w for w in words if w.address == "L"), None)
                at = l_word.span if l_word is not None else span
                yield make(
                    MB405,
                    tr(
                        "{call} repeat count {count} is outside 1-9999",
                        call=call.kind,
                        count=call.repeat,
                    ),
                    line,
                    at.start,
                    at.end,
                )
            for word in call.arguments:
                if word.address in FORBIDDEN_ARGUMENTS and not (
                    call.kind == "G66.1" and word.address == "G"
                ):
                    yield make(
                        MB402,
                        tr(
                            "{address} cannot be a {call} argument; "
                            "arguments are A-Z except G, L, N, O, P",
                            address=word.address,
                            call=call.kind,
                        ),
                        line,
                        word.span.start,
                        word.span.end,
                    )
                elif (
                    word.address in SCALED_ARGUMENTS
                    and isinstance(word.value, Num)
                    and not word.value.has_decimal_point
                    and word.value.value != 0.0  # 0 is 0 in any increment
                ):
                    value = word.value.value
                    yield make(
                        MB404,
                        tr(
                            "argument {address}{value_text} has no decimal point: the macro "
                            "receives {value:g} x the least input increment (e.g. {is_b:g} on "
                            "IS-B), not {value:g}; write {address}{value_text}.",
                            address=word.address,
                            value_text=word.value.text,
                            value=value,
                            is_b=value / 1000,
                        ),
                        line,
                        word.span.start,
                        word.span.end,
                        fixes=(_decimal_point(line, word.address, word.value),),
                    )
    yield from _missing_programs(ctx, missing)
    yield from _missing_programs(ctx, vendor)
    yield from _missing_programs(ctx, resident)
    yield from _m_calls_not_set_up(ctx)
    yield from _arguments_not_used(ctx)
    yield from _subprogram_arguments(ctx)
    yield from _subprogram_sets_callers_local(ctx)


def _internal_call(program: Program, call: IndexCall, q_word: Word) -> Iterator[Diagnostic]:
    """``M98 Q<n>`` without P calls the block N<n> of its own program (FANUC 0i-F / 30i; see
    evaluator.calls): MB405 when the program has no N<n> (a computed Q is not known here)."""
    q = constant_value(q_word.value)
    if q is None or (q == int(q) and program.label_line(int(q)) is not None):
        return
    number = f"{q:g}"
    yield make(
        MB405,
        tr(
            "M98 Q{number} calls N{number} of {program}, which has none (alarm "
            "PS0078 SEQUENCE NUMBER NOT FOUND)",
            number=number,
            program=program.display_name,
        ),
        call.line,
        q_word.span.start,
        q_word.span.end,
    )


def _decimal_point(line: int, address: str, value: Num) -> Fix:
    """MB404: ``.`` right after the argument's digits (``A10`` becomes ``A10.``), the value
    the programmer wrote, in the address's units."""
    return Fix(
        tr("Add the decimal point: {address}{value_text}.", address=address, value_text=value.text),
        (FixEdit.insert(line, value.span.end, "."),),
        preferred=True,
    )


class _LineEnds(NamedTuple):
    """What one line holds for MB406 / MB407, worked out once per distinct line."""

    has_statement: bool
    stops: bool  # its last statement never falls through (a jump, the program's own alarm)
    ends: bool  # M02, M30 or M99
    cancels_modal_call: bool  # G67


MB403_DOC = RuleDoc(
    "MB403",
    reports="""
`M98 P`, `G65 P`, `G66 P` or `G66.1 P` with a constant program number that
is in neither the file nor the other files checked with it (a folder or the files given together
on the command line, the open workspace in the editor). `M98 P0013331` is read as one call of
O3331. A file without an O line whose name is a program number (`O8501.NC`, see MB010) holds
that program. Each missing program is reported once, at its first call; the message counts the
calls and lists the other lines.
""",
    why="""
If the program is not in the control's memory either, the
call raises PS0076 PROGRAM NOT FOUND and the program stops there. It is a warning because the
called program often is on the control (a probing or tool-change macro) but not beside the
file.
""",
    example="""
```nc
O1000 (MAIN)
M98 P2000
M30
```
""",
    fix="""
Check the called program in the same run (`fanuc-macro check main.nc subs/`),
correct the number, or disable the rule for programs that live only on the control.
""",
    not_reported="""
Calls whose program number is computed (`M98 P#1`: the evaluator
reports where it leads, MB706), Haas `M97` (MB002), and each further call of a program already
reported. Programs the control calls through parameters (custom G and M codes calling
O9010–O9029, a T code calling O9000, set up in `machine.customCalls`), which the parameter
says the control has. A program listed in `machine.programsOnControl` (`--on-control`), and
a vendor's known cycle (MB408 names it), and a program numbered O8000-O9999, the ranges of
resident programs (MB410's hint). A program in another
file of the workspace, or of the files given together, or a file without an O line named by
the number. Nothing, in a file read only in part (MB013): the program may be in the unread part.
""",
)


MB408_DOC = RuleDoc(
    "MB408",
    reports="""
`G65 P`, `G66 P` or `M98 P` with the number of a probing or tool-setting cycle a vendor
installs on the control (Renishaw Inspection Plus O9801-O9843, the tool setting cycles
O9851-O9858; `program/vendor_cycles.py` lists them with their sources), when no file
checked with it holds that program. The hint names the cycle.
""",
    why="""
The cycle is on the control, not beside the shop's programs: its call is no mistake, but the
analysis cannot follow it, and what it does to variables and positions after the call is
unknown. Hovering the call gives the cycle's arguments as the vendor's manual gives them.
""",
    example="""
```nc
O1000 (BORE CHECK)
G65 P9814 D50. Z-10. S1.
M30
```
""",
    fix="""
Nothing to fix. Check the cycle's copy with the program (`fanuc-macro check main.nc probe/`)
to have its run followed; list the programs with `machine.programsOnControl`
(`--on-control O9000-O9999`) to silence the hint.
""",
    not_reported="""
A cycle in the workspace (it is run), and a number the settings list as kept on the control.
Other numbers not in the workspace are MB403's.
""",
)


MB410_DOC = RuleDoc(
    "MB410",
    reports="""
`M98 P`, `G65 P`, `G66 P` or `G66.1 P` with a constant number in O8000-O8999 or O9000-O9999
that no file checked with it holds, and that is no vendor's known cycle (MB408's). Each
program once, at its first call, with the other calls as related places.
""",
    why="""
Those two ranges are the ones the control can protect from editing (parameter 3202, NE8 and
NE9): machine builders, probe vendors and shops keep their resident programs there (a tool
change, a pallet change, a probing routine), in the control's memory rather than beside the
part programs. The call is most likely right, but the analysis cannot follow it, and if the
program is not in the memory the control stops with PS0076 PROGRAM NOT FOUND.
""",
    example="""
```nc
O1000 (LATHE PART)
/2 M98 P8001 (BAR PULL)
M30
```
""",
    fix="""
Nothing to fix when the program is on the control: list it in `machine.programsOnControl`
(`--on-control O8000-O9999`) to silence the hint, or check its copy with the program
(`fanuc-macro check main.nc resident/`) to have its run followed.
""",
    not_reported="""
A program in the workspace (it is run), one the settings list as kept on the control, a
vendor's known cycle (MB408), a computed number (`M98 P#1`). Numbers outside the two ranges
are MB403's warnings.
""",
)


def _missing_programs(
    ctx: RuleContext, missing: dict[int, list[IndexCall]]
) -> Iterator[Diagnostic]:
    """MB403 once per missing program, at its first call, with the others as related places."""
    if ctx.doc.unread_from is not None:
        return  # the programs may be in the part of this file the analysis does not read
    where = tr("this file") if ctx.workspace_programs is None else tr("the workspace")
    for number, calls in missing.items():
        first = calls[0]
        span = first.program_span
        assert span is not None
        cycle = known_cycle(number)
        protected = resident_range(number)
        if cycle is not None:
            code = MB408
            message = tr(
                "{call} calls {cycle}; a cycle kept on the control, not in {where}: the "
                "analysis does not follow it",
                call=first.kind,
                cycle=describe(cycle),
                where=where,
            )
        elif protected is not None:
            code = MB410
            message = tr(
                "{call} calls O{number:04d}, which is not in {where}: {protected}; the call "
                "needs it in the control's memory (alarm PS0076 if not)",
                call=first.kind,
                number=number,
                where=where,
                protected=protected,
            )
        else:
            code = MB403
            message = tr(
                "{call} calls O{number:04d}, which is not in {where} (alarm PS0076 if it is not "
                "in the control's memory)",
                call=first.kind,
                number=number,
                where=where,
            )
        if len(calls) > 1:
            also = line_list([c.line for c in calls[1:]])
            message = tr(
                "{message}; it is called {count} times in all (also at lines {lines})",
                message=message,
                count=len(calls),
                lines=also,
            )
        yield make(
            code,
            message,
            first.line,
            span.start,
            span.end,
            related=[
                Related(c.line, 0, 0, tr("O{number:04d} called again here", number=number))
                for c in calls[1:20]
            ],
            data={"program": number},
        )


MB409_DOC = RuleDoc(
    "MB409",
    reports="""
A block with an M code that is not a standard FANUC code, with no G code, with a `P` word and
an argument word that a plain M block never takes (A-E, I-K, Q, R, U-W):
`M165 P9814 D1.415 S1.`. Such a block is a macro call through an M code (parameters 6080-6089
register the M code that calls O9020-O9029) on the machine it was written for.
""",
    why="""
Without the setting, the program the block calls is not run: nothing in it is checked, and its
arguments are not known to it. The block's words are not checked as NC words either (`D1.415` is
an argument, not an offset number).
""",
    example="""
```nc
O1000 (PROBE)
M165 P9814 D1.415 S1.
M30
```
""",
    fix="""
Set the code up as the control's parameter does, in the setting `machine.customCalls`:
`{"M165": 9022}` (`--custom-call M165=9022`).
""",
    not_reported="""
An M code set up in `machine.customCalls`, the standard M codes, a block with a G code, and an
M block with only P (`M98`-like codes of other controls are MB002's).
""",
)


def _m_calls_not_set_up(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB409: the candidates whose M code the settings do not set up as a call."""
    for line, value, start, end in unset_m_calls(ctx.doc, ctx.config.custom_calls):
        code = f"M{value:g}"
        yield make(
            MB409,
            tr(
                "{code} with P and argument words reads as a macro call through an M code, which "
                "the settings do not set up: name the program the control's parameter "
                "(6080-6089) makes it call, one of O9020-O9029, in machine.customCalls "
                '({{"{code}": 9022}}, --custom-call {code}=9022)',
                code=code,
            ),
            line,
            start,
            end,
        )


def _line_ends(parsed: ParsedLine) -> _LineEnds:
    statements = statements_of(parsed.statement)
    ends = g67 = False
    for statement in statements:
        if not isinstance(statement, NcStatement):
            continue
        for word in statement.words:
            address = word.address
            if address == "M":
                ends = ends or constant_value(word.value) in (2.0, 30.0, 99.0)
            elif address == "G":
                g67 = g67 or constant_value(word.value) == 67.0
    return _LineEnds(bool(statements), bool(statements) and _stops_here(statements[-1]), ends, g67)


_ends_of: PerLine[_LineEnds] = PerLine(_line_ends)
_ENDS_AND_G67 = frozenset({("M", 2.0), ("M", 30.0), ("M", 99.0), ("G", 67.0)})


def _end_or_g67(parsed: ParsedLine) -> _LineEnds | None:
    statement = parsed.statement
    if type(statement) is PlainNc:
        # Its G and M codes say it at once, without a cache entry for every line.
        for code in statement.codes:
            if code in _ENDS_AND_G67:
                break
        else:
            return None
    elif type(statement) is NcStatement:
        for word in statement.words:  # as a plain block's codes, from its words' values
            address = word.address
            if (address == "M" or address == "G") and (
                address,
                constant_value(word.value),
            ) in _ENDS_AND_G67:
                break
        else:
            return None
    elif type(statement) is not Mixed:
        return None  # only NC words end a program or cancel a modal call
    # Not through the per-line cache: the map keeps what it finds and looks again only at the
    # lines that changed (the cache serves the programs' last blocks, below).
    found = _line_ends(parsed)
    return found if found.ends or found.cancels_modal_call else None


# The blocks that end a program or cancel a modal call: few, and kept from edit to edit.
_ends_and_g67s: LineMap[_LineEnds] = LineMap(_end_or_g67)


MB406_DOC = RuleDoc(
    "MB406",
    reports="""
A `G66` or `G66.1` modal call with no `G67` after it in the same O
program.
""",
    why="""
After `G66 P...`, the control calls the macro after every
block that moves an axis, until `G67`. FANUC requires the `G66` and its `G67` in one program.
Without the `G67`, the retract and the moves to the tool change at the end of the program each
call the macro too: a hole is drilled at the retract position, or the pattern is repeated
where no part is.
""",
    example="""
```nc
O0001 (DRILL PATTERN)
G66 P1001 Z-5. R2. F100.
X50. Y0
X100. Y0
G00 Z100.
M30
O1001
G81 Z#26 R#18 F#9
M99
```
""",
    fix="""
Put `G67` after the last block that should call the macro (here before
`G00 Z100.`).
""",
    not_reported="""
A `G66` whose `G67` stands later in the same program, on any
path; a `G67` without `G66`; a program that goes on past the part of a big file the analysis
reads (MB013), whose `G67` may stand in the unread part.
""",
)


def check_programs(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB406 and MB407: what each O program must hold from its first block to its last."""
    programs = ctx.index.programs
    unread = ctx.doc.unread_from
    blocks = ctx.doc.blocks
    found_ends = _ends_and_g67s(ctx.doc)
    marked_lines, marked = found_ends.lines, found_ends.values
    for i, program in enumerate(programs):
        if program.number is None:
            continue  # text before the first O number: a fragment, or MB010's
        if unread is not None and program.end_line >= unread:
            continue  # its end, and a G67, may be in the part the analysis does not read
        # After the O line; a program named by its file (no O line) from its first block.
        first = program.first_line + (1 if program.header_line is not None else 0)
        lo = bisect_left(marked_lines, first)
        hi = bisect_left(marked_lines, program.end_line)
        ends = any(found.ends for found in marked[lo:hi])
        g67_lines = [
            line
            for line, found in zip(marked_lines[lo:hi], marked[lo:hi], strict=True)
            if found.cancels_modal_call
        ]
        last_statement = next(
            (
                line
                for line in range(program.end_line - 1, first - 1, -1)
                if blocks[line].parsed.statement is not None
            ),
            None,
        )
        last_stops = last_statement is not None and _ends_of(blocks[last_statement].parsed).stops
        for call in program.calls:
            if call.kind in ("G66", "G66.1") and not (g67_lines and g67_lines[-1] > call.line):
                yield make(
                    MB406,
                    tr(
                        "{call} at line {line} has no G67 after it in {program}: every later "
                        "block that moves an axis calls the macro again, to the end of the "
                        "program (FANUC: G66 and G67 pair in one program)",
                        call=call.kind,
                        line=call.line + 1,
                        program=program.display_name,
                    ),
                    call.line,
                    call.span.start,
                    call.span.end,
                )
        if ends or last_stops or last_statement is None:
            continue
        if _calls_outside(ctx, program, last_statement):
            continue  # the program it calls last, not in the files, may end the run
        yield _not_ended(
            ctx, program, programs[i + 1] if i + 1 < len(programs) else None, last_statement
        )


def _calls_outside(ctx: RuleContext, program: Program, line: int) -> bool:
    """Whether the block at ``line`` calls a program not in the analysed files (or one whose
    number is computed): what that program does at its end (M30, M99) is not known."""
    known = {p.number for p in ctx.index.programs} | set(ctx.workspace_programs or ())
    return any(
        call.line == line and (call.program is None or call.program not in known)
        for call in program.calls
        if call.kind in ("M98", "G65")
    )


def _stops_here(statement: Statement) -> bool:
    """A last block that never falls through: a jump back, or the program's own alarm."""
    if isinstance(statement, Goto):
        return True
    if isinstance(statement, Assign) and isinstance(statement.target, Var):
        return statement.target.number == 3000.0  # #3000=n stops with alarm 3000+n
    return False


def _calls_by_number(ctx: RuleContext) -> dict[int | None, list[tuple[Program, IndexCall]]]:
    """The calls of each program number with the program that makes them: gathered once, not
    for each program that has no end."""
    found = ctx.memo.get("statements.calls")
    if found is None:
        by_number: dict[int | None, list[tuple[Program, IndexCall]]] = {}
        for p in ctx.index.programs:
            for c in p.calls:
                by_number.setdefault(c.program, []).append((p, c))
        found = ctx.memo["statements.calls"] = by_number
    return cast("dict[int | None, list[tuple[Program, IndexCall]]]", found)


MB407_DOC = RuleDoc(
    "MB407",
    reports="""
An O program with no `M30`, `M02` or `M99` anywhere in it, whose last block
is not a jump or a `#3000` alarm. When the next O number cuts it off, it is reported on that O
line (a second O number in the middle of a program); otherwise on the program's last block.
""",
    why="""
A subprogram without `M99` never returns to its caller: the
blocks after the `M98` or `G65` (the retract, the spindle stop) are not run. An O number typed
in the middle of a program splits it into two when the file is loaded: the first part stops
without an end, the second runs without the setup of the first.
""",
    example="""
```nc
O0201 (POCKET)
G54 G90 G00 X0 Y0
S1000 M03
O0202
G01 Z-5. F100.
M30
```
""",
    fix="""
End every program with `M30` (main program) or `M99` (subprogram or macro);
delete an O number that does not start a program of its own.
""",
    not_reported="""
Text before the first O number (MB010 speaks of it), programs
that end with `GOTO` or `#3000=n`, and a program that goes on past the part of a big file the
analysis reads (MB013): its end is in the unread part. Nor a program whose last block calls a
program that is not in the analysed files (`M98 P9004` of a program kept on the control): what
that program does at its end (`M30`, `M99`) is not known.
""",
)


def _not_ended(
    ctx: RuleContext, program: Program, following: Program | None, last_statement: int
) -> Diagnostic:
    name = program.display_name
    callers = [
        (p.display_name, c.kind, c.line)
        for p, c in _calls_by_number(ctx).get(program.number, ())
        if p is not program
    ]
    closed_by_tape_mark = any(
        ctx.doc.blocks[line].parsed.tape_mark for line in range(last_statement, program.end_line)
    )
    if (
        following is not None
        and following.header_line == program.end_line
        and not closed_by_tape_mark
    ):
        line = following.header_line
        block = ctx.doc.blocks[line]
        span = block.statement.span if block.statement is not None else None
        start, end = (span.start, span.end) if span is not None else (0, 0)
        return make(
            MB407,
            tr(
                "{following} starts here while {program} (line {line}) has no M30, M02 or M99: "
                "in the control's memory {program} ends at line {last} without an end, and the "
                "blocks from here on are another program",
                following=following.display_name,
                program=name,
                line=program.first_line + 1,
                last=last_statement + 1,
            ),
            line,
            start,
            end,
        )
    text = ctx.doc.blocks[last_statement].parsed.text
    if callers:
        caller, kind, call_line = callers[0]
        why = tr(
            "it is called with {call} from {caller} (line {line}), and without M99 the control "
            "never returns there",
            call=kind,
            caller=caller,
            line=call_line + 1,
        )
    else:
        why = tr(
            "as a subprogram or macro it never returns to its caller, and as a main program "
            "it leaves the end to the '%'; add M99 or M30"
        )
    return make(
        MB407,
        tr("{program} ends at this block without M30, M02 or M99: {why}", program=name, why=why),
        last_statement,
        0,
        len(text.rstrip()),
    )


def _words(ctx: RuleContext, line: int) -> tuple[Word, ...]:
    for statement in statements_of(ctx.doc.blocks[line].statement):
        nc = statement.words if isinstance(statement, IfNc) else statement
        if isinstance(nc, NcStatement):
            return nc.words
    return ()


MB411_DOC = RuleDoc(
    "MB411",
    reports="""
An argument word of a `G65`, `G66` or `G66.1` call (`I5.`, `R20.`) whose local variable (I
#4, R #18, by argument specification I, or II for repeated I, J, K) the called program never
names, in any block, or always sets before it reads it (a program without `GOTO`, whose
blocks run in the order of the lines, sets it on an earlier line outside any loop the read is
not in). The called program must be in the files checked (this one or the others given with
it). The message names the locals the program reads before it sets them that the call does
not pass: usually the letter meant.
""",
    why="""
A G65 call gives its arguments to the called program's locals and nothing else: an argument
the program never reads is lost, and the local the programmer meant to fill stays vacant.
`G65 P9010 I50. H6.` to a bolt circle that reads its radius from `#18` (R) drills six holes
at the centre: #18 is vacant, and a vacant variable counts as 0.
""",
    example="""
```nc
O1000 (SIX HOLES ON A 50 MM RADIUS)
G65 P9010 I50. H6. Z-10. F150.
M30
O9010 (BOLT CIRCLE)
#1=0
WHILE[#1LT#11]DO1
G81 X[#18*COS[#1*360/#11]] Y[#18*SIN[#1*360/#11]] Z#26 R2. F#9
#1=#1+1
END1
G80
M99
```
""",
    fix="""
Pass the letter the program reads (`R50.` for #18), or read the argument in the program.
""",
    not_reported="""
A program that names a local indirectly (`#[#1+4]`: it may read any of them) or calls a
subprogram with `M98` (it shares the locals, and may read them there), one that names no local
at all (a placeholder of a cycle kept on the control, a program of fixed moves), a called
program not in
the files checked (MB403, MB408, MB410), a computed program number, `M98` (it passes no
arguments), and the codes the settings make call a program (their words are checked as
arguments only by the run).
""",
)


def _arguments_not_used(ctx: RuleContext) -> Iterator[Diagnostic]:
    for program in ctx.index.programs:
        for call in program.calls:
            if call.kind not in _MACRO_CALLS or call.code is not None or call.program is None:
                continue
            found = ctx.program_numbered(call.program)
            if found is None:
                continue
            doc, callee = found
            use = ctx.locals_named(doc, callee)
            if use is None or not use.named:  # no local at all: a placeholder, fixed moves
                continue
            words = call.arguments
            numbers = argument_numbers([w.address for w in words])
            given = {n for n in numbers if n is not None}
            wanted = [n for n in use.read_first if n not in given]
            also: Text | None = None
            if wanted:
                names = ", ".join(local_name(n) for n in wanted[:4])
                also = (
                    tr(
                        "it reads {variables} and more, which this call does not pass",
                        variables=names,
                    )
                    if len(wanted) > 4
                    else tr("it reads {variables}, which this call does not pass", variables=names)
                )
            for word, n in zip(words, numbers, strict=True):
                if n is None or n in use.used:
                    continue
                written = ctx.doc.blocks[call.line].text[word.span.start : word.span.end]
                fate = (
                    tr("sets #{number} before it reads it", number=n)
                    if n in use.named
                    else tr("never uses #{number}", number=n)
                )
                lost = tr(
                    "{word_text} gives #{number} to {program}, which {fate}: the value is lost",
                    word_text=written.strip(),
                    number=n,
                    program=callee.display_name,
                    fate=fate,
                )
                yield make(
                    MB411,
                    lost if also is None else tr("{message}; {more}", message=lost, more=also),
                    call.line,
                    word.span.start,
                    word.span.end,
                )


def _m98_calls(
    ctx: RuleContext,
) -> Iterator[tuple[Program, IndexCall, Document, Program, LocalsNamed]]:
    """Each M98 with a constant P whose subprogram is in the files checked and names its
    locals directly: the caller, the call, the subprogram's document, it and its locals."""
    for program in ctx.index.programs:
        for call in program.calls:
            if call.kind != "M98" or call.program is None:
                continue
            found = ctx.program_numbered(call.program)
            if found is None:
                continue
            doc, callee = found
            use = ctx.locals_named(doc, callee, with_subprograms=False)
            if use is not None:
                yield program, call, doc, callee, use


MB412_DOC = RuleDoc(
    "MB412",
    reports="""
A word of an `M98` block (`R50.`, `H6.`) whose argument local (R #18, H #11) the called
subprogram reads before it sets it, when the calling program never names that local and takes
none from a caller of its own (it reads no local before setting it): the word was meant as an
argument, as `G65` passes one. The subprogram must be in the files checked.
""",
    why="""
`M98` passes no arguments: the subprogram shares its caller's locals, and the block's other
words are NC words, executed before the call (an `R` or `H` alone does nothing, an `X` moves).
The subprogram reads the local vacant, as 0, or leaves the word out of its blocks.
""",
    example="""
```nc
O1000 (SIX HOLES ON A 50 MM RADIUS)
M98 P9010 R50. H6.
M30
O9010 (BOLT CIRCLE)
#1=0
WHILE[#1LT#11]DO1
G81 X[#18*COS[#1*360/#11]] Y[#18*SIN[#1*360/#11]] Z-10. R2. F150.
#1=#1+1
END1
G80
M99
```
""",
    fix="""
Call it with `G65 P9010 R50. H6.`, or set the locals before the `M98` (`#18=50.`).
""",
    not_reported="""
Words whose local the subprogram does not read before setting it, or that the calling program
names (it may set it before the call), a calling program that reads a local before setting it
(a macro or subprogram whose locals come from its own caller), `P`, `L`, `Q`, `M`, a subprogram
not in the files checked, and one that names a local indirectly (`#[...]`).
""",
)


def _subprogram_arguments(ctx: RuleContext) -> Iterator[Diagnostic]:
    for program, call, _doc, callee, use in _m98_calls(ctx):
        meant: list[tuple[Word, int]] = []
        for word in _words(ctx, call.line):
            n = ARGUMENT_VARIABLES.get(word.address)
            if n is not None and word.address not in _NOT_M98_ARGUMENTS and n in use.read_first:
                meant.append((word, n))
        if not meant:
            continue  # most calls: P and L alone; the caller's locals need not be read
        caller = ctx.locals_named(ctx.doc, program, with_subprograms=False)
        if caller is None or caller.read_first:
            continue
        meant = [(w, n) for w, n in meant if n not in caller.named]
        if not meant:
            continue
        text = ctx.doc.blocks[call.line].text
        words = " ".join(text[w.span.start : w.span.end].strip() for w, _ in meant)
        locals_ = ", ".join(f"#{n} ({w.address})" for w, n in meant)
        yield make(
            MB412,
            tr_n(
                "{words_text} is no argument: M98 passes none, and {program} reads {variables} "
                "before setting it, vacant here; G65 P{number} passes it",
                "{words_text} are no arguments: M98 passes none, and {program} reads "
                "{variables} before setting them, vacant here; G65 P{number} passes them",
                len(meant),
                words_text=words,
                program=callee.display_name,
                variables=locals_,
                number=call.program,
            ),
            call.line,
            meant[0][0].span.start,
            meant[-1][0].span.end,
        )


MB413_DOC = RuleDoc(
    "MB413",
    reports="""
An `M98 P...` call whose subprogram sets a local (`#1`-`#33`) before reading it, where the
calling program set that local before the call and, after the call, counts with it: updates it
from itself (`#1 = #1 + 1`) on a later line, or tests it in the `WHILE` of a loop around the
call. The message names the local, the subprogram's line that sets it and the caller's line
that counts with it.
""",
    why="""
M98 opens no local level: the subprogram's `#1`-`#33` are its caller's (0i-F Custom Macro,
"Local variables"; G65 opens a new level). A subprogram that uses `#1` for its own counter
overwrites the caller's row counter: the caller's loop ends early, runs again from another
value, or never ends.
""",
    example="""
```nc
O1000
#1 = 0
WHILE [#1 LT 3] DO1
M98 P2000
#1 = #1 + 1
END1
M30
O2000
#1 = 0
WHILE [#1 LT 4] DO1
#1 = #1 + 1
END1
M99
```
""",
    fix="""
Give the subprogram locals the caller does not use (or common variables), or call it with
`G65 P2000`, which gives it locals of its own.
""",
    not_reported="""
A local the subprogram reads before setting (a value it takes from its caller, or gives back),
a local the caller only reads after the call (a value the subprogram returns), subprograms not
in the files checked or called by a computed P, and programs that name a local indirectly
(`#[...]`).
""",
)


def _subprogram_sets_callers_local(ctx: RuleContext) -> Iterator[Diagnostic]:
    caller_uses: dict[int, list[LocalUse] | None] = {}
    for program, call, doc, callee, named in _m98_calls(ctx):
        own = named.named - set(named.read_first)  # set before any read of it
        if not own:
            continue
        if program.first_line not in caller_uses:
            caller_uses[program.first_line] = local_uses(ctx.doc, program)
        uses, callee_uses = caller_uses[program.first_line], local_uses(doc, callee)
        if uses is None or callee_uses is None:
            continue
        counted = _counted_across(program, uses, call.line)
        for n in sorted(own & counted.keys()):
            sets = next(u.line for u in callee_uses if u.sets == n)
            yield make(
                MB413,
                tr(
                    "M98 P{number} shares this program's locals, and {program} sets #{variable} "
                    "on line {line}, which this program counts with on line {counted}: after the "
                    "call #{variable} holds {program}'s value; G65 gives the subprogram locals "
                    "of its own",
                    number=call.program,
                    program=callee.display_name,
                    variable=n,
                    line=sets + 1,
                    counted=counted[n] + 1,
                )
                if doc is ctx.doc
                else tr(
                    "M98 P{number} shares this program's locals, and {program} sets #{variable} "
                    "on line {line} of its file, which this program counts with on line "
                    "{counted}: after the call #{variable} holds {program}'s value; G65 gives "
                    "the subprogram locals of its own",
                    number=call.program,
                    program=callee.display_name,
                    variable=n,
                    line=sets + 1,
                    counted=counted[n] + 1,
                ),
                call.line,
                call.span.start,
                call.span.end,
            )


def _counted_across(program: Program, uses: list[LocalUse], line: int) -> dict[int, int]:
    """The locals a program sets before ``line`` and counts with after it: updates from
    themselves on a later line, or tests in the WHILE of a loop around it; by the line."""
    before = {u.sets for u in uses if u.line < line and u.sets is not None}
    counted: dict[int, int] = {}
    around = {
        loop.do_line
        for loop in program.loops
        if loop.end_line is not None and loop.do_line < line < loop.end_line
    }
    for u in uses:
        if u.line > line and u.sets is not None and u.sets in u.reads and u.sets in before:
            counted.setdefault(u.sets, u.line)
        elif u.line in around:
            for n in sorted(set(u.reads) & before):
                counted.setdefault(n, u.line)
    return counted


# Words of an M98 block that have their own meaning there: the call, its repeat count, a
# sequence number to call (M98 Q), other M codes.
_NOT_M98_ARGUMENTS = frozenset("MQ")
_MACRO_CALLS = frozenset({"G65", "G66", "G66.1"})
