"""The configuration file, ``fanuc-macro.toml`` (or ``[tool.fanuc-macro]`` in a
``pyproject.toml``): found from the checked file's folder upwards, nearest first, with
``extend`` naming a parent file, as ruff reads its own. One table of keys (:data:`KEYS`) is the
schema: the loader checks each value against it, the JSON Schema published with the package is
written from it (``scripts/config_schema.py``), and each key names the editor setting it stands
for, so that the file, the command line and the editor's settings fill one settings object
(:meth:`Config.from_settings`) in one order: command line, then file, then editor, then
defaults."""

from __future__ import annotations

import re
import sys
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # the same parser, before it joined the standard library
    import tomli as tomllib

from .config import ATAN_RANGES, CONTROLLERS, G_CODE_SYSTEMS, SPACING, Config, FormatSettings

FILE_NAME = "fanuc-macro.toml"
PYPROJECT = "pyproject.toml"
TOOL_TABLE = ("tool", "fanuc-macro")
# Files of ``extend`` followed before a chain is taken for a loop.
_MAX_EXTENDS = 16


@dataclass(frozen=True)
class Key:
    """One key of the file: ``[section] name`` (spelled as ruff spells its own, in kebab
    case), the editor setting it stands for (``fanuc-macro.`` + ``setting``), its JSON type,
    and what it means."""

    section: str
    name: str
    setting: str
    kind: str  # "string", "number", "integer", "boolean", "strings", "table", "programs"
    description: str
    choices: tuple[str, ...] = ()
    editor: bool = True  # an editor setting stands for it (package.json)

    @property
    def dotted(self) -> str:
        return f"{self.section}.{self.name}"


def _keys() -> tuple[Key, ...]:
    controllers = CONTROLLERS
    return (
        Key("machine", "controller", "controller", "string",
            "The control the programs are for; 0i-F reads each file as a lathe or a mill as "
            "its codes show.", controllers),
        Key("machine", "max-spindle-speed", "machine.maxSpindleSpeed", "number",
            "The machine's maximum spindle speed, rpm (MB602); not checked when not set."),
        Key("machine", "max-threading-feed", "machine.maxThreadingFeed", "number",
            "The largest feed while threading, S x lead, mm/min (MB807)."),
        Key("machine", "atan-range", "machine.atanRange", "string",
            "ATAN's result: 0 to 360 degrees, or -180 to 180 with parameter 6004#0 (NAT).",
            ATAN_RANGES),
        Key("machine", "extended-commons", "machine.extendedCommons", "boolean",
            "The machine has the extended common variables #200-#499."),
        Key("machine", "custom-calls", "machine.customCalls", "table",
            "Codes the control's parameters make call a program: { M165 = 9022, T = 9000 }."),
        Key("machine", "programs-on-control", "machine.programsOnControl", "programs",
            "Programs kept on the control, not beside the files: numbers or ranges "
            '("O9000-O9999").'),
        Key("machine", "g-code-system", "machine.gCodeSystem", "string",
            "The lathe's G code system (parameters GSB, GSC).", G_CODE_SYSTEMS),
        Key("threading", "max-depth-per-pass", "threading.maxDepthPerPass", "number",
            "The deepest threading pass, mm of radius."),
        Key("rules", "select", "rules.select", "strings",
            "The rules reported, by code, name or prefix of codes (MB6) or ALL (the default).",
            editor=False),
        Key("rules", "extend-select", "rules.extendSelect", "strings",
            "Rules reported besides those of select.", editor=False),
        Key("rules", "ignore", "rules.disabled", "strings",
            "Rules not reported, by code or name (MB403, call-target-missing)."),
        Key("rules", "per-file-ignores", "rules.perFileIgnores", "table",
            'Rules not reported in some files: { "probe/*.nc" = ["MB601"] } (a glob without '
            "/ is a file name anywhere below this file's folder).", editor=False),
        Key("rules", "severity", "rules.severity", "table",
            'Severity by rule: { MB403 = "information" } (error, warning, information, hint).'),
        Key("files", "exclude", "files.exclude", "strings",
            "What check skips in the folders it walks, as --exclude: a name anywhere (*.bak, "
            "old) or, with a /, a path from the folder walked.", editor=False),
        Key("files", "extensions", "files.extensions", "strings",
            'More extensions of program files, besides .nc, .mac, .tap and the others (".pgm").',
            editor=False),
        Key("analysis", "step-budget", "analysis.stepBudget", "integer",
            "Blocks one run of a program may execute."),
        Key("analysis", "time-limit", "analysis.timeLimit", "number",
            "Seconds per analysis after which the evaluator gives up (a safety net)."),
        Key("analysis", "max-line-length", "analysis.maxLineLength", "integer",
            "A longer block is not analysed (MB011)."),
        Key("analysis", "max-blocks", "analysis.maxBlocks", "integer",
            "Blocks of a file the analysis reads (MB013)."),
        Key("analysis", "max-file-size", "analysis.maxFileSize", "integer",
            "Characters of a file the analysis reads (MB013)."),
        Key("hover", "full-precision", "hover.fullPrecision", "boolean",
            "Hovers show values in full, not at the least input increment."),
        Key("view", "stock-diameter", "view.stockDiameter", "number",
            "The bar's diameter the Toolpath view draws on a lathe, in the program's unit; "
            "the program's when not set."),
        Key("cycle-time", "rapid-rate-x", "cycleTime.rapidRateX", "number",
            "The X axis's rapid traverse rate for the cycle time, mm/min (along the radius)."),
        Key("cycle-time", "rapid-rate-y", "cycleTime.rapidRateY", "number",
            "The Y axis's rapid traverse rate for the cycle time, mm/min."),
        Key("cycle-time", "rapid-rate-z", "cycleTime.rapidRateZ", "number",
            "The Z axis's rapid traverse rate for the cycle time, mm/min."),
        Key("cycle-time", "tool-change-seconds", "cycleTime.toolChangeSeconds", "number",
            "Seconds a tool change takes (a lathe's T, a mill's M06) in the cycle time."),
        Key("cycle-time", "m-code-seconds", "cycleTime.mCodeSeconds", "table",
            "Seconds the machine waits for M codes, in the cycle time: { M08 = 0.5 }."),
        Key("format", "upper-case", "format.upperCase", "boolean",
            "The formatter writes addresses and keywords in upper case."),
        Key("format", "space-between-words", "format.spaceBetweenWords", "string",
            "Spaces between words: keep, always, never.", SPACING),
        Key("format", "spaces-around-assignment", "format.spacesAroundAssignment", "string",
            "Spaces around '=': keep, always, never.", SPACING),
        Key("format", "renumber-step", "format.renumberStep", "integer",
            "The step of Renumber N labels."),
    )  # fmt: skip


