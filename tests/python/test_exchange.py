"""radwalk.exchange against `radwalk exchange` (one library pipeline, solve/heat_exchange.h): the same J, q, Q, T
with their errors per patch, the same table per object and the same energy balance, number for number as the CLI
writes them (12 significant digits in the CSV, round-trip doubles in the JSON); and the refusals of options it
cannot honour."""
import csv
import json

import pytest

import radwalk
from conftest import run_cli

# The unit cube in metres, six materials (one re-radiating), each face its own object.
EPS = [0.9, 0.3, 0.55, 0.7, 1.0, 0.05]
TEMPERATURE = [600, 300, 350, None, 280, 450]
FACES = ["1 4 8 5", "2 6 7 3", "1 5 6 2", "4 3 7 8", "1 2 3 4", "5 8 7 6"]


def write_cube(d):
    with open(d / "thermal.mtl", "w") as f:
        for i in range(6):
            f.write("newmtl t%d\nKd 0.5\nradwalk_emissivity %g\n" % (i, EPS[i]))
            f.write("radwalk_heat_flux 0\n" if TEMPERATURE[i] is None else "radwalk_temperature %g\n" % TEMPERATURE[i])
    with open(d / "thermal.obj", "w") as f:
        f.write("mtllib thermal.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n")
        for i, face in enumerate(FACES):
            f.write("o f%d\nusemtl t%d\nf %s\n" % (i, i, face))
    return d / "thermal.obj"


def write_block_room(d):
    """A 2 m room facing in with a 0.5 m block standing on its floor (a contact)."""
    with open(d / "c.mtl", "w") as f:
        f.write("newmtl wall\nradwalk_emissivity 0.9\nradwalk_temperature 293\n"
                "newmtl block\nradwalk_emissivity 0.8\nradwalk_temperature 330\n")
    lines = ["mtllib c.mtl"]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 4, 7, 3)]
    for base, (name, mat, a0, a1, h, inward) in enumerate([("room", "wall", 0, 2, 2, True),
                                                           ("block", "block", 0.5, 1.0, 0.5, False)]):
        lines += ["o " + name, "usemtl " + mat]
        lines += ["v %g %g %g" % (x, y, z) for z in (0, h) for (x, y) in ((a0, a0), (a1, a0), (a1, a1), (a0, a1))]
        for q in quads:
            q = q[::-1] if inward else q
            lines.append("f " + " ".join(str(8 * base + 1 + k) for k in q))
    (d / "c.obj").write_text("\n".join(lines) + "\n")
    return d / "c.obj"


def g12(x):
    return "" if x != x else ("%.12g" % x)


def test_python_equals_cli(tmp_path):
    obj = write_cube(tmp_path)
    run_cli("exchange", obj, "--max-edge", "0.5", "--rays", "500", "--seed", "3", "--solver", "direct",
            "--csv", tmp_path / "x.csv", "--groups", tmp_path / "g.csv", "--json", tmp_path / "x.json")
    scene = radwalk.load(str(obj), max_edge=0.5)
    r = radwalk.exchange(scene, rays=500, seed=3, solver="direct")
    rows = list(csv.DictReader(open(tmp_path / "x.csv")))
    assert len(rows) == len(r.J) == 24
    for name in ("J", "J_se", "G", "q", "q_se", "Q", "Q_se", "T", "T_se", "J_disc", "J_err", "q_disc", "q_err",
                 "Q_disc", "Q_err", "T_disc", "T_err", "emissivity", "temperature_given", "sky", "back",
                 "contact", "cavity"):
        values = getattr(r, name)
        for i, row in enumerate(rows):
            assert row[name] == g12(values[i]), (name, i, row[name], values[i])
    groups = list(csv.DictReader(open(tmp_path / "g.csv")))
    assert [g["object"] for g in groups] == [g["name"] for g in r.groups] == r.group_names
    for g, p in zip(groups, r.groups):
        for key in ("area", "Q", "Q_se", "T_radiant", "sky", "back"):
            assert g[key] == g12(p[key]), (key, g[key], p[key])
    x = json.load(open(tmp_path / "x.json"))["exchange"]
    for key, value in r.balance.items():
        assert x[key] == value, (key, x[key], value)
    # The group view factors: rows sum to 1 in the closed cube (up to its sky and back fractions).
    F = r.group_factors
    for k, g in enumerate(r.groups):
        assert abs(F[k].sum() + g["sky"] + g["back"] - 1) < 1e-6


