"""No module-level mutable state outside the analysis database, constant tables read-only and
UPPER_CASE, and no function over 120 lines.

The analysis state has one owner, ``fanuc_macro.database``: any other module-level value is a
declaration (a module, class, function, type variable, context variable, logger, or a query
declared on the database: ``PerLine``, ``LineMap``, ``Kept``, ``TableKey``) or an immutable constant
named in UPPER_CASE. Each allow-list below names what still breaks a rule and the part of the
code that owns it; it only shrinks: a test fails when an allowed name no longer breaks it.
"""

from __future__ import annotations

import ast
import contextvars
import dataclasses
import enum
import functools
import importlib
import logging
import operator
import pkgutil
import re
import types
import typing
from collections.abc import Iterator
from pathlib import Path

import fanuc_macro
from fanuc_macro.lazy_regex import LazyPattern

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "server" / "fanuc_macro"

# The one module allowed module-level mutable state.
DATABASE_MODULE = "fanuc_macro.database"
# Written by scripts/grammar_tables.py: data, not code to read.
GENERATED = {"syntax/grammar_tables.py"}
MAX_FUNCTION_LINES = 120

# Module-level names that still break the rules, with the part of the code that owns them.
# Remove a name when it is fixed; the list ends empty.
ALLOWED_STATE: dict[str, str] = {}

# Functions still over MAX_FUNCTION_LINES ("path:qualified name"), with their owner.
ALLOWED_LONG: dict[str, str] = {}

UPPER_CASE = re.compile(r"_*[A-Z][A-Z0-9_]*")
# Set by the import system on every module: not the module's own state.
IMPORT_DUNDERS = frozenset(
    {
        "__name__",
        "__doc__",
        "__file__",
        "__loader__",
        "__spec__",
        "__path__",
        "__package__",
        "__cached__",
        "__builtins__",
        "__annotations__",
    }
)
CALLABLES = (
    types.FunctionType,
    types.BuiltinFunctionType,
    types.MethodType,
    types.BuiltinMethodType,
    types.MethodWrapperType,
    types.WrapperDescriptorType,
    types.MethodDescriptorType,
    types.MemberDescriptorType,  # a slot's descriptor, and its __get__/__set__ bound to it
    types.GetSetDescriptorType,
    property,
    operator.itemgetter,
    operator.attrgetter,
    operator.methodcaller,
)
BOUND_METHODS = (types.BuiltinMethodType, types.MethodType, types.MethodWrapperType)
SCALARS = (int, float, complex, str, bytes, bool, type(None), range, re.Pattern, LazyPattern)


def _modules() -> list[types.ModuleType]:
    names = [fanuc_macro.__name__]
    for info in pkgutil.walk_packages(fanuc_macro.__path__, fanuc_macro.__name__ + "."):
        if info.name.rsplit(".", 1)[-1] != "__main__":  # importing one runs its program
            names.append(info.name)
    return [importlib.import_module(name) for name in sorted(names)]


def _query_declarations() -> tuple[type, ...]:
    """The immutable descriptors of what the database keeps: their storage is in it."""
    from fanuc_macro import line_maps
    from fanuc_macro.per_line import PerLine

    kinds: list[type] = [PerLine, line_maps.LineMap]
    # What a rule keeps between edits, once a declaration whose storage is the database's.
    kept: type | None = getattr(line_maps, "Kept", None)
    params = getattr(kept, "__dataclass_params__", None)
    if kept is not None and params is not None and params.frozen:
        kinds.append(kept)
    try:
        database = importlib.import_module(DATABASE_MODULE)
    except ModuleNotFoundError:
        pass
    else:
        kinds += [database.TableKey, database.Derived]  # a derived query: a declaration too
    return tuple(kinds)


