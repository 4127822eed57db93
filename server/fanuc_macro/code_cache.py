"""A cache of the code that class builders generate, kept between runs as Python keeps .pyc files.

``dataclasses``, ``attrs`` and ``cattrs`` write the source of each class's ``__init__``,
``__eq__``, ``__repr__`` and converter hooks at run time and compile it: importing
``lsprotocol.types`` (about 570 attrs classes) spends about half of its 0.26-0.31 s in
``compile``, and the package's own dataclasses a further 30-40 ms of a ``check``. Compiling the
same source gives the same code, so the entry points (the command line and the language server)
install this cache first: it shadows ``compile`` (``exec`` in ``dataclasses``) in those
modules' globals with a function that looks the source up first, and keeps the code objects it
used in a ``marshal`` file per kind of process and per Python version, under the user's cache
directory.

What the cached code does is what the compiled code does: the key is the exact source, the
file name, the mode and the ``__future__`` flags the builder's module compiles with, and a
file written by another Python version is not read (its name carries the interpreter's magic
number, as .pyc files do). A missing, unreadable or corrupt file only means compiling again.
``FANUC_MACRO_CODE_CACHE=0`` turns it off; another value names the directory to keep it in.

Loading a file runs its code, so a file is read only if this user could have written it and
no one else could have changed it (see :func:`_untrusted_file`), and only if its digest,
keyed by the package's and Python's versions, matches its content.
"""

from __future__ import annotations
import __future__

import builtins
import contextlib
import importlib
import marshal
import os
import stat
import sys
from collections.abc import Callable, Mapping
from importlib.util import MAGIC_NUMBER
from pathlib import Path
from types import CodeType, MappingProxyType, ModuleType
from typing import Any

from . import __version__

try:  # the builtin module: hashlib would load OpenSSL, 4 ms of a start
    from _blake2 import blake2b
except ImportError:  # pragma: no cover - a Python built without it
    from hashlib import blake2b

ENVIRONMENT = "FANUC_MACRO_CODE_CACHE"

# The modules that build classes for each kind of process, and the name of the builtin each
# compiles through. The command line builds only dataclasses; the language server also builds
# lsprotocol's attrs classes and cattrs' hooks for the messages it receives.
BUILDERS: Mapping[str, tuple[tuple[str, str], ...]] = MappingProxyType(
    {
        "cli": (("dataclasses", "exec"),),
        "server": (
            ("dataclasses", "exec"),
            ("attr._make", "compile"),
            ("cattrs.gen", "compile"),
            ("cattrs.gen.typeddicts", "compile"),
        ),
    }
)
# The attribute of a shadowing compile or exec that holds its cache: the one record of the
# cache a process installed is on the builtins it shadows.
SHADOW_ATTRIBUTE = "fanuc_macro_code_cache"

# A file holding more entries than this is not read: it was written by a process gone wrong.
MAX_ENTRIES = 50_000

# A few classes give a new source at every start (attrs' frozen classes hash a salt that
# depends on the hash seed into theirs, e.g. cattrs' AttributeOverride): up to this many
# sources compiled again under names the file holds do not make it be written again.
CHANGING_SOURCES = 8

Key = tuple[str, str, str, int]

# A file is this mark, the digest of what follows, then the marshalled code.
MARK = b"fanuc-macro code cache\n"
DIGEST_SIZE = 32
# The digest is keyed by the versions, so a file written by another version of the package or
# of Python does not match. It is no signature: whoever can write the file can write a digest
# that matches. What keeps out a foreign writer is the check of the file's owner and mode and
# of its directory; the digest keeps out a stale, truncated or otherwise damaged file.
DIGEST_KEY = blake2b(f"{__version__}\0{sys.version}\0{MAGIC_NUMBER.hex()}".encode()).digest()


def _digest(payload: bytes | memoryview) -> bytes:
    return blake2b(payload, digest_size=DIGEST_SIZE, key=DIGEST_KEY).digest()


def encode(known: dict[Key, CodeType]) -> bytes:
    """The content of a file holding these code objects."""
    payload = marshal.dumps(known)
    return MARK + _digest(payload) + payload


def decode(data: bytes) -> object:
    """The object a file's content holds; ValueError if its mark or digest do not match."""
    start = len(MARK) + DIGEST_SIZE
    if not data.startswith(MARK) or len(data) < start:
        raise ValueError("not a code cache file")
    payload = memoryview(data)[start:]
    if _digest(payload) != data[len(MARK) : start]:
        raise ValueError("digest does not match the content")
    return marshal.loads(payload)


