"""The crown fit of ``drum-groove``: least squares in plain Python, no numpy needed; checked
against numpy's least squares (numpy is a test dependency only)."""

from __future__ import annotations

import math
import os
import random
import subprocess
import sys
from pathlib import Path

import pytest

from fanuc_macro.generators.drum_groove_generator import DRUM_PROFILE
from fanuc_macro.threads.profile import fit_crown, least_squares

ROOT = Path(__file__).resolve().parents[1]


def test_drum_groove_fits_the_crown_where_numpy_cannot_be_imported(tmp_path: Path) -> None:
    """As in the extension's bundled server, which has no numpy: the crown is still fitted."""
    blocker = tmp_path / "blocker" / "numpy"
    blocker.mkdir(parents=True)
    (blocker / "__init__.py").write_text('raise ImportError("numpy is not installed here")\n')
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join([str(blocker.parent), str(ROOT / "server")]),
    }
    done = subprocess.run(
        [sys.executable, "-m", "fanuc_macro.cli", "drum-groove", "--pitch", "12"],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert "crown: R3792.2 mm, the best-fit circle of the 12 points" in done.stderr
    assert "\n(CROWN R3792.2 " in done.stdout


def test_the_papers_points_give_numpys_fit() -> None:
    np = pytest.importorskip("numpy")
    crown = fit_crown(DRUM_PROFILE)
    r = np.array([x / 2.0 for x, _ in DRUM_PROFILE])
    z = np.array([z for _, z in DRUM_PROFILE])
    design = np.column_stack([2.0 * r, 2.0 * z, np.ones_like(r)])
    (a, b, c), *_ = np.linalg.lstsq(design, r * r + z * z, rcond=None)
    assert crown.radius == pytest.approx(math.sqrt(c + a * a + b * b), rel=1e-12)
    assert (crown.centre_radial, crown.centre_z) == pytest.approx((a, b), rel=1e-9, abs=1e-9)
    assert f"{crown.radius:.1f}" == "3792.2"


@pytest.mark.parametrize("seed", range(20))
def test_least_squares_agrees_with_numpy_on_random_systems(seed: int) -> None:
    np = pytest.importorskip("numpy")
    rng = random.Random(seed)
    m = rng.randrange(3, 40)
    scale = 10.0 ** rng.uniform(-3, 4)
    rows = [[rng.uniform(-scale, scale) for _ in range(3)] for _ in range(m)]
    rhs = [rng.uniform(-scale, scale) for _ in range(m)]
    expected, _, rank, _ = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)
    assert rank == 3
    got = least_squares(rows, rhs)
    assert got is not None
    assert got == pytest.approx(list(expected), rel=1e-8, abs=1e-8 * scale)


@pytest.mark.parametrize("seed", range(20))
def test_circle_fit_agrees_with_numpy_on_random_arcs(seed: int) -> None:
    """Arcs of every size, from a small radius to a crown of kilometres, with noise (a short
    arc of a large circle leaves its radius ill-determined: both fits must agree all the
    same)."""
    np = pytest.importorskip("numpy")
    rng = random.Random(seed)
    radius = 10.0 ** rng.uniform(0.5, 6)
    centre_r, centre_z = rng.uniform(-radius, radius), rng.uniform(-500.0, 500.0)
    sweep = rng.uniform(0.01, 1.0) * min(1.0, 300.0 / radius)
    start = rng.uniform(0.0, 2 * math.pi)
    points = []
    for k in range(rng.randrange(3, 30)):
        angle = start + sweep * k / 10
        noise = rng.gauss(0.0, 0.001)
        r = centre_r + (radius + noise) * math.cos(angle)
        z = centre_z + (radius + noise) * math.sin(angle)
        points.append((2.0 * r, z))
    # numpy's least squares of the same system, the points about their mean.
    r_np = np.array([x / 2.0 for x, _ in points])
    z_np = np.array([z for _, z in points])
    r_np, z_np = r_np - r_np.mean(), z_np - z_np.mean()
    design = np.column_stack([2.0 * r_np, 2.0 * z_np, np.ones_like(r_np)])
    (a, b, c), _, rank, _ = np.linalg.lstsq(design, r_np**2 + z_np**2, rcond=None)
    assert rank == 3
    crown = fit_crown(points)
    assert crown.radius == pytest.approx(math.sqrt(c + a * a + b * b), rel=1e-9)


def test_points_on_a_line_have_no_crown() -> None:
    for points in (
        [(300.0, 0.0), (300.0, 10.0), (300.0, 20.0)],  # a cylinder
        [(300.0, 0.0), (302.0, 10.0), (304.0, 20.0), (306.0, 30.0)],  # a taper
    ):
        with pytest.raises(ValueError, match="straight line"):
            fit_crown(points)
    assert least_squares([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [1.0, 0.0, 1.0]], [1, 2, 3]) is None
