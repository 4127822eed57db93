"""AST to closures: each expression becomes a Python function of the running frame.

Compiling once per parsed line (cached with it) keeps the run loop free of tree walking, which
is what makes a few hundred thousand macro statements a second possible in Python.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from itertools import islice
from types import MappingProxyType
from typing import Any, Protocol, TypeVar

from ..database import TableKey, current
from ..syntax.tree import (
    BareCond,
    Binary,
    Bracket,
    Call,
    Compare,
    Cond,
    Expr,
    Logic,
    Num,
    Unary,
    Var,
)
from ..translation import tr
from .values import (
    ONE_ARG,
    TWO_ARG,
    AlarmKind,
    MacroAlarm,
    Unknown,
    Value,
    bit_and,
    bit_or,
    bit_xor,
    compare,
    divide,
    f_round,
    fmt,
    merge_unknown,
    modulo,
)


class Frame(Protocol):
    locals: list[Value]
    store: dict[int, Value]

    def read_global(self, number: int) -> Value: ...
    def read_indirect(self, number: Value, node: Var) -> Value: ...

    # The control's settings and modal state that a few functions depend on.
    @property
    def signed_atan(self) -> bool: ...  # ATAN gives -180..180 (parameter 6004#0 NAT), not 0..360
    @property
    def length_increment(self) -> float: ...  # least input increment: 0.001 mm, 0.0001 inch

    def note_rounding(self, name: str, argument: float, result: float) -> None: ...


Evaluator = Callable[[Frame], Value]
_NO_FRAME: Any = None  # what a constant expression is evaluated with: it reads no variable
CondEvaluator = Callable[[Frame], "bool | Unknown | None"]

_float = float
K = TypeVar("K")
V = TypeVar("V")


def _zero(v: Value) -> float | Unknown:
    """A value in arithmetic: vacant counts as 0 (in a function argument and after a unary
    minus too: unverified on FANUC's own table, which shows only + and *)."""
    if v is None:
        return 0.0
    return v


def _constant(value: Value) -> Evaluator:
    # A closure of a number other than zero is shared by every expression with that number
    # (a program writes the same few constants in thousands of lines); 0.0 and -0.0, equal as
    # keys, get their own.
    if type(value) is not _float or not value:
        return _constant_closure(value)
    constants = current().table(CONSTANTS)
    found = constants.get(value)
    if found is None:
        found = kept(constants, value, _constant_closure(value), MAX_SHARED_CONSTANTS)
    return found


def kept(cache: dict[K, V], key: K, made: V, limit: int) -> V:
    """Keep ``made`` in ``cache`` under ``key``; past ``limit`` entries the oldest quarter
    goes (insertion order), not the whole cache."""
    if len(cache) >= limit:
        for oldest in list(islice(cache, limit // 4)):
            cache.pop(oldest, None)  # another thread may have taken it
    cache[key] = made
    return made


def _constant_closure(value: Value) -> Evaluator:
    def constant(_: Frame, value: Value = value) -> Value:
        return value

    return constant


# The closures of numbers, shared by every expression with the number.
CONSTANTS: TableKey[float, Evaluator] = TableKey("evaluator.constants", cache=True)
MAX_SHARED_CONSTANTS = 10_000


# Functions whose result depends on the control's state, not on the arguments alone: ATAN
# (its range is a parameter); ROUND in an NC address (the address's least input increment).
_STATEFUL = frozenset({"ATAN"})

# A compiled node: its evaluator, its value when it is a constant, and whether it could be one
# (no variable, no function that depends on the control's state).
_Compiled = tuple[Evaluator, float | None, bool]


def constant_of(expr: Expr, in_address: bool = False) -> float | None:
    """The value of an expression without variables (``[1.*0.1]``, ``[7./8.]*SIN[60]``), worked
    out once; None when it reads a variable, depends on the control's state or raises an
    alarm (the run reports that). ``in_address``: the expression is an NC address's value."""
    if isinstance(expr, Num):
        return expr.value
    if isinstance(expr, Var) and expr.index is None:
        return None
    return _compile_tree(expr, in_address)[1]


def compile_expr(expr: Expr, in_address: bool = False) -> Evaluator:
    """``in_address``: the value of an NC address, where ROUND rounds to the address's least
    input increment instead of to a whole number (FANUC Custom Macro B manual, "ROUND")."""
    if isinstance(expr, Num):  # most NC words: no tree to walk
        return _constant(expr.value)
    if isinstance(expr, Var) and expr.index is None:
        return _compile_var(expr, None)
    return _compile_tree(expr, in_address)[0]


def compile_with_constant(
    expr: Expr, in_address: bool = False, variables: list[Var] | None = None
) -> tuple[Evaluator, float | None]:
    """``compile_expr`` and ``constant_of`` of ``expr`` from one walk of its tree, which adds
    its variables to ``variables`` in the order of ``walk.variables``."""
    if isinstance(expr, Num):
        return _constant(expr.value), expr.value
    if isinstance(expr, Var) and expr.index is None:
        if variables is not None:
            variables.append(expr)
        return _compile_var(expr, None), None
    compiled = _compile_tree(expr, in_address, variables)
    return compiled[0], compiled[1]


def _compile_tree(root: Expr, in_address: bool, variables: list[Var] | None = None) -> _Compiled:
    """Compile an expression bottom-up with an explicit stack, folding constant parts as it
    goes: each node is compiled once, whatever the depth (recursion failed past a few hundred
    levels, and folding at every level made it quadratic). Its variables go to ``variables``,
    parents before the variables of their indexes, left to right."""
    # (node, in an address, children: -1 before they are compiled, else how many there are)
    todo: list[tuple[Expr, bool, int]] = [(root, in_address, -1)]
    done: list[_Compiled] = []  # the compiled children, left to right, of the nodes under way
    while todo:
        node, address, count = todo.pop()
        if count >= 0:
            start = len(done) - count
            compiled = _compile_node(node, address, done[start:])
            del done[start:]
            done.append(compiled)
            continue
        kind = type(node)
        # [x] and +x compile to x's closure: no step of their own.
        while kind is Bracket or (kind is Unary and node.op == "+"):  # type: ignore[union-attr]
            node = node.inner if kind is Bracket else node.operand  # type: ignore[union-attr]
            kind = type(node)
        if kind is Var and variables is not None:
            variables.append(node)  # type: ignore[arg-type]
        children = _CHILDREN[kind](node)
        if not children:
            done.append(_compile_leaf(node))
            continue
        for child in children:
            if type(child) is not Num and (type(child) is not Var or child.index is not None):
                break
        else:  # #100+2., SIN[#1]: compiled at once, without the stack
            if variables is not None:
                variables.extend(c for c in children if type(c) is Var)
            done.append(_compile_node(node, address, [_compile_leaf(c) for c in children]))
            continue
        todo.append((node, address, len(children)))
        # An index #[...] is a variable number, not the address's value: ROUND in it is plain.
        child_address = address and kind is not Var
        for child in reversed(children):
            todo.append((child, child_address, -1))
    return done[0]


def _compile_leaf(node: Expr) -> _Compiled:
    if type(node) is Num:
        return _constant(node.value), node.value, True
    assert type(node) is Var
    return _compile_var(node, None), None, False


# A node's children, by its class (type, not isinstance: no class of the tree is subclassed).
_CHILDREN: Mapping[type, Callable[[Any], tuple[Expr, ...]]] = MappingProxyType(
    {
        Num: lambda _: (),
        Var: lambda n: () if n.index is None else (n.index,),
        Unary: lambda n: (n.operand,),
        Binary: lambda n: (n.left, n.right),
        Bracket: lambda n: (n.inner,),
        Call: lambda n: n.args,
    }
)


def _compile_node(node: Expr, in_address: bool, children: list[_Compiled]) -> _Compiled:
    kind = type(node)
    if kind is Bracket:
        return children[0]
    if kind is Var:
        return _compile_var(node, children[0][0]), None, False  # type: ignore[arg-type]
    if kind is Unary:
        if node.op == "+":  # type: ignore[union-attr]
            return children[0]
        evaluator = _negate(children[0][0])
    elif kind is Binary:
        right = children[1][1]
        evaluator = _compile_binary(
            node,  # type: ignore[arg-type]
            children[0][0],
            children[1][0],
            right if type(right) is _float else None,
            _local_number(node.left),  # type: ignore[union-attr]
            _local_number(node.right),  # type: ignore[union-attr]
        )
    else:
        assert kind is Call
        evaluator = _compile_call(node, in_address, [c[0] for c in children])  # type: ignore[arg-type]
    foldable = all(c[2] for c in children) and not (
        kind is Call and (node.name in _STATEFUL or (in_address and node.name == "ROUND"))  # type: ignore[union-attr]
    )
    if not foldable or any(c[1] is None for c in children):
        return evaluator, None, foldable
    # Constant parts are folded: the run only computes what depends on variables.
    try:
        value = evaluator(_NO_FRAME)
    except MacroAlarm:  # the run raises it, where it can say where it stands
        return evaluator, None, foldable
    if not isinstance(value, float):
        return evaluator, None, foldable
    return _constant(value), value, True


def _negate(inner: Evaluator) -> Evaluator:
    def negate(f: Frame, inner: Evaluator = inner) -> Value:
        v = inner(f)
        if v.__class__ is _float:
            return -v
        if v is None:
            return 0.0
        return v

    return negate


def _compile_var(var: Var, index: Evaluator | None) -> Evaluator:
    if var.number is not None:
        n = int(var.number)
        if var.number != n:
            unknown = Unknown(frozenset())

            def haas(_: Frame) -> Value:  # #30001.116: Haas NGC, not a FANUC variable
                return unknown

            return haas
        readers = current().table(READERS)
        found = readers.get(n)
        if found is None:
            found = kept(readers, n, _reader(n), MAX_SHARED_READERS)
        return found
    assert index is not None

    def indirect(f: Frame) -> Value:
        return f.read_indirect(index(f), var)

    return indirect


def _reader(n: int) -> Evaluator:
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


# The readers of #n, shared by every expression that reads #n (a reader depends on n only).
READERS: TableKey[int, Evaluator] = TableKey("evaluator.readers", cache=True)
MAX_SHARED_READERS = 10_000


# The operations, one function each, shared by every expression.
_ARITH: Mapping[str, Callable[[float, float], float]] = MappingProxyType(
    {
        "+": lambda a, b: a + b,
        "-": lambda a, b: a - b,
        "*": lambda a, b: a * b,
        "/": divide,
        "MOD": modulo,
        "AND": bit_and,
        "OR": bit_or,
        "XOR": bit_xor,
    }
)


_LARGEST = 1.7976931348623157e308  # the largest double: past it a result is inf


def _overflow(expr: Binary, a: float, b: float) -> MacroAlarm:
    """PS0111 for an operation whose result no control holds (a float would be inf)."""
    alarm = MacroAlarm(
        "PS0111",
        AlarmKind.OVERFLOW,
        tr(
            "{left} {operator} {right} overflows: the result is beyond any value a control "
            "holds (CALCULATED DATA OVERFLOW)",
            left=fmt(a),
            operator=expr.op,
            right=fmt(b),
        ),
        a,
    )
    alarm.node = expr
    return alarm


def _slow_binary(expr: Binary, a: Value, b: Value) -> Value:
    """An operation on what is not two numbers (vacant, unknown), or that may raise."""
    x, y = _zero(a), _zero(b)
    if isinstance(x, Unknown) or isinstance(y, Unknown):
        return merge_unknown(x, y)
    try:
        result = _ARITH[expr.op](x, y)
    except MacroAlarm as alarm:
        alarm.node = expr
        raise
    except OverflowError:  # AND/OR/XOR of integers past the largest double
        raise _overflow(expr, x, y) from None
    if -_LARGEST <= result <= _LARGEST:
        return result
    raise _overflow(expr, x, y)


def _local_number(expr: Expr) -> int:
    """``n`` when ``expr`` reads local #n directly, else 0: an operation reads such an operand
    itself, without the call of a reader."""
    if type(expr) is Var and expr.number is not None:
        n = int(expr.number)
        if n == expr.number and 1 <= n <= 33:
            return n
    return 0


def _with_number(expr: Binary, left: Evaluator, c: float, n: int) -> Evaluator:
    """``left op c`` for a number ``c`` (not 0 for "/"), ``left`` local #n when ``n``: the
    closure holds the number, and the operation on other values is shared. One closure per
    operator, written out: the operator as a parameter would cost a call or a test on every
    run of the block, the loop's hottest path. What it holds are its parameters' defaults, not
    cells: read as locals, and one tuple for the cyclic collector to look at, not a cell each
    (a program of 20,000 lines makes some 100,000 cells)."""
    op = expr.op
    if op == "+":

        def add_number(
            f: Frame, n: int = n, left: Evaluator = left, c: float = c, expr: Binary = expr
        ) -> Value:
            a = f.locals[n] if n else left(f)
            if a.__class__ is _float:
                result = a + c
                if -_LARGEST <= result <= _LARGEST:
                    return result
                raise _overflow(expr, a, c)
            return _slow_binary(expr, a, c)

        return add_number
    if op == "-":

        def sub_number(
            f: Frame, n: int = n, left: Evaluator = left, c: float = c, expr: Binary = expr
        ) -> Value:
            a = f.locals[n] if n else left(f)
            if a.__class__ is _float:
                result = a - c
                if -_LARGEST <= result <= _LARGEST:
                    return result
                raise _overflow(expr, a, c)
            return _slow_binary(expr, a, c)

        return sub_number
    if op == "*":

        def mul_number(
            f: Frame, n: int = n, left: Evaluator = left, c: float = c, expr: Binary = expr
        ) -> Value:
            a = f.locals[n] if n else left(f)
            if a.__class__ is _float:
                result = a * c
                if -_LARGEST <= result <= _LARGEST:
                    return result
                raise _overflow(expr, a, c)
            return _slow_binary(expr, a, c)

        return mul_number

    def div_number(
        f: Frame, n: int = n, left: Evaluator = left, c: float = c, expr: Binary = expr
    ) -> Value:
        a = f.locals[n] if n else left(f)
        if a.__class__ is _float:
            result = a / c
            if -_LARGEST <= result <= _LARGEST:
                return result
            raise _overflow(expr, a, c)
        return _slow_binary(expr, a, c)

    return div_number


def _compile_binary(
    expr: Binary,
    left: Evaluator,
    right: Evaluator,
    constant_right: float | None,
    ln: int = 0,
    rn: int = 0,
) -> Evaluator:
    """``constant_right``: the right operand's value when it is a number (``#100+3.``): the
    closure holds it, and needs no closure of the number. ``ln``, ``rn``: the local an
    operand reads directly (0: none), which the closure reads itself. A closure holds only
    what it reads (the operands, the node), as its parameters' defaults (see
    ``_with_number``); the operation on other values is shared."""
    op = expr.op
    # Each operation checks its result: an overflow is the control's alarm where it happens,
    # with its operands, and no inf or NaN reaches the rest of the analysis. A division by
    # zero takes the general way, which raises the control's alarm.
    if constant_right is not None and op in _NUMBER_OPS and (op != "/" or constant_right):
        return _with_number(expr, left, constant_right, ln)
    if op == "+":

        def add(
            f: Frame,
            ln: int = ln,
            rn: int = rn,
            left: Evaluator = left,
            right: Evaluator = right,
            expr: Binary = expr,
        ) -> Value:
            a = f.locals[ln] if ln else left(f)
            b = f.locals[rn] if rn else right(f)
            if a.__class__ is _float and b.__class__ is _float:
                result = a + b
                if -_LARGEST <= result <= _LARGEST:
                    return result
                raise _overflow(expr, a, b)
            return _slow_binary(expr, a, b)

        return add
    if op == "-":

        def sub(
            f: Frame,
            ln: int = ln,
            rn: int = rn,
            left: Evaluator = left,
            right: Evaluator = right,
            expr: Binary = expr,
        ) -> Value:
            a = f.locals[ln] if ln else left(f)
            b = f.locals[rn] if rn else right(f)
            if a.__class__ is _float and b.__class__ is _float:
                result = a - b
                if -_LARGEST <= result <= _LARGEST:
                    return result
                raise _overflow(expr, a, b)
            return _slow_binary(expr, a, b)

        return sub
    if op == "*":

        def mul(
            f: Frame,
            ln: int = ln,
            rn: int = rn,
            left: Evaluator = left,
            right: Evaluator = right,
            expr: Binary = expr,
        ) -> Value:
            a = f.locals[ln] if ln else left(f)
            b = f.locals[rn] if rn else right(f)
            if a.__class__ is _float and b.__class__ is _float:
                result = a * b
                if -_LARGEST <= result <= _LARGEST:
                    return result
                raise _overflow(expr, a, b)
            return _slow_binary(expr, a, b)

        return mul
    if op == "/":

        def div(
            f: Frame,
            ln: int = ln,
            rn: int = rn,
            left: Evaluator = left,
            right: Evaluator = right,
            expr: Binary = expr,
        ) -> Value:
            a = f.locals[ln] if ln else left(f)
            b = f.locals[rn] if rn else right(f)
            if a.__class__ is _float and b.__class__ is _float and b:
                result = a / b
                if -_LARGEST <= result <= _LARGEST:
                    return result
                raise _overflow(expr, a, b)
            return _slow_binary(expr, a, b)

        return div

    def other(f: Frame) -> Value:
        return _slow_binary(expr, left(f), right(f))

    return other


_NUMBER_OPS = frozenset({"+", "-", "*", "/"})  # those _with_number makes


def _near_integer(x: float) -> bool:
    """A value a hair off a whole number: the residue of binary floating point (0.1 added up
    ten times is 0.9999999999999999), which FIX and FUP then push to the wrong integer."""
    nearest = round(x)
    return x != nearest and abs(x - nearest) <= 1e-9 * max(1.0, abs(x))


def _signed_angle(angle: float) -> float:
    return angle - 360.0 if angle > 180.0 else angle


def _compile_call(expr: Call, in_address: bool, args: list[Evaluator]) -> Evaluator:
    name = expr.name
    if len(expr.args) == 2:
        fn2 = TWO_ARG[name]
        a_eval, b_eval = args
        signed = name == "ATAN"

        def call2(f: Frame) -> Value:
            a, b = _zero(a_eval(f)), _zero(b_eval(f))
            if isinstance(a, Unknown) or isinstance(b, Unknown):
                return merge_unknown(a, b)
            try:
                result = fn2(a, b)
            except MacroAlarm as alarm:
                alarm.node = expr
                raise
            except OverflowError:
                raise _function_overflow(expr, a, b) from None
            return _signed_angle(result) if signed and f.signed_atan else result

        return call2
    fn1 = ONE_ARG[name]
    arg = args[0]
    if name == "ROUND" and in_address:

        def round_address(f: Frame) -> Value:
            a = _zero(arg(f))
            if isinstance(a, Unknown):
                return a
            step = f.length_increment
            try:
                return round(f_round(a / step) * step, 6)
            except OverflowError:
                raise _function_overflow(expr, a) from None

        return round_address
    if name in ("FIX", "FUP"):

        def truncate(f: Frame) -> Value:
            a = _zero(arg(f))
            if isinstance(a, Unknown):
                return a
            try:
                result = fn1(a)
            except OverflowError:
                raise _function_overflow(expr, a) from None
            if f is not None and _near_integer(a) and result != round(a):
                f.note_rounding(name, a, result)  # 7.9999999999 truncated to 7, not 8
            return result

        return truncate
    signed = name == "ATAN"

    def call1(f: Frame) -> Value:
        a = arg(f)
        if a.__class__ is not _float:
            a = _zero(a)
            if isinstance(a, Unknown):
                return a
        try:
            result = fn1(a)
        except MacroAlarm as alarm:
            alarm.node = expr
            raise
        except OverflowError:
            raise _function_overflow(expr, a) from None
        return _signed_angle(result) if signed and f.signed_atan else result

    return call1


def _function_overflow(expr: Call, *args: float) -> MacroAlarm:
    shown = ",".join(fmt(a) for a in args)
    alarm = MacroAlarm(
        "PS0111",
        AlarmKind.OVERFLOW,
        tr(
            "{function}[{arguments}] overflows (CALCULATED DATA OVERFLOW)",
            function=expr.name,
            arguments=shown,
        ),
        args[0],
    )
    alarm.node = expr
    return alarm


def compile_cond(cond: Cond) -> CondEvaluator:
    """A condition: True, False, or an Unknown when it depends on what cannot be known."""
    # [[c1] AND [c2]] OR [c3] nests Logic nodes: compiled bottom-up with an explicit stack.
    todo: list[tuple[Cond, bool]] = [(cond, False)]
    done: list[CondEvaluator] = []
    while todo:
        node, children_done = todo.pop()
        if not isinstance(node, Logic):
            done.append(_compile_simple_cond(node))
        elif children_done:
            count = 1 + len(node.rest)
            terms = done[len(done) - count :]
            del done[len(done) - count :]
            ops = [op for op, _ in node.rest]
            done.append(_logic(terms[0], list(zip(ops, terms[1:], strict=True))))
        else:
            todo.append((node, True))
            todo.extend((c, False) for _, c in reversed(node.rest))
            todo.append((node.first, False))
    assert len(done) == 1
    return done[0]


def _compared(op: str, a: Value, b: Value) -> bool | Unknown:
    """A comparison of what is not two numbers (vacant, unknown)."""
    result = compare(op, a, b)
    if result is None:
        return merge_unknown(a, b)
    return result


def _compile_simple_cond(cond: Compare | BareCond) -> CondEvaluator:
    if isinstance(cond, Compare):
        left = compile_expr(cond.left)
        ln = _local_number(cond.left)
        number = cond.right.value if type(cond.right) is Num else None
        if type(number) is _float:
            return _compare_number(cond.op, left, ln, number)
        return _compare(cond.op, left, ln, compile_expr(cond.right), _local_number(cond.right))
    value = compile_expr(cond.value)

    def bare(f: Frame) -> bool | Unknown | None:
        v = value(f)
        if isinstance(v, Unknown):
            return v
        return v is not None and v != 0.0

    return bare


def _compare_number(op: str, left: Evaluator, n: int, c: float) -> CondEvaluator:
    """``left op c`` for a number ``c``, ``left`` local #n when ``n``: numbers compared in
    the closure, each operator its own (the rest as ``compare`` has it)."""
    if op == "LT":

        def lt(f: Frame) -> bool | Unknown | None:
            a = f.locals[n] if n else left(f)
            return a < c if a.__class__ is _float else _compared(op, a, c)

        return lt
    if op == "LE":

        def le(f: Frame) -> bool | Unknown | None:
            a = f.locals[n] if n else left(f)
            return a <= c if a.__class__ is _float else _compared(op, a, c)

        return le
    if op == "GT":

        def gt(f: Frame) -> bool | Unknown | None:
            a = f.locals[n] if n else left(f)
            return a > c if a.__class__ is _float else _compared(op, a, c)

        return gt
    if op == "GE":

        def ge(f: Frame) -> bool | Unknown | None:
            a = f.locals[n] if n else left(f)
            return a >= c if a.__class__ is _float else _compared(op, a, c)

        return ge
    if op == "EQ":

        def eq(f: Frame) -> bool | Unknown | None:
            a = f.locals[n] if n else left(f)
            return a == c if a.__class__ is _float else _compared(op, a, c)

        return eq

    def ne(f: Frame) -> bool | Unknown | None:
        a = f.locals[n] if n else left(f)
        return a != c if a.__class__ is _float else _compared(op, a, c)

    return ne


def _compare(op: str, left: Evaluator, ln: int, right: Evaluator, rn: int) -> CondEvaluator:
    """``left op right``, an operand local #n when its ``ln`` or ``rn`` is n."""

    def cmp(f: Frame) -> bool | Unknown | None:
        a = f.locals[ln] if ln else left(f)
        b = f.locals[rn] if rn else right(f)
        return _compared(op, a, b)

    return cmp


def _logic(first: CondEvaluator, rest: list[tuple[str, CondEvaluator]]) -> CondEvaluator:
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
