"""Values written into Scene.rho and Scene.E are held to the rules the MTL reader applies to Kd and Ke (rho in
[0, 1), E = pi Ke finite, >= 0 and at most pi x 1e300): every computation refuses them before it starts, with
radwalk.InputError naming the patch, channel and value. Before, they reached the walks and the path tracer
unchecked and came back as NaN or silently wrong B. set_material takes a number or (r, g, b), under the same
rules."""
import numpy as np
import pytest

import radwalk
from conftest import mesh

BAD = [("rho", -0.25, "rho = -0.25"), ("rho", 1.0, "rho = 1"), ("rho", 1.5, "rho = 1.5"), ("rho", np.nan, "rho = nan"),
       ("E", -1.0, "E = -1"), ("E", np.inf, "E = inf"), ("E", np.nan, "E = nan"), ("E", 1e301 * np.pi, "E = 3.14")]

COMPUTATIONS = {
    "solve": lambda s, ff: radwalk.solve(s, ff),
    "gathering walks": lambda s, ff: radwalk.random_walk(s, ff, walks_per_patch=50),
    "shooting walks": lambda s, ff: radwalk.random_walk(s, ff, method="shoot-collision", particles=500),
    "ray-kernel walks": lambda s, ff: radwalk.random_walk(s, kernel="ray", walks_per_patch=50),
    "compare": lambda s, ff: radwalk.compare(s, ff, runs=2, walks_per_patch=50),
    "exact_variance": lambda s, ff: radwalk.exact_variance(s, ff),
    "measure": lambda s, ff: radwalk.measure(s, "patches:0", ff, method="gather-collision", walks=100),
    "pathtrace": lambda s, ff: radwalk.pathtrace(s, spp=4),
    "solve_adaptive": lambda s, ff: radwalk.solve_adaptive(s, steps=1, rays=50),
}


@pytest.fixture(scope="module")
def ff():
    return radwalk.form_factors(radwalk.load(mesh("cube.obj")), rays=200, seed=2)


@pytest.mark.parametrize("array, value, text", BAD, ids=[f"{a}={v}" for a, v, _ in BAD])
@pytest.mark.parametrize("computation", list(COMPUTATIONS))
def test_bad_rho_or_E_is_refused_by_every_computation(ff, computation, array, value, text):
    scene = radwalk.load(mesh("cube.obj"))
    getattr(scene, array)[3, 1] = value
    with pytest.raises(radwalk.InputError) as error:
        COMPUTATIONS[computation](scene, ff)
    message = str(error.value)
    assert message.startswith("patch 3, channel 1: " + text) and "\n" not in message


def test_values_a_material_may_hold_are_accepted(ff):
    scene = radwalk.load(mesh("cube.obj"))
    scene.rho[:] = 0.999
    scene.rho[0] = 0.0
    scene.E[2] = (0.0, 1e300, 1.0)
    r = radwalk.solve(scene, ff)
    assert np.isfinite(r.B).all()


def test_set_material_takes_a_number_or_three_and_refuses_what_an_MTL_may_not_hold():
    scene = radwalk.load(mesh("cube.obj"))
    scene.set_material("white", rho=0.25)
    white = [m.name for m in scene.materials].index("white")
    assert np.all(scene.rho[scene.material == white] == 0.25)
    scene.set_material("light", Ke=2)
    assert np.all(scene.E[scene.material != white] == 2 * np.pi)
    scene.set_material(white, rho=(0.1, 0.2, 0.3))
    assert np.all(scene.rho[scene.material == white] == (0.1, 0.2, 0.3))
    for kwargs in ({"rho": 1.0}, {"rho": -0.1}, {"rho": np.nan}, {"Ke": -1}, {"Ke": np.inf}, {"rho": (0.1, 0.2)},
                   {"rho": "red"}):
        with pytest.raises(radwalk.InputError):
            scene.set_material("white", **kwargs)
    for material in (2**70, -1, 1.5, None):
        with pytest.raises(radwalk.InputError):
            scene.set_material(material, rho=0.5)
    assert np.all(scene.rho[scene.material == white] == (0.1, 0.2, 0.3))  # refusals change nothing