KEYS: tuple[Key, ...] = _keys()


def default_of(dotted: str) -> Any:
    """The value of the key ``dotted`` when nothing sets it (None: not set, not checked)."""
    config, fmt = Config(), FormatSettings()
    found: dict[str, Any] = {
        "machine.controller": config.controller,
        "machine.atan-range": ATAN_RANGES[1] if config.atan_signed else ATAN_RANGES[0],
        "machine.extended-commons": config.extended_commons,
        "machine.custom-calls": {},
        "machine.programs-on-control": [],
        "machine.g-code-system": config.g_code_system,
        "threading.max-depth-per-pass": config.max_depth_per_pass,
        "rules.select": ["ALL"],
        "rules.extend-select": [],
        "rules.ignore": sorted(config.disabled),
        "rules.per-file-ignores": {},
        "rules.severity": {},
        "files.exclude": [],
        "files.extensions": [],
        "analysis.step-budget": config.step_budget,
        "analysis.time-limit": config.time_limit,
        "analysis.max-line-length": config.max_line_length,
        "analysis.max-blocks": config.max_blocks,
        "analysis.max-file-size": config.max_file_size,
        "hover.full-precision": config.hover_full_precision,
        "cycle-time.rapid-rate-x": config.rapid_rate_x,
        "cycle-time.rapid-rate-y": config.rapid_rate_y,
        "cycle-time.rapid-rate-z": config.rapid_rate_z,
        "cycle-time.tool-change-seconds": config.tool_change_seconds,
        "cycle-time.m-code-seconds": {},
        "format.upper-case": fmt.upper_case,
        "format.space-between-words": fmt.space_between_words,
        "format.spaces-around-assignment": fmt.spaces_around_assignment,
        "format.renumber-step": fmt.renumber_step,
    }
    return found.get(dotted)


KEYS_BY_NAME: Mapping[str, Key] = MappingProxyType({k.dotted: k for k in KEYS})
SECTIONS = tuple(dict.fromkeys(k.section for k in KEYS))


class ConfigFileError(Exception):
    """A file that cannot be used: the message names the file, the line and the key."""


