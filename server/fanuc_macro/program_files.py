"""Which files are programs, and the walk of a folder for them.

A file is a program by its extension (``.nc``, ``.mpf``, ...), or, for an extension that other
files use too (``.txt``, ``.prg``, ``.iso``) and for a file with none, by its content: its first
meaningful line is a tape mark, a program number or an NC block, and most of its first lines
are blocks (:func:`looks_like_program`). A walk skips hidden folders and tools' folders
(``node_modules``, ``build``, a virtualenv, ...) and the ``--exclude`` patterns; a file or
folder named by the user is always taken, as ruff does.

Nothing here imports the rest of the package: the language server's folder scan, the debugger
and the command line all decide the same way.
"""

from __future__ import annotations

import codecs
import fnmatch
import os
import re
from collections.abc import Iterable, Sequence
from collections.abc import Set as AbstractSet
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

# Programs by extension, in any case: what controls and CAM post-processors write. Other
# controls' programs among them (Siemens, Okuma, LinuxCNC) are read too: the checker names what
# FANUC would not run. Heidenhain's conversational .h is no G-code, and a 3D printer's .gcode is
# no control's: neither is taken from a folder.
PROGRAM_SUFFIXES = frozenset(
    {
        ".nc",  # FANUC, Haas, most CAM posts
        ".cnc",
        ".tap",  # tape files; Mach3
        ".eia",  # Mazak EIA/ISO
        ".mac",  # macro programs
        ".ngc",  # LinuxCNC; Haas NGC
        ".ncd",  # NCVC
        ".min",  # Okuma main programs
        ".mpf",  # Siemens main programs
        ".spf",  # Siemens sub programs
    }
)
# Extensions that other files have too (notes, dBase .prg, disk images .iso, subtitles .sub):
# a program only when its content looks like one.
SNIFFED_SUFFIXES = frozenset(
    {
        ".txt",  # FANUC's memory card punch (ALL-PROG.TXT), DNC software, notes alike
        ".prg",  # Mitsubishi, Brother
        ".iso",  # ISO programs of Fagor, Mazak, Heidenhain's ISO mode
        ".ptp",  # punched tape images
        ".sub",  # Okuma sub programs
        ".ssb",  # Okuma system sub programs
        ".mc12",  # a Mastercam post's
    }
)
# Tools' folders, never a shop's: package managers, builds, caches, virtualenvs. Every hidden
# folder (.git, .venv, .vscode, ...) is skipped as well, a Python package's *.egg-info and
# *.dist-info, and any folder holding a virtualenv's pyvenv.cfg or a cache's CACHEDIR.TAG,
# whatever its name.
SKIPPED_FOLDERS = frozenset(
    {
        "node_modules",
        "bower_components",
        "__pycache__",
        "__pypackages__",
        "site-packages",
        "venv",
        "build",
        "dist",
        "_build",
        "buck-out",
    }
)
TOOL_MARKERS = ("pyvenv.cfg", "CACHEDIR.TAG")
TOOL_FOLDER_SUFFIXES = (".egg-info", ".dist-info")  # Python packages' metadata

SNIFF_BYTES = 8192
SNIFF_LINES = 40
NC_SHARE = 0.5  # of the meaningful lines looked at, the blocks a program has at least

_NUMBER_NAME = re.compile(r"O\d{1,8}", re.I)
_EXTENSION = re.compile(r"\.(?=[^.]*[A-Za-z])[A-Za-z0-9_+-]{1,16}")  # a letter, no space
_LINE_END = re.compile(r"\r\n|\r|\n")
_COMMENT = re.compile(r"\([^)]*\)?|;.*|//.*")  # FANUC's, LinuxCNC's, DDCS's
_SPACE = re.compile(r"\s+")
# On a line without comments and spaces, in upper case:
# '%', or '%' run into a program number ('%O100') or a Syntec header ('%@MACRO')
_TAPE_MARK = re.compile(r"%(?:$|O\d|O<|:\d|@)")
_WORD = r"(?:,?[A-Z][-+]?(?:\d+\.?\d*|\.\d+|#\d+|#?\[.*?\]+))"
_HEAD = re.compile(rf"(?:O\d{{1,8}}|O<[^>]+>|:\d{{1,8}})(?:{_WORD}*|SUB)")  # LinuxCNC: o<x> sub
_BLOCK = re.compile(
    rf"(?:/\d?)?(?:{_WORD}+|(?:N\d+)?"
    r"(?:#\d+=|#\[|#<|IF[\[(]|WHILE[\[(]|GOTO[\d#\[]|END\d|ENDIF$|ELSE$|DO\d|[BD]PRNT\[|POPEN$|PCLOS$).*)"
)


