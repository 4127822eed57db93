"""A thread module recognised by what its formulas compute, not by its number or comments.

The symmetric module of seed paper 000 (and any program written the same way) cuts its last
pass at ``X[#100-2.*#4]``: a base diameter minus twice a height (an internal thread: the
minor diameter plus twice it). That shape names the variables:

* the base is the nominal diameter d (external), or D1 whose own formula
  ``#100 - 2.*[5./8.]*SIN[60]*#101`` names the nominal diameter D (internal);
* the variable of the cut's ``F`` is the lead (the pitch of a one-start thread);
* the height's formula, ``[7./8.]*SIN[60]*#101-#3+#103/2.+#104/4.`` read as a linear form,
  names the nose radius (the term subtracted, also offset by ``r·tan30°`` in the side step) and
  the inputs added to it (es and Td2 in the paper's table 2).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from ..evaluator.facts import DocumentFacts, RunValues
from ..line_maps import LineMap
from ..per_line import PerLine
from ..program.index import Program, ProgramIndex
from ..syntax.parser import statements_of
from ..syntax.tree import (
    Assign,
    Binary,
    Bracket,
    Call,
    Document,
    Expr,
    IfThen,
    NcStatement,
    ParsedLine,
    Var,
)
from ..syntax.walk import subexpressions, top_expressions
from ..translation import tr
from .geometry import SIN60, TAN30
from .jobs import ThreadJob
from .linear import Linear, linear_form

D1_FACTOR = 2.0 * 5.0 / 8.0 * SIN60  # D1 = D - 1.0825 P


@dataclass(eq=False, repr=False)
class ModuleShape:
    """The variables of a thread module, found from where they are used."""

    base_var: int
    height_var: int
    height: float | None
    major_var: int | None = None
    major: float | None = None
    pitch_var: int | None = None
    pitch: float | None = None  # the value of the cut's F variable: the lead
    height_line: int | None = None  # the assignment of the height
    height_form: Linear | None = None
    radius_var: int | None = None
    radius: float | None = None
    radius_line: int | None = None
    radius_how: str = ""  # a message's words: how the formulas use the radius
    inputs: dict[int, float] = field(default_factory=dict)  # other terms of the height
    x_text: str = ""  # the deepest pass's X, as written

    def describe(self) -> str:
        parts: list[str] = [tr("last pass X[{x_text}]", x_text=self.x_text)]
        if self.major_var is not None and self.major is not None:
            parts.append(
                tr("#{var} = {value:g} the nominal diameter", var=self.major_var, value=self.major)
            )
        if self.pitch_var is not None and self.pitch is not None:
            parts.append(f"F#{self.pitch_var} = {self.pitch:g}")
        return tr("the module's formulas ({parts})", parts=listed(parts))


def in_turn(parts: Sequence[str]) -> str:
    """Parts of a message one after another, between semicolons (said in the user's
    language: a Chinese semicolon in Chinese)."""
    said = parts[0] if parts else ""
    for part in parts[1:]:
        said = tr("{earlier}; {later}", earlier=said, later=part)
    return said


def listed(parts: Sequence[str]) -> str:
    """Parts of a message one after another, between commas (as :func:`in_turn`)."""
    said = parts[0] if parts else ""
    for part in parts[1:]:
        said = tr("{earlier}, {later}", earlier=said, later=part)
    return said


def word(doc: Document, line: int, address: str) -> Expr | None:
    """The value of an NC word of a line (its first ``address``)."""
    for statement in statements_of(doc.blocks[line].statement):
        if isinstance(statement, NcStatement):
            found = statement.find(address)
            if found is not None:
                return found.value
    return None


def assignment(doc: Document, line: int, number: int) -> Assign | None:
    for statement in statements_of(doc.blocks[line].statement):
        target = statement.then if isinstance(statement, IfThen) else statement
        if isinstance(target, Assign) and target.target.number == number:
            return target
    return None


def read_value(facts: DocumentFacts, line: int, number: int) -> float | None:
    """The value ``#number`` had at ``line``, when it had one value every time."""
    summary = facts.reads.get((line, number))
    if summary is None or not summary.constant:
        return None
    return float(summary.minimum)


def written_value(facts: DocumentFacts, line: int) -> float | None:
    write = facts.writes.get(line)
    if write is None or not write[1].constant:
        return None
    return float(write[1].minimum)


def writes_of(facts: DocumentFacts, program: Program, number: int) -> list[int]:
    """The lines of ``program`` that wrote ``#number`` when the run came by."""
    return sorted(
        line for line, (n, _s) in facts.writes.items() if n == number and program.contains(line)
    )


