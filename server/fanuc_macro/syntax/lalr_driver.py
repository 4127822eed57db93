"""A lean LALR(1) driver over the tables Lark has already built for a grammar.

Lark's general machinery (lexer thread, line counter, per-token ``ParserState.feed_token``) costs
most of the time of a one-line parse. :class:`TableParser` keeps everything Lark computed — the
parse table, the terminal definitions and the rules' options — and runs them with compiled
master regexes and one flat shift/reduce loop, calling the transformer as Lark's tree builder
does. It returns what ``lark.parse(code)`` returns; an error is raised with the data Lark puts
in its exceptions (position, the terminals allowed or expected, the token), as this module's
:class:`UnexpectedCharacters` and :class:`UnexpectedToken`.

The shipped tables run without Lark: the tokens and the errors are this module's own, and Lark
is imported only to read a grammar's tables from a Lark object (:func:`lalr_tables`), for a
transformer of Lark's that needs it (``v_args``, in-place) or to build a tree for a rule that
the transformer has no method for (a ``check`` of a small file then loads no Lark: 60 million
instructions fewer).

Only what :mod:`fanuc_macro.syntax.parser` uses is supported: ``parser="lalr"``,
``lexer="basic"``, a ``str`` input, no ``postlex``, no ``lexer_callbacks``, no ``use_bytes``,
no ``propagate_positions``.
"""

from __future__ import annotations

import importlib
import re
import sys
from collections.abc import Callable, Collection, Iterable, Mapping
from functools import partial
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from lark import Lark
    from lark.lexer import TerminalDef

__all__ = (
    "TABLES_FORMAT",
    "TableParser",
    "Token",
    "UnexpectedCharacters",
    "UnexpectedInput",
    "UnexpectedToken",
    "lalr_tables",
)

_Callback = Callable[[list[Any]], Any]
_Match = Callable[[str, int], Any]
# A reduction: (2 * arity = its length on the parse stack, nonterminal to go to, callback,
# unit chain or None). A unit chain maps the state under the top one to the state reached after
# a run of one-child `?rule` reductions that return their child unchanged: one step for the run.
_Rule = tuple[int, str, _Callback, dict[int, int] | None]
# The same in the tables' data, with the index of the Lark rule whose callback it runs.
_RuleData = tuple[int, str, int, dict[int, int] | None]

_END = "$END"
_ASCII = frozenset(chr(i) for i in range(128))
_new_str = str.__new__


class Token(str):
    """A token: its text, with its terminal's name and where it is (lines and columns from 1,
    positions from 0), with the attributes and the equality of Lark's ``Token``."""

    __slots__ = (
        "column",
        "end_column",
        "end_line",
        "end_pos",
        "line",
        "start_pos",
        "type",
        "value",
    )
    __match_args__ = ("type", "value")

    type: str
    start_pos: int | None
    value: Any
    line: int | None
    column: int | None
    end_line: int | None
    end_column: int | None
    end_pos: int | None

    def __new__(
        cls,
        type: str,  # Lark's name, which transformers use
        value: Any,
        start_pos: int | None = None,
        line: int | None = None,
        column: int | None = None,
        end_line: int | None = None,
        end_column: int | None = None,
        end_pos: int | None = None,
    ) -> Token:
        token = _new_str(cls, value)
        token.type = type
        token.start_pos = start_pos
        token.value = value
        token.line = line
        token.column = column
        token.end_line = end_line
        token.end_column = end_column
        token.end_pos = end_pos
        return token

    def update(self, type: str | None = None, value: Any = None) -> Token:
        """A token at the same place, of another terminal or with another text."""
        return Token.new_borrow_pos(
            self.type if type is None else type, self.value if value is None else value, self
        )

    @classmethod
    def new_borrow_pos(cls, type_: str, value: Any, borrow_t: Token) -> Token:
        """A token at the place of ``borrow_t``."""
        return cls(
            type_, value, borrow_t.start_pos, borrow_t.line, borrow_t.column,
            borrow_t.end_line, borrow_t.end_column, borrow_t.end_pos,
        )  # fmt: skip

    def __reduce__(self) -> tuple[Any, ...]:
        return (self.__class__, (self.type, self.value, self.start_pos, self.line, self.column))

    def __repr__(self) -> str:
        return f"Token({self.type!r}, {self.value!r})"

    def __eq__(self, other: object) -> bool:
        # Two tokens of different terminals differ, whatever their text; a token equals a str.
        if isinstance(other, Token) and self.type != other.type:
            return False
        return str.__eq__(self, other)

    __hash__ = str.__hash__