def extension(path: Path) -> str:
    """The extension that says what ``path`` is, in lower case; '' for none. A "suffix" with
    spaces or without a letter ('1.5 inch bore', 'PART.001') is part of a name, not an
    extension."""
    suffix = path.suffix
    return suffix.lower() if _EXTENSION.fullmatch(suffix) else ""


def _text_head(data: bytes, complete: bool) -> str | None:
    """The first lines of ``data`` as text for the sniff, None for bytes that are no text.
    ASCII is all a block needs, so legacy encodings (GB18030, Shift-JIS in comments) are read
    byte for byte."""
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        even = data if complete else data[: len(data) // 2 * 2]
        text = even.decode("utf-16", errors="replace")
    elif b"\0" in data:
        return None
    else:
        text = data.removeprefix(codecs.BOM_UTF8).decode("latin-1")
    if not complete:  # the last line is cut short
        text = text[: max(text.rfind("\n"), text.rfind("\r"), 0)]
    return text


def looks_like_program(data: bytes, complete: bool = True) -> bool:
    """Whether ``data`` (a file's first bytes; ``complete`` when they are all of it) reads as
    an NC program: its first meaningful line (not blank, not only a comment) is a tape mark
    ``%``, a program number (``O1234``, ``O<NAME>``, ``:1234``) or a block, and when it is a
    block, at least half of its first meaningful lines are blocks (``G00 X1.``, ``N10 M30``,
    ``#1=2``, ``IF[...]GOTO5``, ``WHILE[...]DO1``)."""
    text = _text_head(data, complete)
    if text is None:
        return False
    lines: list[str] = []
    for raw in _LINE_END.split(text):
        line = _SPACE.sub("", _COMMENT.sub("", raw)).upper()
        if line.startswith("%") and not lines:
            return _TAPE_MARK.match(line) is not None
        if line:
            lines.append(line)
            if len(lines) == SNIFF_LINES:
                break
    if not lines:
        return False
    if _HEAD.fullmatch(lines[0]):
        return True
    if not _BLOCK.fullmatch(lines[0]):
        return False
    blocks = sum(1 for line in lines if _BLOCK.fullmatch(line) or _TAPE_MARK.match(line))
    return blocks >= NC_SHARE * len(lines)


def _content_is_program(path: Path) -> bool:
    try:
        with path.open("rb") as f:
            data = f.read(SNIFF_BYTES + 1)
    except OSError:
        return False
    return looks_like_program(data[:SNIFF_BYTES], complete=len(data) <= SNIFF_BYTES)


def is_sniffed(path: Path) -> bool:
    """Whether ``path``'s content decides if it is a program: an extension other files share,
    or none (:data:`SNIFFED_SUFFIXES`)."""
    suffix = extension(path)
    return suffix in SNIFFED_SUFFIXES or not suffix


def is_program_file(path: Path, extensions: AbstractSet[str] = frozenset()) -> bool:
    """Whether a file met in a folder is a program: by its extension
    (:data:`PROGRAM_SUFFIXES`, and ``extensions``, a shop's own: ".pgm"), by a name that is a
    program number ('O09010', as a control's memory card holds them), or, for the extensions
    of :data:`SNIFFED_SUFFIXES` and none, by its content (:func:`looks_like_program`)."""
    suffix = extension(path)
    if suffix in PROGRAM_SUFFIXES or suffix in extensions:
        return True
    if not suffix and _NUMBER_NAME.fullmatch(path.name):
        return True
    return is_sniffed(path) and _content_is_program(path)


def is_tool_folder(path: Path) -> bool:
    """Whether a folder met in a walk is hidden or a tool's (:data:`SKIPPED_FOLDERS`, a
    virtualenv, a tagged cache), never a shop's programs."""
    name = path.name
    if name.startswith(".") or name in SKIPPED_FOLDERS or name.endswith(TOOL_FOLDER_SUFFIXES):
        return True
    return any((path / marker).is_file() for marker in TOOL_MARKERS)


def _pattern(text: str) -> str:
    text = text.replace("\\", "/").strip()
    while text.startswith("./"):
        text = text[2:]
    return text.rstrip("/")


def excluded(relative: PurePosixPath, shown: PurePosixPath, patterns: Sequence[str]) -> bool:
    """Whether a path of a walk matches an ``--exclude`` pattern, as ruff's ``--exclude``: a
    pattern without '/' matches a file's or folder's name anywhere in the walk ('*.bak',
    'old'); one with '/' matches the path from the folder walked ('old/*.nc'), or as shown
    ('progs/old'). ``**/`` matches any folders, none too."""
    for raw in patterns:
        pattern = _pattern(raw)
        if not pattern:
            continue
        if "/" not in pattern:
            if fnmatch.fnmatch(relative.name, pattern):
                return True
            continue
        forms = {pattern}
        while pattern.startswith("**/"):
            pattern = pattern[3:]
            forms.add(pattern)
        for form in forms:
            if fnmatch.fnmatch(relative.as_posix(), form) or fnmatch.fnmatch(
                shown.as_posix(), form
            ):
                return True
    return False


@dataclass
class Found:
    """What a walk of the paths given found."""

    programs: list[Path] = field(default_factory=list)
    # Files of a sniffed extension (or none) whose content is not a program.
    not_programs: list[Path] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)  # paths given that are not there
    empty: list[str] = field(default_factory=list)  # folders given without a program


