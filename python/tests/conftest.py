"""Fixtures of the nmesh Python tests: the bundled bunny, the command-line tool, small clouds.

The tests import the installed package (PYTHONPATH=<prefix>/lib/python3/dist-packages), not the
source tree's python/nmesh, which has no compiled extension. The command-line tool, for the
byte-for-byte comparisons, is $NMESH_CLI (e.g. <build>/nmesh); without it those tests skip.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import Callable, List

import numpy as np
import pytest

import nmesh

REPO = Path(__file__).resolve().parents[2]
BUNNY = REPO / "examples" / "data" / "bunny.ply"


def pytest_report_header(config: pytest.Config) -> List[str]:
    return [f"nmesh {nmesh.__version__} from {Path(nmesh.__file__).parent}",
            f"NMESH_CLI={os.environ.get('NMESH_CLI', '(unset: the command-line comparisons skip)')}"]


@pytest.fixture(scope="session")
def bunny_path() -> Path:
    assert BUNNY.is_file(), f"the bundled cloud is missing: {BUNNY}"
    return BUNNY


@pytest.fixture(scope="session")
def bunny(bunny_path: Path) -> np.ndarray:
    """The bunny's 35,947 points, read once; read-only so that no test changes them for another."""
    points = nmesh.read_points(bunny_path)
    points.flags.writeable = False
    return points


@pytest.fixture(scope="session")
def cli() -> Callable[..., subprocess.CompletedProcess]:
    """Runs the command-line tool with the given arguments; fails the test on a non-zero exit."""
    path = os.environ.get("NMESH_CLI")
    if not path:
        pytest.skip("NMESH_CLI is not set (the path of the nmesh command-line tool)")
    assert os.access(path, os.X_OK), f"NMESH_CLI={path} is not an executable"

    def run(*args: object) -> subprocess.CompletedProcess:
        done = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 0, f"nmesh {' '.join(map(str, args))} failed:\n{done.stderr}"
        return done

    return run


def sphere_points(n: int, seed: int = 0) -> np.ndarray:
    """n points spread over the unit sphere (a Fibonacci spiral), slightly jittered: a cloud that
    reconstructs in a few milliseconds."""
    i = np.arange(n) + 0.5
    z = 1.0 - 2.0 * i / n
    r = np.sqrt(1.0 - z * z)
    phi = np.pi * (1.0 + 5.0**0.5) * i
    points = np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)
    points += np.random.default_rng(seed).normal(scale=1e-3, size=points.shape)
    return points.astype(np.float32)


@pytest.fixture(scope="session")
def make_sphere() -> Callable[..., np.ndarray]:
    return sphere_points


@pytest.fixture(scope="session")
def sphere() -> np.ndarray:
    points = sphere_points(2000)
    points.flags.writeable = False
    return points


@pytest.fixture(scope="session")
def bunny_mesh(bunny: np.ndarray) -> nmesh.Reconstruction:
    """A 500-vertex bunny, for the tests that need a real mesh."""
    return nmesh.reconstruct(bunny, 500, seed=2)