def writes_in_document(facts: DocumentFacts, number: int, value: float | None = None) -> list[int]:
    """The lines that wrote ``#number`` (only those that wrote ``value``, when given)."""
    return sorted(
        line
        for line, (n, summary) in facts.writes.items()
        if n == number
        and (value is None or (summary.constant and abs(summary.minimum - value) < 1e-9))
    )


def _value_at(facts: DocumentFacts, line: int, number: int) -> float | None:
    value = read_value(facts, line, number)
    if value is None and (write := facts.writes.get(line)) and write[0] == number:
        value = written_value(facts, line)
    return value


def _tan30_factor(expr: Expr) -> int | None:
    """``#r*TAN[30]`` (or ``TAN[30]*#r``): the variable offset by r·tan30°."""
    if not isinstance(expr, Binary) or expr.op != "*":
        return None
    for var, other in ((expr.left, expr.right), (expr.right, expr.left)):
        if isinstance(var, Var) and var.number is not None and _is_tan30(other):
            return int(var.number)
    return None


def _is_tan30(expr: Expr) -> bool:
    form = linear_form(expr)
    return not form.terms and abs(form.constant - TAN30) < 1e-4


def _line_tan30(parsed: ParsedLine) -> frozenset[int]:
    found: set[int] = set()
    for statement in statements_of(parsed.statement):
        if not isinstance(statement, Assign | IfThen):
            continue
        for top in top_expressions(statement):
            for node in subexpressions(top):
                n = _tan30_factor(node)
                if n is not None:
                    found.add(n)
    return frozenset(found)


# The variables a line's assignment offsets by ·TAN[30], per distinct line.
_tan30_of: PerLine[frozenset[int]] = PerLine(_line_tan30)


def _tan30_line(parsed: ParsedLine) -> frozenset[int] | None:
    if "TAN" not in parsed.text and not parsed.has_lowercase:  # spare most lines the lookup
        return None
    return _tan30_of(parsed) or None


_tan30_lines: LineMap[frozenset[int]] = LineMap(_tan30_line)


def _tan30_offsets(doc: Document, program: Program) -> set[int]:
    found: set[int] = set()
    for _line, offsets in _tan30_lines(doc).within(program.first_line, program.end_line):
        found |= offsets
    return found


ValueAt = Callable[[int, int], "float | None"]


def module_shape(
    doc: Document,
    index: ProgramIndex,
    facts: DocumentFacts,
    job: ThreadJob,
    internal: bool,
    run: RunValues | None = None,
) -> ModuleShape | None:
    """The module's variables, when its deepest pass is written base ∓ 2·height. ``run``:
    the variables of the job's execution, for a module called more than once."""
    program = index.program_at(job.program_line)
    if program is None or not job.xs:
        return None

    def value_at(line: int, number: int) -> float | None:
        if run is not None:
            v = run.value(number)
            if v is not None:
                return v
        return _value_at(facts, line, number)

    deep = job.deepest(internal)
    x_expr = word(doc, deep.line, "X")
    if x_expr is None:
        return None
    form = linear_form(x_expr)
    variables = form.variables()
    sign = 1.0 if internal else -1.0
    base = [n for n, c in variables.items() if abs(c - 1.0) < 1e-9]
    depth = [n for n, c in variables.items() if abs(c - 2.0 * sign) < 1e-9]
    if len(base) != 1 or not depth or form.opaque():
        return None
    values = {n: value_at(deep.line, n) for n in depth}
    height_var = max(depth, key=lambda n: values[n] or 0.0)
    block = doc.blocks[deep.line]
    shape = ModuleShape(
        base[0],
        height_var,
        values[height_var],
        x_text=block.source(x_expr.span).strip().strip("[]"),
    )
    for m in job.passes:
        f_expr = word(doc, m.line, "F")
        if f_expr is None:
            continue
        f_vars = linear_form(f_expr).variables()
        if len(f_vars) == 1:
            ((pitch_var, coefficient),) = f_vars.items()
            if coefficient == 1.0:
                shape.pitch_var = pitch_var
                shape.pitch = value_at(m.line, pitch_var)
        break
    _find_major(doc, facts, program, deep.line, shape, internal, value_at)
    _find_height_formula(doc, facts, program, deep.line, shape, value_at)
    return shape


def _find_major(
    doc: Document,
    facts: DocumentFacts,
    program: Program,
    line: int,
    shape: ModuleShape,
    internal: bool,
    value_at: ValueAt,
) -> None:
    base_value = value_at(line, shape.base_var)
    if not internal:
        shape.major_var, shape.major = shape.base_var, base_value
        return
    # Internal: the base is D1; its formula D - 2·(5/8)·sin60·P names D.
    for write in writes_of(facts, program, shape.base_var):
        assign = assignment(doc, write, shape.base_var)
        if assign is None:
            continue
        terms = linear_form(assign.value).variables()
        majors = [n for n, c in terms.items() if abs(c - 1.0) < 1e-9]
        pitches = [n for n, c in terms.items() if abs(c + D1_FACTOR) < 1e-6]
        if len(majors) == 1 and len(pitches) == 1:
            shape.major_var = majors[0]
            shape.major = value_at(write, majors[0])
            return
    if base_value is not None and shape.pitch is not None:
        shape.major = base_value + D1_FACTOR * shape.pitch


