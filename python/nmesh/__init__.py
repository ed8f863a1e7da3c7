"""nmesh: a triangle mesh from a point cloud (Neural Meshes ES), from Python.

    import nmesh

    points = nmesh.read_points("bunny.ply")            # (N, 3) float32
    result = nmesh.reconstruct(points, 30000, seed=1)  # the learning runs without the GIL
    print(result.stats["seconds"], result.stats["metrics"]["hausdorff_rel"])
    nmesh.write_mesh("bunny_mesh.ply", result.vertices, result.faces)

The functions take any array-like of shape (N, 3) with real numbers; a C-contiguous float32
NumPy array is read in place (no copy), anything else is converted once. Errors of the library
are Python's: a bad parameter raises ValueError naming it (its name also as e.parameter, as for
an argument of the wrong type, a TypeError), a file that cannot be read or written OSError (the
message starts with the path, which is e.path), points that cannot be reconstructed (fewer than
4 distinct, all on one line, a NaN or infinite coordinate) nmesh.InputError, a ValueError.
"""

from __future__ import annotations

import json
import numbers
import operator
import os
from dataclasses import dataclass
from typing import Any, Callable, Dict, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

try:
    from . import _nmesh
except ImportError as error:  # the source tree's python/nmesh, or a build without the extension
    raise ImportError(
        "nmesh: the compiled extension nmesh._nmesh is missing: configure with -DNMESH_BUILD_PYTHON=ON, "
        "build, cmake --install, and put <prefix>/lib/python3/dist-packages on PYTHONPATH"
    ) from error

from ._nmesh import InputError

__all__ = [
    "Float32Array",
    "InputError",
    "Int32Array",
    "PathArg",
    "ProgressCallback",
    "Reconstruction",
    "evaluate",
    "read_mesh",
    "read_points",
    "reconstruct",
    "write_mesh",
]

__version__: str = _nmesh.__version__

#: The type of a path argument: str, bytes or os.PathLike.
PathArg = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]

#: (N, 3) float32 points or vertices, and (F, 3) int32 faces, as the functions return them.
Float32Array = npt.NDArray[np.float32]
Int32Array = npt.NDArray[np.int32]

#: progress(vertices, target_vertices, seconds) -> continue? (None or True continue, False cancels)
ProgressCallback = Callable[[int, int, float], Optional[bool]]

_UINT32_MAX = 2**32 - 1
_UINT64_MAX = 2**64 - 1


@dataclass(frozen=True, eq=False)
class Reconstruction:
    """The result of reconstruct().

    vertices: (V, 3) float32, in the coordinates of the input points.
    faces: (F, 3) int32, counter-clockwise seen from outside; a 2-manifold of the cloud's genus,
        closed unless topology="open".
    stats: the record `nmesh reconstruct --stats` writes, as a dict (its "input" is "<array>"):
        seed, parameters, vertices, faces, the counts and timings of the learning ("seconds" is
        the learning time, "seconds_finish" the finishing stage's), cancelled, and "metrics",
        the quality report of `nmesh eval` of this mesh against the whole cloud (None when
        reconstruct was called with metrics=False).
    cancelled: True when the progress callback returned False: the mesh is the one reached so far.
    """

    vertices: Float32Array
    faces: Int32Array
    stats: Dict[str, Any]
    cancelled: bool

    def __repr__(self) -> str:
        return (
            f"Reconstruction(vertices={len(self.vertices)}, faces={len(self.faces)}, "
            f"seconds={self.stats.get('seconds')}, cancelled={self.cancelled})"
        )


def _named(error: Exception, parameter: str) -> Exception:
    """`error` with the name of the argument it is about as its `parameter` attribute, as the
    library's ValueErrors have it."""
    setattr(error, "parameter", parameter)
    return error


def _path(path: PathArg) -> bytes:
    """The path as the bytes the operating system sees (any str, bytes or os.PathLike)."""
    if not isinstance(path, (str, bytes, os.PathLike)):
        raise _named(TypeError(f"path must be str, bytes or os.PathLike, not {type(path).__name__}"), "path")
    return os.fsencode(path)