class UnexpectedInput(Exception):
    """A text the grammar does not take, at ``line`` and ``column`` (from 1), ``pos_in_stream``
    (from 0)."""

    line: int | None
    column: int | None
    pos_in_stream: int | None


class UnexpectedCharacters(UnexpectedInput):
    """No terminal matches the text at ``pos_in_stream``; ``allowed``: the terminals the lexer
    tried."""

    def __init__(
        self,
        text: str,
        pos: int,
        line: int,
        column: int,
        allowed: set[str],
        token_history: list[Token] | None = None,
    ) -> None:
        super().__init__()
        self.line = line
        self.column = column
        self.pos_in_stream = pos
        self.char = text[pos]
        self.allowed = allowed
        self.token_history = token_history

    def __str__(self) -> str:
        return (
            f"No terminal matches {self.char!r} at line {self.line} col {self.column}; "
            f"expected one of {sorted(self.allowed)}"
        )


class UnexpectedToken(UnexpectedInput):
    """The parser cannot take ``token`` (``$END``: the end of the text) where it stands;
    ``expected``: the terminals it could."""

    def __init__(self, token: Token, expected: set[str]) -> None:
        super().__init__()
        self.token = token
        self.expected = expected
        self.line = token.line
        self.column = token.column
        self.pos_in_stream = token.start_pos

    def __str__(self) -> str:
        return (
            f"Unexpected token {self.token!r} at line {self.line}, column {self.column}; "
            f"expected one of {sorted(self.expected)}"
        )


def _only_child(children: list[Any]) -> Any:
    """ExpandSingleChild with one child: the child itself."""
    return children[0]


def _has_newline(regexp: str) -> bool:
    """Lark's test of whether a terminal may span lines (only those update the line count)."""
    return (
        "\n" in regexp
        or "\\n" in regexp
        or "\\s" in regexp
        or "[^" in regexp
        or ("(?s" in regexp and "." in regexp)
    )


def _order_key(term: TerminalDef) -> tuple[int, int, int, str]:
    # The order BasicLexer tries terminals in: priority, then longest possible match.
    return (-term.priority, -term.pattern.max_width, -len(term.pattern.value), term.name)


# ---- first characters of a regex (to split the master regex by the next input character)
#
# A regex alternation is tried branch by branch, so one master regex of 35 terminals spends
# most of its time failing branches. Each ASCII character gets its own master regex holding
# only the terminals that can start with it, in Lark's order: the first branch that matches is
# the same. The analysis may say "any" (None) when unsure; that only costs speed.


def _re_module(new: str, old: str) -> Any:
    """``re._parser`` / ``re._constants`` since Python 3.11, ``sre_parse`` before."""
    try:
        return importlib.import_module(new)
    except ImportError:
        return importlib.import_module(old)


_sre: Any = _re_module("re._parser", "sre_parse")
_sc: Any = _re_module("re._constants", "sre_constants")
# Python 3.11 added these two opcodes; on 3.10 no pattern can contain them.
_POSSESSIVE_REPEAT: Any = getattr(_sc, "POSSESSIVE_REPEAT", object())
_ATOMIC_GROUP: Any = getattr(_sc, "ATOMIC_GROUP", object())


def _class_first(items: Iterable[tuple[Any, Any]], ignorecase: bool) -> frozenset[str] | None:
    """ASCII characters a character class [...] accepts, or None if unsure."""
    negate = False
    members: set[str] = set()
    for op, av in items:
        if op is _sc.NEGATE:
            negate = True
        elif op is _sc.LITERAL:
            if av >= 128 and ignorecase:
                return None  # e.g. KELVIN SIGN matches "k" when case is ignored
            members.add(chr(av))
        elif op is _sc.RANGE:
            lo, hi = av
            if hi >= 128 and ignorecase:
                return None
            members.update(chr(c) for c in range(lo, min(hi, 127) + 1))
        else:  # categories (\d, \s, \w) and the rest: not worth modelling
            return None
    if ignorecase:
        if negate:
            return None
        members |= {c.swapcase() for c in members}
    found = frozenset(members) & _ASCII
    return _ASCII - found if negate else found


