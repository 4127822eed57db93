"""The imports follow ARCHITECTURE.md's code map: each layer imports only the layers below it,
and only the language server knows the protocol."""

from __future__ import annotations

import ast
import importlib
import os
import re
import subprocess
import sys
import types
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "server" / "fanuc_macro"

BASE = {"cancel", "database", "diagnostics", "translation", "lazy_regex", "program_files"}
SYNTAX = BASE | {"syntax", "line_maps", "per_line"}
CONFIG = SYNTAX | {"config"}
PROGRAM = CONFIG | {"program"}
EVALUATOR = PROGRAM | {"evaluator"}
THREADS = EVALUATOR | {"threads"}
RULES = THREADS | {"rules"}
ANALYSIS = RULES | {"analysis"}
WORKSPACE = ANALYSIS | {"workspace", "rules_doc", "config_file"}
GENERATORS = WORKSPACE | {"generators"}
IDE = GENERATORS | {"ide"}
FRONT_END = {
    "ide",
    "generators",
    "debugger",
    "workspace",
    "analysis",
    "config",
    "config_file",
    "rules_doc",
    "diagnostics",
    "translation",
    "cancel",
    "database",
    "code_cache",
    "framing",
    "program_files",
    "__version__",
}

# What each module or folder may import from the package (ARCHITECTURE.md, "Code map").
ALLOWED: dict[str, set[str]] = {
    "cancel": set(),
    "database": {"cancel"},
    "code_cache": {"__version__"},
    "diagnostics": set(),
    "translation": {"database"},
    "framing": set(),
    "lazy_regex": set(),
    "program_files": set(),
    "syntax": {"cancel", "database", "diagnostics", "translation", "lazy_regex"},
    "per_line": {"database", "syntax"},
    "line_maps": {"cancel", "database", "syntax"},
    "config": {"database", "diagnostics", "translation", "syntax"},
    "program": CONFIG,
    "evaluator": PROGRAM,
    "threads": EVALUATOR,
    "rules": THREADS,
    "analysis": RULES,
    "workspace": ANALYSIS,
    "rules_doc": ANALYSIS,
    "config_file": ANALYSIS,
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


# ---- ARCHITECTURE.md stays short and true ------------------------------------------------------

ARCHITECTURE = ROOT / "ARCHITECTURE.md"
MAX_WORDS_PER_SENTENCE = 22
# Folders that hold nothing ARCHITECTURE.md names: version control, installed, built, cached.
NOT_SOURCE = {
    ".git",
    ".mypy_cache",
    ".pytest_cache",
    ".ruff_cache",
    ".venv",
    "__pycache__",
    "build",
    "dist",
    "node_modules",
    "out",
}
FILE_SUFFIXES = (".py", ".ts", ".mjs", ".md", ".lark", ".json", ".lua", ".toml")
# First parts of dotted names in backticks that are not the package's modules.
NOT_MODULES = {"vscode", "vim"}
_LIST_ITEM = re.compile(r"([-*]|\d+\.)\s+")
_SENTENCE_END = re.compile(r"[.!?](?=\s|$)")
_ABBREVIATION = re.compile(r"\b(e\.g|i\.e)\.$")
_CODE_SPAN = re.compile(r"`([^`]+)`")
_LOWER_PATH = re.compile(r"[a-z0-9_.-]+(/[a-z0-9_.-]+)*/?")
_DOTTED = re.compile(r"([a-z_][a-z0-9_]*(?:/[a-z_][a-z0-9_]*)*)\.([A-Za-z_]\w*)")
_CLASS_DOTTED = re.compile(r"([A-Z]\w*)\.([A-Za-z_]\w*)")


def prose_units(text: str) -> list[str]:
    """The paragraphs and list items of a markdown text, each joined into one line; fenced
    code blocks, table rows and headings are left out."""
    units: list[str] = []
    current: list[str] = []
    fenced = False

    def end_unit() -> None:
        if current:
            units.append(" ".join(current))
            current.clear()

    for raw in text.splitlines():
        line = raw.strip()
        if line.startswith("```"):
            end_unit()
            fenced = not fenced
        elif fenced or not line or line.startswith(("|", "#")):
            end_unit()
        else:
            item = _LIST_ITEM.match(line)
            if item:
                end_unit()
                line = line[item.end() :]
            current.append(line)
    end_unit()
    return units


def sentences(unit: str) -> list[str]:
    """A unit's sentences: each ends at ``.``, ``!`` or ``?`` before white space or the end,
    except inside inline code and after ``e.g.``/``i.e.``; what follows the last end (a list
    item without a full stop) is a sentence too."""
    masked = _CODE_SPAN.sub(lambda m: "x" * len(m.group()), unit)
    found: list[str] = []
    start = 0
    for end in _SENTENCE_END.finditer(masked):
        if _ABBREVIATION.search(masked[: end.end()]):
            continue
        found.append(unit[start : end.end()])
        start = end.end()
    found.append(unit[start:])
    return [s.strip() for s in found if s.strip()]


def words_per_sentence(text: str) -> float:
    """Words are what white space separates (an inline code span without spaces is one)."""
    counts = [len(s.split()) for unit in prose_units(text) for s in sentences(unit)]
    return sum(counts) / len(counts)


def test_the_sentence_count_reads_prose_only() -> None:
    text = (
        "# A heading is no sentence\n"
        "\n"
        "One two three. The file `per_line.py` is one word, e.g. this\n"
        "goes on over a line break.\n"
        "\n"
        "- an item without a full stop\n"
        "- another item. And a second sentence!\n"
        "\n"
        "| a table row. | is left out. |\n"
        "```\n"
        "code is. left out.\n"
        "```\n"
    )
    found = [s for unit in prose_units(text) for s in sentences(unit)]
    assert found == [
        "One two three.",
        "The file `per_line.py` is one word, e.g. this goes on over a line break.",
        "an item without a full stop",
        "another item.",
        "And a second sentence!",
    ]
    assert words_per_sentence(text) == (3 + 14 + 6 + 2 + 4) / 5


def test_architecture_sentences_are_short() -> None:
    """ARCHITECTURE.md averages at most 22 words a sentence (rust-analyzer's about 15).

    Counted: prose paragraphs (their lines joined) and list items (``-``, ``*``, ``1.``), each
    split into sentences at ``.``, ``!`` or ``?`` before white space, never inside inline code
    or after ``e.g.``/``i.e.``. Fenced code blocks, table rows and headings are not prose.
    """
    average = words_per_sentence(ARCHITECTURE.read_text("utf-8"))
    assert average <= MAX_WORDS_PER_SENTENCE, f"{average:.1f} words a sentence"


def _repository_names() -> tuple[set[str], set[str]]:
    """Every file and every folder of the repository, by each tail of its path
    (``a/b/c.py`` as ``a/b/c.py``, ``b/c.py`` and ``c.py``)."""
    files: set[str] = set()
    folders: set[str] = set()
    for folder, subfolders, names in os.walk(ROOT):
        subfolders[:] = [s for s in subfolders if s not in NOT_SOURCE]
        parts = Path(folder).relative_to(ROOT).parts
        for tails, children in ((folders, subfolders), (files, names)):
            for child in children:
                path = [*parts, child]
                tails.update("/".join(path[i:]) for i in range(len(path)))
    return files, folders


def _package_modules() -> dict[str, Path]:
    """The package's modules by dotted name (a package by its ``__init__.py``)."""
    modules: dict[str, Path] = {}
    for module, path in MODULES:
        modules[module.removesuffix(".__init__")] = path
    return modules


def _defines(source: str, name: str) -> bool:
    """Whether a module's text defines ``name`` (a function, class, assignment, annotated
    name or import)."""
    defined = re.compile(
        rf"^\s*((async\s+)?def|class)\s+{name}\b|^\s*{name}\s*[:=]|^\s*(from\s.*)?import\s.*\b{name}\b"
        rf"|\bself\.{name}\s*[:=]",
        re.M,
    )
    return defined.search(source) is not None


def named_in_code(text: str) -> Iterator[str]:
    """The words of the inline code spans outside fenced code blocks."""
    outside = re.sub(r"(?ms)^```.*?^```", "", text)
    for span in _CODE_SPAN.finditer(outside):
        yield from span.group(1).split()


def missing_names(text: str) -> list[str]:
    """The paths and ``module.name``s in backticks that the repository does not hold.

    A word is a path when it ends in a file suffix (``.py``, ``.ts``...) or ``/``, or when it
    has a ``/`` and is all lower case (``textDocument/publishDiagnostics`` is a protocol
    method); a path matches any file or folder whose path ends with it (``lines.py``,
    ``evaluator/checkpoints.py``, ``src/extension.ts``). A lower case ``module.name`` must
    name a module of the package whose text defines ``name``, or a submodule; a
    ``Class.name`` must name a class of the package whose module defines ``name``. Words with
    ``<``, ``*`` or ``@``, or starting with ``.``, are patterns or outside names, not checked.
    """
    files, folders = _repository_names()
    modules = _package_modules()
    texts = {module: path.read_text("utf-8") for module, path in modules.items()}
    missing: list[str] = []
    for word in named_in_code(text):
        word = word.split("#")[0].strip("()[],;:")
        if not word or word.startswith((".", "@")) or any(c in word for c in "<*"):
            continue
        if word.endswith("/") and _LOWER_PATH.fullmatch(word):
            if word.rstrip("/") not in folders:
                missing.append(word)
        elif word.endswith(FILE_SUFFIXES):
            if word not in files:
                missing.append(word)
        elif dotted := _DOTTED.fullmatch(word):
            module, name = dotted.group(1).replace("/", "."), dotted.group(2)
            if module.split(".")[0] in NOT_MODULES:
                continue
            owners = [m for m in modules if m == module or m.endswith("." + module)]
            if not any(
                f"{owner}.{name}" in modules or _defines(texts[owner], name) for owner in owners
            ):
                missing.append(word)
        elif dotted := _CLASS_DOTTED.fullmatch(word):
            cls, name = dotted.groups()
            has_class = re.compile(rf"^\s*class\s+{cls}\b", re.M)
            if not any(has_class.search(s) and _defines(s, name) for s in texts.values()):
                missing.append(word)
        elif (
            "/" in word
            and _LOWER_PATH.fullmatch(word)
            and word not in files
            and word not in folders
        ):
            missing.append(word)
    return missing


def test_the_name_check_sees_a_missing_name() -> None:
    text = (
        "`lines.py`, `evaluator/checkpoints.py`, `tests/fixtures/rules/`, `src/extension.ts`,\n"
        "`per_line.PerLine`, `program/knowledge.modal_group`, `fanuc_macro.cli`,\n"
        "`docs/rules.md#x`, `textDocument/publishDiagnostics`, `vscode.l10n`,\n"
        "`data/messages.<locale>.json`,\n"
        "`Workspace.analyse`, `Workspace.db`, `ParsedLine.bare`, `Database.table`,\n"
        "`ide/debugger.py`, `nowhere.py`, `per_line.Nothing`, `nomodule.thing`, `gone/`,\n"
        "`Workspace.nothing`, `NoSuchClass.analyse`\n"
        "```\n`in_a_code_block.py`\n```\n"
    )
    assert missing_names(text) == [
        "ide/debugger.py",
        "nowhere.py",
        "per_line.Nothing",
        "nomodule.thing",
        "gone/",
        "Workspace.nothing",
        "NoSuchClass.analyse",
    ]


def test_architecture_names_what_exists() -> None:
    """Every path and ``module.name`` ARCHITECTURE.md names in backticks exists, so that the
    map stays true when code moves."""
    missing = missing_names(ARCHITECTURE.read_text("utf-8"))
    assert not missing, f"ARCHITECTURE.md names what the repository does not hold: {missing}"


PACKAGES = sorted(path.parent for path in PACKAGE.rglob("__init__.py"))


@pytest.mark.parametrize(
    "package", PACKAGES, ids=[p.relative_to(PACKAGE.parent).as_posix() for p in PACKAGES]
)
def test_every_package_says_what_it_owns(package: Path) -> None:
    """Each package's ``__init__.py`` has a docstring, and the modules it names with
    ``:mod:`` exist."""
    docstring = ast.get_docstring(ast.parse((package / "__init__.py").read_text("utf-8")))
    assert docstring, f"{package.name}/__init__.py has no docstring"
    modules = _package_modules()
    here = ".".join(package.relative_to(PACKAGE.parent).parts)
    for named in re.findall(r":mod:`~?([\w.]+)`", docstring):
        full = here + named if named.startswith(".") else named
        assert full in modules, f"{package.name}/__init__.py names {named}, which is not a module"


# The packages the front ends see only through their public API (the package's names).
FACADES = ("ide", "generators", "debugger")
FRONT_ENDS = ("lsp", "cli", "dap")
# The layers below the analysis whose types stay behind the ide layer.
BEHIND_THE_IDE = {"syntax", "line_maps", "per_line", "program", "evaluator", "threads", "rules"}


def _public(package: str) -> set[str]:
    module = importlib.import_module(f"fanuc_macro.{package}")
    public = getattr(module, "PUBLIC", None)
    return set(public) if public is not None else set(module.__all__)


def _checked_names(package: str) -> set[str]:
    """The names a package's ``TYPE_CHECKING`` block imports: what the type checker sees."""
    tree = ast.parse((PACKAGE / package / "__init__.py").read_text("utf-8"))
    names: set[str] = set()
    for node in tree.body:
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING":
            for statement in node.body:
                assert isinstance(statement, ast.ImportFrom)
                names.update(alias.asname or alias.name for alias in statement.names)
    return names


@pytest.mark.parametrize("module,path", MODULES, ids=[m for m, _ in MODULES])
def test_front_ends_import_the_public_api_of_ide_generators_and_debugger(
    module: str, path: Path
) -> None:
    if _layer(module) not in FRONT_ENDS:
        return
    wrong = []
    for line, name in _imported(module, path):
        parts = name.split(".")
        layer = _target_layer(name)
        if layer in BEHIND_THE_IDE:
            wrong.append(f"line {line}: {name} (behind the ide layer)")
        elif (
            layer in FACADES
            and len(parts) > 2
            and (len(parts) > 3 or parts[2] not in _public(layer))
        ):
            wrong.append(f"line {line}: {name} (not in {layer}'s public API)")
    assert not wrong, f"{module} imports past a package's public API: {wrong}"


@pytest.mark.parametrize("package", ["ide", "generators"])
def test_a_public_name_is_what_its_module_defines(package: str) -> None:
    module = importlib.import_module(f"fanuc_macro.{package}")
    public = module.PUBLIC
    assert _checked_names(package) == set(public)
    for name, defined_in in public.items():
        value = getattr(module, name)
        assert value is getattr(importlib.import_module(f"{module.__name__}.{defined_in}"), name)
        assert not isinstance(value, types.ModuleType), name


def test_the_ide_public_api_is_its_own() -> None:
    """What ide gives the front ends is defined in ide (or is a type alias of it), never a
    syntax, program or evaluator type passed on."""
    ide = importlib.import_module("fanuc_macro.ide")
    foreign = [
        f"{name} ({value.__module__})"
        for name in ide.PUBLIC
        for value in [getattr(ide, name)]
        if isinstance(value, type | types.FunctionType)
        and not value.__module__.startswith("fanuc_macro.ide.")
    ]
    assert not foreign, f"ide passes on what it does not define: {foreign}"
    for path in (PACKAGE / "ide").glob("*.py"):
        module = importlib.import_module(f"fanuc_macro.ide.{path.stem}")
        for name in getattr(module, "__all__", ()):
            value = getattr(module, name)
            if isinstance(value, type | types.FunctionType):
                assert value.__module__ == module.__name__, f"ide/{path.name} passes on {name}"


def test_a_module_loaded_first_does_not_hide_a_public_function() -> None:
    """``ide.hover`` is the function even when ``ide/hover.py`` was imported by its path first:
    the import system binds a module to its package's attribute of the same name."""
    script = (
        "import fanuc_macro.ide.hover, fanuc_macro.ide.trace\n"
        "import fanuc_macro.generators.thread_module\n"
        "from fanuc_macro import generators, ide\n"
        "from fanuc_macro.ide import hover, trace\n"
        "assert callable(hover) and hover is ide.hover and hover.__name__ == 'hover'\n"
        "assert callable(trace) and trace.__name__ == 'trace'\n"
        "assert callable(generators.load_generator)\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_no_public_name_of_generators_is_a_module_name() -> None:
    modules = {path.stem for path in (PACKAGE / "generators").glob("*.py")}
    assert not modules & _public("generators")
