"""The settings of a command-line run: the configuration file nearest each checked file
(:mod:`..config_file`) under the options given on the command line, which win over it; the
defaults under both."""

from __future__ import annotations

import argparse
import copy
import json
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..config import Config
from ..config_file import (
    KEYS,
    ConfigFileError,
    FileSettings,
    Key,
    default_of,
    find_config_file,
    json_schema,
    load_config_file,
    put_setting,
    setting_of,
    shown,
)
from ..translation import tr
from .language import said, said_error

DEFAULT = "default"


@dataclass(frozen=True)
class Resolved:
    """The settings of one file: the configuration, the settings object it was read from,
    where each key's value came from (by ``Key.dotted``), and the files read (nearest
    first; none with ``--isolated`` or when none was found)."""

    config: Config
    settings: dict[str, Any]
    origins: dict[str, str]
    files: tuple[Path, ...]


# Each option of the command line and the key of the configuration file it stands for.
_OPTIONS = (
    ("controller", "machine.controller", "--controller"),
    ("max_spindle_speed", "machine.max-spindle-speed", "--max-spindle-speed"),
    ("max_threading_feed", "machine.max-threading-feed", "--max-threading-feed"),
    ("extended_commons", "machine.extended-commons", "--extended-commons"),
    ("g_code_system", "machine.g-code-system", "--g-code-system"),
    ("max_line_length", "analysis.max-line-length", "--max-line-length"),
    ("max_blocks", "analysis.max-blocks", "--max-blocks"),
    ("max_file_size", "analysis.max-file-size", "--max-file-size"),
    ("step_budget", "analysis.step-budget", "--step-budget"),
    ("time_limit", "analysis.time-limit", "--time-limit"),
)


class ConfigResolver:
    """The settings of each file of a run, read once per configuration file."""

    def __init__(self, args: argparse.Namespace) -> None:
        self._args = args
        self._by_file: dict[Path | None, Resolved] = {}
        self._explicit: Path | None = Path(args.config) if getattr(args, "config", None) else None
        self._isolated = bool(getattr(args, "isolated", False))

    def file_for(self, path: Path | None) -> Path | None:
        """The configuration file of ``path`` (None: the current folder's)."""
        if self._isolated:
            return None
        if self._explicit is not None:
            return self._explicit
        return find_config_file(path if path is not None else Path.cwd())

    def for_path(self, path: Path | None) -> Resolved:
        """The settings of the program at ``path`` (standard input: its --stdin-filename, or
        the current folder). Raises ConfigFileError for a file that cannot be used."""
        file = self.file_for(path)
        found = self._by_file.get(file)
        if found is None:
            loaded = load_config_file(file) if file is not None else FileSettings()
            found = self._by_file[file] = _resolve(loaded, self._args)
            for problem in found.config.setting_problems:
                print(f"fanuc-macro: {said(problem)}", file=sys.stderr)
        return found


def _resolve(loaded: FileSettings, args: argparse.Namespace) -> Resolved:
    settings = copy.deepcopy(loaded.settings)  # the options below are put into it
    origins = {dotted: str(origin) for dotted, origin in loaded.origins.items()}
    for attribute, dotted, option in _OPTIONS:
        value = getattr(args, attribute, None)
        if value is not None:
            put_setting(settings, setting_of(dotted), value)
            origins[dotted] = option
    disabled = [c for codes in getattr(args, "disable", None) or () for c in sorted(codes)]
    if disabled:
        rules = settings.setdefault("rules", {})
        rules["disabled"] = sorted({*rules.get("disabled", ()), *disabled})
        origins["rules.ignore"] = _joined(origins.get("rules.ignore"), "--disable")
    _rule_options(settings, origins, args)
    calls = getattr(args, "custom_call", None)
    if calls:
        machine = settings.setdefault("machine", {})
        machine["customCalls"] = {**machine.get("customCalls", {}), **dict(calls)}
        origins["machine.custom-calls"] = _joined(
            origins.get("machine.custom-calls"), "--custom-call"
        )
    ranges = getattr(args, "on_control", None)
    if ranges:
        machine = settings.setdefault("machine", {})
        given = [f"{a}-{b}" for group in ranges for a, b in group]
        machine["programsOnControl"] = [*machine.get("programsOnControl", ()), *given]
        origins["machine.programs-on-control"] = _joined(
            origins.get("machine.programs-on-control"), "--on-control"
        )
    for key in KEYS:
        origins.setdefault(key.dotted, DEFAULT)
    return Resolved(Config.from_settings(settings), settings, origins, tuple(loaded.files))