def _seq_first(items: Iterable[tuple[Any, Any]], flags: int) -> tuple[frozenset[str] | None, bool]:
    """(ASCII characters a match can start with or None if unsure, can it match empty)."""
    first: set[str] = set()
    for op, av in items:
        ignorecase = bool(flags & _sc.SRE_FLAG_IGNORECASE)
        part: frozenset[str] | None
        nullable = False
        if op is _sc.LITERAL:
            ch = chr(av)
            if av >= 128:
                part = None if ignorecase else frozenset()
            else:
                part = frozenset({ch, ch.swapcase()}) if ignorecase else frozenset(ch)
        elif op is _sc.IN:
            part = _class_first(av, ignorecase)
        elif op is _sc.BRANCH:
            part, nullable = frozenset(), False
            for alt in av[1]:
                alt_first, alt_nullable = _seq_first(alt, flags)
                if alt_first is None:
                    return None, False
                part |= alt_first
                nullable = nullable or alt_nullable
        elif op is _sc.SUBPATTERN:
            _group, add_flags, del_flags, sub = av
            part, nullable = _seq_first(sub, (flags | add_flags) & ~del_flags)
        elif op in (_sc.MAX_REPEAT, _sc.MIN_REPEAT, _POSSESSIVE_REPEAT):
            low, _high, sub = av
            part, nullable = _seq_first(sub, flags)
            nullable = nullable or low == 0
        elif op is _ATOMIC_GROUP:
            part, nullable = _seq_first(av, flags)
        elif op in (_sc.AT, _sc.ASSERT, _sc.ASSERT_NOT):
            part, nullable = frozenset(), True  # zero width: the next item decides
        else:  # ANY, NOT_LITERAL, group references, ...
            return None, False
        if part is None:
            return None, False
        first |= part
        if not nullable:
            return frozenset(first), False
    return frozenset(first), True


def _regex_first(regexp: str, flags: int) -> frozenset[str] | None:
    try:
        parsed = _sre.parse(regexp, flags)
    except Exception:  # a syntax this analysis does not know: stay correct, just slower
        return None
    first, nullable = _seq_first(parsed, parsed.state.flags)
    return None if nullable else first