class CodeCache:
    """The code objects of one kind of process: those read from its file, and those it used."""

    def __init__(self, path: Path | None, known: dict[Key, CodeType]) -> None:
        self.path = path
        self.known = known
        self.known_names = {key[1] for key in known}
        self.used: dict[Key, CodeType] = {}
        self.compiled = 0  # sources not found in the file
        self.compiled_unnamed = 0  # of those, the ones under a name the file does not hold
        self.saved_at = (0, 0)  # the two counts when the file was last written
        self.loaded = len(known)  # the entries read from the file
        self.rejected: str | None = None  # why the file was not read, if it was there

    def code(self, source: str, filename: str, mode: str, flags: int) -> CodeType:
        key = (source, filename, mode, flags)
        code = self.used.get(key)
        if code is None:
            code = self.known.get(key)
            if type(code) is not CodeType:
                code = builtins.compile(source, filename, mode, flags, dont_inherit=True)
                self.compiled += 1
                self.compiled_unnamed += filename not in self.known_names
            self.used[key] = code
        return code

    def worth_saving(self) -> bool:
        compiled, unnamed = self.saved_at
        return self.compiled_unnamed > unnamed or self.compiled - compiled > CHANGING_SOURCES

    def save(self) -> bool:
        """Writes the code this process used, if it compiled what the file did not hold; what
        it did not use is left out, so code of upgraded packages does not pile up."""
        if self.path is None or not self.worth_saving():
            return False
        temporary = self.path.with_name(f"{self.path.name}.{os.getpid()}.tmp")
        created = False
        try:
            self.path.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
            # dict() copies in one C call, while another thread may be building a class
            data = encode(dict(self.used))
            # Only the user may write it, whatever the umask: a reader trusts nothing else.
            # O_EXCL and O_NOFOLLOW: not through a file or link someone else put there.
            flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
            fd = os.open(temporary, flags | getattr(os, "O_BINARY", 0), 0o600)
            created = True
            with open(fd, "wb") as file:
                file.write(data)
            os.replace(temporary, self.path)  # a reader sees the old file or the new, whole
        except OSError as err:
            _log_debug("code cache not written to %s: %s", self.path, err)
            if created:  # not a file of that name someone else made
                with contextlib.suppress(OSError):
                    temporary.unlink()
            return False
        self.saved_at = (self.compiled, self.compiled_unnamed)
        return True


def _log_debug(message: str, *args: object) -> None:
    # logging is imported when there is something to say: a start does not load it.
    import logging

    logging.getLogger(__name__).debug(message, *args)


def cache_directory() -> Path | None:
    """Where the files are kept: ``FANUC_MACRO_CODE_CACHE`` if it names a directory, else the
    user's cache directory; None when the cache is turned off."""
    chosen = os.environ.get(ENVIRONMENT, "")
    if chosen in ("0", "off", "false", "no"):
        return None
    if chosen:
        return Path(chosen)
    try:
        return _user_cache_directory()
    except (RuntimeError, KeyError, OSError):  # no home directory to be found: no cache
        return None


def _user_cache_directory() -> Path:
    if sys.platform == "win32":
        base = os.environ.get("LOCALAPPDATA") or str(Path.home() / "AppData" / "Local")
    elif sys.platform == "darwin":
        base = str(Path.home() / "Library" / "Caches")
    else:
        base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "fanuc-macro"


def cache_file(directory: Path, kind: str) -> Path:
    optimized = f"-O{sys.flags.optimize}" if sys.flags.optimize else ""
    tag = sys.implementation.cache_tag or sys.implementation.name
    return directory / f"code-{kind}-{tag}-{MAGIC_NUMBER.hex()}{optimized}.marshal"


class Untrusted(PermissionError):
    """A file or directory someone other than this user could have written."""

    def __init__(self, reason: str, directory: bool) -> None:
        super().__init__(f"not trusted: {reason}")
        self.directory = directory


def _untrusted_directory(status: os.stat_result) -> str | None:
    """Why a directory's files could have been put there by another user, or None."""
    if status.st_uid not in (os.geteuid(), 0):
        return "directory owned by another user"
    # In a directory others can write, they can rename this user's files away and put theirs;
    # with the sticky bit (/tmp) they cannot, and a file they create there is theirs.
    if status.st_mode & 0o022 and not status.st_mode & stat.S_ISVTX:
        return "directory others can write"
    return None


def _untrusted_file(status: os.stat_result) -> str | None:
    """Why a file could have been written by someone other than this user, or None."""
    if not stat.S_ISREG(status.st_mode):
        return "not a regular file"
    if status.st_uid != os.geteuid():
        return "file owned by another user"
    if status.st_mode & 0o022:
        return "file others can write"
    return None


