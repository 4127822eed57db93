"""The imports follow ARCHITECTURE.md's code map: each layer imports only the layers below it,
and only the language server knows the protocol."""

from __future__ import annotations

import ast
import re
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "server" / "fanuc_macro"

BASE = {"cancel", "database", "diagnostics", "lazy_regex", "program_files"}
SYNTAX = BASE | {"syntax", "line_maps", "per_line"}
CONFIG = SYNTAX | {"config"}
PROGRAM = CONFIG | {"program"}
EVALUATOR = PROGRAM | {"evaluator"}
THREADS = EVALUATOR | {"threads"}
RULES = THREADS | {"rules"}
ANALYSIS = RULES | {"analysis"}
WORKSPACE = ANALYSIS | {"workspace", "rules_doc"}
GENERATORS = WORKSPACE | {"generators"}
IDE = GENERATORS | {"ide"}
FRONT_END = {
    "ide",
    "generators",
    "debugger",
    "workspace",
    "analysis",
    "config",
    "diagnostics",
    "cancel",
    "database",
    "code_cache",
    "program_files",
    "__version__",
}

# What each module or folder may import from the package (ARCHITECTURE.md, "Code map").
ALLOWED: dict[str, set[str]] = {
    "cancel": set(),
    "database": {"cancel"},
    "code_cache": {"__version__"},
    "diagnostics": set(),
    "lazy_regex": set(),
    "program_files": set(),
    "syntax": {"cancel", "diagnostics", "lazy_regex", "line_maps", "per_line"},
    "per_line": {"syntax"},
    "line_maps": {"cancel", "syntax"},
    "config": {"diagnostics", "syntax"},
    "program": CONFIG,
    "evaluator": PROGRAM,
    "threads": EVALUATOR,
    "rules": THREADS,
    "analysis": RULES,
    "workspace": ANALYSIS,
    "rules_doc": ANALYSIS,
    "generators": WORKSPACE,
    "ide": GENERATORS,
    "debugger": IDE,
    "lsp": FRONT_END,
    "cli": FRONT_END,
    "dap": FRONT_END,
    "__init__": set(),
}


def _modules() -> Iterator[tuple[str, Path]]:
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        yield ".".join(parts), path


def _layer(module: str) -> str:
    parts = module.split(".")
    if len(parts) == 1:
        return "__init__"
    return parts[1]


def _imported(module: str, path: Path) -> Iterator[tuple[int, str]]:
    """(line, module or package attribute) of every import of the package, wherever it is
    (top level, functions, TYPE_CHECKING blocks)."""
    package = module.split(".")[:-1]  # a package's __init__ is named as a module in it
    for node in ast.walk(ast.parse(path.read_text("utf-8"))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "fanuc_macro":
                    yield node.lineno, alias.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                target = ".".join([*base, *([node.module] if node.module else [])])
            else:
                target = node.module or ""
            if target.split(".")[0] != "fanuc_macro":
                continue
            for alias in node.names:
                yield node.lineno, f"{target}.{alias.name}"


def _target_layer(name: str) -> str:
    parts = name.split(".")
    if len(parts) == 2 and parts[1] == "__version__":
        return "__version__"
    return parts[1] if len(parts) > 1 else "__init__"


MODULES = list(_modules())


def test_every_module_is_in_the_map() -> None:
    layers = {_layer(module) for module, _ in MODULES}
    assert layers <= set(ALLOWED), f"not in ARCHITECTURE.md's code map: {layers - set(ALLOWED)}"
    text = (ROOT / "ARCHITECTURE.md").read_text("utf-8")
    for layer in layers - {"__init__"}:
        shown = f"`{layer}/`" if (PACKAGE / layer).is_dir() else f"`{layer}.py`"
        assert shown in text, f"ARCHITECTURE.md does not name {shown}"


@pytest.mark.parametrize("module,path", MODULES, ids=[m for m, _ in MODULES])
def test_imports_follow_the_code_map(module: str, path: Path) -> None:
    layer = _layer(module)
    allowed = ALLOWED[layer] | {layer}
    wrong = [
        f"line {line}: {name}"
        for line, name in _imported(module, path)
        if _target_layer(name) not in allowed
    ]
    assert not wrong, f"{module} imports what its layer may not ({layer}): {wrong}"


def test_only_the_language_server_knows_the_protocol() -> None:
    protocol = re.compile(r"^\s*(from|import)\s+(lsprotocol|pygls)\b", re.M)
    found = [
        module
        for module, path in MODULES
        if _layer(module) != "lsp" and protocol.search(path.read_text("utf-8"))
    ]
    assert not found, f"modules outside lsp/ that import lsprotocol or pygls: {found}"


def test_the_map_check_sees_a_wrong_import(tmp_path: Path) -> None:
    """The check reads imports the way they are written: relative, absolute, in functions."""
    rule = tmp_path / "fanuc_macro" / "rules" / "example.py"
    rule.parent.mkdir(parents=True)
    rule.write_text(
        "from ..syntax.tree import Block\n"
        "def f():\n"
        "    from ..lsp import server\n"
        "    import fanuc_macro.cli\n",
        "utf-8",
    )
    names = [name for _, name in _imported("fanuc_macro.rules.example", rule)]
    assert names == ["fanuc_macro.syntax.tree.Block", "fanuc_macro.lsp.server", "fanuc_macro.cli"]
    assert [_target_layer(n) for n in names] == ["syntax", "lsp", "cli"]