class TableParser:
    """Parses one text with the tables of a ``Lark(parser="lalr", lexer="basic")`` object, or
    with those tables as plain data (:func:`lalr_tables`, shipped in ``lalr_tables.py``).

    ``parse`` keeps all its state in locals, so one instance serves several threads.
    """

    def __init__(self, lark: Lark, start: str | None = None) -> None:
        from lark import Tree

        self._load(
            lalr_tables(lark, start), lark.options.transformer, lark.options.tree_class or Tree
        )

    @classmethod
    def from_tables(
        cls, tables: Mapping[str, Any], transformer: Any, tree_class: Any = None
    ) -> TableParser:
        """The parser of :func:`lalr_tables`' data, its callbacks made for ``transformer`` as
        Lark makes them: no grammar to load, no table to convert. ``tree_class`` builds the
        nodes of the rules the transformer has no method for (by default Lark's ``Tree``,
        imported when such a node is first needed)."""
        parser = cls.__new__(cls)
        parser._load(tables, transformer, tree_class)
        return parser

    # ---- set-up: from the tables' data

    def _load(self, tables: Mapping[str, Any], transformer: Any, tree_class: Any) -> None:
        if tables["format"] != TABLES_FORMAT:
            raise ValueError(f"tables of format {tables['format']}, not {TABLES_FORMAT}")
        propagate_positions, maybe_placeholders = tables["tree_options"]
        if propagate_positions:
            raise ValueError("TableParser does not propagate positions")
        re_module: Any = importlib.import_module(tables["re_module"])
        flags: int = tables["flags"]
        scanned: list[tuple[str, str]] = tables["scanned"]

        def compile_match(indices: Iterable[int]) -> _Match:
            parts = [f"(?P<{scanned[i][0]}>{scanned[i][1]})" for i in indices]
            regexp = "|".join(parts) if parts else "(?!)"  # "(?!)" matches nothing
            match: _Match = re_module.compile(regexp, flags).match
            return match

        def install_master(match: _Match) -> None:
            self._master_match = match

        self._master_match = _on_first_use(
            partial(compile_match, range(len(scanned))), install_master
        )
        # Per ASCII character: the terminal's name when the first terminal that can start with
        # it is that very character as a literal (it always wins: the alternation takes the
        # first branch that matches), else a master regex of just the terminals that can.
        # A scanner's regex is compiled when a text first needs it (a short program meets a
        # few of the 20): the first call puts the compiled one in place for all its chars.
        self._singles: dict[str, str] = {ch: sys.intern(n) for ch, n in tables["singles"].items()}
        scanners: dict[str, _Match] = {}

        def install(chars: str, match: _Match) -> None:
            for ch in chars:
                scanners[ch] = match

        for chars, subset in tables["scanners"]:
            lazy = _on_first_use(partial(compile_match, subset), partial(install, chars))
            for ch in chars:
                scanners[ch] = lazy
        self._scanners = scanners
        self._scanned_names = tuple(name for name, _ in scanned)  # for tests: Lark's order
        self._retype: Mapping[str, Any] = {
            name: re_module.compile(regexp, flags) for name, regexp in tables["retype"].items()
        }
        self._ignore = frozenset(tables["ignore"])
        self._newline_types = frozenset(tables["newline_types"])
        self._allowed = frozenset(tables["allowed"])

        # The parser: a shift (or goto) is the target state, a reduce is ~index in the rules.
        rows = tuple({sys.intern(s): a for s, a in row.items()} for row in tables["rows"])
        self._rows = rows
        self._start_state: int = tables["start_state"]
        self._end_state: int = tables["end_state"]
        # What Lark's feed_token reports: the state's terminals (nonterminals are lowercase).
        self._expected = tuple(frozenset(s for s in row if s.isupper()) for row in rows)
        # The start symbol: what the start state goes to the end state on.
        start = {s for s, a in rows[self._start_state].items() if a == self._end_state}
        callbacks = [
            _rule_callback(rule, transformer, tree_class, maybe_placeholders, start)
            for rule in tables["lark_rules"]
        ]
        self._rules: tuple[_Rule, ...] = tuple(
            (span, sys.intern(origin), callbacks[i], chain)
            for span, origin, i, chain in tables["rules"]
        )
        # Lark also calls a transformer method named after a terminal on each shifted token.
        self._token_callbacks: dict[str, Callable[[Token], Any]] = {}
        for name, *_ in tables["terminals"]:
            callback = getattr(transformer, name, None)
            if callback is not None:
                self._token_callbacks[sys.intern(name)] = callback

    # ---- parsing

    def parse(self, code: str) -> Any:
        """What ``lark.parse(code)`` returns, or the exception it raises."""
        singles = self._singles
        scanners = self._scanners
        master = self._master_match
        ignore = self._ignore
        retype = self._retype
        token_callbacks = self._token_callbacks
        rows = self._rows
        rules = self._rules
        end_state = self._end_state
        new_str = _new_str
        has_newline = "\n" in code
        newline_types = self._newline_types

        # One stack for both: state, value, state, value, ..., state (the top one is last).
        stack: list[Any] = [self._start_state]
        row = rows[self._start_state]
        pos = 0
        size_text = len(code)
        line = 1
        line_start = 0  # position of the first character of the current line
        last: Token | None = None

        while True:
            # ---- the next token (the basic lexer never depends on the parser state)
            if pos < size_text:
                value = code[pos]
                single = singles.get(value)
                if single is not None:
                    kind = single
                    end = pos + 1
                else:
                    m = scanners.get(value, master)(code, pos)
                    if m is None:
                        raise self._unexpected_characters(
                            code, pos, line, pos - line_start + 1, last
                        )
                    kind = m.lastgroup
                    value = m.group()
                    end = m.end()
                    if kind in ignore:
                        if has_newline and kind in newline_types and "\n" in value:
                            line += value.count("\n")
                            line_start = pos + value.rindex("\n") + 1
                        pos = end
                        continue
                    if retype and kind in retype:
                        full = retype[kind].fullmatch(value)
                        if full is not None:
                            kind = full.lastgroup
                # Filling the slots here skips Token.__new__'s argument handling.
                tok: Token = new_str(Token, value)
                tok.type = kind
                tok.value = value
                tok.start_pos = pos
                tok.end_pos = end
                tok.line = line
                tok.column = pos - line_start + 1
                if has_newline and kind in newline_types and "\n" in value:
                    line += value.count("\n")
                    line_start = pos + value.rindex("\n") + 1
                tok.end_line = line
                tok.end_column = end - line_start + 1
                pos = end
                last = tok
            else:
                kind = _END
            # ---- feed it: reduce as long as the table says so, then shift (or accept)
            while True:
                try:
                    action = row[kind]
                except KeyError:
                    raise self._unexpected_token(stack[-1], kind, last) from None
                if action >= 0:
                    if token_callbacks and kind in token_callbacks:
                        stack.append(token_callbacks[kind](tok))
                    else:
                        stack.append(tok)
                    stack.append(action)
                    row = rows[action]
                    break
                span, origin, callback, chain = rules[~action]
                if chain is not None:
                    goto = chain[stack[-3]]
                    stack[-1] = goto
                    row = rows[goto]
                    continue
                if span:
                    children = stack[-span::2]
                    del stack[-span:]
                else:
                    children = []
                result = callback(children)
                goto = rows[stack[-1]][origin]
                if goto == end_state and kind == _END:
                    return result
                stack.append(result)
                stack.append(goto)
                row = rows[goto]

    # ---- errors, with the data Lark puts in them

    def _unexpected_characters(
        self, code: str, pos: int, line: int, column: int, last: Token | None
    ) -> UnexpectedCharacters:
        history = [last] if last is not None else None
        return UnexpectedCharacters(code, pos, line, column, set(self._allowed), history)

    def _unexpected_token(self, state: int, kind: str, last: Token | None) -> UnexpectedToken:
        token: Token
        if kind != _END:
            assert last is not None
            token = last
        elif last is not None:  # Lark's $END borrows the position of the last token
            token = Token.new_borrow_pos(_END, "", last)
        else:
            token = Token(_END, "", 0, 1, 1)
        return UnexpectedToken(token, set(self._expected[state]))


