"""MB3xx: expressions and variables: bracket nesting, variable numbers, read-only targets."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from operator import itemgetter

from ..diagnostics import (
    Diagnostic,
    Fix,
    FixEdit,
    Related,
    RuleDoc,
    RuleInfo,
    Severity,
    make,
)
from ..line_maps import LineMap
from ..program.variables import classify
from ..syntax.parser import default_parser, statements_of
from ..syntax.tree import (
    Assign,
    Binary,
    BlockIf,
    Compare,
    Cond,
    Expr,
    IfGoto,
    IfNc,
    IfThen,
    Logic,
    NcStatement,
    Num,
    ParsedLine,
    PlainNc,
    Statement,
    Unary,
    Var,
    While,
)
from ..syntax.walk import (
    all_line_variables,
    bracket_depth,
    line_variables,
    plain_variables,
    top_expressions,
)
from ..translation import tr, tr_n
from .context import LineFinding, RuleContext

FAMILY = "expressions"
MAX_BRACKET_NESTING = 5

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB301 = RuleInfo("MB301", "bracket-nesting", Severity.ERROR,
                 "Brackets nested more than five deep, function brackets included (PS0118).",
                 FAMILY)
MB302 = RuleInfo("MB302", "no-such-variable", Severity.ERROR,
                 "A variable number that does not exist on a FANUC control (PS0115).", FAMILY)
MB303 = RuleInfo("MB303", "extended-common", Severity.INFORMATION,
                 "A common variable of #200-#499, which exists only with an option.", FAMILY)
MB304 = RuleInfo("MB304", "write-read-only", Severity.ERROR,
                 "An assignment to #0 or to a read-only system variable (PS0116).", FAMILY)
MB305 = RuleInfo("MB305", "logic-operand-unbracketed", Severity.WARNING,
                 "AND, OR or XOR without brackets in a comparison's operand: it binds tighter than "
                 "the comparison and works on the values bit by bit.", FAMILY)
# fmt: on


def check_line(parsed: ParsedLine) -> Iterable[LineFinding]:
    whole = parsed.statement
    if type(whole) is PlainNc:
        return []  # numbers only: no variable, no bracket
    if type(whole) is NcStatement:
        plain = plain_variables(whole)
        if plain is not None:  # no brackets, no condition, no target: only the numbers
            return [f for var in plain if (f := _no_such_variable(var)) is not None]
    if (type(whole) is Assign or type(whole) is NcStatement) and (
        parsed.text.count("[") <= MAX_BRACKET_NESTING
    ):
        # The next most: an assignment, NC words with brackets (no condition). As
        # _check_line: the variables, then the target, at once.
        found = [
            f for var in all_line_variables(parsed) if (f := _no_such_variable(var)) is not None
        ]
        if type(whole) is Assign:
            found.extend(_read_only_target(whole))
        return found
    return list(_check_line(parsed))


MB301_DOC = RuleDoc(
    "MB301",
    reports="""
An expression whose brackets nest more than five deep. Function brackets
(`SIN[`, `SQRT[`) and the brackets of `#[...]` count.
""",
    why="""
FANUC allows five levels; a sixth raises PS0118 TOO MANY
BRACKET NESTING and stops the program at that block.
""",
    example="""
```nc
O9020 (TAPER PASS)
#1=[[[[[[#2+#3]*#4]+#5]*#6]+#7]*#8]
M99
```
""",
    fix="""
Split the expression into steps with intermediate variables:
`#9=[#2+#3]*#4+#5` then `#1=[[#9*#6]+#7]*#8`.
""",
    not_reported="""
