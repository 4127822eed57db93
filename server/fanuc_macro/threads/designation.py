"""Parsing of ISO general-purpose metric thread designations (ISO 965-1, GB/T 197).

Accepted forms (spaces are ignored, the pitch separator may be ``x``, ``X``, ``×`` or ``*``)::

    M50x3-5g6g      external, pitch-diameter class 5g, crest-diameter class 6g
    M50×3-4H5H      internal, pitch-diameter class 4H, crest-diameter class 5H
    M10-6g          coarse pitch taken from ISO 261 (1.5 mm)
    M20x1.5LH-6H    left hand (also ``M20x1.5-6H-LH``)
    M20x2-7g6g-L    length-of-engagement group S / N / L
    M10x1.5         no class: GB/T 197 medium default (6H/6g, or 5H/6h up to 1.4 mm)
    M16xPh3P1.5-6H  multiple-start: lead Ph 3, pitch P 1.5, so two starts (ISO 965-1)

The letter case of the tolerance position tells internal (upper case, nut) from external
(lower case, bolt).  CNC comments are often all upper case (``M50X3-5G6G``); such a string
cannot say which one is meant, so it is accepted, ``internal_basis`` records that the answer
was assumed (or taken from the caller's ``internal=`` argument) and the position letter is
normalised to the case that matches the chosen reading.  A string that contains any lower-case
letter or a typographic ``×`` is taken to mean what its case says.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Literal

from ..lazy_regex import LazyPattern

__all__ = [
    "COARSE_PITCH",
    "EXTERNAL_POSITIONS",
    "INTERNAL_POSITIONS",
    "InternalBasis",
    "ThreadDesignation",
    "ToleranceClass",
    "coarse_pitch",
    "parse_designation",
]

# Tolerance positions for which ISO 965-1:1998 / GB/T 197-2003 tabulate fundamental deviations.
EXTERNAL_POSITIONS: frozenset[str] = frozenset("efgh")
INTERNAL_POSITIONS: frozenset[str] = frozenset("GH")

# ISO 261 / ISO 262 coarse-pitch series (mm).  First- and second-choice sizes M1..M68, plus the
# third-choice sizes M9 and M11, which ISO 261 also lists with a coarse pitch.  Above M68 ISO 261
# has fine pitches only; sizes such as M50 or M55 (third choice) have no coarse pitch at all.
COARSE_PITCH: dict[float, float] = {
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

InternalBasis = Literal["case", "caller", "assumed"]


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
    ``"caller"`` (the text was ambiguous and the caller's ``internal=`` was used) or
    ``"assumed"`` (ambiguous and nobody said; see :func:`parse_designation`).
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
        """True when the text itself does not say internal or external."""
        return self.internal_basis != "case"

    def canonical(self) -> str:
        """The designation written the ISO way, e.g. ``M50x3-5g6g``."""
        pitch = "" if self.coarse_pitch_used else f"x{_fmt(self.pitch)}"
        if self.lead:
            pitch = f"xPh{_fmt(self.lead)}P{_fmt(self.pitch)}"
        if self.pitch_class == self.crest_class:
            cls = str(self.pitch_class)
        else:
            cls = f"{self.pitch_class}{self.crest_class}"
        text = f"M{_fmt(self.nominal_diameter)}{pitch}-{cls}"
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


def _decide_internal(
    letter: str, case_meaningful: bool, internal: bool | None, text: str
) -> tuple[bool, InternalBasis]:
    if letter.islower() or case_meaningful:
        from_case = letter.isupper()
        if internal is not None and internal != from_case:
            side = "internal" if from_case else "external"
            raise ValueError(
                f"{text!r}: the letter case of {letter!r} says {side}, "
                f"but internal={internal} was requested"
            )
        return from_case, "case"
    # All upper case: the case carries no information.
    if internal is not None:
        return internal, "caller"
    low = letter.lower()
    if low in EXTERNAL_POSITIONS and letter not in INTERNAL_POSITIONS:
        # E or F: only the external reading exists in the tables, so it is the likely one.
        return False, "assumed"
    # G or H: both readings exist; take the letter at face value (internal).
    return True, "assumed"


def _position_for(letter: str, internal: bool, text: str) -> str:
    position = letter.upper() if internal else letter.lower()
    allowed = INTERNAL_POSITIONS if internal else EXTERNAL_POSITIONS
    if position not in allowed:
        side = "internal" if internal else "external"
        names = ", ".join(sorted(allowed))
        raise ValueError(
            f"{text!r}: tolerance position {position!r} is not defined for {side} threads "
            f"in ISO 965-1 (available: {names})"
        )
    return position


def parse_designation(text: str, *, internal: bool | None = None) -> ThreadDesignation:
    """Parse an ISO metric thread designation such as ``M50x3-5g6g``.

    ``internal`` resolves designations whose letter case cannot tell internal from external
    (all upper case, as CNC comments are written).  It must agree with the letter case when
    the text does tell.  When neither the text nor the caller decides, positions G/H are read
    as internal and E/F as external, and ``internal_basis`` is ``"assumed"``.
    """
    original = text
    compact = "".join(text.split())
    if not compact:
        raise ValueError("empty thread designation")
    if compact[:1] not in ("M", "m") or compact[:2].upper() == "MJ":
        for pattern, what in _NON_METRIC:
            if pattern.search(compact):
                raise ValueError(
                    f"{original!r} is {what}; only ISO metric 'M' threads "
                    "(ISO 261 / ISO 965-1) are supported"
                )
        raise ValueError(
            f"{original!r} is not an ISO metric thread designation (expected e.g. M10x1.5-6g)"
        )
    if "/" in compact:
        raise ValueError(
            f"{original!r} looks like a fit (e.g. 6H/6g); parse the internal and external "
            "designations separately"
        )

    head, *tail = compact.split("-")
    match = _HEAD.match(head)
    if match is None:
        raise ValueError(
            f"{original!r}: cannot read diameter and pitch from {head!r} "
            "(expected e.g. M10 or M10x1.5)"
        )
    diameter = _number(match["d"])
    left_hand = (match["lh"] or "").upper() == "LH"
    if diameter <= 0:
        raise ValueError(f"{original!r}: nominal diameter must be positive")

    class_text: str | None = None
    engagement: str | None = None
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
                f"{original!r}: write the pitch after 'x' (M{_fmt(diameter)}x{part}), not after '-'"
            )
        else:
            raise ValueError(f"{original!r}: unexpected part {part!r}")

    lead = 0.0
    if match["ph"] is not None:
        lead, pitch = _number(match["ph"]), _number(match["pp"])
        coarse_used = False
        if pitch <= 0 or lead < pitch or abs(lead / pitch - round(lead / pitch)) > 1e-6:
            raise ValueError(
                f"{original!r}: the lead Ph {_fmt(lead)} must be a whole multiple of the "
                f"pitch P {_fmt(pitch)}"
            )
    else:
        coarse_used = match["p"] is None
        pitch = coarse_pitch(diameter) if coarse_used else _number(match["p"])
    if pitch <= 0:
        raise ValueError(f"{original!r}: pitch must be positive")
    if pitch >= diameter:
        raise ValueError(f"{original!r}: pitch {_fmt(pitch)} is not smaller than the diameter")

    # Case carries meaning only if the writer could use lower case: a lower-case letter or a
    # typographic '×' shows that; an all-capital ASCII string may have been upper-cased.
    has_lower = any(ch.islower() for ch in compact) or "×" in compact
    if class_text is None:
        # GB/T 197: the medium classes are not written (5H/6h up to 1.4 mm, else 6H/6g).
        basis: InternalBasis
        if internal is None:
            is_internal, basis = False, "assumed"
        else:
            is_internal, basis = internal, "caller"
        small = diameter <= 1.4
        if is_internal:
            cls = ToleranceClass(5 if small else 6, "H")
        else:
            cls = ToleranceClass(6, "h" if small else "g")
        return ThreadDesignation(
            nominal_diameter=diameter,
            pitch=pitch,
            internal=is_internal,
            pitch_class=cls,
            crest_class=cls,
            left_hand=left_hand,
            coarse_pitch_used=coarse_used,
            text=original,
            internal_basis=basis,
            class_omitted=True,
            engagement=engagement,
            lead=lead if lead != pitch else 0.0,
        )

    cmatch = _CLASS.match(class_text)
    assert cmatch is not None  # matched in the loop above
    letter1 = cmatch["p1"]
    letter2 = cmatch["p2"] or letter1
    if letter1.isupper() != letter2.isupper():
        raise ValueError(f"{original!r}: mixed letter case in tolerance class {class_text!r}")
    if letter1.lower() != letter2.lower():
        raise ValueError(
            f"{original!r}: pitch and crest classes must share one tolerance position "
            f"({letter1!r} vs {letter2!r})"
        )
    is_internal, basis = _decide_internal(letter1, has_lower, internal, original)
    position = _position_for(letter1, is_internal, original)
    grade1 = int(cmatch["g1"])
    grade2 = int(cmatch["g2"]) if cmatch["g2"] else grade1
    return ThreadDesignation(
        nominal_diameter=diameter,
        pitch=pitch,
        internal=is_internal,
        pitch_class=ToleranceClass(grade1, position),
        crest_class=ToleranceClass(grade2, position),
        left_hand=left_hand,
        coarse_pitch_used=coarse_used,
        text=original,
        internal_basis=basis,
        engagement=engagement,
        lead=lead if lead != pitch else 0.0,
    )