@dataclass(frozen=True)
class Origin:
    """Where a value came from: a file and line, the command line, the editor, a default."""

    where: str

    def __str__(self) -> str:
        return self.where


@dataclass
class FileSettings:
    """What the files found for one program say: the editor-shaped settings object, where
    each setting came from, and the files read (nearest first)."""

    settings: dict[str, Any] = field(default_factory=dict)
    origins: dict[str, Origin] = field(default_factory=dict)  # by Key.dotted
    files: list[Path] = field(default_factory=list)


def shown(path: Path) -> str:
    """A file as a message names it: from the current folder when it is below it (as the user
    typed the paths), else whole."""
    try:
        return path.relative_to(Path.cwd()).as_posix()
    except ValueError:
        return str(path)


def find_config_file(start: Path) -> Path | None:
    """The configuration file nearest ``start`` (a file or a folder), looking up each
    folder to the root: ``fanuc-macro.toml``, else a ``pyproject.toml`` that has a
    ``[tool.fanuc-macro]`` table."""
    folder = start if start.is_dir() else start.parent
    for candidate in (folder.resolve(), *folder.resolve().parents):
        own = candidate / FILE_NAME
        if own.is_file():
            return own
        pyproject = candidate / PYPROJECT
        if pyproject.is_file() and _has_tool_table(pyproject):
            return pyproject
    return None


def _has_tool_table(path: Path) -> bool:
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return False  # not ours to judge: a pyproject.toml is another tool's file too
    return isinstance(data.get("tool"), dict) and TOOL_TABLE[1] in data["tool"]


def load_config_file(path: Path) -> FileSettings:
    """The settings of ``path`` and of the files it extends (the nearer file's value wins).
    Raises :class:`ConfigFileError` for a file that cannot be read, a key not known, a value
    of the wrong type, or an ``extend`` chain that loops."""
    chain: list[Path] = []
    current: Path | None = path.resolve()
    tables: list[tuple[Path, dict[str, Any], str]] = []
    while current is not None:
        if current in chain:
            loop = " -> ".join(shown(p) for p in (*chain, current))
            raise ConfigFileError(f"{shown(chain[-1])}: extend makes a loop: {loop}")
        if len(chain) >= _MAX_EXTENDS:
            raise ConfigFileError(f"{shown(path)}: extend goes past {_MAX_EXTENDS} files")
        chain.append(current)
        text, table = _read_table(current)
        tables.append((current, table, text))
        extend = table.get("extend")
        if extend is None:
            current = None
        elif not isinstance(extend, str):
            line = _line_of(text, (), "extend", current.name == PYPROJECT)
            raise ConfigFileError(f"{shown(current)}:{line}: extend: {extend!r} is not a path")
        else:
            current = (current.parent / Path(extend).expanduser()).resolve()
            if not current.is_file():
                raise ConfigFileError(f"{shown(chain[-1])}: extend: no such file: {shown(current)}")
    found = FileSettings(files=chain)
    for file, table, text in reversed(tables):  # the farthest first: the nearer overwrites
        for key, value, line in _values(file, table, text):
            put_setting(found.settings, key.setting, value)
            found.origins[key.dotted] = Origin(f"{shown(file)}:{line}" if line else shown(file))
    return found


def _read_table(path: Path) -> tuple[str, dict[str, Any]]:
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise ConfigFileError(f"{shown(path)}: cannot be read: {e.strerror or e}") from None
    except UnicodeDecodeError:
        raise ConfigFileError(f"{shown(path)}: is not UTF-8 text (TOML files are)") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ConfigFileError(f"{shown(path)}: not TOML: {e}") from None
    if path.name == PYPROJECT:
        tool = data.get("tool")
        inner = tool.get(TOOL_TABLE[1]) if isinstance(tool, dict) else None
        return text, inner if isinstance(inner, dict) else {}
    return text, data