Five levels or fewer. The brackets of an `IF` or `WHILE` condition
and those around joined conditions (`[[#1 LT 0] AND [#2 LT 0]]`) are not counted: they are not
expression brackets (whether the control counts them is unverified).
""",
)


def _check_line(parsed: ParsedLine) -> Iterator[LineFinding]:
    # Each level of nesting opens with a "[" of its own: a line of few has none too deep.
    text, whole = parsed.text, parsed.statement
    deep = text.count("[") > MAX_BRACKET_NESTING
    for statement, statement_variables in zip(
        statements_of(whole), line_variables(parsed), strict=True
    ):
        for expr in top_expressions(statement) if deep else ():
            depth = bracket_depth(expr)
            if depth > MAX_BRACKET_NESTING:
                yield LineFinding(
                    "MB301",
                    tr(
                        "brackets nested {depth} deep; FANUC allows {allowed} (alarm PS0118)",
                        depth=depth,
                        allowed=MAX_BRACKET_NESTING,
                    ),
                    expr.span.start,
                    expr.span.end,
                )
        for var in statement_variables:
            finding = _no_such_variable(var)
            if finding is not None:
                yield finding
        fixed_compares: set[int] = set()  # a comparison's fixes go on its first finding
        for found in logic_operands(statement):
            fixes: tuple[Fix, ...] = ()
            if id(found.compare) not in fixed_compares:
                fixed_compares.add(id(found.compare))
                fixes = logic_quick_fixes(text, found, _logic_count(whole))
            yield _logic_finding(text, found, fixes)
        targets = [statement] if isinstance(statement, Assign) else []
        if isinstance(statement, IfThen):
            targets.append(statement.then)
        for assign in targets:
            yield from _read_only_target(assign)


MB304_DOC = RuleDoc(
    "MB304",
    reports="""
An assignment to `#0` (always vacant) or to a read-only system variable:
date and time (`#3011`, `#3012`), modal information (`#4001`–), positions (`#5001`–`#5120`),
and others. Writable system variables (`#3000`, `#3001`, `#3004`, `#3901`, work offsets, tool
offsets) are not reported.
""",
    why="""
The control raises PS0116 WRITE PROTECTED VARIABLE and stops
at the block. Writing `#5021` was probably meant to move the axis or to set an offset; neither
happens.
""",
    example="""
```nc
O9050 (RESTORE STATE)
#4001=1
#0=1
M99
```
""",
    fix="""
Restore modal state with a G code (`G#10` after `#10=#4001`), move with a motion
block, set work offsets through `#5221`– and tool offsets through `#2001`– or `#10001`–.
""",
    not_reported="""
The writable system variables (`#3000`, `#3001`, `#3004`, `#3901`,
offsets), system variables whose protection the checker does not know, and indirect assignments
`#[...] = `, whose target is known only at run time (MB902).
""",
)


def _read_only_target(assign: Assign) -> list[LineFinding]:
    """MB304 for an assignment to #0 or a read-only system variable."""
    number = assign.target.number
    if number is None or number != int(number) or 1 <= number <= 999:
        return []  # computed, Haas's, or a local or common variable (none is read-only)
    kind = classify(int(number))
    if not kind.read_only:
        return []
    target = assign.target
    what = tr("#0 is always vacant") if number == 0 else kind.meaning
    return [
        LineFinding(
            "MB304",
            tr(
                "#{number} is read-only ({meaning}); writing it raises alarm PS0116",
                number=int(number),
                meaning=what,
            ),
            target.span.start,
            target.span.end,
        )
    ]


MB302_DOC = RuleDoc(
    "MB302",
    reports="""
A variable number that no FANUC control has: `#34`–`#99`. Locals are
`#1`–`#33`, commons `#100`–`#199` and `#500`–`#999`, system variables `#1000` and up. Once
per number, at its first use: the message counts and names the other lines that use it.
""",
    why="""
Reading or writing it raises PS0115 VARIABLE NO. OUT OF
RANGE, which stops the program at that block. The variable was usually meant as another one
(`#50` for `#150` or `#500`), so the value the program would use is wrong as well.
""",
    example="""
```nc
O9030 (THREAD MACRO)
#50=#26-#17
G00 X#50
M99
```
""",
    fix="""
Use a local (`#1`–`#33`) or a common variable (`#100`–`#199`, `#500`–`#999`).
""",
    not_reported="""
Numbers the analysis knows only at run time (`#[#1+30]`, MB903),
numbers with a decimal part (`#30001.116`, Haas's, MB002), the extended commons `#200`–`#499`
(MB303), and numbers from `#1000` up, which are taken as system variables without a list of
every control's.
""",
)


