"""The GIL is released while the library computes: another Python thread keeps running during a solve."""
import threading
import time

import numpy as np

import radwalk
from conftest import mesh


def test_python_runs_while_a_random_walk_runs():
    scene = radwalk.load(mesh("cube.obj"), max_edge=0.25)
    ff = radwalk.form_factors(scene, rays=200, threads=1)
    span = {}

    def solve():
        span["start"] = time.perf_counter()
        radwalk.random_walk(scene, ff, walks_per_patch=400000, seed=2, threads=1)
        span["end"] = time.perf_counter()

    worker = threading.Thread(target=solve)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    duration = span["end"] - span["start"]
    assert duration > 0.2, "the solve must take long enough for the test to mean something"
    inside = np.array([t for t in ticks if span["start"] <= t <= span["end"]])
    # Held GIL: no tick inside the C++ call, one gap as long as the solve. Released: ticks throughout.
    gaps = np.diff(np.concatenate(([span["start"]], inside, [span["end"]])))
    assert gaps.max() < duration / 4