def _values(path: Path, table: dict[str, Any], text: str) -> Iterator[tuple[Key, Any, int]]:
    """Each key of ``table`` checked against :data:`KEYS`: the key, its value as the editor's
    setting holds it, and its line (0: not found in the text)."""
    nested = path.name == PYPROJECT
    for section, body in table.items():
        if section == "extend":
            continue
        if section not in SECTIONS or not isinstance(body, dict):
            line = _line_of(text, (), section, nested)
            known = ", ".join(f"[{s}]" for s in SECTIONS)
            raise ConfigFileError(
                f"{shown(path)}:{line}: {section!r} is not a table of it ({known})"
            )
        for name, value in body.items():
            line = _line_of(text, (section,), name, nested)
            key = KEYS_BY_NAME.get(f"{section}.{name}")
            if key is None:
                names = ", ".join(k.name for k in KEYS if k.section == section)
                raise ConfigFileError(
                    f"{shown(path)}:{line}: {section}.{name} is not a key of [{section}] ({names})"
                )
            problem = _type_problem(key, value)
            if not problem and key.section == "rules":
                value, problem = _rules_value(key, value, path.parent)
            if problem:
                raise ConfigFileError(f"{shown(path)}:{line}: {key.dotted}: {problem}")
            yield key, value, line


_KIND_WORDS = MappingProxyType(
    {
        "string": "a string",
        "number": "a number",
        "integer": "a whole number",
        "boolean": "true or false",
        "strings": "a list of strings",
        "table": "a table",
        "programs": "a list of program numbers or ranges",
    }
)


def _type_problem(key: Key, value: Any) -> str:
    """Why ``value`` cannot be ``key``'s, or ''."""
    kind = key.kind
    fits = {
        "string": isinstance(value, str),
        "number": isinstance(value, int | float) and not isinstance(value, bool),
        "integer": isinstance(value, int) and not isinstance(value, bool),
        "boolean": isinstance(value, bool),
        "strings": isinstance(value, list) and all(isinstance(v, str) for v in value),
        "table": isinstance(value, dict),
        "programs": isinstance(value, list)
        and all(isinstance(v, str | int) and not isinstance(v, bool) for v in value),
    }[kind]
    if not fits:
        return f"{value!r} is not {_KIND_WORDS[kind]}"
    if kind in ("number", "integer") and value <= 0:
        return f"{value!r} is not above 0"
    if key.choices and value not in key.choices:
        return f"{value!r} is not one of {', '.join(key.choices)}"
    return ""


def rule_code(text: str) -> str | None:
    """The code of the rule ``text`` names by its code or its name, in any case
    (``mb403``, ``Call-Target-Missing``, ``call_target_missing``); None for no rule."""
    from .analysis import RULES  # every rule family: loaded only when a file names rules

    code = text.strip().upper()
    if code in RULES:
        return code
    name = text.strip().lower().replace("_", "-")
    return next((c for c, info in RULES.items() if info.name == name), None)


def rule_selector(text: str) -> str | None:
    """``text`` as select reads it: "ALL", a rule's code or name, or a prefix of codes
    ("MB6"); None when it names no rule."""
    from .analysis import RULES

    code = rule_code(text)
    if code is not None:
        return code
    prefix = text.strip().upper()
    if prefix == "ALL" or (len(prefix) > 2 and any(c.startswith(prefix) for c in RULES)):
        return prefix
    return None


def _rules_value(key: Key, value: Any, folder: Path) -> tuple[Any, str]:
    """A value of [rules] with its rules as codes (``select`` keeps prefixes; a per-file
    ignore takes the file's folder), or why it cannot be read."""
    from .diagnostics import Severity

    if key.name in ("select", "extend-select"):
        found = [rule_selector(v) for v in value]
        bad = [v for v, f in zip(value, found, strict=True) if f is None]
        if bad:
            return value, f"{bad[0]!r} is not a rule's code or name, a prefix of codes or ALL"
        return found, ""
    if key.name == "severity":
        levels = [s.value for s in Severity]
        for level in value.values():
            if level not in levels:
                return value, f"{level!r} is not a severity ({', '.join(levels)})"
        codes, problem = _codes(list(value))
        return dict(zip(codes, value.values(), strict=True)), problem
    if key.name == "per-file-ignores":
        found_rules: list[list[Any]] = []
        for glob, names in value.items():
            if not isinstance(names, list):
                return value, f"{glob!r}: {names!r} is not a list of rules"
            codes, problem = _codes(names)
            if problem:
                return value, f"{glob!r}: {problem}"
            found_rules.append([str(folder), glob, codes])
        return found_rules, ""
    return _codes(value)


def _codes(names: list[Any]) -> tuple[list[str], str]:
    """The codes of the rules ``names`` names, or why not (the first name of no rule)."""
    codes = [rule_code(str(n)) for n in names]
    for name, code in zip(names, codes, strict=True):
        if code is None:
            return [], f"{name!r} is not a rule's code or name (docs/rules.md lists them)"
    return [c for c in codes if c is not None], ""


