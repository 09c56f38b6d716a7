"""Arguments are held to the CLI's bounds: threads from 0 (all cores) to 1024 wherever a `threads` argument
exists, images of at most 2^26 pixels (the CLI's check, core/image.h, before anything is traced), and the walk
count a method does not read refused as the CLI refuses --walks-per-patch with shooting walks."""
import pytest

import radwalk
from conftest import mesh, run_cli


@pytest.fixture(scope="module")
def scene():
    return radwalk.load(mesh("cube.obj"))


@pytest.fixture(scope="module")
def ff(scene):
    return radwalk.form_factors(scene, rays=100)


CALLS = {
    "form_factors": lambda s, ff, t: radwalk.form_factors(s, rays=16, threads=t),
    "solve": lambda s, ff, t: radwalk.solve(s, ff, threads=t),
    "random_walk": lambda s, ff, t: radwalk.random_walk(s, ff, walks_per_patch=16, threads=t),
    "compare": lambda s, ff, t: radwalk.compare(s, ff, runs=2, walks_per_patch=16, threads=t),
    "exact_variance": lambda s, ff, t: radwalk.exact_variance(s, ff, threads=t),
    "measure": lambda s, ff, t: radwalk.measure(s, "patches:0", ff, threads=t),
    "pathtrace": lambda s, ff, t: radwalk.pathtrace(s, spp=2, threads=t),
    "solve_adaptive": lambda s, ff, t: radwalk.solve_adaptive(s, steps=1, rays=16, threads=t),
}


@pytest.mark.parametrize("threads", [-1, 1025, 2**31, -2**63])
@pytest.mark.parametrize("call", list(CALLS))
def test_thread_counts_outside_the_CLIs_bounds_are_refused(scene, ff, call, threads):
    with pytest.raises(radwalk.InputError, match=f"threads {threads}: expected a whole number from 0"):
        CALLS[call](scene, ff, threads)


def test_the_CLI_refuses_the_same_thread_counts():
    for threads in (-1, 1025):
        assert run_cli("check", mesh("cube.obj"), "--threads", threads, check=False).returncode == 2
    assert run_cli("check", mesh("cube.obj"), "--threads", 1024).returncode == 0


@pytest.mark.parametrize("call", list(CALLS))
def test_thread_counts_within_the_bounds_run(scene, ff, call):
    CALLS[call](scene, ff, 1024 if call == "form_factors" else 1)


@pytest.mark.parametrize("width, height", [(8193, 8192), (2**31 - 1, 2**31 - 1), (0, 16), (16, -1)])
def test_an_image_too_large_or_empty_is_refused_before_anything_is_traced(scene, width, height):
    with pytest.raises(radwalk.InputError, match=f"width={width}, height={height}: ") as error:
        radwalk.pathtrace(scene, spp=2, averages=False, image=True, width=width, height=height)
    if width > 0 and height > 0:
        assert "pixels would need at least" in str(error.value) and "at most 67108864 pixels" in str(error.value)


def test_the_CLI_refuses_an_image_above_2_26_pixels_with_the_same_text(tmp_path):
    r = run_cli("pathtrace", mesh("cube.obj"), "--spp", 2, "--width", 8193, "--height", 8192, "--image",
                tmp_path / "a.png", check=False)
    assert r.returncode == 2
    assert ("--width 8193 --height 8192: 67117056 pixels would need at least 3221618688 bytes (48 per pixel for the"
            " image and its standard error); at most 67108864 pixels (e.g. 8192 x 8192)") in r.stderr
    assert not (tmp_path / "a.png").exists()


def test_samples_outside_the_CLIs_bounds_are_refused(scene):
    for spp in (1, 2**32 + 1, -5):
        with pytest.raises(radwalk.InputError, match="spp"):
            radwalk.pathtrace(scene, spp=spp)


def test_the_walk_count_the_method_does_not_read_is_refused(scene, ff):
    with pytest.raises(radwalk.InputError, match="walks_per_patch counts gathering walks"):
        radwalk.random_walk(scene, ff, method="shoot-collision", walks_per_patch=100)
    with pytest.raises(radwalk.InputError, match="particles counts shooting particles"):
        radwalk.random_walk(scene, ff, method="gather-collision", particles=100)
    radwalk.random_walk(scene, ff, method="shoot-collision", particles=200)
    radwalk.random_walk(scene, ff, method="gather-collision", walks_per_patch=20)