def _rows_of_three(array: npt.ArrayLike, name: str) -> npt.NDArray[Any]:
    """`array` as an ndarray of real numbers of shape (N, 3), not yet converted; the checks."""
    a = np.asarray(array)  # no copy for an ndarray (a subclass gives a view of the same memory)
    if a.dtype.kind == "c":
        raise _named(TypeError(f"{name} must hold real numbers, not complex ({a.dtype})"), name)
    if a.dtype.kind not in "fiu":  # bool, object, strings, bytes, datetimes, structured arrays...
        message = f"{name} must hold real numbers (an integer or floating-point array), not {a.dtype}"
        raise _named(TypeError(message), name)
    if a.ndim != 2 or a.shape[1] != 3:
        raise _named(ValueError(f"{name} must be an array of shape (N, 3), got shape {a.shape}"), name)
    return a


def _as_points(points: npt.ArrayLike, name: str = "points") -> Float32Array:
    """`points` as a C-contiguous, aligned float32 (N, 3) array: the same object when it already
    is one (reconstruct then reads the caller's buffer in place), else one converted copy.
    Values beyond float32's range become infinite (as the file readers do), which the library
    refuses as non-finite (InputError)."""
    a = _rows_of_three(points, name)
    with np.errstate(over="ignore", invalid="ignore"):  # overflow to inf is reported by the library
        return np.require(a, dtype=np.float32, requirements=("C", "A"))


def _as_faces(faces: npt.ArrayLike, vertex_count: int) -> npt.NDArray[np.uint32]:
    """`faces` as a C-contiguous uint32 (F, 3) array, every index checked to be in [0, V): so
    that no int64 index wraps around to a valid one on the way to uint32."""
    f = np.asarray(faces)
    if f.dtype.kind not in "iu":
        raise _named(TypeError(f"faces must be an integer array, not {f.dtype}"), "faces")
    if f.ndim != 2 or f.shape[1] != 3:
        raise _named(ValueError(f"faces must be an array of shape (F, 3), got shape {f.shape}"), "faces")
    if f.size:
        low, high = int(f.min()), int(f.max())
        if low < 0 or high >= vertex_count:
            bad = low if low < 0 else high
            raise _named(ValueError(f"faces: index {bad} is out of range for {vertex_count} vertices"), "faces")
    return np.require(f, dtype=np.uint32, requirements=("C", "A"))


def _count(name: str, value: Any, maximum: int = _UINT32_MAX) -> int:
    """An integer keyword in [0, maximum] (the library's unsigned fields); its finer range is
    checked by the library (ValueError naming the parameter)."""
    if isinstance(value, (bool, np.bool_)):
        raise _named(TypeError(f"{name} must be an integer, not bool"), name)
    try:
        n = operator.index(value)  # int, NumPy integers; not floats or strings
    except TypeError:
        raise _named(TypeError(f"{name} must be an integer, not {type(value).__name__}"), name) from None
    if not 0 <= n <= maximum:
        raise _named(ValueError(f"invalid parameter {name}: must be in [0, {maximum}], got {n}"), name)
    return n