def _no_such_variable(var: Var) -> LineFinding | None:
    """MB302 for a variable written with its number."""
    if var.number is None or var.number != int(var.number):
        return None
    number = int(var.number)
    if 1 <= number <= 33 or 100 <= number <= 199 or 500 <= number <= 999:
        return None  # the locals and the commons, as classify has them, without the call
    if classify(number).kind != "none":
        return None
    return LineFinding(
        "MB302",
        tr(
            "#{number} does not exist on a FANUC control (alarm "
            "PS0115): locals are #1-#33, commons #100-#199 and #500-#999",
            number=number,
        ),
        var.span.start,
        var.span.end,
    )


def fold_missing_variables(
    blocks: list[tuple[int, ParsedLine, tuple[LineFinding, ...]]],
) -> list[tuple[int, ParsedLine, tuple[LineFinding, ...]]]:
    """MB302 once per variable number: the first use keeps it and counts the others (the
    program stops at the first with PS0115; renumbering the variable fixes them all)."""
    uses: dict[str, list[int]] = {}  # "#48" -> the indexes in ``blocks`` of its lines
    for n, (_, _, findings) in enumerate(blocks):
        for f in findings:
            if f.code == "MB302":
                lines = uses.setdefault(f.message.split(" ", 1)[0], [])
                if not lines or lines[-1] != n:
                    lines.append(n)
    repeated = {name: lines for name, lines in uses.items() if len(lines) > 1}
    if not repeated:
        return blocks
    out = list(blocks)
    for name, lines in repeated.items():
        others = [blocks[n][0] + 1 for n in lines[1:]]
        shown = (
            tr(
                "{lines} and {more} more",
                lines=", ".join(map(str, others[:8])),
                more=len(others) - 8,
            )
            if len(others) > 8
            else ", ".join(map(str, others))
        )
        first = lines[0]
        line, parsed, findings = out[first]
        kept: list[LineFinding] = []
        for f in findings:
            if f.code == "MB302" and f.message.startswith(name + " "):
                if any(k.code == "MB302" and k.message.startswith(name + " ") for k in kept):
                    continue  # a second use on the same line
                f = f._replace(
                    message=tr(
                        "{message}; {more}",
                        message=f.message,
                        more=tr_n(
                            "{variable} is used on {count} more line ({lines}), not "
                            "reported one by one",
                            "{variable} is used on {count} more lines ({lines}), not "
                            "reported one by one",
                            len(others),
                            variable=name,
                            lines=shown,
                        ),
                    )
                )
            kept.append(f)
        out[first] = (line, parsed, tuple(kept))
        for n in lines[1:]:
            line, parsed, findings = out[n]
            out[n] = (
                line,
                parsed,
                tuple(
                    f
                    for f in findings
                    if not (f.code == "MB302" and f.message.startswith(name + " "))
                ),
            )
    return [b for b in out if b[2]]


def _extended_commons(parsed: ParsedLine) -> tuple[tuple[int, int, int], ...]:
    """(number, start, end) of each #200-#499 the line names, in source order."""
    if parsed.statement is None or "#" not in parsed.text:  # no variable
        return ()
    found: list[tuple[int, int, int]] = []
    for var in all_line_variables(parsed):
        number = var.number
        if number is not None and 200 <= number <= 499 and number == int(number):
            found.append((int(number), var.span.start, var.span.end))
    return tuple(sorted(found, key=itemgetter(1))) if found else ()


# The lines that name one, kept from one analysis of a document to the next.
_extended_lines: LineMap[tuple[tuple[int, int, int], ...]] = LineMap(_extended_commons)