def _imported_names(module: types.ModuleType) -> set[str]:
    """The names the module's own top-level statements bind by ``import``: checked where they
    are defined."""
    path = getattr(module, "__file__", None)
    if path is None:
        return set()
    tree = ast.parse(Path(path).read_text(encoding="utf-8"))
    names: set[str] = set()
    pending: list[ast.stmt] = list(tree.body)
    while pending:
        node = pending.pop()
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            for alias in node.names:
                names.add(alias.asname or alias.name.split(".")[0])
        elif isinstance(node, (ast.If, ast.Try, ast.With)):
            pending.extend(node.body)
            pending.extend(getattr(node, "orelse", []))
            pending.extend(getattr(node, "finalbody", []))
            for handler in getattr(node, "handlers", []):
                pending.extend(handler.body)
    return names


def _bound_to(value: object) -> object | None:
    """The object a bound method reads and may change (``{}.get``'s dict), None for a function
    of a module or class."""
    if not isinstance(value, BOUND_METHODS):
        return None
    owner = getattr(value, "__self__", None)
    return None if owner is None or isinstance(owner, (types.ModuleType, type)) else owner


def _is_declaration(value: object) -> bool:
    """A module, class, function, type, type variable, context variable or logger: code, not
    state (a function behind ``functools.lru_cache`` is not: it holds a cache; nor is a method
    bound to a mutable object)."""
    if isinstance(value, functools._lru_cache_wrapper):
        return False
    owner = _bound_to(value)
    if owner is not None:
        return _mutable_part(owner) is None
    if isinstance(value, (types.ModuleType, type, *CALLABLES)):
        return True
    if isinstance(value, (typing.TypeVar, typing.ParamSpec, contextvars.ContextVar)):
        return True
    if isinstance(value, (logging.Logger, logging.LoggerAdapter)):
        return True
    # Type aliases: list[int], int | None, Union[...], Callable[...], NewType.
    if isinstance(value, (types.GenericAlias, types.UnionType)):
        return True
    return type(value).__module__ in ("typing", "typing_extensions")


def _mutable_part(value: object, seen: set[int] | None = None) -> str | None:
    """None when ``value`` is immutable all the way down, else the type of the first mutable
    part found."""
    seen = set() if seen is None else seen
    if id(value) in seen:
        return None
    seen.add(id(value))
    if isinstance(value, (*SCALARS, enum.Enum)) or type(value) is object:  # sentinels
        return None
    if isinstance(value, functools.partial):
        parts: tuple[object, ...] = (value.func, *value.args, *value.keywords.values())
        return _first_mutable(parts, seen, "functools.partial")
    owner = _bound_to(value)
    if owner is not None:
        return _first_mutable((owner,), seen, "a method")
    if _is_declaration(value):
        return None
    if isinstance(value, (tuple, frozenset)):
        return _first_mutable(tuple(value), seen, None)
    if isinstance(value, types.MappingProxyType):
        return _first_mutable(tuple(value.keys()) + tuple(value.values()), seen, None)
    if (
        dataclasses.is_dataclass(value)
        and not isinstance(value, type)
        and type(value).__dataclass_params__.frozen  # type: ignore[attr-defined]
    ):
        fields = tuple(getattr(value, field.name) for field in dataclasses.fields(value))
        return _first_mutable(fields, seen, None)
    return _type_name(value)


def _first_mutable(parts: tuple[object, ...], seen: set[int], whole: str | None) -> str | None:
    for part in parts:
        found = _mutable_part(part, seen)
        if found is not None:
            return found if whole is None else f"{whole} of {found}"
    return None


def _type_name(value: object) -> str:
    kind = type(value)
    if kind.__module__ == "builtins":
        return kind.__qualname__
    return f"{kind.__module__}.{kind.__qualname__}"


def _problems(module: types.ModuleType, descriptors: tuple[type, ...]) -> Iterator[str]:
    imported = _imported_names(module)
    for name, value in vars(module).items():
        if name in IMPORT_DUNDERS or name in imported:
            continue
        where = f"{module.__name__}.{name}"
        if name == "__all__":
            if not isinstance(value, tuple):
                yield f"{where}: {_type_name(value)} (__all__ must be a tuple)"
            continue
        if isinstance(value, descriptors) or _is_declaration(value):
            continue
        mutable = _mutable_part(value)
        if isinstance(value, functools._lru_cache_wrapper):
            mutable = "functools.lru_cache"
        dunder = name.startswith("__") and name.endswith("__")
        if mutable is not None:
            yield f"{where}: {_type_name(value)} (mutable: {mutable})"
        elif not dunder and not UPPER_CASE.fullmatch(name):
            yield f"{where}: {_type_name(value)} (a constant's name is UPPER_CASE)"


