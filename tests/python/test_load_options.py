"""load's patching options act as the CLI's: two-sided faces, --max-area and the contact cut give the same patches
and, solved on the same seed, the same CSV byte for byte."""
import pytest

import radwalk
from conftest import mesh, run_cli, without_run_id

CORNELL = mesh("cornell_box.obj")
RAYS, SEED = 300, 5


def cli_and_module_csv(tmp_path, flags, **load):
    run_cli("solve", CORNELL, "--rays", RAYS, "--seed", SEED, *flags, "--csv", tmp_path / "cli.csv")
    scene = radwalk.load(CORNELL, **load)
    ff = radwalk.form_factors(scene, rays=RAYS, seed=SEED)
    result = radwalk.solve(scene, ff)
    radwalk.write_csv(tmp_path / "py.csv", scene, {**ff.diagnostics, **result.fields})
    cli = without_run_id(open(tmp_path / "cli.csv", "rb").read())
    return scene, cli, without_run_id(open(tmp_path / "py.csv", "rb").read())


@pytest.mark.parametrize("flags, load", [
    (["--two-sided"], {"two_sided": True}),
    (["--max-edge", 150, "--max-area", 5000], {"max_edge": 150, "max_area": 5000}),
    (["--max-edge", 150, "--contact-cut"], {"max_edge": 150, "contact_cut": True}),
    (["--max-edge", 150, "--no-contact-cut"], {"max_edge": 150, "contact_cut": False}),
])
def test_patching_options_equal_the_cli(tmp_path, flags, load):
    scene, cli, py = cli_and_module_csv(tmp_path, flags, **load)
    assert cli == py
    assert cli.count(b"\n") == len(scene.areas) + 1  # the header and a row per patch


def test_two_sided_doubles_the_patches_and_contact_cut_adds_some():
    plain = radwalk.load(CORNELL)
    assert len(radwalk.load(CORNELL, two_sided=True).areas) == 2 * len(plain.areas)
    uncut = radwalk.load(CORNELL, max_edge=150, contact_cut=False)
    cut = radwalk.load(CORNELL, max_edge=150)  # the cut is the default, made when faces are split
    assert cut.contact_cut and cut.cut and not uncut.contact_cut and not uncut.cut
    assert not plain.cut and len(plain.areas) == 37  # without a split the input faces stay the patches
    assert len(cut.areas) > len(uncut.areas)
    assert abs(cut.areas.sum() - uncut.areas.sum()) <= 1e-9 * uncut.areas.sum()  # the cut tiles the same surface