# ---- the callbacks of the reductions, as Lark's tree builder makes them for a transformer
#
# A rule's callback is the transformer's method named after the rule's alias (or its name),
# else the transformer's ``__default__``, else a tree of the rule. A ``?rule`` without alias
# gives its only child unchanged; the children Lark filters out (anonymous tokens, unless
# keep_all_tokens) are dropped, and those of an inlined ``_rule`` take its place.


class _Inlined:
    """The node of a ``_rule`` for which the transformer has no method: its parent's callback
    takes its children in its place, so it needs nothing else (a ``Tree`` would need Lark)."""

    __slots__ = ("children", "data")

    def __init__(self, data: str, children: list[Any]) -> None:
        self.data = data
        self.children = children


def _rule_callback(
    rule: list[Any],
    transformer: Any,
    tree_class: Any,
    maybe_placeholders: bool,
    start: Collection[str],
) -> _Callback:
    origin, symbols, _order, alias, options = rule
    keep_all_tokens, expand1, _priority, template_source, empty_indices = options
    expand_single = bool(expand1) and not alias
    child_filter = _child_filter(
        symbols, keep_all_tokens, empty_indices if maybe_placeholders else None
    )
    if child_filter is None and expand_single and len(symbols) == 1:
        # Lark tests len(children) == 1 on each call; with LALR that length is the arity.
        return _only_child
    name: str = alias or template_source or origin
    user: _Callback
    try:
        method = getattr(transformer, name)
    except AttributeError:
        default = getattr(transformer, "__default__", None)
        if default is not None:
            user = partial(_call_default, default, name)
        elif origin.startswith("_") and origin not in start:
            user = partial(_Inlined, name)
        else:
            if tree_class is None:
                from lark import Tree as tree_class
            user = partial(tree_class, name)
    else:
        user = _lark_method(transformer, method, name)
    if child_filter is None:
        return user
    return partial(child_filter, _expand_single_child(user) if expand_single else user)


def _call_default(
    default: Callable[[str, list[Any], Any], Any], name: str, children: list[Any]
) -> Any:
    return default(name, children, None)


def _lark_method(transformer: Any, method: Any, name: str) -> _Callback:
    """A transformer's method, wrapped as Lark wraps those of its ``v_args`` and in-place
    transformers (a transformer that is not Lark's has neither)."""
    wrapper = getattr(method, "visit_wrapper", None)
    visitors = sys.modules.get("lark.visitors")
    if wrapper is not None or (
        visitors is not None and isinstance(transformer, visitors.Transformer_InPlace)
    ):
        from lark.parse_tree_builder import apply_visit_wrapper, inplace_transformer

        if wrapper is not None:
            wrapped: _Callback = apply_visit_wrapper(method, name, wrapper)  # type: ignore[no-untyped-call]
        else:
            wrapped = inplace_transformer(method)  # type: ignore[no-untyped-call]
        return wrapped
    callback: _Callback = method
    return callback