def _state_problems() -> dict[str, str]:
    descriptors = _query_declarations()
    found: dict[str, str] = {}
    for module in _modules():
        if module.__name__ == DATABASE_MODULE:
            continue
        for problem in _problems(module, descriptors):
            found[problem.split(":", 1)[0]] = problem
    return found


def _long_functions() -> dict[str, int]:
    found: dict[str, int] = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE).as_posix()
        if relative in GENERATED:
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for qualname, node in _functions(tree.body, ""):
            assert node.end_lineno is not None
            lines = node.end_lineno - node.lineno + 1
            if lines > MAX_FUNCTION_LINES:
                found[f"{relative}:{qualname}"] = lines
    return found


def _functions(
    nodes: list[ast.stmt] | list[ast.AST], prefix: str
) -> Iterator[tuple[str, ast.FunctionDef | ast.AsyncFunctionDef]]:
    for node in nodes:
        if isinstance(node, ast.ClassDef):
            yield from _functions(node.body, f"{prefix}{node.name}.")
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield f"{prefix}{node.name}", node
            yield from _functions(node.body, f"{prefix}{node.name}.")
        else:
            yield from _functions(list(ast.iter_child_nodes(node)), prefix)


def _report(title: str, lines: list[str]) -> str:
    return title + "\n" + "\n".join(f"  {line}" for line in lines)


def test_module_level_values_are_declarations_or_read_only_upper_case_constants() -> None:
    found = _state_problems()
    offending = sorted(problem for name, problem in found.items() if name not in ALLOWED_STATE)
    fixed = sorted(name for name in ALLOWED_STATE if name not in found)
    assert not offending, _report(
        "module-level mutable state or a constant not UPPER_CASE:", offending
    )
    assert not fixed, _report("fixed: remove from ALLOWED_STATE:", fixed)


def test_no_function_is_over_120_lines() -> None:
    found = _long_functions()
    offending = sorted(
        f"{name}: {lines} lines" for name, lines in found.items() if name not in ALLOWED_LONG
    )
    fixed = sorted(name for name in ALLOWED_LONG if name not in found)
    assert not offending, _report(f"over {MAX_FUNCTION_LINES} lines:", offending)
    assert not fixed, _report("fixed: remove from ALLOWED_LONG:", fixed)


def test_the_checks_see_what_they_look_for() -> None:
    """The checks' own cases, so that an empty allow-list means what it says."""
    module = types.ModuleType("fanuc_macro.example")
    module.__file__ = None
    module.__dict__.update(
        {
            "__all__": ["a"],
            "TABLE": {"a": 1},
            "_PAIRS": ((1, [2]),),
            "READ_ONLY": types.MappingProxyType({"a": (1, frozenset({2}))}),
            "lower_constant": 3,
            "_SENTINEL": object(),
            "cached": functools.lru_cache(maxsize=None)(lambda: 1),
            "function": lambda: 1,
            "lookup": {}.get,
            "_match": re.compile("a").match,
        }
    )
    problems = {problem.split(":", 1)[0]: problem for problem in _problems(module, ())}
    assert sorted(problems) == [
        "fanuc_macro.example.TABLE",
        "fanuc_macro.example._PAIRS",
        "fanuc_macro.example.__all__",
        "fanuc_macro.example.cached",
        "fanuc_macro.example.lookup",
        "fanuc_macro.example.lower_constant",
    ]
    assert problems["fanuc_macro.example._PAIRS"].endswith("(mutable: list)")
    tree = ast.parse(
        "def f():\n    def g():\n        pass\nclass C:\n    def m(self):\n        pass\n"
    )
    assert [name for name, _ in _functions(tree.body, "")] == ["f", "f.g", "C.m"]