MB303_DOC = RuleDoc(
    "MB303",
    reports="""
The use of common variables of `#200`–`#499`, which exist only with the
extended common variable option. It is reported once per file, at the first use; the message
gives the number of uses in the file, the range of their lines and the variables used.
""",
    why="""
On a control without the option the variable does not exist
and the block raises PS0115 VARIABLE NO. OUT OF RANGE. The same program works on the machine
that has the option and stops on the one that does not.
""",
    example="""
```nc
O9040 (PROBE RESULTS)
#200=#5061
M99
```
""",
    fix="""
If the machine has the option, say so: the setting
`fanuc-macro.machine.extendedCommons` (`true`), or `--extended-commons` on the command line.
Otherwise use `#100`–`#199` or `#500`–`#999`.
""",
    not_reported="""
Any use when the setting says the option is there; every use after
the first (the option is one fact about the machine, so one note per file says it, with the
count); `#100`–`#199` and `#500`–`#999`, which every control with Custom Macro B has; an
indirect `#[...]` whose number is known only at run time.
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB303, once per file at the first use: whether the option is there is one fact about
    the machine, not about each block. The range #200-#499 is the reference's (macro-b.md 2.1:
    "Extended ranges ... are options" [K], unverified against B-64604EN)."""
    if ctx.config.extended_commons:
        return
    scanned = _extended_lines(ctx.doc)
    uses = [  # (line, number, start, end)
        (line, number, start, end)
        for line, found in zip(scanned.lines, scanned.values, strict=True)
        for number, start, end in found
    ]
    if not uses:
        return
    line, number, start, end = uses[0]
    last = uses[-1][0]
    numbers = sorted({u[1] for u in uses})
    shown = ", ".join(f"#{n}" for n in numbers[:6]) + (", ..." if len(numbers) > 6 else "")
    if len(uses) == 1:
        where = tr("its only use in this file")
    else:
        where = tr(
            "the first of {count} uses of #200-#499 in this file, lines {first}-{last} "
            "({variables})",
            count=len(uses),
            first=line + 1,
            last=last + 1,
            variables=shown,
        )
    yield make(
        MB303,
        tr(
            "#{number} is {where}: these common variables exist only with the extended common "
            "variable option (0i-F / 30i); without it each use stops with alarm PS0115. If the "
            "machine has the option, say so (setting fanuc-macro.machine.extendedCommons, "
            "--extended-commons)",
            number=number,
            where=where,
        ),
        line,
        start,
        end,
        related=[Related(last, uses[-1][2], uses[-1][3], tr("the last use"))]
        if last != line
        else [],
    )


# ---- MB305: AND / OR / XOR inside a comparison's operand ---------------------------------------

LOGIC_OPERATORS = ("AND", "OR", "XOR")


@dataclass(frozen=True, slots=True, eq=False, repr=False)
class LogicOperand:
    """A comparison whose operand holds an AND/OR/XOR outside brackets: ``#1 AND #2 LT 0``."""

    compare: Compare
    side: str  # "left" or "right": the operand that holds it
    nodes: tuple[Binary, ...]  # the outermost such operations in that operand


def _conditions(statement: Statement) -> Cond | None:
    if isinstance(statement, IfGoto | IfThen | IfNc):
        return statement.cond
    if isinstance(statement, While | BlockIf):
        return statement.cond
    return None


def _compares(cond: Cond) -> list[Compare]:
    if isinstance(cond, Compare):
        return [cond]
    if isinstance(cond, Logic):
        found = _compares(cond.first)
        for _, rest in cond.rest:
            found.extend(_compares(rest))
        return found
    return []


def _unbracketed_logic(expr: Expr) -> list[Binary]:
    """The outermost AND/OR/XOR of ``expr`` that no bracket, function or #[ ] encloses."""
    if isinstance(expr, Binary):
        if expr.op in LOGIC_OPERATORS:
            return [expr]
        return _unbracketed_logic(expr.left) + _unbracketed_logic(expr.right)
    if isinstance(expr, Unary):
        return _unbracketed_logic(expr.operand)
    return []


def _is_mask(node: Binary) -> bool:
    """``#1003 AND 4``: a bit mask, a constant beside the operator; the control's reading,
    ``[#1003 AND 4] EQ 4``, is the bit test meant."""
    return isinstance(node.left, Num) or isinstance(node.right, Num)


def logic_operands(statement: Statement) -> list[LogicOperand]:
    cond = _conditions(statement)
    if cond is None:
        return []
    found: list[LogicOperand] = []
    for compare in _compares(cond):
        for side, operand in (("left", compare.left), ("right", compare.right)):
            nodes = _unbracketed_logic(operand)
            if nodes and not all(_is_mask(n) for n in nodes):
                found.append(LogicOperand(compare, side, tuple(nodes)))
    return found


def _chain(expr: Expr, op: str) -> list[Expr] | None:
    """The operands of ``a OP b OP c`` (one operator throughout), or None."""
    if not isinstance(expr, Binary) or expr.op != op:
        return None
    left = _chain(expr.left, op) or [expr.left]
    right = expr.right
    if isinstance(right, Binary) and right.op in LOGIC_OPERATORS:
        return None  # 'a AND [b OR c]' without brackets cannot be: OR binds looser
    return [*left, right]


def _source(text: str, expr: Expr | Compare) -> str:
    return text[expr.span.start : expr.span.end].strip()


def logic_fixes(text: str, found: LogicOperand) -> list[tuple[str, str]]:
    """(what it means, the comparison rewritten) for the comparison of ``found``, the likely
    intent first: each operand compared on its own (``[#1 LT 0] AND [#2 LT 0]``, "#1 and #2
    below 0", as the words read), when the operand is one chain of one operator; then the
    control's own reading made explicit (``[#1 AND #2] LT 0``), which changes nothing."""
    compare = found.compare
    fixes: list[tuple[str, str]] = []
    operand = compare.left if found.side == "left" else compare.right
    other = _source(text, compare.right if found.side == "left" else compare.left)
    ops = {n.op for n in found.nodes}
    if len(found.nodes) == 1 and len(ops) == 1:
        op = ops.pop()
        parts = _chain(operand, op)
        if parts is not None and found.nodes[0] is operand:
            pieces = [
                f"[{_source(text, p)} {compare.op} {other}]"
                if found.side == "left"
                else f"[{other} {compare.op} {_source(text, p)}]"
                for p in parts
            ]
            fixes.append(
                (
                    tr("compare each operand on its own, joined by {operator}", operator=op),
                    f" {op} ".join(pieces),
                )
            )
    start = compare.span.start
    explicit = text[start : compare.span.end]
    for node in sorted(found.nodes, key=lambda n: n.span.start, reverse=True):
        a, b = node.span.start - start, node.span.end - start
        explicit = explicit[:a] + "[" + explicit[a:b] + "]" + explicit[b:]
    fixes.append((tr("bracket it as the control reads it"), explicit.strip()))
    return fixes


def _logic_count(whole: Statement | None) -> int:
    return sum(len(logic_operands(s)) for s in statements_of(whole))


def logic_quick_fixes(text: str, found: LogicOperand, before: int) -> tuple[Fix, ...]:
    """MB305's fixes, on line 0: the comparison rewritten with brackets, the likely intent
    first (each operand compared on its own, preferred), then the control's own reading made
    explicit. A rewrite is offered only when the line it gives parses, keeps within five
    brackets and has fewer such comparisons than the ``before`` of the line as written."""
    compare = found.compare
    start, end = compare.span.start, compare.span.end
    fixes: list[Fix] = []
    for i, (what, rewritten) in enumerate(logic_fixes(text, found)):
        if acceptable_fix(text[:start] + rewritten + text[end:], before):
            fixes.append(
                Fix(
                    tr(
                        "Bracket the condition: {condition_text} ({what})",
                        condition_text=rewritten,
                        what=what,
                    ),
                    (FixEdit(0, start, 0, end, rewritten),),
                    preferred=i == 0,
                )
            )
    return tuple(fixes)


def acceptable_fix(fixed: str, before: int) -> bool:
    """The rewritten line parses, nests no bracket more than five deep (the IF's own and the
    conditions' brackets counted too, to be safe: PS0118), and has fewer MB305 findings. (The
    one rule that parses: a fix is offered only if the line it gives reads as meant.)"""
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
    if deepest > MAX_BRACKET_NESTING:
        return False
    return _logic_count(parsed.statement) < before


MB305_DOC = RuleDoc(
    "MB305",
    reports="""
A comparison in an `IF` or `WHILE` whose operand holds `AND`, `OR` or
`XOR` outside brackets: `IF [#1 AND #2 LT 0]`, `IF [#3 EQ #1 OR #2]`. The message says how the
control reads it and how to write each operand's test.
""",
    why="""
In an expression `AND`, `OR` and `XOR` work bit by bit on
the integer values and bind like `*` (`AND`) and `+` (`OR`, `XOR`), tighter than `EQ`...`LE`:
`[#1 AND #2 LT 0]` is `[[#1 AND #2] LT 0]`, the bits #1 and #2 share compared with 0, which is
almost never below 0. The branch meant for "#1 and #2 below 0" is never taken (or always
taken), and the safety check or the pass it guards does not do what was written. (The
precedence is the reference's, from background knowledge: to be checked against B-64304EN,
"Arithmetic and logic operation".)
""",
    example="""
```nc
O9060 (PROBE CHECK)
IF [#1 AND #2 LT 0] GOTO 90
M99
N90 #3000=1(OUT OF TOLERANCE)
```
""",
    fix="""
Put each comparison in its own brackets and join them:
`IF [[#1 LT 0] AND [#2 LT 0]] GOTO 90` (FANUC 0i-D and later combine conditions so). If the
bitwise reading was meant, say so with brackets: `IF [[#1 AND #2] LT 0] GOTO 90`. In the editor
the quick fix offers both, each operand compared on its own first (the likely intent, as the
words read: "if #1 and #2 are below 0"); it is offered only when the operand is one chain of one
operator (`#1 AND #2 AND #3`) and the rewritten line stays within five brackets.
""",
    not_reported="""
A bit mask with a constant (`IF [#1003 AND 4 EQ 4]`): the
control's reading is the bit test meant. `AND`, `OR`, `XOR` already in brackets
(`[[#1 AND #2] LT 0]`) or between bracketed conditions (`[#1 LT 0] AND [#2 LT 0]`), and in an
assignment (`#3=#1 AND #2`), where no comparison binds to them.
""",
)


def _logic_finding(text: str, found: LogicOperand, fixes: tuple[Fix, ...]) -> LineFinding:
    """MB305. AND/OR/XOR in an expression are bitwise on the integer values and bind like '*'
    and '+', tighter than EQ...LE: '[#1 AND #2 LT 0]' is '[[#1 AND #2] LT 0]' (macro-b.md 9,
    [K]: check B-64304EN "Arithmetic and logic operation"; unverified)."""
    compare = found.compare
    node = found.nodes[0]
    written = " ".join(_source(text, compare).split())
    rewrites = logic_fixes(text, found)
    read_as = rewrites[-1][1]
    if len(rewrites) > 1:
        message = tr(
            "'{condition_text}' is read [{read_text}]: {logic} binds tighter than {compare} and "
            "works bit by bit on the integer values; to test each operand, write [{fixed_text}]",
            condition_text=written,
            read_text=read_as,
            logic=node.op,
            compare=compare.op,
            fixed_text=rewrites[0][1],
        )
    else:
        message = tr(
            "'{condition_text}' is read [{read_text}]: {logic} binds tighter than {compare} and "
            "works bit by bit on the integer values",
            condition_text=written,
            read_text=read_as,
            logic=node.op,
            compare=compare.op,
        )
    return LineFinding("MB305", message, compare.span.start, compare.span.end, fixes)
