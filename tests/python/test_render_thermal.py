"""Thermal pictures: scripts/render_vtp.py --field q renders a `radwalk exchange` .vtp colour-mapped with a colour
bar (diverging, symmetric about 0), and the picture is not flat. The same render of the radiosity's colour field
(B_rgb, no bar) fails the bar check: the check can fail."""
import os
import shutil
import subprocess

import pytest
from conftest import CLI, SOURCE
from vtkmodules.vtkIOImage import vtkPNGReader

SIZE = 240


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(str(path))
    reader.Update()
    image = reader.GetOutput()
    nx, ny, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    comps = scalars.GetNumberOfComponents()
    return nx, ny, lambda x, y: tuple(int(scalars.GetComponent(y * nx + x, c)) for c in range(3)) if comps >= 3 else None


def render(vtp, png, *args):
    cmd = [str(SOURCE / "scripts" / "with_xvfb.sh"), "/usr/bin/python3", str(SOURCE / "scripts" / "render_vtp.py"),
           str(vtp), str(png), "--size", str(SIZE)] + list(args)
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    assert r.returncode == 0, r.stdout
    return r.stdout


def bar_colours(png):
    """Distinct colours down the middle column of the colour bar's place (x = 0.86 + 0.02 of the width)."""
    nx, ny, at = pixels(png)
    x = int(0.88 * nx)
    return [at(x, y) for y in range(int(0.15 * ny), int(0.85 * ny))]


@pytest.fixture(scope="module")
def exchange_vtp(tmp_path_factory):
    if shutil.which("Xvfb") is None and not os.environ.get("DISPLAY"):
        pytest.skip("no X server (Xvfb) for VTK's render window")
    work = tmp_path_factory.mktemp("thermal")
    vtp = work / "cube.vtp"
    r = subprocess.run([CLI, "exchange", str(SOURCE / "meshes" / "cube.obj"), "-q", "--analytic", "--max-edge", "0.25",
                        "--set", "light.emissivity=0.9", "--set", "light.temperature=600", "--set",
                        "white.emissivity=0.8", "--set", "white.temperature=300", "-o", str(vtp)],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    assert r.returncode == 0, r.stdout
    return vtp


def test_q_is_colour_mapped_with_a_diverging_bar(exchange_vtp, tmp_path):
    png = tmp_path / "q.png"
    out = render(exchange_vtp, png, "--field", "q")
    assert "diverging" in out and "W/m^2" in out, out
    column = bar_colours(png)
    distinct = set(column)
    # A 256-entry map drawn over ~170 pixel rows: many distinct colours, from blue (gain) to red (loss).
    assert len(distinct) >= 40, len(distinct)
    assert any(b > r + 60 for r, g, b in column), "no blue end"
    assert any(r > b + 60 for r, g, b in column), "no red end"
    # The scene (left of the bar) is not flat: the hot light (red) and the walls it heats (blue).
    nx, ny, at = pixels(png)
    scene = {at(x, y) for x in range(0, int(0.8 * nx), 4) for y in range(0, ny, 4)}
    assert any(r > b + 60 for r, g, b in scene) and any(b > r + 30 for r, g, b in scene), sorted(scene)[:10]


def test_T_uses_a_sequential_map_with_kelvin(exchange_vtp, tmp_path):
    out = render(exchange_vtp, tmp_path / "T.png", "--field", "T", "--range", "290", "610")
    assert "sequential" in out and "[290, 610] K" in out, out


def test_the_bar_check_fails_without_a_bar(exchange_vtp, tmp_path):
    vtp, png = tmp_path / "B.vtp", tmp_path / "B.png"
    r = subprocess.run([CLI, "solve", str(SOURCE / "meshes" / "cube.obj"), "-q", "--analytic", "--max-edge", "0.25",
                        "-o", str(vtp)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    assert r.returncode == 0, r.stdout
    render(vtp, png, "--field", "B_rgb")
    assert len(set(bar_colours(png))) < 40
