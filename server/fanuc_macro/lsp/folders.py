"""The workspace folders: their program files read into the workspace in chunks, so that calls
across files resolve, those of a folder that leaves forgotten, files changed on disk read
again. Bounded in all: SCAN_MAX_FILES files of at most SCAN_MAX_BYTES each."""

from __future__ import annotations

import asyncio
import os
from collections.abc import Callable, Iterable, Sequence
from collections.abc import Set as AbstractSet
from pathlib import Path, PurePosixPath
from typing import TYPE_CHECKING

from lsprotocol import types
from pygls.uris import from_fs_path, to_fs_path

from .documents import key_of

if TYPE_CHECKING:
    from .engine import Engine

SCAN_MAX_FILES = 2000
SCAN_MAX_BYTES = 2 * 1024 * 1024
SCAN_CHUNK = 25  # files per worker job, so that edits are analysed between chunks


class Folders:
    """The folders of the workspace and their scans, on the engine's worker."""

    def __init__(self, engine: Engine) -> None:
        self.engine = engine
        self.paths: list[Path] = []
        self.scan_done = asyncio.Event()
        self.scanned_files = 0
        self._scans = 0  # folder scans under way
        self._scan_listed = 0  # files listed by all scans (the bound is for all of them)

    def _schedule_all(self) -> None:
        self.engine.schedule_all(self.engine.debounce)

    def contains(self, path: Path) -> bool:
        """``path`` is under a workspace folder."""
        for folder in self.paths:
            try:
                path.relative_to(folder)
                return True
            except ValueError:
                continue
        return False

    def add(self, folders: Iterable[str]) -> None:
        """Add the program files of workspace folders (bounded in all: SCAN_MAX_FILES files of
        at most SCAN_MAX_BYTES each), in chunks, so that calls across files resolve."""
        paths: list[Path] = []
        for folder in folders:
            path = path_of(folder)
            if path is not None and path.is_dir() and path not in self.paths:
                paths.append(path)
        self.paths.extend(paths)
        if not paths:
            if self._scans == 0:
                self.scan_done.set()
            return
        self._scans += 1
        self.scan_done.clear()
        budget = max(0, SCAN_MAX_FILES - self._scan_listed)

        def walk() -> list[Path]:
            try:
                files = list(program_files(paths, budget, files_settings))
            except Exception as err:  # an unreadable folder: scan nothing there
                self.engine.report(f"fanuc-macro: cannot list {paths}: {err!r}", err)
                return []
            self._scan_listed += len(files)
            # The first chunk in the same job: an analysis the client asks for next (its
            # first document opened) then sees the programs of a small workspace.
            self._add_files(files[:SCAN_CHUNK])
            return files[SCAN_CHUNK:]

        self.engine.scheduler.submit(walk, then=self._scan_chunk)

    def remove(self, folders: Iterable[str]) -> None:
        """Forget the files of folders that left the workspace (open documents stay)."""
        gone = [p for p in (path_of(f) for f in folders) if p is not None]
        self.paths = [f for f in self.paths if f not in gone]

        def under(path: Path) -> bool:
            return any(path.is_relative_to(folder) for folder in gone)

        def forget() -> None:
            for key in self.engine.file_keys():
                path = path_of(key)
                is_open = self.engine.documents.is_open(key)
                if path is not None and not is_open and under(path):
                    self.engine.remove_file(key)

        self.engine.scheduler.submit(
            forget, then=lambda _: self.engine.schedule_all(self.engine.debounce)
        )

    def _add_files(self, chunk: list[Path]) -> None:
        """Read files of a folder scan into the workspace (worker only)."""
        for path in chunk:
            key = key_of(from_fs_path(str(path)) or path.as_uri())
            if self.engine.documents.is_open(key) or self.engine.has_file(key):
                continue
            data = read_program(path)
            if data is None:
                continue
            try:
                self.engine.add_file(key, data)
                self.scanned_files += 1
            except Exception as err:  # one unreadable file must not end the scan
                self.engine.report(f"fanuc-macro: cannot read {path}: {err!r}", err)

    def _scan_chunk(self, files: list[Path]) -> None:
        """The rest of a folder scan, a chunk per job, so that edits are analysed between."""
        if not files:
            self._scans -= 1
            if self._scans == 0:
                self.scan_done.set()
            self.engine.schedule_all(0.0)
            return
        chunk, rest = files[:SCAN_CHUNK], files[SCAN_CHUNK:]
        self.engine.scheduler.submit(
            lambda: self._add_files(chunk), then=lambda _: self._scan_chunk(rest)
        )

    def files_changed(self, events: Sequence[types.FileEvent]) -> None:
        """Files changed on disk (workspace/didChangeWatchedFiles): those not open are reread."""
        todo: list[tuple[str, Path | None, bool]] = []
        for event in events:
            key = key_of(event.uri)
            if key in self.engine.docs:
                continue  # the editor's text wins
            path = path_of(key)
            deleted = event.type == types.FileChangeType.Deleted
            if path is None or (not deleted and not is_program_file(path)):
                continue
            todo.append((key, path, deleted))
        if not todo:
            return

        def apply() -> frozenset[str]:
            return self.engine.changed_files(
                {
                    key: None if deleted or path is None else read_program(path)
                    for key, path, deleted in todo
                }
            )

        self.engine.scheduler.submit(apply, then=self.engine.schedule_each)