def _real(name: str, value: Any) -> float:
    """A real-valued keyword (its range is checked by the library)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise _named(TypeError(f"{name} must be a real number, not {type(value).__name__}"), name)
    return float(value)


def _flag(name: str, value: Any) -> bool:
    """A True/False keyword: only bools (a string such as "false" would be truthy)."""
    if not isinstance(value, (bool, np.bool_)):
        raise _named(TypeError(f"{name} must be True or False, not {type(value).__name__}"), name)
    return bool(value)


def reconstruct(
    points: npt.ArrayLike,
    vertices: int = 10000,
    *,
    topology: str = "closed",
    alpha_w: float = 0.08,
    alpha_n: float = 0.01,
    alpha: float = 0.95,
    cvs: int = 100,
    cec: int = 20,
    edge_swap: bool = True,
    fold_guard: bool = True,
    solid_start: bool = True,
    min_hole: float = 0.0,
    stray_ratio: float = 6.0,
    adaptivity: float = 0.0,
    finish: bool = True,
    seed: int = 1,
    progress: Optional[ProgressCallback] = None,
    finish_rounds: int = 10,
    fit_rounds: int = 0,
    surface_fit_rounds: int = 4,
    exchange_passes: int = 10,
    settle: float = 0.0,
    index_points_per_vertex: int = 64,
    threads: int = 0,
    metrics: bool = True,
) -> Reconstruction:
    """Learns a triangle mesh of exactly `vertices` vertices from the points (closed, unless
    topology="open" leaves the scan's holes open, which takes the vertices inside them away).

    The same points, parameters and seed give the same mesh, bit for bit, as
    `nmesh reconstruct IN -o OUT --vertices N --seed S` (written with write_mesh, the same file).

    points: array-like of shape (N, 3), real numbers. A C-contiguous float32 ndarray is read in
        place, without a copy (do not modify it from another thread meanwhile); any other array
        (float64, integers, a non-contiguous view, a list) is converted to float32 once.
    vertices: the target vertex count (>= 4). The defaults of the other parameters are Table 2 of
        the Neural Meshes ES paper; the command-line tool's --help explains each.
    topology: "closed" (a closed surface of the cloud's genus: read from the solid the cloud
        walls round, or handles learnt where it has through-holes), "sphere" (genus 0: the
        paper's algorithm) or "open" (as closed, then opened where the cloud has no data); other
        values raise ValueError.
    alpha_w, alpha_n: learning rates of the winner vertex and of its neighbours.
    alpha: the signal counter decay per iteration.
    cvs: a vertex split every `cvs` iterations.  cec: inactive vertices removed every cec * n.
    edge_swap: Neural Meshes ES (False: basic Neural Meshes).
    fold_guard: step 3 may not fold the winner's triangles (False: eq. (2) as the paper has it).
    solid_start: closed and open: start from the solid the cloud walls round, when it walls one
        (False: grow from a tetrahedron, the handles from the handle search).
    min_hole: open: the smallest hole to open, the distance from its middle to the nearest point
        in local point spacings (0: the default rule, which keeps the sampling's gaps and holes a
        few spacings across closed).
    stray_ratio: a point whose 8th nearest neighbour is more than stray_ratio times the cloud's
        median of that distance away is a stray sample, left out before the learning (0 keeps
        every point).
    adaptivity: closed and open, from the solid's start: a win counts 1 + adaptivity * (the
        winner's distance / its mean)^2, so that tips and bends get vertices sooner (0: the paper's
        signal counter).
    finish: the finishing stage (flips, relaxation onto the cloud, repair of folds).
    seed: the random seed (an integer in [0, 2**64 - 1]).
    progress: called about every 65,536 iterations and once when the learning ends, as
        progress(vertices, target_vertices, seconds), from the thread that called reconstruct,
        with the GIL held. Returning False (or any false value but None) cancels: reconstruct
        then returns the mesh reached so far with `cancelled` True (no exception). An exception
        raised by the callback cancels the learning and propagates out of reconstruct.
    finish_rounds, fit_rounds: the finishing stage's regularisation and centroid-fit rounds.
    surface_fit_rounds: the finishing stage's surface fit (the vertices moved to where the mesh
        best matches the points, least squares), in rounds; 0 turns it off.
    exchange_passes: the finishing stage's vertex exchange (vertices moved from flat parts to
        where the surface bends, at most 2% of them per pass; 10, the default, measured best); 0
        keeps them where the learning's sample density put them.
    settle: settle * n iterations without topology changes once the target size is reached.
    index_points_per_vertex: cloud points indexed per target vertex (0: all of them).
    threads: threads for the work beside the learning (the solid's reading, the finishing stage's
        relaxation and fit, the output check, the metrics); 0, the machine's cores, or 1 to 1024.
        The same mesh for every count.
    metrics: measure the mesh against the whole cloud for stats["metrics"], as the command-line
        tool does for --stats: about 0.25 s on the 36k-point bunny whatever the mesh size, which
        is most of the time of a small reconstruction (0.07 s at 500 vertices). False leaves
        stats["metrics"] None.

    The learning and the measuring run with the GIL released. Ctrl-C (SIGINT, in the main
    thread) cancels a running reconstruct and raises KeyboardInterrupt.

    Returns a Reconstruction: vertices, faces, stats (the --stats record, with the quality
    metrics of the mesh against the whole cloud, as the command-line tool computes them) and
    cancelled.

    Raises ValueError naming the parameter for a parameter out of range, TypeError or ValueError
    for points of the wrong dtype or shape (the argument's name, the keyword's for a parameter,
    is the error's `parameter` attribute), nmesh.InputError (a ValueError) for points that
    cannot be reconstructed, including any NaN or infinite coordinate.
    """
    if not isinstance(topology, str):
        raise _named(TypeError(f"topology must be a str, not {type(topology).__name__}"), "topology")
    if progress is not None and not callable(progress):
        raise _named(TypeError(f"progress must be callable or None, not {type(progress).__name__}"), "progress")
    cloud = _as_points(points)
    vertices_out, faces_out, stats_json, cancelled = _nmesh.reconstruct(
        cloud,
        target_vertices=_count("vertices", vertices),
        alpha_w=_real("alpha_w", alpha_w),
        alpha_n=_real("alpha_n", alpha_n),
        alpha=_real("alpha", alpha),
        cvs=_count("cvs", cvs),
        cec=_count("cec", cec),
        edge_swap=_flag("edge_swap", edge_swap),
        topology=topology,
        fold_guard=_flag("fold_guard", fold_guard),
        solid_start=_flag("solid_start", solid_start),
        min_hole=_real("min_hole", min_hole),
        stray_ratio=_real("stray_ratio", stray_ratio),
        adaptivity=_real("adaptivity", adaptivity),
        finish=_flag("finish", finish),
        seed=_count("seed", seed, _UINT64_MAX),
        settle=_real("settle", settle),
        finish_rounds=_count("finish_rounds", finish_rounds),
        fit_rounds=_count("fit_rounds", fit_rounds),
        surface_fit_rounds=_count("surface_fit_rounds", surface_fit_rounds),
        exchange_passes=_count("exchange_passes", exchange_passes),
        index_points_per_vertex=_count("index_points_per_vertex", index_points_per_vertex),
        threads=_count("threads", threads),
        progress=progress,
        metrics=_flag("metrics", metrics),
    )
    stats = json.loads(stats_json)
    if not metrics:
        stats["metrics"] = None  # write_run_json wrote an empty report's zeros
    return Reconstruction(vertices_out, faces_out, stats, cancelled)


def read_points(path: PathArg) -> Float32Array:
    """The points of a file (.ply, .xyz/.txt/.pts/.csv, .obj, .off) as an (N, 3) float32 array,
    in file order; points with a NaN or infinite coordinate are dropped. Raises OSError (the
    message starts with the path, which is its `path` attribute) for a file that is missing,
    unreadable or malformed."""
    return _nmesh.read_points(_path(path))


def read_mesh(path: PathArg) -> Tuple[Float32Array, Int32Array]:
    """(vertices (V, 3) float32, faces (F, 3) int32) of a .ply, .obj or .off file (polygons are
    fan-triangulated; a point file gives no faces). Raises OSError as read_points does."""
    return _nmesh.read_mesh(_path(path))


def write_mesh(path: PathArg, vertices: npt.ArrayLike, faces: npt.ArrayLike, *, ascii: bool = False) -> None:
    """Writes a mesh to a .ply (binary little-endian, or ASCII with ascii=True), .obj or .off
    file, chosen by the extension; atomically (the file is either replaced whole or untouched).
    read_mesh gives the same vertices and faces back, bit for bit.

    vertices: (V, 3) real numbers (written as float32); faces: (F, 3) integers in [0, V).
    Raises OSError for an unknown extension or a file that cannot be written, ValueError for a
    non-finite coordinate or a face index out of range, TypeError for non-integer faces."""
    v = _as_points(vertices, "vertices")
    f = _as_faces(faces, len(v))
    _nmesh.write_mesh(_path(path), v, f, _flag("ascii", ascii))


def evaluate(
    points: npt.ArrayLike, vertices: npt.ArrayLike, faces: npt.ArrayLike, *, threads: int = 0
) -> Dict[str, Any]:
    """The metrics of `nmesh eval POINTS MESH --json` as a dict: DM(X,T), point-to-surface and
    surface-to-cloud distances, Hausdorff (each also relative to the cloud's bounding-box
    diagonal, the *_rel keys), topology (closed, manifold, euler, genus, components,
    boundary_loops, self_intersections...) and triangle quality. Deterministic (a fixed sampling
    seed), and the same for any number of `threads` (0: the machine's cores, or 1 to 1024).

    Raises nmesh.InputError for no points, no faces, or a NaN or infinite coordinate."""
    p = _as_points(points)
    v = _as_points(vertices, "vertices")
    f = _as_faces(faces, len(v))
    result: Dict[str, Any] = json.loads(_nmesh.evaluate(p, v, f, _count("threads", threads)))
    return result
