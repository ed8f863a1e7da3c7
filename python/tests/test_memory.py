"""No leak: reference counts of the arguments, the result arrays' ownership, memory over many calls."""

from __future__ import annotations

import gc
import os
import sys
import tracemalloc

import numpy as np
import pytest

import nmesh


def test_reference_counts_unchanged_after_50_calls(make_sphere) -> None:
    points = make_sphere(1000)
    floats = points.astype(np.float64)

    def progress(vertices, target, seconds):
        return None

    def cancel(vertices, target, seconds):
        return False

    def fail(vertices, target, seconds):
        raise RuntimeError("fail")

    watched = [points, floats, progress, cancel, fail]
    before = [sys.getrefcount(o) for o in watched]
    for i in range(50):
        nmesh.reconstruct(points, 300, progress=progress, metrics=i % 10 == 0)
        nmesh.reconstruct(floats, 300, progress=cancel, metrics=False)
        with pytest.raises(RuntimeError):
            nmesh.reconstruct(points, 300, progress=fail, metrics=False)
        with pytest.raises(nmesh.InputError):
            nmesh.reconstruct(points[:3], 300, progress=progress)
    gc.collect()
    assert [sys.getrefcount(o) for o in watched] == before


def test_result_arrays_own_the_librarys_buffers(bunny_mesh: nmesh.Reconstruction, tmp_path) -> None:
    # The arrays' base is the capsule holding the library's vector: only the array refers to it,
    # so the vector goes with the array.
    r = nmesh.reconstruct(bunny_mesh.vertices, 100, metrics=False)
    for array in (r.vertices, r.faces):
        assert array.base is not None and not isinstance(array.base, np.ndarray)
        count = sys.getrefcount(array.base)  # outside the assert, whose rewriting holds a reference
        assert count == 2  # the array's reference, and the argument's
    nmesh.write_mesh(tmp_path / "m.off", r.vertices, r.faces)
    for array in nmesh.read_mesh(tmp_path / "m.off") + (nmesh.read_points(tmp_path / "m.off"),):
        count = sys.getrefcount(array.base)
        assert count == 2


def rss_bytes() -> int:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


@pytest.fixture()
def one_call(make_sphere, bunny_path, bunny_mesh, tmp_path):
    """One round of every function: a reconstruct of float64 points (so that a 240 KB copy is
    made too) with a callback, a write, a read of the mesh and of the bunny's 431 KB of points."""
    points = make_sphere(20000).astype(np.float64)
    path = tmp_path / "m.ply"
    nmesh.write_mesh(path, bunny_mesh.vertices, bunny_mesh.faces)

    def call() -> None:
        r = nmesh.reconstruct(points, 300, progress=lambda *_: None, metrics=False)
        nmesh.write_mesh(tmp_path / "r.ply", r.vertices, r.faces)
        nmesh.read_mesh(path)
        nmesh.read_points(bunny_path)

    return call


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="needs /proc")
def test_process_memory_bounded_over_200_calls(one_call) -> None:
    # A leak of the result arrays alone would be 11 KB (reconstruct) + 18 KB (read_mesh) +
    # 431 KB (read_points) a call: 2 MB to 90 MB over 200 calls.
    for _ in range(20):  # warm up the allocator's pools
        one_call()
    gc.collect()
    before = rss_bytes()
    for _ in range(200):
        one_call()
    gc.collect()
    growth = rss_bytes() - before
    assert growth < 1_000_000, f"the process grew by {growth} bytes over 200 calls"


def test_no_python_allocation_left_over_50_calls(one_call) -> None:
    one_call()
    gc.collect()
    tracemalloc.start()
    try:
        for _ in range(50):
            one_call()
        gc.collect()
        traced, _ = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    # NumPy's own buffers (the float64 points' float32 copy) are traced; so are Python objects.
    assert traced < 100_000, f"{traced} bytes of Python allocations still held after 50 calls"
