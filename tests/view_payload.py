"""The Toolpath view's payload (ide/toolpath_view.py) read back as a browser reads it: base64 of
little-endian typed arrays, decoded here with struct, apart from the server's code."""

from __future__ import annotations

import base64
import struct
from typing import Any

# Each packed field's struct code: uint8, int32, uint16, int32, int32; the points are float64.
SEGMENT_FIELDS = {"kind": "B", "line": "i", "path": "H", "point": "i", "motion": "i"}
# Per motion record: uint16 code index, float64 feed and speed, uint8 surface speed or not.
BLOCK_FIELDS = {"code": "H", "feed": "d", "speed": "d", "surface": "B"}


def values(code: str, text: str) -> list[Any]:
    raw = base64.b64decode(text, validate=True)
    size = struct.calcsize("<" + code)
    assert len(raw) % size == 0, (code, len(raw))
    return list(struct.unpack(f"<{len(raw) // size}{code}", raw))


def unpacked(data: dict[str, Any]) -> dict[str, list[Any]]:
    """``kind``, ``line``, ``path``, ``point``, ``motion`` per segment and ``points`` (x, y, z
    each) as lists, ``start``/``end`` per segment (x, y, z tuples) that they make, and per
    motion record ``code`` (the code's text), ``feed``, ``speed`` and ``surface``."""
    assert data["format"] == 3
    s = data["segments"]
    out: dict[str, list[Any]] = {k: values(code, s[k]) for k, code in SEGMENT_FIELDS.items()}
    assert all(len(out[k]) == data["count"] for k in SEGMENT_FIELDS)
    points = values("d", data["points"])
    assert len(points) % 3 == 0
    out["points"] = points
    out["start"] = [tuple(points[3 * p : 3 * p + 3]) for p in out["point"]]
    out["end"] = [tuple(points[3 * p + 3 : 3 * p + 6]) for p in out["point"]]
    assert all(len(e) == 3 for e in out["end"])
    b = data["blocks"]
    records = {k: values(code, b[k]) for k, code in BLOCK_FIELDS.items()}
    assert len({len(v) for v in records.values()}) == 1
    out["block_code"] = [data["codes"][c] for c in records["code"]]
    out["block_feed"] = records["feed"]
    out["block_speed"] = records["speed"]
    out["block_surface"] = records["surface"]
    return out