def merged(low: dict[str, Any], high: dict[str, Any]) -> dict[str, Any]:
    """Settings objects merged: each value of ``high`` replaces ``low``'s (tables merged key by
    key), so a file's value wins over the editor's and the editor's stays where the file says
    nothing."""
    out = dict(low)
    for key, value in high.items():
        below = out.get(key)
        if isinstance(value, dict) and isinstance(below, dict) and key not in _WHOLE_TABLES:
            out[key] = merged(below, value)
        else:
            out[key] = value
    return out


# Settings whose table is one value (a file's custom calls replace the editor's whole).
_WHOLE_TABLES = frozenset({"customCalls", "severity", "perFileIgnores", "mCodeSeconds"})


def files_of(settings: dict[str, Any]) -> tuple[tuple[str, ...], frozenset[str]]:
    """A settings object's ``[files]``: what a walk of folders skips (as ``--exclude``), and
    a shop's own extensions of program files, each as a file's is compared (".pgm" for
    "pgm", ".PGM" or "*.pgm")."""
    files = settings.get("files", {})
    extensions = frozenset(
        "." + str(e).strip().lstrip("*").lstrip(".").lower() for e in files.get("extensions", ())
    )
    return tuple(files.get("exclude", ())), extensions


def setting_of(dotted: str) -> str:
    """The editor setting (below ``fanuc-macro.``) the file's key ``dotted`` stands for."""
    return KEYS_BY_NAME[dotted].setting


def put_setting(settings: dict[str, Any], dotted: str, value: Any) -> None:
    """``value`` put at the editor setting ``dotted`` (``machine.maxSpindleSpeed``)."""
    *parents, last = dotted.split(".")
    for part in parents:
        settings = settings.setdefault(part, {})
    settings[last] = value


_HEADER = re.compile(r"^\s*\[\s*([^\]\[]+?)\s*\]\s*(?:#.*)?$")


def _line_of(text: str, tables: tuple[str, ...], name: str, nested: bool) -> int:
    """The line (from 1) of ``name`` in the table ``tables`` of ``text`` (inside
    ``[tool.fanuc-macro]`` when ``nested``), written as ``name =`` under its header or
    dotted (``machine.controller =``); 0 when it cannot be found (an inline table)."""
    prefix = (*TOOL_TABLE, *tables) if nested else tables
    current: tuple[str, ...] = ()
    for number, line in enumerate(text.splitlines(), 1):
        header = _HEADER.match(line)
        if header:
            current = tuple(p.strip().strip('"') for p in header.group(1).split("."))
            if current == (*prefix, name):
                return number
            continue
        left, sep, _ = line.partition("=")
        if not sep:
            continue
        path = current + tuple(p.strip().strip('"') for p in left.split("."))
        if path == (*prefix, name):
            return number
    return 0


def _schema_type(kind: str) -> dict[str, Any]:
    """The JSON Schema of a value of ``Key.kind``."""
    number = {"exclusiveMinimum": 0}
    schemas: dict[str, dict[str, Any]] = {
        "string": {"type": "string"},
        "number": {"type": "number", **number},
        "integer": {"type": "integer", **number},
        "boolean": {"type": "boolean"},
        "strings": {"type": "array", "items": {"type": "string"}},
        "table": {"type": "object"},
        "programs": {"type": "array", "items": {"type": ["string", "integer"]}},
    }
    return schemas[kind]


def json_schema() -> dict[str, Any]:
    """The JSON Schema of ``fanuc-macro.toml`` (draft 2020-12), written from :data:`KEYS`:
    editors that read TOML with a schema (Even Better TOML, taplo) complete and check the
    file with it. Rule codes and the values of tables are checked by the loader only."""
    sections: dict[str, Any] = {}
    for key in KEYS:
        body = sections.setdefault(
            key.section, {"type": "object", "additionalProperties": False, "properties": {}}
        )
        entry = {**_schema_type(key.kind), "description": key.description}
        if key.choices:
            entry["enum"] = list(key.choices)
        body["properties"][key.name] = entry
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "fanuc-macro configuration (fanuc-macro.toml, [tool.fanuc-macro])",
        "type": "object",
        "additionalProperties": False,
        "properties": {
            "extend": {
                "type": "string",
                "description": "A configuration file this one extends (its path from this "
                "file's folder); this file's values win.",
            },
            **sections,
        },
    }
