"""Parsing of ISO general-purpose metric thread designations (ISO 965-1, GB/T 197).

Accepted forms (spaces are ignored, the pitch separator may be ``x``, ``X``, ``×`` or ``*``)::

    M50x3-5g6g      external, pitch-diameter class 5g, crest-diameter class 6g
    M50×3-4H5H      internal, pitch-diameter class 4H, crest-diameter class 5H
    M10-6g          coarse pitch taken from ISO 261 (1.5 mm)
    M20x1.5LH-6H    left hand (also ``M20x1.5-6H-LH``)
    M20x2-7g6g-L    length-of-engagement group S / N / L
    M10x1.5         no class: GB/T 197 medium default (6H/6g, or 5H/6h up to 1.4 mm)
    M16xPh3P1.5-6H  multiple-start: lead Ph 3, pitch P 1.5, so two starts (ISO 965-1)

ISO 965-1 writes the tolerance position of an external thread in lower case (``6g``) and of
an internal one in upper case (``6H``).  A string with a lower-case letter or a typographic
``×`` is read by its case.  An all-capital string (``M50X3-5G6G``, as CNC controls write;
the seed paper writes ``M50X3-5g6g`` and ``M50X3-4H5H``) may have lost its case: its class is
read as whichever kind has it in the standard (``6E`` only external, ``4H5H`` only internal,
as ISO 965-1 has no crest grade 5 for external threads), and a class that both kinds have
(``5G6G``: 5g6g or 5G6G), or no class at all, is decided only by the caller's ``internal=``;
without it :class:`SideUndecided` is raised, never a guess.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Literal

from ..lazy_regex import LazyPattern

__all__ = (
    "COARSE_PITCH",
    "EXTERNAL_CREST_GRADES",
    "EXTERNAL_PITCH_GRADES",
    "EXTERNAL_POSITIONS",
    "INTERNAL_CREST_GRADES",
    "INTERNAL_PITCH_GRADES",
    "INTERNAL_POSITIONS",
    "InternalBasis",
    "SideConflict",
    "SideUndecided",
    "ThreadDesignation",
    "ToleranceClass",
    "coarse_pitch",
    "parse_designation",
)

# Tolerance positions for which ISO 965-1:1998 / GB/T 197-2003 tabulate fundamental deviations:
# e, f, g, h for external threads, G, H for internal ones (as GB/T 197-2003 tabulates them;
# unverified against the ISO 965-1 text itself, whose 2013 edition may add more).
EXTERNAL_POSITIONS: frozenset[str] = frozenset("efgh")
INTERNAL_POSITIONS: frozenset[str] = frozenset("GH")

# Tolerance grades the same tables have (ISO 965-1:1998 as GB/T 197-2003 tabulates it, the
# tables of iso965.py; unverified against the ISO text): Td2 3-9 and Td 4, 6, 8 for external
# threads, TD2 and TD1 4-8 for internal ones.  In ``5g6g`` the first class is the pitch
# diameter's, the second the crest's.
EXTERNAL_PITCH_GRADES: tuple[int, ...] = (3, 4, 5, 6, 7, 8, 9)
EXTERNAL_CREST_GRADES: tuple[int, ...] = (4, 6, 8)
INTERNAL_PITCH_GRADES: tuple[int, ...] = (4, 5, 6, 7, 8)
INTERNAL_CREST_GRADES: tuple[int, ...] = (4, 5, 6, 7, 8)

# ISO 261 / ISO 262 coarse-pitch series (mm).  First- and second-choice sizes M1..M68, plus the
# third-choice sizes M9 and M11, which ISO 261 also lists with a coarse pitch.  Above M68 ISO 261
# has fine pitches only; sizes such as M50 or M55 (third choice) have no coarse pitch at all.
COARSE_PITCH: Mapping[float, float] = MappingProxyType(
    {
        1.0: 0.25,
        1.1: 0.25,
        1.2: 0.25,
        1.4: 0.3,
        1.6: 0.35,
        1.8: 0.35,
        2.0: 0.4,
        2.2: 0.45,
        2.5: 0.45,
        3.0: 0.5,
        3.5: 0.6,
        4.0: 0.7,
        4.5: 0.75,
        5.0: 0.8,
        6.0: 1.0,
        7.0: 1.0,
        8.0: 1.25,
        9.0: 1.25,
        10.0: 1.5,
        11.0: 1.5,
        12.0: 1.75,
        14.0: 2.0,
        16.0: 2.0,
        18.0: 2.5,
        20.0: 2.5,
        22.0: 2.5,
        24.0: 3.0,
        27.0: 3.0,
        30.0: 3.5,
        33.0: 3.5,
        36.0: 4.0,
        39.0: 4.0,
        42.0: 4.5,
        45.0: 4.5,
        48.0: 5.0,
        52.0: 5.0,
        56.0: 5.5,
        60.0: 5.5,
        64.0: 6.0,
        68.0: 6.0,
    }
)

# How a designation's side was decided: by the letter case of its class, by its class being
# one only one kind has in ISO 965-1 (the case lost), or by the caller (the text fits both).
InternalBasis = Literal["case", "class", "caller"]


@dataclass(frozen=True)
class ToleranceClass:
    """One tolerance class: grade (3..9) and position letter (``g``, ``H`` ...)."""

    grade: int
    position: str

    @property
    def internal(self) -> bool:
        return self.position.isupper()

    def __str__(self) -> str:
        return f"{self.grade}{self.position}"


@dataclass(frozen=True)
class ThreadDesignation:
    """A parsed ISO metric thread designation; lengths in mm.

    ``pitch_class`` is the pitch-diameter class (first in ``5g6g``), ``crest_class`` the
    crest-diameter class (major diameter d for external, minor diameter D1 for internal).
    ``internal_basis`` says how ``internal`` was decided: ``"case"`` (from the letter case),
    ``"class"`` (the case is lost, and only one kind has the class) or ``"caller"`` (the text
    fits both kinds and the caller's ``internal=`` said which).
    """

    nominal_diameter: float
    pitch: float
    internal: bool
    pitch_class: ToleranceClass
    crest_class: ToleranceClass
    left_hand: bool
    coarse_pitch_used: bool
    text: str
    internal_basis: InternalBasis = "case"
    class_omitted: bool = False
    engagement: str | None = None
    lead: float = 0.0  # Ph of a multiple-start thread; 0.0: the pitch (one start)

    @property
    def starts(self) -> int:
        return max(1, round(self.lead / self.pitch)) if self.lead else 1

    @property
    def thread_lead(self) -> float:
        """What one turn advances: the pitch times the number of starts."""
        return self.lead or self.pitch

    @property
    def internal_ambiguous(self) -> bool:
        """True when the text itself does not say internal or external: the caller did."""
        return self.internal_basis == "caller"

    @property
    def side(self) -> str:
        return "internal" if self.internal else "external"

    def class_text(self) -> str:
        """The tolerance class as ISO 965-1 writes it: ``5g6g``, ``6H`` (one grade for both)."""
        if self.pitch_class == self.crest_class:
            return str(self.pitch_class)
        return f"{self.pitch_class}{self.crest_class}"

    def canonical(self) -> str:
        """The designation written the ISO way, e.g. ``M50x3-5g6g``."""
        pitch = "" if self.coarse_pitch_used else f"x{_fmt(self.pitch)}"
        if self.lead:
            pitch = f"xPh{_fmt(self.lead)}P{_fmt(self.pitch)}"
        text = f"M{_fmt(self.nominal_diameter)}{pitch}-{self.class_text()}"
        if self.engagement is not None:
            text += f"-{self.engagement}"
        if self.left_hand:
            text += "-LH"
        return text


def _fmt(value: float) -> str:
    return f"{value:g}"


def coarse_pitch(nominal_diameter: float) -> float:
    """The ISO 261 coarse pitch for ``nominal_diameter`` (mm); ValueError if there is none."""
    for size, pitch in COARSE_PITCH.items():
        if abs(size - nominal_diameter) < 1e-9:
            return pitch
    if nominal_diameter > 68.0:
        reason = "ISO 261 defines coarse pitches only up to M68"
    else:
        reason = "it is not a coarse-pitch size in ISO 261 (fine pitches only, or not listed)"
    raise ValueError(
        f"M{_fmt(nominal_diameter)} has no coarse pitch: {reason}; "
        f"write the pitch explicitly, e.g. M{_fmt(nominal_diameter)}x<pitch>"
    )


# Other thread systems, recognised only to give a useful message.
_NON_METRIC: tuple[tuple[LazyPattern, str], ...] = (
    (LazyPattern(r"^TR\d", re.I), "a trapezoidal thread (ISO 2904 'Tr')"),
    (LazyPattern(r"^MJ\d", re.I), "an MJ (aerospace, ISO 5855) thread"),
    (LazyPattern(r"^NPT|^NPS|^NPTF", re.I), "an American pipe thread"),
    (LazyPattern(r"UN[CFEJRS]?\b|UN[CFEJRS]?$|\d+\s*TPI", re.I), "a Unified inch thread"),
    (LazyPattern(r"^R[CP]?\s*\d", re.I), "a taper pipe thread (ISO 7 'R/Rc/Rp')"),
    (LazyPattern(r"^G\s*\d", re.I), "a parallel pipe thread (ISO 228 'G')"),
    (LazyPattern(r"^PG\s*\d", re.I), "a steel conduit thread (DIN 40430 'Pg')"),
    (LazyPattern(r"^[BS]\d", re.I), "a buttress (saw-tooth) thread"),
    (LazyPattern(r"^\d+(\s+\d+)?/\d+"), "an inch (fractional) designation"),
)

_NUMBER = r"\d+(?:[.,]\d+)?"
_HEAD = re.compile(
    rf"^M(?P<d>{_NUMBER})(?:[xX×*](?:(?P<p>{_NUMBER})|PH(?P<ph>{_NUMBER})P(?P<pp>{_NUMBER})))?"
    r"(?P<lh>LH|RH)?$",
    re.IGNORECASE,
)
_CLASS = re.compile(r"^(?P<g1>\d)(?P<p1>[A-Za-z])(?:(?P<g2>\d)(?P<p2>[A-Za-z]))?$")


def _number(text: str) -> float:
    return float(text.replace(",", "."))


def _side(internal: bool) -> str:
    return "internal" if internal else "external"


class SideUndecided(ValueError):
    """A designation that fits an external and an internal thread and does not say which: an
    all-capital class both kinds have (``M50X3-5G6G``), or no class (``M10x1.5``).

    ``external`` and ``internal`` are its two readings; :meth:`question` words the refusal
    with how the caller's user can say which."""

    def __init__(
        self, external: ThreadDesignation, internal: ThreadDesignation, written_class: str | None
    ) -> None:
        self.external = external
        self.internal = internal
        self.written_class = written_class
        super().__init__(self.question())

    @property
    def text(self) -> str:
        return self.external.text.strip()

    def what(self) -> str:
        """What is undecided, e.g. "M50X3-5G6G: the class 5G6G fits an external (5g6g) or an
        internal (5G6G) thread": no advice."""
        if self.written_class is None:
            return f"{self.text} {self.fits()}"
        return f"{self.text}: the class {self.written_class} {self._kinds()}"

    def fits(self) -> str:
        """What the designation fits, to follow its name: "has the class 5G6G, which fits an
        external (5g6g) or an internal (5G6G) thread"."""
        if self.written_class is None:
            return (
                f"has no tolerance class, so it may be an external thread "
                f"({self.external.class_text()}) or an internal one ({self.internal.class_text()})"
            )
        return f"has the class {self.written_class}, which {self._kinds()}"

    def _kinds(self) -> str:
        ext, nut = self.external.class_text(), self.internal.class_text()
        return f"fits an external ({ext}) or an internal ({nut}) thread"

    def question(self, how: str = "") -> str:
        """The refusal; ``how`` tells how to say which, e.g. "with --external or --internal"."""
        ext, nut = self.external.canonical(), self.internal.canonical()
        write = (
            "write the class"
            if self.written_class is None
            else "write the class in the standard's case"
        )
        said = f" {how}" if how else ""
        return f"{self.what()}: say which{said}, or {write}: {ext} external, {nut} internal"


class SideConflict(ValueError):
    """The caller asked for the other kind of thread than the designation's class is."""

    def __init__(self, designation: ThreadDesignation, because: str) -> None:
        self.designation = designation  # as its text reads
        self.because = because
        super().__init__(self.refusal(f"an {_side(not designation.internal)} thread was asked for"))

    def refusal(self, asked: str) -> str:
        """The refusal, ``asked`` saying what asked for the other kind (e.g. "--internal was
        given")."""
        des = self.designation
        return f"{des.text.strip()} is an {des.side} thread ({self.because}), but {asked}"


# By kind: False external, True internal.
_POSITIONS: Mapping[bool, frozenset[str]] = MappingProxyType(
    {False: EXTERNAL_POSITIONS, True: INTERNAL_POSITIONS}
)
_PITCH_GRADES: Mapping[bool, tuple[int, ...]] = MappingProxyType(
    {False: EXTERNAL_PITCH_GRADES, True: INTERNAL_PITCH_GRADES}
)
_CREST_GRADES: Mapping[bool, tuple[int, ...]] = MappingProxyType(
    {False: EXTERNAL_CREST_GRADES, True: INTERNAL_CREST_GRADES}
)


def _position(letter: str, internal: bool) -> str:
    return letter.upper() if internal else letter.lower()


def _grades(grades: tuple[int, ...]) -> str:
    if grades == tuple(range(grades[0], grades[-1] + 1)):
        return f"{grades[0]}-{grades[-1]}"
    return ", ".join(map(str, grades))


def _kinds_with_class(
    letter: str, pitch: int, crest: int, written: str, shown: str
) -> tuple[list[bool], str]:
    """The kinds (False external, True internal) whose ISO 965-1 tables have the class
    ``written`` of a designation whose case is lost, and, when only one has it, why.
    ValueError when none has it."""
    by_position = [k for k in (False, True) if _position(letter, k) in _POSITIONS[k]]
    if not by_position:
        raise ValueError(
            f"{shown}: ISO 965-1 has no tolerance position {letter} (external threads: "
            "e, f, g, h; internal threads: G, H)"
        )
    if len(by_position) == 1:
        kind = by_position[0]
        return by_position, (
            f"ISO 965-1 has the position {letter} only for {_side(kind)} threads, "
            f"as {_position(letter, kind)}"
        )
    by_grades = [k for k in by_position if pitch in _PITCH_GRADES[k] and crest in _CREST_GRADES[k]]
    if not by_grades:
        raise ValueError(
            f"{shown}: neither kind of thread has the class {written} in "
            f"ISO 965-1 (external: pitch-diameter grades {_grades(EXTERNAL_PITCH_GRADES)}, "
            f"crest grades {_grades(EXTERNAL_CREST_GRADES)}; internal: "
            f"{_grades(INTERNAL_PITCH_GRADES)} both)"
        )
    if len(by_grades) == 1:
        other = not by_grades[0]
        if pitch not in _PITCH_GRADES[other]:
            missing = f"pitch-diameter grade {pitch}"
        else:
            missing = f"crest-diameter grade {crest}"
        return by_grades, f"ISO 965-1 has no {missing} for {_side(other)} threads"
    return by_grades, ""


def _check_position(letter: str, internal: bool, shown: str) -> None:
    """ValueError when ``letter`` (in the case that tells ``internal``) is no position of the
    kind in ISO 965-1."""
    if letter in _POSITIONS[internal]:
        return
    names = ", ".join(sorted(_POSITIONS[internal]))
    other = _position(letter, not internal)
    elsewhere = (
        f"; {other} is an {_side(not internal)} position"
        if other in _POSITIONS[not internal]
        else ""
    )
    raise ValueError(
        f"{shown}: the tolerance position {letter} is not defined for {_side(internal)} threads "
        f"in ISO 965-1 ({_side(internal)} threads have {names}{elsewhere})"
    )


def parse_designation(text: str, *, internal: bool | None = None) -> ThreadDesignation:
    """Parse an ISO metric thread designation such as ``M50x3-5g6g``.

    ``internal`` says the kind of thread when the text does not: an all-capital class that both
    kinds have in ISO 965-1 (``M50X3-5G6G``), or no class.  Without it such a text raises
    :class:`SideUndecided`, which holds both readings.  When the text does say (by its case, or
    by an all-capital class only one kind has, ``6E`` or ``4H5H``), an ``internal`` that says
    otherwise raises :class:`SideConflict`.
    """
    shown = text.strip()
    compact = "".join(text.split())
    _check_metric(compact, shown)
    head, *tail = compact.split("-")
    match = _HEAD.match(head)
    if match is None:
        raise ValueError(
            f"{shown}: cannot read the diameter and pitch from {head or 'its start'} "
            "(expected e.g. M10 or M10x1.5)"
        )
    diameter = _number(match["d"])
    if diameter <= 0:
        raise ValueError(f"{shown}: the nominal diameter must be positive")
    class_text, engagement, left_hand = _read_tail(tail, diameter, shown)
    pitch, lead, coarse_used = _pitch_and_lead(match, diameter, shown)
    written = _Written(
        text=text,
        diameter=diameter,
        pitch=pitch,
        lead=lead,
        coarse_pitch_used=coarse_used,
        left_hand=left_hand or (match["lh"] or "").upper() == "LH",
        engagement=engagement,
    )
    if class_text is None:
        return _class_omitted(written, internal)
    return _class_written(written, class_text, case_kept=_case_kept(compact), internal=internal)


def _check_metric(compact: str, shown: str) -> None:
    """ValueError unless ``compact`` (the text without spaces) starts as an ISO metric thread:
    another thread system, a fit (``6H/6g``) or nothing are refused."""
    if not compact:
        raise ValueError("empty thread designation")
    if compact[:1] not in ("M", "m") or compact[:2].upper() == "MJ":
        for pattern, what in _NON_METRIC:
            if pattern.search(compact):
                raise ValueError(
                    f"{shown} is {what}; only ISO metric M threads (ISO 261 / ISO 965-1) "
                    "are supported"
                )
        raise ValueError(
            f"{shown} is not an ISO metric thread designation (expected e.g. M10x1.5-6g)"
        )
    if "/" in compact:
        raise ValueError(
            f"{shown} looks like a fit (e.g. 6H/6g); give the internal and the external "
            "designation separately"
        )


def _read_tail(tail: list[str], diameter: float, shown: str) -> tuple[str | None, str | None, bool]:
    """The parts after the first dash: (the tolerance class as written, the length of
    engagement ``S``/``N``/``L``, whether one says ``LH``)."""
    class_text: str | None = None
    engagement: str | None = None
    left_hand = False
    for part in tail:
        upper = part.upper()
        if upper == "LH":
            left_hand = True
        elif upper == "RH":
            pass
        elif upper in ("S", "N", "L"):
            engagement = upper
        elif _CLASS.match(part) and class_text is None:
            class_text = part
        elif re.fullmatch(_NUMBER, part):
            raise ValueError(
                f"{shown}: write the pitch after an x (M{_fmt(diameter)}x{part}), not after a dash"
            )
        elif not part:
            raise ValueError(f"{shown}: nothing between two dashes")
        else:
            raise ValueError(f"{shown}: unexpected part {part}")
    return class_text, engagement, left_hand


def _pitch_and_lead(head: re.Match[str], diameter: float, shown: str) -> tuple[float, float, bool]:
    """(pitch, lead Ph or 0.0 when not written, whether the pitch is ISO 261's coarse one)."""
    lead = 0.0
    if head["ph"] is not None:
        lead, pitch = _number(head["ph"]), _number(head["pp"])
        coarse_used = False
        if pitch <= 0 or lead < pitch or abs(lead / pitch - round(lead / pitch)) > 1e-6:
            raise ValueError(
                f"{shown}: the lead Ph {_fmt(lead)} must be a whole multiple of the "
                f"pitch P {_fmt(pitch)}"
            )
    else:
        coarse_used = head["p"] is None
        pitch = coarse_pitch(diameter) if coarse_used else _number(head["p"])
    if pitch <= 0:
        raise ValueError(f"{shown}: the pitch must be positive")
    if pitch >= diameter:
        raise ValueError(f"{shown}: pitch {_fmt(pitch)} is not smaller than the diameter")
    return pitch, lead, coarse_used


def _case_kept(compact: str) -> bool:
    """Whether the letter case of a designation carries meaning: only if the writer could use
    lower case. A lower-case letter or a typographic '×' shows that; an all-capital ASCII
    string may have been upper-cased."""
    return any(ch.islower() for ch in compact) or "×" in compact


@dataclass(frozen=True)
class _Written:
    """What a designation's text says besides its tolerance class."""

    text: str
    diameter: float
    pitch: float
    lead: float  # 0.0 when not written
    coarse_pitch_used: bool
    left_hand: bool
    engagement: str | None

    def reading(
        self,
        internal: bool,
        basis: InternalBasis,
        pitch_class: ToleranceClass,
        crest_class: ToleranceClass,
        omitted: bool = False,
    ) -> ThreadDesignation:
        """The designation read as an internal or an external thread of these classes."""
        return ThreadDesignation(
            nominal_diameter=self.diameter,
            pitch=self.pitch,
            internal=internal,
            pitch_class=pitch_class,
            crest_class=crest_class,
            left_hand=self.left_hand,
            coarse_pitch_used=self.coarse_pitch_used,
            text=self.text,
            internal_basis=basis,
            class_omitted=omitted,
            engagement=self.engagement,
            lead=self.lead if self.lead != self.pitch else 0.0,
        )


def _class_omitted(written: _Written, internal: bool | None) -> ThreadDesignation:
    """A designation without a class: GB/T 197's medium classes, which are not written (5H/6h up
    to 1.4 mm, else 6H/6g), on the side the caller says."""
    small = written.diameter <= 1.4
    nut = ToleranceClass(5 if small else 6, "H")
    bolt = ToleranceClass(6, "h" if small else "g")
    if internal is None:
        raise SideUndecided(
            written.reading(False, "caller", bolt, bolt, True),
            written.reading(True, "caller", nut, nut, True),
            None,
        )
    cls = nut if internal else bolt
    return written.reading(internal, "caller", cls, cls, True)


def _class_written(
    written: _Written, class_text: str, *, case_kept: bool, internal: bool | None
) -> ThreadDesignation:
    """A designation with the class ``class_text``: on the side its letter case says when the
    case is kept, else on the side whose ISO 965-1 tables have the class, or the caller's."""
    shown = written.text.strip()
    letter, pitch_grade, crest_grade = _class_parts(class_text, shown)

    def read_as(is_internal: bool, basis: InternalBasis) -> ThreadDesignation:
        position = _position(letter, is_internal)
        pitch_class = ToleranceClass(pitch_grade, position)
        return written.reading(
            is_internal, basis, pitch_class, ToleranceClass(crest_grade, position)
        )

    if case_kept:
        kind = letter.isupper()
        _check_position(letter, kind, shown)
        if internal is not None and internal != kind:
            case = "upper" if kind else "lower"
            raise SideConflict(read_as(kind, "case"), f"its class {class_text} is in {case} case")
        return read_as(kind, "case")
    kinds, because = _kinds_with_class(letter, pitch_grade, crest_grade, class_text, shown)
    if internal is None:
        if len(kinds) == 2:
            raise SideUndecided(read_as(False, "caller"), read_as(True, "caller"), class_text)
        return read_as(kinds[0], "class")
    if internal not in kinds:
        raise SideConflict(read_as(kinds[0], "class"), because)
    return read_as(internal, "class" if len(kinds) == 1 else "caller")


def _class_parts(class_text: str, shown: str) -> tuple[str, int, int]:
    """(the position letter as written, the pitch-diameter grade, the crest-diameter grade) of
    a class such as ``5g6g`` or ``6H``; ValueError when its two letters differ."""
    found = _CLASS.match(class_text)
    assert found is not None  # matched when the parts were read
    letter1 = found["p1"]
    letter2 = found["p2"] or letter1
    if letter1.isupper() != letter2.isupper():
        raise ValueError(
            f"{shown}: the class {class_text} mixes letter cases (upper case is internal, "
            "lower case external)"
        )
    if letter1.lower() != letter2.lower():
        raise ValueError(
            f"{shown}: the pitch and crest classes must share one tolerance position "
            f"({letter1} and {letter2} in {class_text})"
        )
    grade1 = int(found["g1"])
    grade2 = int(found["g2"]) if found["g2"] else grade1
    return letter1, grade1, grade2
