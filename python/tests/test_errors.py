"""The library's errors as Python exceptions; arguments of the wrong type, shape or value."""

from __future__ import annotations

import numpy as np
import pytest

import nmesh


@pytest.mark.parametrize(
    "options, name",
    [
        ({"vertices": 3}, "vertices"),
        ({"vertices": -1}, "vertices"),
        ({"vertices": 2**40}, "vertices"),
        ({"alpha_w": 0.0}, "alpha_w"),
        ({"alpha_n": 1.5}, "alpha_n"),
        ({"alpha": 1.0}, "alpha"),
        ({"alpha": float("nan")}, "alpha"),
        ({"cvs": 0}, "cvs"),
        ({"cec": 0}, "cec"),
        ({"settle": -1.0}, "settle"),
        ({"finish_rounds": 1001}, "finish_rounds"),
        ({"fit_rounds": 1, "finish": False}, "fit_rounds"),
        ({"surface_fit_rounds": 101}, "surface_fit_rounds"),
        ({"exchange_passes": 101}, "exchange_passes"),
        ({"seed": -1}, "seed"),
        ({"seed": 2**64}, "seed"),
        ({"topology": "plane"}, "topology"),
    ],
)
def test_a_bad_parameter_is_a_valueerror_naming_it(sphere: np.ndarray, options: dict, name: str) -> None:
    with pytest.raises(ValueError, match=f"invalid parameter {name}\\b") as error:
        nmesh.reconstruct(sphere, **options)
    assert not isinstance(error.value, nmesh.InputError)
    assert error.value.parameter == name  # the keyword, whether the package or the library refused it
    assert "target_vertices" not in str(error.value)  # the Python keyword, not the C++ field


@pytest.mark.parametrize(
    "options, name",
    [
        ({"vertices": "100"}, "vertices"),
        ({"vertices": 100.0}, "vertices"),
        ({"vertices": True}, "vertices"),
        ({"alpha_w": "0.1"}, "alpha_w"),
        ({"edge_swap": "no"}, "edge_swap"),
        ({"finish": 0}, "finish"),
        ({"progress": 5}, "progress"),
        ({"topology": None}, "topology"),
    ],
)
def test_a_parameter_of_the_wrong_type_is_a_typeerror_naming_it(sphere: np.ndarray, options: dict, name: str) -> None:
    with pytest.raises(TypeError, match=name) as error:
        nmesh.reconstruct(sphere, **options)
    assert error.value.parameter == name


def test_numpy_scalars_are_accepted(sphere: np.ndarray) -> None:
    r = nmesh.reconstruct(sphere, np.int64(40), alpha_w=np.float32(0.08), edge_swap=np.bool_(True), metrics=False)
    assert len(r.vertices) == 40


@pytest.mark.parametrize("shape", [(10, 2), (10, 4), (30,), (10, 3, 1), (3, 10), (0,)])
def test_points_of_the_wrong_shape(shape: tuple) -> None:
    with pytest.raises(ValueError, match=r"points must be an array of shape \(N, 3\), got shape"):
        nmesh.reconstruct(np.ones(shape, dtype=np.float32))


@pytest.mark.parametrize(
    "points, what",
    [
        (np.ones((10, 3), dtype=np.complex128), "complex"),
        (np.ones((10, 3), dtype=bool), "bool"),
        (np.full((10, 3), "1.0"), "<U3"),
        (np.array([[1, 2, None]] * 10, dtype=object), "object"),
        ([[1, 2, "x"]] * 10, "<U"),
    ],
)
def test_points_of_the_wrong_dtype(points, what: str) -> None:
    with pytest.raises(TypeError, match=f"points must hold real numbers.*{what}"):
        nmesh.reconstruct(points)


@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf, 1e300])
def test_non_finite_points_are_an_inputerror(sphere: np.ndarray, value: float) -> None:
    points = sphere.astype(np.float64)
    points[123, 2] = value  # 1e300 is infinite as float32
    with pytest.raises(nmesh.InputError, match="non-finite"):
        nmesh.reconstruct(points, 50)


@pytest.mark.parametrize(
    "points, message",
    [
        (np.eye(3), "3 points"),
        (np.zeros((0, 3)), "0 points"),
        (np.arange(30.0).reshape(10, 3), "one line"),
        (np.ones((10, 3)), "identical"),
        (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]] * 5), "3 distinct points"),
    ],
)
def test_unreconstructable_points_are_an_inputerror(points: np.ndarray, message: str) -> None:
    with pytest.raises(nmesh.InputError, match=message):
        nmesh.reconstruct(points, 10)


def test_inputerror_is_a_valueerror_of_the_package() -> None:
    assert issubclass(nmesh.InputError, ValueError)
    assert nmesh.InputError.__module__ == "nmesh" and nmesh.InputError.__name__ == "InputError"
    assert nmesh.InputError is nmesh._nmesh.InputError


def test_a_cloud_too_small_for_the_target_is_an_inputerror(make_sphere) -> None:
    # 60 points cannot carry 2000 vertices: the mesh stops growing.
    with pytest.raises(nmesh.InputError, match="stopped growing"):
        nmesh.reconstruct(make_sphere(60), 2000, metrics=False)