def _read_trusted(path: Path) -> bytes:
    """The file's content if this user owns it and its directory, and no one else can write
    either; else OSError. The checks are of the open file and directory, not of their names,
    so that what is read is what was checked."""
    if not hasattr(os, "geteuid"):  # Windows: no owners to check, the digest only
        return path.read_bytes()
    # O_NONBLOCK: a FIFO in the file's place is refused below instead of blocking the start
    flags = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0)
    directory = os.open(path.parent, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    try:
        reason = _untrusted_directory(os.fstat(directory))
        if reason is not None:
            raise Untrusted(reason, directory=True)
        if os.open in os.supports_dir_fd:
            fd = os.open(path.name, flags, dir_fd=directory)
        else:  # pragma: no cover - every POSIX Python this runs on has dir_fd
            fd = os.open(path, flags)
        with open(fd, "rb") as file:
            reason = _untrusted_file(os.fstat(file.fileno()))
            if reason is not None:
                raise Untrusted(reason, directory=False)
            return file.read()
    finally:
        os.close(directory)


def _read(path: Path) -> tuple[dict[Key, CodeType], str | None, bool]:
    """The code objects the file holds; why it was not read (None if it was, or if there was
    none), and whether its directory may be written: any doubt only means compiling again."""
    try:
        known = decode(_read_trusted(path))
    except FileNotFoundError:
        return {}, None, True
    except (OSError, EOFError, ValueError, TypeError) as err:
        _log_debug("code cache %s not read: %s", path, err)
        # A directory others could write to is not written to: its file would not be read.
        writable = not (isinstance(err, Untrusted) and err.directory)
        return {}, str(err) or type(err).__name__, writable
    if not isinstance(known, dict) or len(known) > MAX_ENTRIES:
        return {}, "not a table of code", True
    return known, None, True


def _future_flags(module: ModuleType) -> int:
    """The ``__future__`` flags a ``compile`` called in ``module`` would inherit."""
    flags = 0
    for name in __future__.all_feature_names:
        feature: Any = getattr(__future__, name)
        flag: int = feature.compiler_flag
        if module.__dict__.get(name) is feature:
            flags |= flag
    return flags


def _compile_through(cache: CodeCache, flags: int) -> Callable[..., Any]:
    def compile(  # shadows the builtin in the builder's module
        source: Any,
        filename: Any,
        mode: str,
        extra_flags: int = 0,
        dont_inherit: bool = False,
        optimize: int = -1,
    ) -> Any:
        if type(source) is str and type(filename) is str and not extra_flags and optimize == -1:
            return cache.code(source, filename, mode, 0 if dont_inherit else flags)
        inherited = 0 if dont_inherit else flags
        return builtins.compile(source, filename, mode, extra_flags | inherited, True, optimize)

    return compile


def _exec_through(cache: CodeCache, flags: int) -> Callable[..., Any]:
    def exec(  # shadows the builtin in the builder's module
        source: Any, globals: Any = None, locals: Any = None, /, **options: Any
    ) -> None:
        if type(source) is str:
            source = cache.code(source, "<string>", "exec", flags)
        builtins.exec(source, globals, locals, **options)

    return exec


def install_code_cache(kind: str) -> CodeCache | None:
    """Installs the cache for a kind of process (a key of :data:`BUILDERS`) once; later calls
    return the installed one."""
    installed = installed_code_cache()
    if installed is not None:
        return installed
    directory = cache_directory()
    if directory is None:
        return None
    path = cache_file(directory, kind)
    known, rejected, writable = _read(path)
    cache = CodeCache(path if writable else None, known)
    cache.rejected = rejected
    makers = {"compile": _compile_through, "exec": _exec_through}
    for module_name, builtin in BUILDERS[kind]:
        try:
            module = importlib.import_module(module_name)
        except ImportError:
            continue
        if module.__dict__.get(builtin, getattr(builtins, builtin)) is not getattr(
            builtins, builtin
        ):
            continue  # the module has a compile of its own: leave it alone
        shadow = makers[builtin](cache, _future_flags(module))
        shadow.__dict__[SHADOW_ATTRIBUTE] = cache
        setattr(module, builtin, shadow)
    return cache


def installed_code_cache() -> CodeCache | None:
    """The cache this process installed, if any: the one the builders' modules compile
    through."""
    for builders in BUILDERS.values():
        for module_name, builtin in builders:
            module = sys.modules.get(module_name)
            shadow = None if module is None else module.__dict__.get(builtin)
            cache = getattr(shadow, SHADOW_ATTRIBUTE, None)
            if isinstance(cache, CodeCache):
                return cache
    return None


def save_code_cache() -> None:
    """Writes the installed cache if this process compiled what its file lacked."""
    installed = installed_code_cache()
    if installed is not None:
        installed.save()
