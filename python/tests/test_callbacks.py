"""The progress callback: its arguments, cancelling, its exceptions, Ctrl-C, and the GIL."""

from __future__ import annotations

import os
import signal
import threading
import time
from typing import List, Tuple

import numpy as np
import pytest

import nmesh


@pytest.fixture()
def python_sigint_handler():
    """Python's own SIGINT handler (KeyboardInterrupt), which Python does not install when it
    starts with SIGINT ignored, as a background job of a non-interactive shell does."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_progress_arguments(bunny: np.ndarray) -> None:
    calls: List[Tuple[int, int, float]] = []
    threads = set()

    def progress(vertices, target, seconds):
        calls.append((vertices, target, seconds))
        threads.add(threading.get_ident())

    r = nmesh.reconstruct(bunny, 1500, progress=progress, metrics=False)
    assert not r.cancelled
    # About every 65,536 iterations (1500 vertices take ~150 * 1500 of them), and once at the end.
    assert len(calls) >= 3
    assert all(type(v) is int and type(t) is int and type(s) is float for v, t, s in calls)
    assert all(t == 1500 for _, t, _ in calls)
    assert calls[-1][0] == 1500
    seconds = [s for _, _, s in calls]
    assert seconds == sorted(seconds)
    # Since reconstruct began: the last report comes as the learning time is taken.
    assert seconds[-1] == pytest.approx(r.stats["seconds"], rel=0.01, abs=0.002)
    assert threads == {threading.get_ident()}  # the caller's thread, which runs the learning


def test_returning_false_cancels_with_the_mesh_so_far(bunny: np.ndarray) -> None:
    calls = []

    def progress(vertices, target, seconds):
        calls.append(vertices)
        return len(calls) < 3  # True, True, then False

    r = nmesh.reconstruct(bunny, 5000, progress=progress)
    assert r.cancelled and r.stats["cancelled"] is True
    assert len(calls) == 3  # not called again once cancelled
    assert 4 <= len(r.vertices) < 5000 and r.stats["vertices"] == len(r.vertices)
    assert r.faces.max() < len(r.vertices)
    assert r.stats["metrics"]["closed"]  # the mesh reached so far is still a closed mesh


@pytest.mark.parametrize("answer, cancelled", [(None, False), (True, False), (1, False), (0, True),
                                               (np.False_, True)])
def test_the_answers_truth_decides(sphere: np.ndarray, answer, cancelled: bool) -> None:
    # Grown from the tetrahedron: about 100,000 iterations, so a report comes while it learns
    # (from the solid's start, half the target, it would learn too few: the one report at the end).
    r = nmesh.reconstruct(sphere, 1000, topology="sphere", progress=lambda *_: answer, metrics=False)
    assert r.cancelled is cancelled


def test_an_exception_in_the_callback_propagates(bunny: np.ndarray) -> None:
    calls = []

    def progress(vertices, target, seconds):
        calls.append(vertices)
        if len(calls) == 2:
            raise RuntimeError("boom from the callback")

    with pytest.raises(RuntimeError, match="boom from the callback"):
        nmesh.reconstruct(bunny, 5000, progress=progress)
    assert len(calls) == 2


def test_an_answer_without_a_truth_value_propagates(sphere: np.ndarray) -> None:
    with pytest.raises(ValueError, match="truth value"):
        nmesh.reconstruct(sphere, 1000, progress=lambda *_: np.array([1, 2]))


def test_sigint_in_the_callback_raises_keyboardinterrupt(bunny: np.ndarray, python_sigint_handler) -> None:
    calls = []

    def progress(vertices, target, seconds):
        calls.append(vertices)
        if len(calls) == 2:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        nmesh.reconstruct(bunny, 5000, progress=progress)
    assert len(calls) == 2


def test_ctrl_c_while_learning_raises_keyboardinterrupt(bunny: np.ndarray, python_sigint_handler) -> None:
    # No Python callback at all: the SIGINT arrives from another thread while the main thread is
    # inside the library, without the GIL; the library's progress report lets Python run its
    # handler. A 30,000-vertex bunny learns for seconds; the interrupt must end it at once.
    assert threading.current_thread() is threading.main_thread()
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    returned = False
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        timer.start()
        try:
            nmesh.reconstruct(bunny, 30000, metrics=False)
            returned = True
        finally:
            timer.join()
            time.sleep(0.05)  # a late signal is raised here, and `returned` fails the test
    elapsed = time.monotonic() - start
    assert not returned
    assert elapsed < 1.5, f"KeyboardInterrupt came {elapsed:.2f} s after the start, the signal at 0.3 s"


def test_the_gil_is_released_while_learning(bunny: np.ndarray) -> None:
    # A Python thread counts, first alone (the main thread sleeping), then while the main thread
    # is inside reconstruct. With the GIL held there it would get one 5 ms switch interval at
    # most (no Python code runs in the learning without a callback): about 1% of its rate.
    stop = threading.Event()
    count = [0]

    def counter() -> None:
        while not stop.is_set():
            count[0] += 1

    thread = threading.Thread(target=counter)
    thread.start()
    try:
        time.sleep(0.05)  # the thread has started counting
        c0, t0 = count[0], time.monotonic()
        time.sleep(0.2)
        alone = (count[0] - c0) / (time.monotonic() - t0)
        c0, t0 = count[0], time.monotonic()
        nmesh.reconstruct(bunny, 3000, metrics=False)
        during = (count[0] - c0) / (time.monotonic() - t0)
    finally:
        stop.set()
        thread.join()
    assert during > 0.2 * alone, f"counted {during:.0f}/s while learning, {alone:.0f}/s alone"