def _expand_single_child(callback: _Callback) -> _Callback:
    def expand(children: list[Any]) -> Any:
        return children[0] if len(children) == 1 else callback(children)

    return expand


def _child_filter(
    symbols: list[list[Any]], keep_all_tokens: bool, empty_indices: list[bool] | None
) -> Callable[[_Callback, list[Any]], Any] | None:
    """The filter of a rule's children, or None when they all stay as they are: tokens filtered
    out are dropped, an inlined ``_rule``'s children take its place, and with placeholders a
    missing ``[optional]`` is a None."""
    if empty_indices:
        # How many Nones go before each symbol (and after the last), from the True ones.
        marks = "".join("1" if empty else "0" for empty in empty_indices)
        nones_before = [len(run) for run in marks.split("0")]
    else:
        nones_before = [0] * (len(symbols) + 1)
    kept: list[tuple[int, bool, int]] = []  # (index, inline it, Nones before it)
    nones = 0
    for i, (symbol, is_term, filter_out) in enumerate(symbols):
        nones += nones_before[i]
        if keep_all_tokens or not (is_term and filter_out):
            kept.append((i, not is_term and symbol.startswith("_"), nones))
            nones = 0
    trailing = nones + nones_before[len(symbols)]
    if not empty_indices and len(kept) == len(symbols) and not any(x for _, x, _ in kept):
        return None
    if empty_indices:
        return partial(_filter_with_placeholders, tuple(kept), trailing)
    return partial(_filter, tuple((i, inline) for i, inline, _ in kept))


def _filter(kept: tuple[tuple[int, bool], ...], callback: _Callback, children: list[Any]) -> Any:
    filtered: list[Any] = []
    for i, inline in kept:
        if inline:
            if filtered:
                filtered += children[i].children
            else:  # a left-recursive rule: extend the first child's list, as Lark does
                filtered = children[i].children
        else:
            filtered.append(children[i])
    return callback(filtered)


def _filter_with_placeholders(
    kept: tuple[tuple[int, bool, int], ...],
    trailing: int,
    callback: _Callback,
    children: list[Any],
) -> Any:
    filtered: list[Any] = []
    for i, inline, nones in kept:
        if nones:
            filtered += [None] * nones
        if inline:
            if filtered:
                filtered += children[i].children
            else:
                filtered = children[i].children
        else:
            filtered.append(children[i])
    if trailing:
        filtered += [None] * trailing
    return callback(filtered)


# ---- the tables as data

TABLES_FORMAT = 1


def lalr_tables(lark: Lark, start: str | None = None) -> dict[str, Any]:
    """What :class:`TableParser` needs of a Lark object, as plain data (str, int, lists,
    dicts), the same whatever the hash seed: the states are numbered in the order a walk from
    the start state meets them, symbols taken in sorted order."""
    from lark import Tree

    frontend: Any = lark.parser  # lark.parser_frontends.ParsingFrontend
    conf: Any = lark.lexer_conf
    options: Any = lark.options
    if options.parser != "lalr" or conf.lexer_type != "basic":
        raise ValueError("TableParser needs parser='lalr' and lexer='basic'")
    if conf.postlex is not None or conf.callbacks or conf.use_bytes:
        raise ValueError("TableParser supports neither postlex, lexer_callbacks nor use_bytes")
    if options.tree_class not in (None, Tree) or options.propagate_positions is not False:
        raise ValueError("TableParser supports neither a tree_class nor a propagate_positions")
    starts: list[str] = list(frontend.parser_conf.start)
    if start is None:
        if len(starts) != 1:
            raise ValueError(f"several start rules, choose one of {starts}")
        start = starts[0]
    lalr: Any = frontend.parser.parser  # lark.parsers.lalr_parser._Parser
    tables: dict[str, Any] = {"format": TABLES_FORMAT}
    tables.update(_lexer_tables(conf))
    tables.update(_parser_tables(lalr.parse_table, lalr.callbacks, start))
    tables["tree_options"] = [options.propagate_positions, bool(options.maybe_placeholders)]
    return tables


