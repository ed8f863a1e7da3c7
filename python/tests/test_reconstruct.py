"""reconstruct(): the same mesh as the command-line tool, any input layout, the result's shape."""

from __future__ import annotations

import inspect
import json
import re
from pathlib import Path

import numpy as np
import pytest

import nmesh
from nmesh import _nmesh

# The keys of the --stats record that differ between two runs, or by design here.
UNEQUAL_STATS = {"input", "seconds", "seconds_finish"}


@pytest.mark.parametrize(
    "vertices, seed, options, flags",
    [
        (1000, 3, {}, []),
        (700, 5, {"edge_swap": False, "cvs": 60, "finish_rounds": 3, "settle": 0.5},
         ["--no-edge-swap", "--cvs", "60", "--finish-rounds", "3", "--settle", "0.5"]),
    ],
)
def test_same_mesh_and_stats_as_the_command_line_tool(tmp_path: Path, bunny_path: Path, bunny: np.ndarray, cli,
                                                      vertices: int, seed: int, options: dict, flags: list) -> None:
    cli_mesh, cli_stats = tmp_path / "cli.ply", tmp_path / "cli.json"
    cli("reconstruct", bunny_path, "-o", cli_mesh, "--vertices", vertices, "--seed", seed, "--quiet",
        "--stats", cli_stats, *flags)
    result = nmesh.reconstruct(bunny, vertices, seed=seed, **options)
    py_mesh = tmp_path / "py.ply"
    nmesh.write_mesh(py_mesh, result.vertices, result.faces)
    assert py_mesh.read_bytes() == cli_mesh.read_bytes()

    expected = json.loads(cli_stats.read_text())
    assert result.stats.keys() == expected.keys()
    assert {k: v for k, v in result.stats.items() if k not in UNEQUAL_STATS} == \
           {k: v for k, v in expected.items() if k not in UNEQUAL_STATS}
    assert result.stats["input"] == "<array>"
    assert result.stats["seconds"] > 0


def test_the_result(bunny_mesh: nmesh.Reconstruction) -> None:
    r = bunny_mesh
    assert not r.cancelled
    assert r.vertices.shape == (500, 3) and r.vertices.dtype == np.float32
    assert r.faces.shape == (2 * 500 - 4, 3) and r.faces.dtype == np.int32  # closed, genus 0
    assert r.faces.min() == 0 and r.faces.max() == 499
    assert r.stats["vertices"] == 500 and r.stats["faces"] == len(r.faces)
    assert r.stats["seed"] == 2 and r.stats["parameters"]["target_vertices"] == 500
    assert r.stats["cancelled"] is False
    m = r.stats["metrics"]
    assert m["closed"] and m["manifold"] and m["genus"] == 0 and m["self_intersections"] == 0
    assert 0 < m["hausdorff_rel"] < 0.1
    assert "vertices=500" in repr(r)
    # The arrays own the library's buffers (through their base), writable like any result.
    assert r.vertices.flags["C_CONTIGUOUS"] and r.vertices.flags["WRITEABLE"]


def test_other_layouts_give_the_same_mesh(bunny: np.ndarray) -> None:
    reference = nmesh.reconstruct(bunny, 400, seed=7, metrics=False)
    wide = np.zeros((len(bunny), 5), dtype=np.float32)
    wide[:, 1:4] = bunny
    layouts = {
        "float64": bunny.astype(np.float64),
        "fortran": np.asfortranarray(bunny),
        "strided view": wide[:, 1:4],
        "big-endian": bunny.astype(">f4"),
        "list": bunny[:5000].tolist(),
    }
    for name, points in layouts.items():
        if name == "list":
            expected = nmesh.reconstruct(bunny[:5000], 400, seed=7, metrics=False)
        else:
            expected = reference
        got = nmesh.reconstruct(points, 400, seed=7, metrics=False)
        assert np.array_equal(got.vertices, expected.vertices), name
        assert np.array_equal(got.faces, expected.faces), name


def test_float32_points_are_not_copied(bunny: np.ndarray) -> None:
    # The package hands a C-contiguous float32 array to the extension as it is...
    assert nmesh._as_points(bunny) is bunny
    assert nmesh._as_points(bunny.astype(np.float64)) is not bunny
    # ...and the extension reads only such arrays, in place: it never converts one itself.
    args = (400, 0.08, 0.01, 0.95, 100, 20, True, True, 1, 0.0, 10, 0, 4, 10, 64, "closed", True, True, 0.0, 6.0, 0.0,
            1, None, False)
    for other in (bunny.astype(np.float64), np.asfortranarray(bunny), bunny[::2], bunny[:, :2]):
        with pytest.raises(TypeError, match="float32 array of shape"):
            _nmesh.reconstruct(other, *args)
    _nmesh.reconstruct(bunny, *args)


