"""Taper pipe threads by their designation: ISO 7-1 (R, Rc, Rp; the same sizes as BS 21,
JIS B 0203's PT and GB/T 7306) and the American NPT (ASME B1.20.1).

Their checks need little of each standard: the pitch (from the threads per inch), the
profile's included angle, the taper (1:16 on the diameter, none for ISO 7-1's parallel
internal Rp), which side of the part the thread is on, and a diameter to tell which job of a
program cuts it. The diameters are the major diameter at the gauge plane (ISO 7-1, Table 1)
and the pipe's outside diameter (NPT, ASME B1.20.1 Table 2): from the tables as commonly
reproduced, unverified against the standards' own text.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from types import MappingProxyType

# ISO 7-1 Table 1: size (numerator, denominator: of an inch) -> (threads per 25.4 mm, the
# major diameter at the gauge plane, mm).
ISO7: Mapping[tuple[int, int], tuple[int, float]] = MappingProxyType(
    {
        (1, 16): (28, 7.723),
        (1, 8): (28, 9.728),
        (1, 4): (19, 13.157),
        (3, 8): (19, 16.662),
        (1, 2): (14, 20.955),
        (3, 4): (14, 26.441),
        (1, 1): (11, 33.249),
        (5, 4): (11, 41.910),
        (3, 2): (11, 47.803),
        (2, 1): (11, 59.614),
        (5, 2): (11, 75.184),
        (3, 1): (11, 87.884),
        (4, 1): (11, 113.030),
        (5, 1): (11, 138.430),
        (6, 1): (11, 163.830),
    }
)
# ASME B1.20.1 Table 2: size (numerator, denominator) -> (threads per inch, the pipe's outside
# diameter, inches).
NPT: Mapping[tuple[int, int], tuple[float, float]] = MappingProxyType(
    {
        (1, 16): (27, 0.3125),
        (1, 8): (27, 0.405),
        (1, 4): (18, 0.540),
        (3, 8): (18, 0.675),
        (1, 2): (14, 0.840),
        (3, 4): (14, 1.050),
        (1, 1): (11.5, 1.315),
        (5, 4): (11.5, 1.660),
        (3, 2): (11.5, 1.900),
        (2, 1): (11.5, 2.375),
        (5, 2): (8, 2.875),
        (3, 1): (8, 3.500),
        (7, 2): (8, 4.000),
        (4, 1): (8, 4.500),
        (5, 1): (8, 5.563),
        (6, 1): (8, 6.625),
        (8, 1): (8, 8.625),
        (10, 1): (8, 10.750),
        (12, 1): (8, 12.750),
    }
)
INCH = 25.4
# Both standards' taper: 1 in 16 on the diameter.
TAPER = 1.0 / 16.0
# ISO 7-1's basic profile: 55°, crest and root rounded with r = 0.137329P.
ISO7_ANGLE = 55.0
ISO7_ROUND = 0.137329
# NPT: 60°, crests and roots flat, the flat at least 0.033P wide (ASME B1.20.1 Table 1,
# unverified): the round of a tool whose tip fits that flat, 0.033P / (2 cos 30°).
NPT_ANGLE = 60.0
NPT_ROUND = 0.033 / (2.0 * 0.8660254037844386)

_SIZE = r"(?P<whole>\d{1,2})(?:(?:\s+|-)(?P<num>\d{1,2})/(?P<den>\d{1,2}))?(?:/(?P<den2>\d{1,2}))?"
# "R1/2", "Rc 3/4", "Rp1", "PT1/2", "BSPT 1/2", "NPT 1/2", "NPTF1". GB/T 7306's R1 and R2 (the
# external thread for Rp and for Rc) are not read: "R25" would be R2 of size 5.
_BEFORE = re.compile(
    rf"(?<![A-Z0-9#.])(?P<kind>NPTF?|BSPT|PT|RC|RP|R)\s*{_SIZE}(?![\d/.X×*])",
    re.IGNORECASE,
)
# "1/2 NPT", '1/2"NPT', "1/2-14 NPT", "1/2-14NPTF".
_AFTER = re.compile(
    rf"(?<![\d/.]){_SIZE}\s*(?:\"|IN(?:CH)?)?\s*(?:-\s*\d+(?:\.\d)?\s*)?(?P<kind>NPTF?)\b",
    re.IGNORECASE,
)


@dataclass(frozen=True, slots=True)
class PipeThread:
    """A taper pipe thread's designation as written, with what its checks need."""

    text: str
    standard: str  # "ISO 7-1" or "NPT"
    kind: str  # "R", "Rc", "Rp" or "NPT"
    size: Fraction
    pitch: float  # mm
    angle: float  # the profile's included angle, degrees
    taper: float  # on the diameter, per unit of length (0 for Rp)
    internal: bool | None  # None: NPT is either
    diameter: float  # mm: the gauge plane's major diameter (ISO 7-1), the pipe's OD (NPT)
    nose_round: float  # the root's round, as a share of the pitch

    @property
    def name(self) -> str:
        return f"{self.text} ({self.standard})"


def pipe_threads(text: str) -> list[PipeThread]:
    """The taper pipe thread designations in a comment's ``text``."""
    found: list[PipeThread] = []
    for pattern in (_BEFORE, _AFTER):
        for m in pattern.finditer(text):
            size = _size(m)
            thread = _thread(m.group(0).strip(), m["kind"].upper(), size) if size else None
            if thread is not None and all(f.text != thread.text for f in found):
                found.append(thread)
    return found


def _size(m: re.Match[str]) -> Fraction | None:
    whole = int(m["whole"])
    if m["den2"] is not None:  # "1/2": the whole is the numerator
        return Fraction(whole, int(m["den2"])) if int(m["den2"]) else None
    if m["num"] is not None:
        den = int(m["den"])
        return whole + Fraction(int(m["num"]), den) if den else None
    return Fraction(whole)


def _thread(text: str, kind: str, size: Fraction) -> PipeThread | None:
    if kind.startswith("NPT"):
        row = NPT.get((size.numerator, size.denominator))
        if row is None:
            return None
        tpi, outside = row
        return PipeThread(
            text, "NPT", "NPT", size, INCH / tpi, NPT_ANGLE, TAPER, None, outside * INCH, NPT_ROUND
        )
    iso = ISO7.get((size.numerator, size.denominator))
    if iso is None:
        return None
    tpi_iso, gauge = iso
    if kind in ("RC", "RP"):
        name, internal, taper = ("Rc", True, TAPER) if kind == "RC" else ("Rp", True, 0.0)
    else:
        name, internal, taper = "R", False, TAPER
    return PipeThread(
        text, "ISO 7-1", name, size, INCH / tpi_iso, ISO7_ANGLE, taper, internal, gauge, ISO7_ROUND
    )