def _lexer_tables(conf: Any) -> dict[str, Any]:
    from lark.lexer import PatternRE, PatternStr

    re_module: Any = conf.re_module
    flags: int = conf.g_regex_flags
    terminals = sorted(conf.terminals, key=_order_key)
    # A string terminal that a regex terminal of the same priority also matches is found
    # through the regex and then renamed (Lark's "unless" rule, e.g. keywords vs. NAME).
    embedded: set[str] = set()
    retype: dict[str, str] = {}
    strings = [t for t in terminals if isinstance(t.pattern, PatternStr)]
    for term in terminals:
        if not isinstance(term.pattern, PatternRE):
            continue
        regexp = term.pattern.to_regexp()
        unless: list[TerminalDef] = []
        for stok in strings:
            if stok.priority != term.priority:
                continue
            m = re_module.match(regexp, stok.pattern.value, flags)
            if m is not None and m.group(0) == stok.pattern.value:
                unless.append(stok)
                if stok.pattern.flags <= term.pattern.flags:
                    embedded.add(stok.name)
        if unless:
            retype[term.name] = _alternation(unless)
    scanned = [t for t in terminals if t.name not in embedded]
    singles: dict[str, str] = {}
    chars_of: dict[tuple[int, ...], list[str]] = {}
    ignore = frozenset(conf.ignore)
    if re_module is re:  # the analysis reads the syntax of the standard re module
        firsts = [_regex_first(t.pattern.to_regexp(), flags) for t in scanned]
        for ch in sorted(_ASCII):
            subset = tuple(i for i, f in enumerate(firsts) if f is None or ch in f)
            if subset:
                head = scanned[subset[0]]
                if head.name not in ignore and _is_char_literal(head, ch, flags):
                    singles[ch] = head.name
                    continue
            chars_of.setdefault(subset, []).append(ch)
    allowed = {t.name for t in scanned} - ignore
    return {
        "re_module": re_module.__name__,
        "flags": flags,
        "terminals": [_terminal_data(t) for t in conf.terminals],
        "scanned": [[t.name, t.pattern.to_regexp()] for t in scanned],
        "singles": singles,
        "scanners": [["".join(chars), list(subset)] for subset, chars in chars_of.items()],
        "retype": retype,
        "ignore": sorted(ignore),
        "newline_types": sorted(
            t.name for t in conf.terminals if _has_newline(t.pattern.to_regexp())
        ),
        "allowed": sorted(allowed or {"<END-OF-FILE>"}),
    }


def _parser_tables(table: Any, callbacks: Mapping[Any, Any], start: str) -> dict[str, Any]:
    from lark.parse_tree_builder import ExpandSingleChild
    from lark.parsers.lalr_analysis import Shift

    lark_states: Mapping[int, Mapping[Any, tuple[Any, Any]]] = table.states
    if sorted(lark_states) != list(range(len(lark_states))):
        raise ValueError("expected Lark's IntParseTable (states numbered 0..n-1)")
    # Lark numbers its states in an order that depends on the hash seed: renumber them in
    # the order of a walk from the start state, symbols in sorted order.
    start_state: int = table.start_states[start]
    number = {start_state: 0}
    walk = [start_state]
    for state in walk:
        for _name, (action, arg) in sorted(lark_states[state].items(), key=lambda i: str(i[0])):
            if action is Shift and arg not in number:
                number[arg] = len(walk)
                walk.append(arg)
    if len(walk) != len(lark_states):
        raise ValueError("states the start state does not reach")
    rule_index: dict[Any, int] = {}
    lark_rules: list[Any] = []
    rules: list[_RuleData] = []
    passes_child: list[bool] = []
    rows: list[dict[str, int]] = []
    for state in walk:
        row: dict[str, int] = {}
        for name, (action, arg) in sorted(lark_states[state].items(), key=lambda i: str(i[0])):
            # Lark's names are often Token objects; plain str keys keep lookups in C
            # (Token.__eq__ is Python code).
            symbol = str(name)
            if action is Shift:
                row[symbol] = number[arg]
                continue
            index = rule_index.get(arg)
            if index is None:
                index = rule_index[arg] = len(rules)
                span = 2 * len(arg.expansion)  # a value and a state per symbol
                rules.append((span, str(arg.origin.name), len(lark_rules), None))
                lark_rules.append(arg)
                callback = callbacks[arg]
                passes_child.append(type(callback) is ExpandSingleChild and span == 2)
            row[symbol] = ~index
        rows.append(row)
    end_state = number[table.end_states[start]]
    _fold_unit_chains(rows, rules, passes_child, end_state)
    return {
        "start_state": 0,
        "end_state": end_state,
        "rows": rows,
        "rules": [list(r) for r in rules],
        "lark_rules": [_lark_rule_data(r) for r in lark_rules],
    }


