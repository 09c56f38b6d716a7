"""A solve that diverged or was refused raises radwalk.NumericalError with the solver's message (the CLI's exit
3); before, it returned a Result (B = None, or B = E for a diverged Jacobi).
The system: the cube's F doubled (rows summing to 2, which a caller's F may hold but the CLI's Matrix Market
reader refuses) with rho = 0.9, spectral radius 1.8: no finite B."""
import numpy as np
import pytest

import radwalk
from conftest import mesh

SCENE = mesh("cube.obj")


@pytest.fixture(scope="module")
def divergent():
    scene = radwalk.load(SCENE)
    scene.set_material("white", rho=(0.9, 0.9, 0.9))
    scene.set_material("light", rho=(0.9, 0.9, 0.9))
    F = radwalk.form_factors(scene, rays=300, seed=4).F * 2
    return scene, F, None


SOLVERS = [("direct", {}), ("jacobi", {}), ("gauss-seidel", {}), ("southwell", {})]
WALKS = [("gather-collision", {"walks_per_patch": 50}), ("shoot-collision", {"particles": 500})]


@pytest.mark.parametrize("solver", [s for s, _ in SOLVERS])
def test_a_divergent_solve_raises_NumericalError(divergent, solver):
    scene, F, _ = divergent
    with pytest.raises(radwalk.NumericalError) as error:
        radwalk.solve(scene, F, solver=solver)
    assert str(error.value) and "\n" not in str(error.value)


@pytest.mark.parametrize("method, counts", WALKS, ids=[m for m, _ in WALKS])
def test_walks_refusing_the_system_raise_NumericalError(divergent, method, counts):
    scene, F, _ = divergent
    with pytest.raises(radwalk.NumericalError) as error:
        radwalk.random_walk(scene, F, method=method, **counts)
    assert str(error.value).startswith(method + " refused: ")
    with pytest.raises(radwalk.NumericalError) as measured:  # the same refusal through measure
        radwalk.measure(scene, "patches:0", F, method=method, walks=50)
    assert str(measured.value) == str(error.value)


def test_compare_raises_NumericalError_when_its_reference_is_refused(divergent):
    scene, F, _ = divergent
    with pytest.raises(radwalk.NumericalError):
        radwalk.compare(scene, F, runs=2, walks_per_patch=50)


def test_max_iterations_is_a_status_not_an_exception():
    scene = radwalk.load(SCENE)
    r = radwalk.solve(scene, radwalk.form_factors(scene, rays=200), solver="jacobi", max_iterations=2)
    assert r.status == "max-iterations" and np.isfinite(r.B).all()