def test_refusals(tmp_path):
    obj = write_block_room(tmp_path)
    # Contact patches left out must be whole patches of the footprint: a scene loaded without the cut cannot
    # honour contact_faces="exclude" (the CLI cuts the supports itself).
    scene = radwalk.load(str(obj), max_edge=0.5, contact_cut=False)
    with pytest.raises(radwalk.InputError, match="cut along the contact footprints"):
        radwalk.exchange(scene, rays=16, contact_faces="exclude")
    with pytest.raises(radwalk.InputError, match="contact_faces must be"):
        radwalk.exchange(scene, rays=16, contact_faces="leave-out")
    with pytest.raises(radwalk.InputError, match="group_by must be"):
        radwalk.exchange(scene, rays=16, group_by="colour")
    with pytest.raises(radwalk.InputError, match="radwalk exchange --solver random-walk"):
        radwalk.exchange(scene, rays=16, solver="random-walk")
    # With the cut it runs, and agrees with the CLI's --contact-faces exclude.
    cut = radwalk.load(str(obj), max_edge=0.5)  # contact_cut=True, the default
    r = radwalk.exchange(cut, rays=200, seed=2, contact_faces="exclude", solver="direct")
    run_cli("exchange", obj, "--max-edge", "0.5", "--rays", "200", "--seed", "2", "--solver", "direct",
            "--contact-faces", "exclude", "--json", tmp_path / "c.json")
    x = json.load(open(tmp_path / "c.json"))["exchange"]
    assert r.balance["contact_patches"] == x["contact_patches"] == 2
    assert abs(r.balance["contact_area"] - 0.5) < 1e-12
    for key, value in r.balance.items():
        assert x[key] == value, (key, x[key], value)


def write_box_room(d, hollow):
    """A 2 m room (floor 293 K, walls 283 K) with a re-radiating box floating in it: its outer shell (group shell)
    and, with `hollow`, an inner shell facing in (group inside), whose faces see only one another."""
    name = "hollow" if hollow else "shell"
    with open(d / (name + ".mtl"), "w") as f:
        f.write("newmtl floor\nradwalk_emissivity 0.95\nradwalk_temperature 293\n"
                "newmtl wall\nradwalk_emissivity 0.9\nradwalk_temperature 283\n"
                "newmtl box\nradwalk_emissivity 0.85\nradwalk_heat_flux 0\n")
    lines = ["mtllib %s.mtl" % name]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 4, 7, 3)]
    boxes = [((0, 2, 0, 2), True, ["o floor", "usemtl floor"], ["o walls", "usemtl wall"]),
             ((0.7, 1.3, 0.5, 1.1), False, ["o box", "g shell", "usemtl box"], [])]
    if hollow:
        boxes.append(((0.72, 1.28, 0.52, 1.08), True, ["g inside"], []))
    for base, ((a0, a1, z0, z1), inward, first, rest) in enumerate(boxes):
        lines += ["v %g %g %g" % (x, y, z) for z in (z0, z1) for (x, y) in ((a0, a0), (a1, a0), (a1, a1), (a0, a1))]
        for k, q in enumerate(quads):
            lines += first if k == 0 else rest if k == 1 else []
            q = q[::-1] if inward else q
            lines.append("f " + " ".join(str(8 * base + 1 + v) for v in q))
    (d / (name + ".obj")).write_text("\n".join(lines) + "\n")
    return d / (name + ".obj")


def test_closed_cavity(tmp_path):
    """The box's interior is a closed cavity (docs/heat-exchange.md, "Closed cavities"): one UserWarning naming
    it, NaN J, G, T there, cavity = 1, and the rest as in the same room without the interior (analytic F, direct
    solve: the same F for those patches, the solves' rounding within 1e-9 of the scale); the box's T_radiant
    leaves the interior out. As the CLI (same library step)."""
    import numpy as np
    solved = {}
    for hollow in (True, False):
        scene = radwalk.load(str(write_box_room(tmp_path, hollow)), max_edge=0.4, orient="none")
        F = radwalk.form_factors(scene, analytic=True)
        if hollow:
            with pytest.warns(UserWarning, match=r"closed cavity: 24 patches \(1.882 m\^2\) of object 'box', group 'inside'"):
                solved[hollow] = radwalk.exchange(scene, F=F, solver="direct", discretisation_directions=0)
        else:
            solved[hollow] = radwalk.exchange(scene, F=F, solver="direct", discretisation_directions=0)
    h, s = solved[True], solved[False]
    common = len(s.J)
    assert len(h.J) == common + 24
    assert list(h.cavity) == [0] * common + [1] * 24
    assert not s.cavity.any()
    for name in ("J", "G", "T", "J_se", "T_se"):
        assert np.isnan(getattr(h, name)[common:]).all(), name
    assert (h.q[common:] == 0).all() and (h.Q[common:] == 0).all()
    (cavity,) = h.cavities
    assert cavity["objects"] == ["box"] and cavity["groups"] == ["inside"] and cavity["materials"] == ["box"]
    assert cavity["patches"] == list(range(common, common + 24))
    assert abs(cavity["area"] - 6 * 0.56 ** 2) < 1e-9 and cavity["leak"] < 1e-4 and cavity["given_Q"] == 0
    scale = s.J.max()
    for name in ("J", "G", "q"):
        assert np.abs(getattr(h, name)[:common] - getattr(s, name)[:common]).max() <= 1e-9 * scale, name
    assert np.abs(h.T[:common] - s.T[:common]).max() <= 1e-9 * 293
    box_T = {hollow: next(g["T_radiant"] for g in solved[hollow].groups if g["name"] == "box") for hollow in solved}
    assert abs(box_T[True] - box_T[False]) <= 1e-9 * 293
    assert 283 <= box_T[False] <= 293