def _fold_unit_chains(
    rows: list[dict[str, int]],
    rules: list[_RuleData],
    passes_child: list[bool],
    end_state: int,
) -> None:
    """Replace each terminal's pass-through reduce by one entry with its whole chain.

    The state reached after reducing a one-symbol rule is goto(state below, rule), and the
    state below does not change along a chain of them; so the chain's end is a function of
    (state below, top state, lookahead), computed here for every possible state below.
    """
    below: list[set[int]] = [set() for _ in rows]
    for state, row in enumerate(rows):
        for action in row.values():
            if action >= 0:
                below[action].add(state)
    folded: list[tuple[int, str, dict[int, int]]] = []
    for top, row in enumerate(rows):
        for kind, action in row.items():
            if action >= 0 or not passes_child[~action] or not kind.isupper():
                continue
            chain: dict[int, int] = {}
            for under in sorted(below[top]):
                end = _chain_end(rows, rules, passes_child, under, top, kind, end_state)
                if end is None:
                    break  # leave this one to the general reduce step
                chain[under] = end
            else:
                if chain:
                    folded.append((top, kind, chain))
    for top, kind, chain in folded:
        span, origin, index, _ = rules[~rows[top][kind]]
        rows[top][kind] = ~len(rules)
        rules.append((span, origin, index, chain))
        passes_child.append(False)


def _terminal_data(term: TerminalDef) -> list[Any]:
    from lark.lexer import PatternStr

    pattern = term.pattern
    kind = "str" if isinstance(pattern, PatternStr) else "re"
    return [term.name, kind, pattern.value, sorted(pattern.flags), pattern.raw, term.priority]


def _lark_rule_data(rule: Any) -> list[Any]:
    o = rule.options
    symbols = [[s.name, s.is_term, bool(getattr(s, "filter_out", False))] for s in rule.expansion]
    empty = list(o.empty_indices)
    return [
        rule.origin.name, symbols, rule.order, rule.alias,
        [o.keep_all_tokens, o.expand1, o.priority, o.template_source, empty],
    ]  # fmt: skip


def _on_first_use(compile_match: Callable[[], _Match], install: Callable[[_Match], None]) -> _Match:
    """A match function that compiles its regex on its first call and has ``install`` put the
    compiled one where the parser looks it up; until then (or in a parse that already holds
    this one) it calls the compiled one itself."""
    compiled: _Match | None = None

    def first_use(code: str, pos: int) -> Any:
        nonlocal compiled
        if compiled is None:
            compiled = compile_match()
            install(compiled)
        return compiled(code, pos)

    return first_use


def _is_char_literal(term: TerminalDef, ch: str, flags: int) -> bool:
    """Does `term` match exactly the one character `ch` (then nothing else can come first)?"""
    from lark.lexer import PatternStr

    pattern = term.pattern
    if not isinstance(pattern, PatternStr) or len(pattern.value) != 1:
        return False
    return re.fullmatch(pattern.to_regexp(), ch, flags) is not None


def _alternation(terms: Iterable[TerminalDef]) -> str:
    return "|".join(f"(?P<{t.name}>{t.pattern.to_regexp()})" for t in terms)


def _chain_end(
    rows: list[dict[str, int]],
    rules: list[_RuleData],
    passes_child: list[bool],
    under: int,
    top: int,
    kind: str,
    end_state: int,
) -> int | None:
    """The top state after the pass-through reductions from `top` on lookahead `kind`.

    None when a step has no goto or reaches the end state (where Lark checks for acceptance).
    """
    action = rows[top][kind]
    for _ in range(len(rows)):  # a chain visits each state at most once
        goto = rows[under].get(rules[~action][1])
        if goto is None or goto == end_state:
            return None
        top = goto
        next_action = rows[top].get(kind)
        if next_action is None or next_action >= 0 or not passes_child[~next_action]:
            return top
        action = next_action
    return None
