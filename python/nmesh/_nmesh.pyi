# Stubs of the compiled extension nmesh._nmesh (python/src/module.cpp). Its functions take arrays
# already in the library's layout (float32 or uint32, C-contiguous, aligned, shape (N, 3)) and
# raise TypeError for any other; the package nmesh converts its arguments before calling them.
from typing import Callable, Optional, Tuple

import numpy as np
import numpy.typing as npt

_Float32Array = npt.NDArray[np.float32]
_Int32Array = npt.NDArray[np.int32]
_UInt32Array = npt.NDArray[np.uint32]

__version__: str

class InputError(ValueError):
    """The points cannot be reconstructed or measured."""

def reconstruct(
    points: _Float32Array,
    target_vertices: int,
    alpha_w: float,
    alpha_n: float,
    alpha: float,
    cvs: int,
    cec: int,
    edge_swap: bool,
    finish: bool,
    seed: int,
    settle: float,
    finish_rounds: int,
    fit_rounds: int,
    surface_fit_rounds: int,
    exchange_passes: int,
    index_points_per_vertex: int,
    topology: str,
    fold_guard: bool,
    solid_start: bool,
    min_hole: float,
    stray_ratio: float,
    adaptivity: float,
    threads: int,
    progress: Optional[Callable[[int, int, float], Optional[bool]]],
    metrics: bool,
) -> Tuple[_Float32Array, _Int32Array, str, bool]: ...
def read_points(path: bytes | str) -> _Float32Array: ...
def read_mesh(path: bytes | str) -> Tuple[_Float32Array, _Int32Array]: ...
def write_mesh(path: bytes | str, vertices: _Float32Array, faces: _UInt32Array, ascii: bool) -> None: ...
def evaluate(points: _Float32Array, vertices: _Float32Array, faces: _UInt32Array, threads: int) -> str: ...
