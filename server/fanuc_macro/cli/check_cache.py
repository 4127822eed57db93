"""The results of ``check`` kept between runs, as ruff keeps its own: a file whose text, whose
settings and whose related files (those it calls and those calling it) did not change is not
analysed again, and a file whose text did not change is not read again to find its programs
and calls.

Everything is keyed by content, never by a file's time: the digest of the file's bytes, of
each related file's name and bytes (in the order the analysis takes them, which decides the
first definition of a number), of the workspace's program numbers, of the settings and the
language the messages are said in (a result keeps them said, for the text form), and of
this package's own files (their names, sizes and times: an edited checkout is another tool).
Two tables in one SQLite file under the user's cache directory (:mod:`..code_cache`): a
file's links (the numbers it defines and calls) by its digest, and a file's findings by the
digest of all of the above. A run stopped by the time limit (the safety net: machine-
dependent) or failed (MB000) is not kept. ``FANUC_MACRO_CHECK_CACHE=0`` or ``--no-cache``
turns it off; another value of the variable names the directory.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import json
import os
import sqlite3
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

from .. import __version__
from ..code_cache import cache_directory
from ..config import Config
from ..workspace import DocumentLinks

ENVIRONMENT = "FANUC_MACRO_CHECK_CACHE"
FILE_NAME = "check-results.sqlite3"
# Seconds a run waits for another run's write to the cache before doing without.
BUSY_TIMEOUT = 5.0
# The package's files whose change makes another tool (its sources and data).
TOOL_SUFFIXES = (".py", ".json", ".lark", ".txt", ".po")


def digest(data: bytes) -> str:
    return hashlib.blake2b(data, digest_size=20).hexdigest()


def tool_fingerprint() -> str:
    """This package as it is on disk: its version and each source's name, size and time."""
    package = Path(__file__).resolve().parent.parent
    parts = [__version__]
    for path in sorted(package.rglob("*")):
        if path.suffix in TOOL_SUFFIXES and "__pycache__" not in path.parts:
            status = path.stat()
            parts.append(f"{path.relative_to(package)}:{status.st_size}:{status.st_mtime_ns}")
    return digest("\n".join(parts).encode())


def settings_fingerprint(config: Config) -> str:
    """The settings, in a form that does not depend on the order of their sets."""
    return digest(json.dumps(_plain(dataclasses.asdict(config)), sort_keys=True).encode())


def _plain(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (set, frozenset)):
        return sorted((_plain(v) for v in value), key=repr)
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, float) and value != value:  # NaN is not JSON
        return "nan"
    return value if isinstance(value, (str, int, float, bool, type(None))) else repr(value)


class CheckCache:
    """The cache of one run: what it found kept is read at once, what it adds is written at
    the end (:meth:`save`), in one transaction."""

    def __init__(self, connection: sqlite3.Connection, run_key: str) -> None:
        self._db = connection
        self._run_key = run_key
        self._new_links: dict[str, str] = {}
        self._new_results: dict[str, str] = {}

    @classmethod
    def open(
        cls, config: Config, locale: str = "en", directory: Path | None = None
    ) -> CheckCache | None:
        """The cache for runs with ``config`` in ``locale``, or None when it is off or cannot be
        opened. A result keeps the messages said in the run's language, so the language is
        part of its key: a run in Chinese never reads a result kept by a run in English."""
        chosen = os.environ.get(ENVIRONMENT, "")
        if chosen in ("0", "off", "false", "no"):
            return None
        if directory is None:
            directory = Path(chosen) if chosen else cache_directory()
        if directory is None:
            return None
        try:
            directory.mkdir(parents=True, exist_ok=True)
            connection = sqlite3.connect(directory / FILE_NAME, timeout=BUSY_TIMEOUT)
            connection.execute(
                "CREATE TABLE IF NOT EXISTS links (key TEXT PRIMARY KEY, value TEXT)"
            )
            connection.execute(
                "CREATE TABLE IF NOT EXISTS results (key TEXT PRIMARY KEY, value TEXT)"
            )
        except (OSError, sqlite3.Error):
            return None
        run_key = digest(f"{tool_fingerprint()}\n{settings_fingerprint(config)}\n{locale}".encode())
        return cls(connection, run_key)

    def links(self, data_digest: str) -> DocumentLinks | None:
        row = self._get("links", data_digest)
        if row is None:
            return None
        defines, reaches, may_reach, written = json.loads(row)
        return DocumentLinks(
            tuple(defines),
            None if reaches is None else tuple(reaches),
            tuple(may_reach),
            tuple(written),
        )

    def keep_links(self, data_digest: str, links: DocumentLinks) -> None:
        value = [links.defines, links.reaches, links.may_reach, links.written]
        self._new_links[data_digest] = json.dumps(value)

    def result_key(
        self,
        name: str,
        data_digest: str,
        related: Sequence[tuple[str, str]] | None,
        everything: str,
        programs: str,
    ) -> str:
        """The key of a file's findings: its name and digest, its related files' names and
        digests in order (None: every file, whose digest is ``everything``), the digest of
        the workspace's program numbers, and the run's tool and settings."""
        parts = [self._run_key, programs, name, data_digest]
        if related is None:
            parts.append(f"all:{everything}")
        else:
            parts.extend(f"{n}:{d}" for n, d in related)
        return digest("\n".join(parts).encode())

    def result(self, key: str) -> Any:
        row = self._get("results", key)
        return None if row is None else json.loads(row)

    def keep_result(self, key: str, value: object) -> None:
        self._new_results[key] = json.dumps(value)

    def save(self) -> None:
        """Writes what the run added; a cache that cannot be written is left as it was."""
        with contextlib.suppress(sqlite3.Error), self._db:
            self._db.executemany(
                "INSERT OR REPLACE INTO links VALUES (?, ?)", self._new_links.items()
            )
            self._db.executemany(
                "INSERT OR REPLACE INTO results VALUES (?, ?)", self._new_results.items()
            )
        self._new_links.clear()
        self._new_results.clear()

    def close(self) -> None:
        with contextlib.suppress(sqlite3.Error):
            self._db.close()

    def _get(self, table: str, key: str) -> str | None:
        try:
            row = self._db.execute(f"SELECT value FROM {table} WHERE key = ?", (key,)).fetchone()
        except sqlite3.Error:
            return None
        return None if row is None else str(row[0])


def numbers_digest(numbers: Iterable[int]) -> str:
    return digest(",".join(map(str, sorted(numbers))).encode())


def all_digest(digests: Mapping[str, str]) -> str:
    return digest("\n".join(f"{k}:{v}" for k, v in digests.items()).encode())
