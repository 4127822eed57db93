"""Expressions read as linear combinations: ``[7./8.]*SIN[60]*#101-#3+#103/2.`` is
0.7578·#101 − 1·#3 + 0.5·#103.

The threading rules recognise a thread module by what its formulas compute, not by its
program number or its comments: the depth of a pass is ``#100 − 2·#9``, the thread height is
``k·P − r + es/2 + Td2/4``. A linear form makes those shapes comparable whatever the brackets
and the order of the terms. Parts that are not linear in one variable (``SQRT[#4]``,
``#5*#7``, ``#[#1]``) are kept as opaque terms named by their text.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..evaluator.compiler import constant_of
from ..syntax.tree import Binary, Bracket, Call, Expr, Num, Unary, Var

Term = int | str  # a variable number, or the text of a part that is not linear


@dataclass(frozen=True)
class Linear:
    terms: dict[Term, float] = field(default_factory=dict)
    constant: float = 0.0

    def coefficient(self, term: Term) -> float:
        return self.terms.get(term, 0.0)

    def variables(self) -> dict[int, float]:
        """The terms that are one variable each, with their coefficients."""
        return {t: c for t, c in self.terms.items() if isinstance(t, int) and c != 0.0}

    def opaque(self) -> dict[str, float]:
        return {t: c for t, c in self.terms.items() if isinstance(t, str) and c != 0.0}


def _scaled(form: Linear, factor: float) -> Linear:
    return Linear({t: c * factor for t, c in form.terms.items()}, form.constant * factor)


def _sum(a: Linear, b: Linear, sign: float) -> Linear:
    terms = dict(a.terms)
    for t, c in b.terms.items():
        terms[t] = terms.get(t, 0.0) + sign * c
    return Linear(terms, a.constant + sign * b.constant)


def linear_form(expr: Expr) -> Linear:
    """``expr`` as a constant plus coefficients of variables and of opaque parts."""
    value = constant_of(expr)
    if value is not None:
        return Linear({}, value)
    if isinstance(expr, Bracket):
        return linear_form(expr.inner)
    if isinstance(expr, Var):
        if expr.number is not None and expr.number == int(expr.number):
            return Linear({int(expr.number): 1.0})
        return Linear({expr_text(expr): 1.0})
    if isinstance(expr, Unary):
        inner = linear_form(expr.operand)
        return _scaled(inner, -1.0) if expr.op == "-" else inner
    if isinstance(expr, Binary) and expr.op in ("+", "-"):
        return _sum(
            linear_form(expr.left), linear_form(expr.right), 1.0 if expr.op == "+" else -1.0
        )
    if isinstance(expr, Binary) and expr.op == "*":
        left, right = constant_of(expr.left), constant_of(expr.right)
        if left is not None:
            return _scaled(linear_form(expr.right), left)
        if right is not None:
            return _scaled(linear_form(expr.left), right)
    if isinstance(expr, Binary) and expr.op == "/":
        right = constant_of(expr.right)
        if right:
            return _scaled(linear_form(expr.left), 1.0 / right)
    return Linear({expr_text(expr): 1.0})


def expr_text(expr: Expr) -> str:
    """The expression written out the FANUC way, without spaces: ``SQRT[#4]``, ``#5*#7``."""
    if isinstance(expr, Num):
        return expr.text
    if isinstance(expr, Var):
        if expr.number is not None:
            n = expr.number
            return f"#{int(n)}" if n == int(n) else f"#{n:g}"
        assert expr.index is not None
        return f"#[{expr_text(expr.index)}]"
    if isinstance(expr, Bracket):
        return f"[{expr_text(expr.inner)}]"
    if isinstance(expr, Unary):
        return f"{expr.op}{expr_text(expr.operand)}"
    if isinstance(expr, Binary):
        return f"{expr_text(expr.left)}{expr.op}{expr_text(expr.right)}"
    assert isinstance(expr, Call)
    if expr.slash_form:
        return f"{expr.name}[{expr_text(expr.args[0])}]/[{expr_text(expr.args[1])}]"
    return f"{expr.name}[{','.join(expr_text(a) for a in expr.args)}]"