def _find_height_formula(
    doc: Document,
    facts: DocumentFacts,
    program: Program,
    line: int,
    shape: ModuleShape,
    value_at: ValueAt,
) -> None:
    lines = [w for w in writes_of(facts, program, shape.height_var) if w < line]
    if not lines:
        return
    shape.height_line = lines[-1]
    assign = assignment(doc, shape.height_line, shape.height_var)
    if assign is None:
        return
    form = linear_form(assign.value)
    shape.height_form = form
    offsets = _tan30_offsets(doc, program)
    terms = form.variables()
    candidates = [n for n, c in terms.items() if abs(c + 1.0) < 1e-6 and n != shape.pitch_var]
    radius = next((n for n in candidates if n in offsets), None)
    if radius is None and len(candidates) == 1:
        radius = candidates[0]
    how = tr("the height subtracts")
    if radius is None:
        in_use = [n for n in offsets if n != shape.pitch_var and n != shape.height_var]
        if len(in_use) == 1:
            radius, how = in_use[0], tr("the side step offsets by r·tan30°")
    elif radius in offsets:
        how = tr("the height subtracts and the side step offsets by r·tan30°")
    if radius is not None:
        shape.radius_var = radius
        shape.radius = value_at(shape.height_line, radius)
        shape.radius_how = how
        writes = writes_of(facts, program, radius) or writes_in_document(facts, radius)
        shape.radius_line = writes[-1] if writes else None
    for n in terms:
        if n in (shape.pitch_var, shape.radius_var):
            continue
        value = value_at(shape.height_line, n)
        if value is not None:
            shape.inputs[n] = value


@dataclass(frozen=True, eq=False, repr=False)
class FittingRadii:
    """An arc thread cut by the fitting method (seed paper 002): the tool centre moves on an
    arc of radius R − r, written ``ASIN[#18/[#4-#18]]`` for the tangency angle."""

    tool_var: int
    groove_var: int
    line: int  # the ASIN formula
    tool: float | None
    groove: float | None
    tool_line: int | None
    groove_line: int | None


def _fitting_pattern(expr: Expr) -> tuple[int, int] | None:
    """``#r/[#R-#r]``: (r, R)."""
    if not isinstance(expr, Binary) or expr.op != "/" or not isinstance(expr.left, Var):
        return None
    if expr.left.number is None:
        return None
    tool = int(expr.left.number)
    terms = linear_form(expr.right).variables()
    if len(terms) == 2 and abs(terms.get(tool, 0.0) + 1.0) < 1e-9:
        groove = next(n for n in terms if n != tool)
        if abs(terms[groove] - 1.0) < 1e-9:
            return tool, groove
    return None


def _line_fitting(parsed: ParsedLine) -> tuple[int, int] | None:
    for statement in statements_of(parsed.statement):
        if not isinstance(statement, Assign):
            continue
        for node in subexpressions(statement.value):
            if isinstance(node, Call) and node.name == "ASIN" and len(node.args) == 1:
                arg = node.args[0]
                while isinstance(arg, Bracket):
                    arg = arg.inner
                found = _fitting_pattern(arg)
                if found is not None:
                    return found
    return None


# The (tool, groove) radii of a line's ASIN[#r/[#R-#r]], per distinct line.
_fitting_of: PerLine[tuple[int, int] | None] = PerLine(_line_fitting)


def _fitting_line(parsed: ParsedLine) -> tuple[int, int] | None:
    if "ASIN" not in parsed.text and not parsed.has_lowercase:  # spare most lines the lookup
        return None
    return _fitting_of(parsed)


_fitting_lines: LineMap[tuple[int, int]] = LineMap(_fitting_line)


def fitting_radii(doc: Document, facts: DocumentFacts, program: Program) -> FittingRadii | None:
    for line, (tool, groove) in _fitting_lines(doc).within(program.first_line, program.end_line):
        tool_lines = writes_of(facts, program, tool) or writes_in_document(facts, tool)
        groove_lines = writes_of(facts, program, groove) or writes_in_document(facts, groove)
        return FittingRadii(
            tool,
            groove,
            line,
            _value_at(facts, line, tool),
            _value_at(facts, line, groove),
            tool_lines[-1] if tool_lines else None,
            groove_lines[-1] if groove_lines else None,
        )
    return None
