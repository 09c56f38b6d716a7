"""The writers and the F reader at the module's boundary: read_form_factors chooses the format by the extension
as the CLI's --form-factors does (an .npz was read as Matrix Market text and refused); write_vtp and write_csv
refuse field and metadata names their files cannot hold with radwalk.InputError, its message one line with the
control characters escaped (before: a RuntimeError carrying the raw newline)."""
import numpy as np
import pytest
import scipy.sparse

import radwalk
from conftest import mesh, run_cli

SCENE = mesh("cube.obj")


def test_read_form_factors_reads_npz_by_its_extension(tmp_path):
    run_cli("formfactors", SCENE, "--rays", 200, "--seed", 3, "-o", tmp_path / "F.npz")
    run_cli("formfactors", SCENE, "--rays", 200, "--seed", 3, "-o", tmp_path / "F.mtx")
    scene = radwalk.load(SCENE)
    from_npz = radwalk.read_form_factors(tmp_path / "F.npz", scene).F
    from_mtx = radwalk.read_form_factors(tmp_path / "F.mtx", scene).F
    assert from_npz.shape == (len(scene), len(scene)) and (from_npz != from_mtx).nnz == 0
    scipy.sparse.save_npz(tmp_path / "zipped.npz", from_mtx, compressed=True)
    with pytest.raises(radwalk.InputError, match="compressed=False"):
        radwalk.read_form_factors(tmp_path / "zipped.npz", scene)


@pytest.mark.parametrize("name", ["B\nfake", "B\r", "B\x1b[31m", "tab\there", "", "9lives", "var", "a-b", "\x7f"])
def test_write_vtp_refuses_a_field_name_ParaView_cannot_hold(tmp_path, name):
    scene = radwalk.load(SCENE)
    values = np.ones(len(scene))
    for fields, metadata in (({name: values}, {}), ({}, {name: 1})):
        with pytest.raises(radwalk.InputError) as error:
            radwalk.write_vtp(tmp_path / "a.vtp", scene, fields, metadata)
        message = str(error.value)
        assert message.isprintable(), repr(message)
        assert "ParaView" in message
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("name", ["B\nfake", "a,b", 'q"', "\x00"])
def test_write_csv_refuses_a_column_name_a_header_cannot_hold(tmp_path, name):
    scene = radwalk.load(SCENE)
    values = np.ones(len(scene))
    for fields in ({name: values}, {"ok": (values, name)}):
        with pytest.raises(radwalk.InputError) as error:
            radwalk.write_csv(tmp_path / "a.csv", scene, fields)
        assert str(error.value).isprintable()
    assert not list(tmp_path.iterdir())


def test_names_the_files_can_hold_are_written(tmp_path):
    scene = radwalk.load(SCENE)
    values = np.arange(len(scene), dtype=float)
    radwalk.write_vtp(tmp_path / "a.vtp", scene, {"my_field": values}, {"note": "x", "count": 3})
    radwalk.write_csv(tmp_path / "a.csv", scene, {"mean-gather": values})
    assert "mean-gather" in (tmp_path / "a.csv").read_text().splitlines()[0]
