"""MB5xx: alarms the arithmetic raises on the values that reach it (evaluator)."""

from __future__ import annotations

from collections.abc import Iterator
from types import MappingProxyType

from ..diagnostics import Diagnostic, RuleDoc, RuleInfo, Severity, make
from ..evaluator.facts import ArithmeticAlarm, UserAlarm
from .context import RuleContext

FAMILY = "math-domain"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB501 = RuleInfo("MB501", "math-domain", Severity.ERROR,
                 "A function gets an argument outside its domain: SQRT of a negative, ASIN/ACOS "
                 "outside [-1, 1], LN of a non-positive number (PS0119).", FAMILY)
MB502 = RuleInfo("MB502", "zero-divide", Severity.ERROR,
                 "A division by zero, TAN of 90 degrees or MOD 0 (PS0112).", FAMILY)
MB503 = RuleInfo("MB503", "macro-alarm-reached", Severity.WARNING,
                 "The program reaches its own #3000 alarm with the values the analysis has.",
                 FAMILY)
# fmt: on


_CODES = MappingProxyType({"zero-divide": MB502, "macro-alarm": MB503, "overflow": MB501})
_DOMAIN = (
    "sqrt-negative",
    "asin-range",
    "acos-range",
    "ln-domain",
    "bin-range",
    "bcd-range",
    "pow-range",
    "atan-zero",
)


MB501_DOC = RuleDoc(
    "MB501",
    reports="""
A function that gets an argument outside its domain when the program runs
with the values the analysis computed: `SQRT` of a negative number, `ASIN`/`ACOS` outside
[-1, 1], `LN` of zero or a negative number, `BIN`/`BCD` of a negative number, `ATAN[0]/[0]`,
and an overflow: an `EXP`, `POW` or `BCD` whose result no control holds, an operation (`*`,
`/`, `+`, `-`, `OR`, `XOR`) whose result is past the largest double, and an assignment past the
controller's range (10^47 on the 0i/16i/18i). The message shows the argument or the two
operands and the variables they came from.
""",
    why="""
The control raises PS0119 ARGUMENT VALUE OUT OF RANGE (PS0111
for an overflow) and stops at the block, usually part-way through a part: the values that make
the argument invalid are those of a real part size.
""",
    example="""
```nc
O5001 (CHAMFER LENGTH)
#1=10.
#2=12.
#3=SQRT[#1*#1-#2*#2]
M30
```
""",
    fix="""
Check the formula (here the operands are swapped) or guard the call with an
`IF [...] GOTO` that raises a clear `#3000` alarm for sizes the formula does not cover.
""",
    not_reported="""
An argument the analysis cannot know (a macro's argument when the
macro is analysed alone, a probe result, a common set by another program), a block the run does
not reach, and a second domain error further on: the first alarm stops the run, as it stops
the control.
""",
)


MB502_DOC = RuleDoc(
    "MB502",
    reports="""
A division by zero, `TAN` of 90 degrees (plus multiples of 180) or `MOD 0`
with the values the analysis computed.
""",
    why="""
The control raises PS0112 ZERO DIVIDE and stops at the block.
""",
    example="""
```nc
O5021 (FEED PER TOOTH)
#1=0
#9=800./#1
M30
```
""",
    fix="""
Check the divisor before dividing (`IF [#1 EQ 0] GOTO ...`) or correct the value
that produces zero.
""",
    not_reported="""
A divisor the analysis cannot know, a block the run does not
reach, and a division after the first alarm of the run.
""",
)


MB503_DOC = RuleDoc(
    "MB503",
    reports="""
The program reaches its own `#3000=n (MESSAGE)` alarm with the values the
analysis has: an argument check fails, or a limit is exceeded, for the values set in the
program.
""",
    why="""
`#3000=n` stops the machine with alarm 3000+n and the
message. It is meant to stop bad input, but if the values in the program reach it, every run
stops there.
""",
    example="""
```nc
O5031 (PECK DEPTH CHECK)
#17=0
IF[#17GT0]GOTO10
#3000=1(PECK Q MUST BE POSITIVE)
N10 M30
```
""",
    fix="""
Correct the value the check rejects, or the check itself.
""",
    not_reported="""
An alarm the run reaches through a condition the analysis could
not decide (an `IF` on an argument, a `WHILE` whose test is unknown: the usual argument check),
and an alarm in a macro analysed on its own, whose arguments are unknown.
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    for f in ctx.findings(ArithmeticAlarm, UserAlarm):
        kind = f.alarm.value
        rule = _CODES.get(kind) or (MB501 if kind in _DOMAIN else None)
        if rule is not None:
            yield make(rule, f.message, f.line, f.column, f.end_column)
