"""The cross-section of a thread job (fanuc_macro.threads.cross_section): its cost on the seed
module's 186 passes and on a 20,000-block threading program, and how a polygon version of the
same cut (shapely, when it is installed: not a dependency) compares in time and in the pitch
diameter it gives.

    PYTHONPATH=server python3 bench/bench_cross_section.py

Prints best-of times; quote them with the machine they ran on (docs/benchmarks.md).
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "server"))

from fanuc_macro.analysis import analyse  # noqa: E402
from fanuc_macro.threads.cross_section import (  # noqa: E402
    CrossSection,
    ToolShape,
    blank_diameter,
    cut_cross_section,
    pass_place,
)
from fanuc_macro.threads.identify import Thread  # noqa: E402


def best_of(run: Callable[[], object], times: int) -> float:
    best = math.inf
    for _ in range(times):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    return best


def threading_program(threads: int, passes: int) -> str:
    """``threads`` M50x3-6g threads of ``passes`` G92 passes each, one after the other along Z:
    threads × (passes + 3) blocks."""
    out = ["%", "O1000 (M50X3-6G)", "G97 S300 M03"]
    depth = 1.84  # radius, about 6g's root with an unknown tool
    for t in range(threads):
        z = -t * 40.0
        out.append(f"G00 X52. Z{z + 5.0:.1f}")
        for p in range(passes):
            x = 50.0 - 2.0 * depth * math.sqrt((p + 1) / passes)
            code = f"G92 X{x:.3f} Z{z - 30.0:.1f} F3." if p == 0 else f"X{x:.3f}"
            out.append(code)
        out.append("G00 X60.")
    out += ["M30", "%"]
    return "\n".join(out) + "\n"


def polyline_cut(thread: Thread) -> CrossSection | None:
    lead = thread.job.lead
    blank = blank_diameter(thread)
    assert lead is not None and blank is not None
    radius = thread.nose_radius if thread.nose_radius is not None else 0.125 * (thread.pitch or 1)
    return cut_cross_section(
        thread.job.passes, lead, bool(thread.internal), blank, ToolShape(60.0, radius)
    )


def all_cuts(threads: list[Thread]) -> list[CrossSection | None]:
    return [polyline_cut(t) for t in threads]


def shapely_cut(thread: Thread) -> float | None:
    """The same cut with polygons: the blank over three leads, each pass's V (its nose as a
    buffered arc) subtracted at its place and one lead either side; the pitch diameter read
    where a line across the middle lead is half in the groove."""
    try:
        from shapely.geometry import LineString, Point, Polygon, box
        from shapely.ops import unary_union
    except ImportError:
        return None
    lead = thread.job.lead
    blank = blank_diameter(thread)
    assert lead is not None and blank is not None and not thread.internal
    r = thread.nose_radius if thread.nose_radius is not None else 0.125 * (thread.pitch or 1)
    passes = [m for m in thread.job.passes if m.x is not None]
    root_x = min(m.x for m in passes if m.x is not None)
    material = box(-lead, 0.0, 2.0 * lead, blank / 2.0)
    half = math.radians(30.0)
    tools = []
    for m in passes:
        assert m.x is not None
        place = pass_place(m, lead, root_x) or 0.0
        tip = m.x / 2.0
        centre = tip + r
        tangent_u = r * math.cos(half)
        tangent_r = centre - r * math.sin(half)
        top = blank / 2.0 + 1.0
        reach = tangent_u + (top - tangent_r) * math.tan(half)
        for shift in (-lead, 0.0, lead):
            u = place + shift
            v = Polygon(
                [
                    (u - tangent_u, tangent_r),
                    (u - reach, top),
                    (u + reach, top),
                    (u + tangent_u, tangent_r),
                ]
            )
            tools.append(unary_union([v, Point(u, centre).buffer(r, quad_segs=16)]))
    for tool in tools:
        material = material.difference(tool)
    lo, hi = root_x / 2.0, blank / 2.0
    for _ in range(40):
        mid = (lo + hi) / 2.0
        line = LineString([(0.0, mid), (lead, mid)])
        solid = line.intersection(material).length
        if solid > lead / 2.0:  # more ridge than groove: the pitch line is higher
            lo = mid
        else:
            hi = mid
    return lo + hi


def main() -> None:
    seed = (ROOT / "tests/fixtures/seeds/o4009_external_m50x3.nc").read_text("utf-8")
    cases = [
        ("seed O4009/O3331 (186 passes)", seed),
        ("20,000 blocks, 100 threads of 197 passes", threading_program(100, 197)),
        ("20,000 blocks, 1 thread of 19,996 passes", threading_program(1, 19996)),
    ]
    for name, text in cases:
        start = time.perf_counter()
        analysis = analyse(text, "bench.nc")
        analysed = time.perf_counter() - start
        threads = [t for t in analysis.threads if t.identified]
        passes = sum(len(t.job.passes) for t in threads)
        t_polyline = best_of(partial(all_cuts, threads), 3)
        cut = polyline_cut(threads[0])
        assert cut is not None
        print(
            f"{name}: {len(threads)} threads, {passes:,} passes; whole analysis "
            f"{analysed * 1000:.0f} ms; cross-sections (polylines) {t_polyline * 1000:.1f} ms, "
            f"{t_polyline / max(passes, 1) * 1e6:.1f} µs a pass; first thread's d2 "
            f"{cut.pitch_diameter:.4f}"
        )
        if passes <= 2000 and len(threads) == 1:
            t_shapely = best_of(partial(shapely_cut, threads[0]), 1)
            d2 = shapely_cut(threads[0])
            if d2 is not None:
                print(
                    f"  polygons (shapely): {t_shapely * 1000:.1f} ms "
                    f"({t_shapely / t_polyline:.0f}x), d2 {d2:.4f} "
                    f"({abs(d2 - cut.pitch_diameter) * 1000:.1f} µm from the polyline's)"
                )


if __name__ == "__main__":
    main()