def test_seed_and_parameters_reach_the_library(bunny: np.ndarray, bunny_mesh: nmesh.Reconstruction) -> None:
    again = nmesh.reconstruct(bunny, 500, seed=2, metrics=False)
    assert np.array_equal(again.vertices, bunny_mesh.vertices)
    assert again.stats["metrics"] is None
    other = nmesh.reconstruct(bunny, 500, seed=3, metrics=False)
    assert not np.array_equal(other.vertices, bunny_mesh.vertices)
    params = nmesh.reconstruct(bunny, 300, alpha_w=0.05, alpha_n=0.02, alpha=0.9, cvs=80, cec=15, finish=False,
                               seed=2**64 - 1, index_points_per_vertex=0, stray_ratio=3.5, threads=2,
                               metrics=False).stats
    assert params["seed"] == 2**64 - 1
    assert params["parameters"] == {"target_vertices": 300, "alpha_w": 0.05, "alpha_n": 0.02, "alpha": 0.9,
                                    "cvs": 80, "cec": 15, "edge_swap": True, "fold_guard": True, "solid_start": True,
                                    "topology": "closed",
                                    "settle": 0, "finish": False,
                                    "finish_rounds": 10, "fit_rounds": 0, "surface_fit_rounds": 4,
                                    "exchange_passes": 10, "min_hole": 0,
                                    "stray_ratio": 3.5, "adaptivity": 0, "index_points_per_vertex": 0, "threads": 2}
    assert params["seconds_finish"] == 0


def test_topology_modes(sphere: np.ndarray) -> None:
    for mode in ("sphere", "closed", "open"):
        r = nmesh.reconstruct(sphere, 300, topology=mode, metrics=False)
        assert r.stats["parameters"]["topology"] == mode
        assert r.stats["genus"] == 0 and r.stats["boundary_loops"] == 0  # a sphere sample: no handle, no hole
    # The default, closed, starts from the solid the sample walls round (150 vertices); without
    # that start it grows from the tetrahedron and finds no handle: the sphere mode's mesh.
    a = nmesh.reconstruct(sphere, 300, topology="sphere", metrics=False)
    b = nmesh.reconstruct(sphere, 300, solid_start=False, metrics=False)
    assert np.array_equal(a.faces, b.faces) and np.array_equal(a.vertices, b.vertices)
    c = nmesh.reconstruct(sphere, 300, metrics=False)
    assert c.stats["start_vertices"] == 150 and a.stats["start_vertices"] == 4
    assert c.vertices.shape == (300, 3) and not np.array_equal(a.vertices, c.vertices)
    with pytest.raises(ValueError, match="topology.*'torus'"):
        nmesh.reconstruct(sphere, 50, topology="torus")


def test_solid_start_keyword(sphere: np.ndarray) -> None:
    r = nmesh.reconstruct(sphere, 300, solid_start=False, metrics=False)
    assert r.stats["parameters"]["solid_start"] is False and r.stats["start_vertices"] == 4
    with pytest.raises(TypeError, match="solid_start"):
        nmesh.reconstruct(sphere, 300, solid_start="no")


def test_every_parameter_is_a_keyword() -> None:
    """Each field of nmesh::Parameters (nmesh/parameters.h in the source tree) is a keyword of
    reconstruct under its own name (target_vertices: vertices): a field added to the library
    without its keyword fails here."""
    header = (Path(__file__).resolve().parents[2] / "nmesh" / "parameters.h").read_text()
    body = header[header.index("struct Parameters {"):header.index("void validate() const;")]
    fields = set(re.findall(r"^\s+[\w:]+ (\w+) = ", body, re.M))
    assert "fold_guard" in fields and "threads" in fields and len(fields) == 22
    keywords = set(inspect.signature(nmesh.reconstruct).parameters) - {"points", "progress", "metrics"}
    assert {"vertices" if f == "target_vertices" else f for f in fields} == keywords


def test_threads_keyword(sphere: np.ndarray) -> None:
    """Any thread count gives the same mesh and metrics; a count out of range is refused by name."""
    one = nmesh.reconstruct(sphere, 300, threads=1)
    two = nmesh.reconstruct(sphere, 300, threads=2)
    assert np.array_equal(one.vertices, two.vertices) and np.array_equal(one.faces, two.faces)
    assert one.stats["metrics"] == two.stats["metrics"]
    assert two.stats["parameters"]["threads"] == 2
    assert nmesh.evaluate(sphere, one.vertices, one.faces, threads=1) == nmesh.evaluate(
        sphere, one.vertices, one.faces, threads=3)
    with pytest.raises(ValueError, match="threads") as e:
        nmesh.reconstruct(sphere, 300, threads=1025)
    assert e.value.parameter == "threads"
    with pytest.raises(TypeError, match="threads"):
        nmesh.reconstruct(sphere, 300, threads=1.5)


def test_fold_guard_keyword(sphere: np.ndarray) -> None:
    r = nmesh.reconstruct(sphere, 300, fold_guard=False, metrics=False)
    assert r.stats["parameters"]["fold_guard"] is False
    with pytest.raises(TypeError, match="fold_guard"):
        nmesh.reconstruct(sphere, 300, fold_guard="no")
