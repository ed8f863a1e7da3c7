# Stubs of the compiled extension nmesh._nmesh (python/src/module.cpp). Its functions take arrays
# already in the library's layout (float32 or uint32, C-contiguous, aligned, shape (N, 3)) and
# raise TypeError for any other; the package nmesh converts its arguments before calling them.
from typing import Callable, Optional, Tuple

import numpy as np

__version__: str

class InputError(ValueError):
    """The points cannot be reconstructed or measured."""

def reconstruct(
    points: np.ndarray,
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
    index_points_per_vertex: int,
    progress: Optional[Callable[[int, int, float], Optional[bool]]],
    metrics: bool,
) -> Tuple[np.ndarray, np.ndarray, str, bool]: ...
def read_points(path: bytes | str) -> np.ndarray: ...
def read_mesh(path: bytes | str) -> Tuple[np.ndarray, np.ndarray]: ...
def write_mesh(path: bytes | str, vertices: np.ndarray, faces: np.ndarray, ascii: bool) -> None: ...
def evaluate(points: np.ndarray, vertices: np.ndarray, faces: np.ndarray) -> str: ...