def walk_folder(
    folder: Path,
    exclude: Sequence[str] = (),
    found: Found | None = None,
    extensions: AbstractSet[str] = frozenset(),
) -> Found:
    """The programs under ``folder`` in path order, hidden files and tools' folders skipped,
    and the text files that are not programs (``extensions``: see :func:`is_program_file`)."""
    found = found if found is not None else Found()
    programs: list[Path] = []
    not_programs: list[Path] = []
    for root, dirs, files in os.walk(folder):
        here = Path(root)
        base = PurePosixPath(here.relative_to(folder).as_posix())
        shown = PurePosixPath(here.as_posix())
        if exclude:
            dirs[:] = [d for d in dirs if not excluded(base / d, shown / d, exclude)]
            files = [f for f in files if not excluded(base / f, shown / f, exclude)]
        dirs[:] = sorted(d for d in dirs if not is_tool_folder(here / d))
        for name in files:
            path = here / name
            if name.startswith(".") or not path.is_file():
                continue
            if is_program_file(path, extensions):
                programs.append(path)
            elif is_sniffed(path):
                not_programs.append(path)
    found.programs.extend(sorted(programs))
    found.not_programs.extend(sorted(not_programs))
    return found


def find_programs(
    paths: Iterable[str], exclude: Sequence[str] = (), extensions: AbstractSet[str] = frozenset()
) -> Found:
    """The programs of the paths given, in order: a file as given, whatever it is; a folder's
    programs (:func:`walk_folder`). A path that is not there, or a folder without programs, is
    noted and the others still walked."""
    found = Found()
    for raw in paths:
        path = Path(raw)
        if path.is_dir():
            before = len(found.programs)
            walk_folder(path, exclude, found, extensions)
            if len(found.programs) == before:
                found.empty.append(raw)
        elif path.is_file():
            found.programs.append(path)
        else:
            found.missing.append(raw)
    return found


__all__ = (
    "PROGRAM_SUFFIXES",
    "SKIPPED_FOLDERS",
    "SNIFFED_SUFFIXES",
    "TOOL_FOLDER_SUFFIXES",
    "TOOL_MARKERS",
    "Found",
    "excluded",
    "extension",
    "find_programs",
    "is_program_file",
    "is_sniffed",
    "is_tool_folder",
    "looks_like_program",
    "walk_folder",
)