def path_of(uri: str) -> Path | None:
    if not uri.startswith("file:"):
        return None
    path = to_fs_path(uri)
    return Path(path) if path else None


def read_program(path: Path) -> bytes | None:
    try:
        if not path.is_file() or path.stat().st_size > SCAN_MAX_BYTES:
            return None
        return path.read_bytes()
    except OSError:
        return None


def files_settings(folder: Path) -> tuple[tuple[str, ...], frozenset[str]]:
    """The ``[files]`` of the configuration file nearest ``folder``: what a walk of it skips
    (as ``check --exclude``) and a shop's own program extensions. A file that cannot be used
    gives none (the engine tells it when it reads the settings)."""
    from ..config_file import ConfigFileError, files_of, find_config_file, load_config_file

    try:
        found = find_config_file(folder)
        return files_of(load_config_file(found).settings if found else {})
    except ConfigFileError:
        return (), frozenset()


def program_files(
    folders: Sequence[Path],
    limit: int,
    settings_of: Callable[[Path], tuple[tuple[str, ...], frozenset[str]]] | None = None,
) -> Iterable[Path]:
    """Program files under ``folders``, hidden and tool folders skipped as ``check`` skips
    them (``program_files.is_tool_folder``), and what ``settings_of`` a folder excludes,
    at most ``limit``."""
    from ..program_files import excluded, is_tool_folder

    count = 0
    seen: set[Path] = set()
    for folder in folders:
        exclude, extensions = settings_of(folder) if settings_of else ((), frozenset[str]())
        for root, dirs, files in os.walk(folder):
            here = Path(root)
            base = PurePosixPath(here.relative_to(folder).as_posix())
            shown = PurePosixPath(here.as_posix())
            dirs[:] = sorted(
                d
                for d in dirs
                if not is_tool_folder(here / d) and not excluded(base / d, shown / d, exclude)
            )
            for name in sorted(files):
                path = Path(root, name)
                if name.startswith(".") or path in seen:
                    continue
                if exclude and excluded(base / name, shown / name, exclude):
                    continue
                try:
                    if path.stat().st_size > SCAN_MAX_BYTES or not is_program_file(
                        path, extensions
                    ):
                        continue
                except OSError:
                    continue
                seen.add(path)
                yield path
                count += 1
                if count >= limit:
                    return


def is_program_file(path: Path, extensions: AbstractSet[str] = frozenset()) -> bool:
    from ..workspace import is_program_file as is_program

    return is_program(path, extensions)


__all__ = ("Folders", "is_program_file", "path_of", "program_files", "read_program")
