"""The analysis database: the one owner of every value derived from the documents.

Parsed and compiled lines, line maps, what rules keep between edits and interning tables all
live in a :class:`Database`, in tables named by :class:`TableKey`. The modules that compute
those values declare their keys (and their ``PerLine`` and ``LineMap`` queries) at module
level; the storage is the current database's. A workspace owns one database and runs its
analyses inside :meth:`Database.active`; closing a document frees what the per-document
tables held for it. Code outside any workspace (a script calling the parser) uses a process
default database.

The active database is a :class:`contextvars.ContextVar`: a thread started inside
:meth:`Database.active` does not inherit it (it sees the default), while
``contextvars.copy_context().run`` does. This module is the only one of the package that holds
module-level mutable state: the context variable and the default database.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Collection, Iterator, Sized
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import Any, Generic, Protocol, TypeVar, cast

A = TypeVar("A")
K = TypeVar("K")
V = TypeVar("V")


@dataclass(frozen=True, eq=False)
class TableKey(Generic[K, V]):
    """The name of a table of every database, declared once at module level by the module
    that fills it, e.g. ``CODES: TableKey[str, Codes] = TableKey("evaluator.codes")``.

    Keys compare by identity (a declaration is one object; hashing it costs what an ``id``
    costs). ``per_document``: the table's keys are document URIs, and
    :meth:`Database.close_document` drops the document's entry. ``cache``: the table's values
    are shared between documents and computed again when asked (interned lines, compiled
    expressions): :meth:`Database.drop_caches` drops the whole table, when a document closes
    and when the caches pass their budget.
    """

    name: str
    per_document: bool = False
    cache: bool = False

    def __repr__(self) -> str:
        return f"TableKey({self.name!r})"


class _Tables(dict[TableKey[Any, Any], dict[Any, Any]]):
    """A database's tables by key; a missing one is made on first use (a hit stays in C)."""

    __slots__ = ("_lock",)

    def __init__(self) -> None:
        super().__init__()
        self._lock = threading.Lock()

    def __missing__(self, key: TableKey[Any, Any]) -> dict[Any, Any]:
        with self._lock:  # two threads asking at once get the same table
            return self.setdefault(key, {})


class _TableOf(Protocol):
    def __call__(self, key: TableKey[K, V], /) -> dict[K, V]: ...


class Database:
    """Every derived value of one workspace (or of the process, for the default database).

    Tables are plain dicts, made on first use; the code that fills one keeps its own order
    and limits (a dict's single operations are atomic; a compound update takes its own
    lock).
    """

    __slots__ = ("_tables", "name", "table")

    table: _TableOf
    """``table(key)``: the table ``key`` of this database, made empty on first use. The dict's
    own look-up, bound: a hit runs in C (hot paths ask once per line)."""

    def __init__(self, name: str = "workspace") -> None:
        self.name = name
        self._tables = _Tables()
        self.table = cast(_TableOf, self._tables.__getitem__)

    def __repr__(self) -> str:
        return f"<Database {self.name}: {len(self._tables)} tables>"

    @contextmanager
    def active(self) -> Iterator[Database]:
        """Make this the current database of this thread (or context) until the block ends.
        Blocks nest: the database active before is active again after."""
        token = _active.set(self)
        try:
            yield self
        finally:
            _active.reset(token)

    def close_document(self, uri: str) -> None:
        """Free what every per-document table holds for ``uri`` (see :meth:`close_documents`)."""
        self.close_documents([uri])

    def close_documents(self, uris: Collection[str]) -> None:
        """Free what every per-document table holds for each of ``uris``, and the shared
        caches, which may hold their lines (:meth:`drop_caches`): once, however many go."""
        for key, table in list(self._tables.items()):
            if key.per_document:
                for uri in uris:
                    table.pop(uri, None)
        self.drop_caches()

    def drop_caches(self) -> None:
        """Drop every cache table (``TableKey.cache``). A table is replaced, not emptied: a
        thread that holds it goes on with it, and the next look-up makes a new one. The open
        documents keep their own lines; what they shared is built again as lines are read."""
        for key in [key for key in list(self._tables) if key.cache]:
            self._tables.pop(key, None)

    def cache_entries(self) -> int:
        """How many entries the cache tables hold: a table of containers (one per-line cache
        per declaration) counts their entries."""
        count = 0
        for key, table in list(self._tables.items()):
            if key.cache:
                count += len(table)
                count += sum(len(v) for v in list(table.values()) if isinstance(v, Sized))
        return count

    def forget(self) -> None:
        """Drop every table (tests, memory pressure): values are computed again when asked."""
        self._tables.clear()

    def tables(self) -> dict[str, int]:
        """How many entries each table holds, by its name (for tests and memory reports)."""
        return {key.name: len(table) for key, table in list(self._tables.items())}


@dataclass(frozen=True, eq=False)
class Derived(Generic[A, V]):
    """A value derived from one document, computed again only when what it reads changed.

    ``reads(arg)`` names the inputs the value is drawn from (say the document's program index
    and how far it was read): the current database keeps the value with them, by document,
    and gives it back while every input is the same (the same object; a number, a string or
    None equal). ``compute(arg)`` gives the value and whether it follows from those inputs
    alone: a value that read more (the evaluator's facts, say) is not kept. The last values
    of ``kept`` documents are kept, the least recently stored dropped first; closing a
    document frees its value.

    So a rule says what it reads, and the database decides what to compute again.
    """

    name: str
    reads: Callable[[A], tuple[object, ...]]
    compute: Callable[[A], tuple[V, bool]]
    kept: int = 16
    table: TableKey[str, tuple[tuple[object, ...], V]] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "table", TableKey(self.name, per_document=True))

    def __call__(self, uri: str, arg: A) -> V:
        values = current().table(self.table)
        inputs = self.reads(arg)
        last = values.get(uri)
        if last is not None and _same_inputs(last[0], inputs):
            return last[1]
        value, keep = self.compute(arg)
        values.pop(uri, None)
        if keep:
            values[uri] = (inputs, value)
            while len(values) > self.kept:  # another thread's call may drop the oldest first
                try:
                    del values[next(iter(values))]
                except (KeyError, RuntimeError, StopIteration):
                    break
        return value


_BY_VALUE = (int, float, str, bool, type(None))


def _same_inputs(old: tuple[object, ...], new: tuple[object, ...]) -> bool:
    """Whether two reads of a query's inputs are the same: each input the same object, or an
    equal number, string or None (an equal object that is another one may differ in what
    the query does not compare: it counts as changed)."""
    return len(old) == len(new) and all(
        a is b or (type(a) is type(b) and isinstance(a, _BY_VALUE) and a == b)
        for a, b in zip(old, new, strict=True)
    )


# The database of code running outside any workspace (the command line's single documents,
# scripts calling the parser): its tables live as long as the process.
_DEFAULT = Database("default")
_active: ContextVar[Database] = ContextVar("fanuc_macro.database", default=_DEFAULT)


# ``current()``: the active database (:meth:`Database.active`), else the process default. The
# context variable's own method, called in C: hot paths ask once per line.
current: Callable[[], Database] = _active.get


def default() -> Database:
    """The process default database (the one :func:`current` gives outside ``active``)."""
    return _DEFAULT


__all__ = ("Database", "Derived", "TableKey", "current", "default")
