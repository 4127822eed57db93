"""AST to closures: each expression becomes a Python function of the running frame.

Compiling once per parsed line (cached with it) keeps the run loop free of tree walking, which
is what makes a few hundred thousand macro statements a second possible in Python.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

from ..syntax import BareCond, Binary, Bracket, Call, Compare, Cond, Expr, Logic, Num, Unary, Var
from ..walk import subexpressions
from .values import (
    ONE_ARG,
    TWO_ARG,
    MacroAlarm,
    Unknown,
    Value,
    bit_and,
    bit_or,
    bit_xor,
    compare,
    divide,
    merge_unknown,
    modulo,
)


class Frame(Protocol):
    locals: list[Value]
    store: dict[int, Value]

    def read_global(self, number: int) -> Value: ...
    def read_indirect(self, number: Value, node: Var) -> Value: ...


Evaluator = Callable[[Frame], Value]
_NO_FRAME: Any = None  # what a constant expression is evaluated with: it reads no variable
CondEvaluator = Callable[[Frame], "bool | Unknown | None"]

_float = float


def _zero(v: Value) -> float | Unknown:
    """A value in arithmetic: vacant counts as 0 (in a function argument and after a unary
    minus too: unverified on FANUC's own table, which shows only + and *)."""
    if v is None:
        return 0.0
    return v


def _constant(value: Value) -> Evaluator:
    def constant(_: Frame) -> Value:
        return value

    return constant


def constant_of(expr: Expr) -> float | None:
    """The value of an expression without variables (``[1.*0.1]``, ``[7./8.]*SIN[60]``), worked
    out once; None when it reads a variable or raises an alarm (the run reports that)."""
    if isinstance(expr, Num):
        return expr.value
    if any(isinstance(node, Var) for node in subexpressions(expr)):
        return None
    try:
        value = _compile(expr)(_NO_FRAME)
    except MacroAlarm:
        return None
    return value if isinstance(value, float) else None


def compile_expr(expr: Expr) -> Evaluator:
    # Constant parts are folded: the run only computes what depends on variables.
    if not isinstance(expr, Num | Var):
        value = constant_of(expr)
        if value is not None:
            return _constant(value)
    return _compile(expr)


def _compile(expr: Expr) -> Evaluator:
    if isinstance(expr, Num):
        return _constant(expr.value)
    if isinstance(expr, Var):
        return _compile_var(expr)
    if isinstance(expr, Bracket):
        return compile_expr(expr.inner)
    if isinstance(expr, Unary):
        inner = compile_expr(expr.operand)
        if expr.op == "+":
            return inner

        def negate(f: Frame) -> Value:
            v = inner(f)
            if v.__class__ is _float:
                return -v
            if v is None:
                return 0.0
            return v

        return negate
    if isinstance(expr, Binary):
        return _compile_binary(expr)
    return _compile_call(expr)


def _compile_var(var: Var) -> Evaluator:
    if var.number is not None:
        n = int(var.number)
        if var.number != n:
            unknown = Unknown(frozenset())

            def haas(_: Frame) -> Value:  # #30001.116: Haas NGC, not a FANUC variable
                return unknown

            return haas
        if n == 0:
            return lambda _f: None
        if 1 <= n <= 33:

            def local(f: Frame) -> Value:
                return f.locals[n]

            return local

        def glob(f: Frame) -> Value:
            v = f.store.get(n, f)
            if v is f:
                return f.read_global(n)
            return v  # type: ignore[return-value]

        return glob
    assert var.index is not None
    index = compile_expr(var.index)

    def indirect(f: Frame) -> Value:
        return f.read_indirect(index(f), var)

    return indirect


def _arith(op: str) -> Callable[[float, float], float]:
    if op == "+":
        return lambda a, b: a + b
    if op == "-":
        return lambda a, b: a - b
    if op == "*":
        return lambda a, b: a * b
    if op == "/":
        return divide
    if op == "MOD":
        return modulo
    if op == "AND":
        return bit_and
    if op == "OR":
        return bit_or
    return bit_xor


def _compile_binary(expr: Binary) -> Evaluator:
    left = compile_expr(expr.left)
    right = compile_expr(expr.right)
    op = expr.op
    fn = _arith(op)

    def slow(a: Value, b: Value) -> Value:
        x, y = _zero(a), _zero(b)
        if isinstance(x, Unknown) or isinstance(y, Unknown):
            return merge_unknown(x, y)
        try:
            return fn(x, y)
        except MacroAlarm as alarm:
            alarm.node = expr
            raise

    if op == "+":

        def add(f: Frame) -> Value:
            a = left(f)
            b = right(f)
            if a.__class__ is _float and b.__class__ is _float:
                return a + b
            return slow(a, b)

        return add
    if op == "-":

        def sub(f: Frame) -> Value:
            a = left(f)
            b = right(f)
            if a.__class__ is _float and b.__class__ is _float:
                return a - b
            return slow(a, b)

        return sub
    if op == "*":

        def mul(f: Frame) -> Value:
            a = left(f)
            b = right(f)
            if a.__class__ is _float and b.__class__ is _float:
                return a * b
            return slow(a, b)

        return mul
    if op == "/":

        def div(f: Frame) -> Value:
            a = left(f)
            b = right(f)
            if a.__class__ is _float and b.__class__ is _float and b:
                return a / b
            return slow(a, b)

        return div

    def other(f: Frame) -> Value:
        return slow(left(f), right(f))

    return other


def _compile_call(expr: Call) -> Evaluator:
    name = expr.name
    if len(expr.args) == 2:
        fn2 = TWO_ARG[name]
        a_eval = compile_expr(expr.args[0])
        b_eval = compile_expr(expr.args[1])

        def call2(f: Frame) -> Value:
            a, b = _zero(a_eval(f)), _zero(b_eval(f))
            if isinstance(a, Unknown) or isinstance(b, Unknown):
                return merge_unknown(a, b)
            try:
                return fn2(a, b)
            except MacroAlarm as alarm:
                alarm.node = expr
                raise

        return call2
    fn1 = ONE_ARG[name]
    arg = compile_expr(expr.args[0])

    def call1(f: Frame) -> Value:
        a = arg(f)
        if a.__class__ is not _float:
            a = _zero(a)
            if isinstance(a, Unknown):
                return a
        try:
            return fn1(a)
        except MacroAlarm as alarm:
            alarm.node = expr
            raise

    return call1


def compile_cond(cond: Cond) -> CondEvaluator:
    """A condition: True, False, or an Unknown when it depends on what cannot be known."""
    if isinstance(cond, Compare):
        left = compile_expr(cond.left)
        right = compile_expr(cond.right)
        op = cond.op

        def cmp(f: Frame) -> bool | Unknown | None:
            a = left(f)
            b = right(f)
            result = compare(op, a, b)
            if result is None:
                return merge_unknown(a, b)
            return result

        return cmp
    if isinstance(cond, BareCond):
        value = compile_expr(cond.value)

        def bare(f: Frame) -> bool | Unknown | None:
            v = value(f)
            if isinstance(v, Unknown):
                return v
            return v is not None and v != 0.0

        return bare
    assert isinstance(cond, Logic)
    first = compile_cond(cond.first)
    rest = [(op, compile_cond(c)) for op, c in cond.rest]

    def logic(f: Frame) -> bool | Unknown | None:
        acc = first(f)
        for op, c in rest:
            b = c(f)
            if isinstance(acc, Unknown) or isinstance(b, Unknown):
                acc = merge_unknown(
                    acc if isinstance(acc, Unknown) else None, b if isinstance(b, Unknown) else None
                )
                continue
            if op == "AND":
                acc = bool(acc) and bool(b)
            elif op == "OR":
                acc = bool(acc) or bool(b)
            else:
                acc = bool(acc) != bool(b)
        return acc

    return logic
