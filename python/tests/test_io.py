"""read_points, read_mesh, write_mesh and evaluate: files, paths and the metrics of `nmesh eval`."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

import nmesh


def test_read_points_gives_the_files_floats(bunny_path: Path, bunny: np.ndarray) -> None:
    # The bundled bunny is a binary little-endian PLY of float x, y, z and nothing else: its body
    # read independently of the library must equal what read_points returns.
    data = bunny_path.read_bytes()
    body = data[data.index(b"end_header\n") + len(b"end_header\n"):]
    expected = np.frombuffer(body, dtype="<f4").reshape(-1, 3)
    assert bunny.shape == (35947, 3)
    assert bunny.dtype == np.float32 and bunny.flags["C_CONTIGUOUS"]
    assert np.array_equal(bunny, expected)


@pytest.mark.parametrize("name", ["mesh.ply", "mesh.obj", "mesh.off", "ascii.ply"])
def test_write_then_read_gives_the_same_mesh(tmp_path: Path, bunny_mesh: nmesh.Reconstruction, name: str) -> None:
    path = tmp_path / name
    nmesh.write_mesh(path, bunny_mesh.vertices, bunny_mesh.faces, ascii=name.startswith("ascii"))
    vertices, faces = nmesh.read_mesh(path)
    assert vertices.dtype == np.float32 and faces.dtype == np.int32
    # Bit for bit, the text formats included (shortest round-tripping decimals).
    assert np.array_equal(vertices.view(np.uint32), bunny_mesh.vertices.view(np.uint32))
    assert np.array_equal(faces, bunny_mesh.faces)
    # The points of a mesh file are its vertices.
    assert np.array_equal(nmesh.read_points(path), bunny_mesh.vertices)


def test_write_mesh_converts_other_dtypes_to_the_same_file(tmp_path: Path, bunny_mesh: nmesh.Reconstruction) -> None:
    nmesh.write_mesh(tmp_path / "a.ply", bunny_mesh.vertices, bunny_mesh.faces)
    nmesh.write_mesh(tmp_path / "b.ply", bunny_mesh.vertices.astype(np.float64),
                     bunny_mesh.faces.astype(np.uint64)[:, :])
    nmesh.write_mesh(tmp_path / "c.ply", np.asfortranarray(bunny_mesh.vertices), bunny_mesh.faces.tolist())
    a = (tmp_path / "a.ply").read_bytes()
    assert a == (tmp_path / "b.ply").read_bytes() == (tmp_path / "c.ply").read_bytes()


def test_paths_may_be_str_bytes_or_pathlike(tmp_path: Path, bunny_mesh: nmesh.Reconstruction) -> None:
    target = tmp_path / "dé jà" / "vu.obj"  # a space and non-ASCII characters
    target.parent.mkdir()
    for path in (target, str(target), os.fsencode(target)):
        nmesh.write_mesh(path, bunny_mesh.vertices, bunny_mesh.faces)
        assert np.array_equal(nmesh.read_mesh(path)[1], bunny_mesh.faces)
    with pytest.raises(TypeError, match="path"):
        nmesh.read_points(42)  # type: ignore[arg-type]


def test_a_point_file_reads_as_a_mesh_without_faces(tmp_path: Path) -> None:
    path = tmp_path / "points.xyz"
    path.write_text("0 0 0\n1 0 0\n0 1 0\n0 0 1\n")
    vertices, faces = nmesh.read_mesh(path)
    assert vertices.shape == (4, 3) and faces.shape == (0, 3)
    assert np.array_equal(nmesh.read_points(path), np.eye(4, 3, k=-1, dtype=np.float32))


def test_missing_and_malformed_files_raise_oserror_with_the_path(tmp_path: Path) -> None:
    missing = tmp_path / "missing.ply"
    for read in (nmesh.read_points, nmesh.read_mesh):
        with pytest.raises(OSError) as error:
            read(missing)
        assert str(missing) in str(error.value)
        assert error.value.path == str(missing)  # the path alone, as a str
    bad = tmp_path / "bad.xyz"
    bad.write_text("1 2 3\n4 five 6\n")
    with pytest.raises(OSError, match="bad.xyz.*line 2") as error:
        nmesh.read_points(os.fsencode(bad))  # a bytes path comes back as os.fsdecode makes it
    assert error.value.path == str(bad)


def test_write_mesh_refusals(tmp_path: Path, bunny_mesh: nmesh.Reconstruction) -> None:
    v, f = bunny_mesh.vertices, bunny_mesh.faces
    with pytest.raises(OSError, match="mesh.stl") as error:
        nmesh.write_mesh(tmp_path / "mesh.stl", v, f)  # no such writer
    assert error.value.path == str(tmp_path / "mesh.stl")
    with pytest.raises(OSError, match="no_such_dir") as error:
        nmesh.write_mesh(tmp_path / "no_such_dir" / "m.ply", v, f)
    assert error.value.path == str(tmp_path / "no_such_dir" / "m.ply")
    out = tmp_path / "m.ply"
    with pytest.raises(ValueError, match="index 500 is out of range"):
        nmesh.write_mesh(out, v, np.where(f == 0, 500, f))
    with pytest.raises(ValueError, match="index -1"):
        nmesh.write_mesh(out, v, np.where(f == 0, -1, f))
    with pytest.raises(ValueError, match="index 4294967296"):  # would wrap to 0 as uint32
        nmesh.write_mesh(out, v, np.where(f == 0, 2**32, f.astype(np.int64)))
    with pytest.raises(TypeError, match="faces must be an integer array") as error:
        nmesh.write_mesh(out, v, f.astype(np.float64))
    assert error.value.parameter == "faces"
    with pytest.raises(ValueError, match=r"faces must be an array of shape \(F, 3\)"):
        nmesh.write_mesh(out, v, f[:, :2])
    with pytest.raises(ValueError, match=r"vertices must be an array of shape \(N, 3\)"):
        nmesh.write_mesh(out, v.ravel(), f)
    nan = v.copy()
    nan[7, 1] = np.nan
    with pytest.raises(ValueError):
        nmesh.write_mesh(out, nan, f)
    assert not out.exists()  # nothing written by any refusal


def test_evaluate_equals_nmesh_eval(tmp_path: Path, bunny_path: Path, bunny: np.ndarray,
                                    bunny_mesh: nmesh.Reconstruction, cli) -> None:
    mesh = tmp_path / "mesh.ply"
    nmesh.write_mesh(mesh, bunny_mesh.vertices, bunny_mesh.faces)
    expected = json.loads(cli("eval", bunny_path, mesh, "--json").stdout)
    report = nmesh.evaluate(bunny, bunny_mesh.vertices, bunny_mesh.faces)
    assert report == expected
    assert report["closed"] and report["manifold"] and report["genus"] == 0
    # The same report as the one reconstruct computed for its stats.
    assert report == bunny_mesh.stats["metrics"]


def test_evaluate_refusals(bunny: np.ndarray, bunny_mesh: nmesh.Reconstruction) -> None:
    v, f = bunny_mesh.vertices, bunny_mesh.faces
    with pytest.raises(nmesh.InputError):
        nmesh.evaluate(np.zeros((0, 3)), v, f)
    with pytest.raises(nmesh.InputError):
        nmesh.evaluate(bunny, v, f[:0])
    inf = np.array(bunny)
    inf[3, 0] = np.inf
    with pytest.raises(nmesh.InputError):
        nmesh.evaluate(inf, v, f)
    with pytest.raises(TypeError, match="complex"):
        nmesh.evaluate(bunny.astype(np.complex64), v, f)