def _rule_options(
    settings: dict[str, Any], origins: dict[str, str], args: argparse.Namespace
) -> None:
    """--select (replaces the file's), --extend-select and --severity (add to it)."""
    rules = settings.setdefault("rules", {})
    select = getattr(args, "select", None)
    if select:  # replaces the file's choice whole, its extend-select too (as ruff's)
        rules["select"] = [c for group in select for c in group]
        rules.pop("extendSelect", None)
        origins["rules.select"] = origins["rules.extend-select"] = "--select"
    extend = getattr(args, "extend_select", None)
    if extend:
        rules["extendSelect"] = [*rules.get("extendSelect", ()), *(c for g in extend for c in g)]
        origins["rules.extend-select"] = _joined(
            origins.get("rules.extend-select"), "--extend-select"
        )
    severity = getattr(args, "severity", None)
    if severity:
        rules["severity"] = {**rules.get("severity", {}), **dict(severity)}
        origins["rules.severity"] = _joined(origins.get("rules.severity"), "--severity")


def _joined(before: str | None, option: str) -> str:
    return option if before is None else f"{before} and {option}"


def config_or_exit(resolver: ConfigResolver, path: Path | None) -> Config:
    """:meth:`ConfigResolver.for_path`'s configuration; a file that cannot be used ends the
    run with its message (exit status 2), as a bad option does."""
    try:
        return resolver.for_path(path).config
    except ConfigFileError as error:
        raise SystemExit(_usage(said_error(error))) from None


def _usage(message: str) -> int:
    print(f"fanuc-macro: {said(message)}", file=sys.stderr)
    return 2


def print_config(args: argparse.Namespace, anchor: Path | None) -> int:
    """``fanuc-macro config``: each key's value for the program at ``anchor`` and where it
    came from; or the file's JSON Schema."""
    out = sys.stdout
    if args.format == "schema":
        json.dump(json_schema(), out, indent=2)
        out.write("\n")
        return 0
    try:
        resolved = ConfigResolver(args).for_path(anchor)
    except ConfigFileError as error:
        return _usage(said_error(error))
    values = {key.dotted: _value(resolved, key) for key in KEYS}
    origins = resolved.origins
    shown_files = [shown(f) for f in resolved.files]
    if args.format == "json":
        json.dump(
            {
                "files": shown_files,
                "settings": {
                    dotted: {"value": value, "from": origins[dotted]}
                    for dotted, value in values.items()
                },
            },
            out,
            indent=1,
        )
        out.write("\n")
        return 0
    files = ", ".join(shown_files) if shown_files else said(tr("none"))
    out.write(said(tr("# configuration files: {files}", files=files)) + "\n")
    section = ""
    for key in KEYS:
        if key.section != section:
            section = key.section
            out.write(f"[{section}]\n")
        origin = origins[key.dotted]
        if values[key.dotted] is None:  # no TOML value says "not set"
            out.write(said(tr("# {key}: not set, not checked", key=key.name)))
            out.write(f"  # {_origin(origin)}\n")
        else:
            out.write(f"{key.name} = {_toml(values[key.dotted])}  # {_origin(origin)}\n")
    return 0


def _origin(origin: str) -> str:
    """Where a value comes from, in the text form: a file, options, or the default."""
    if origin == DEFAULT:
        return said(tr("default"))
    return said(tr(" and ")).join(origin.split(" and "))


def _value(resolved: Resolved, key: Key) -> Any:
    """``key``'s value in force: as set, else the default (None: not set, not checked)."""
    node: Any = resolved.settings
    for part in key.setting.split("."):
        node = node.get(part) if isinstance(node, dict) else None
    if node is not None and key.dotted == "rules.per-file-ignores":
        return {glob: codes for _folder, glob, codes in node}  # the folder: the file's own
    if node is not None:
        return node
    return default_of(key.dotted)


def _toml(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, dict):
        inner = ", ".join(f"{_bare(k)} = {_toml(v)}" for k, v in value.items())
        return "{ " + inner + " }" if inner else "{}"
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return json.dumps(value, ensure_ascii=False) if isinstance(value, str) else str(value)


def _bare(name: str) -> str:
    return name if name.replace("-", "").replace("_", "").isalnum() else json.dumps(name)
