"""Bad input raises ValueError naming the field; no panic reaches Python."""

import numpy as np
import pytest

import tack


def run(text, **overrides):
    return tack.run(text, overrides=overrides or None)


@pytest.mark.parametrize(
    "overrides, expected",
    [
        ({"material.e_star": -1}, "material.e_star = -1 is invalid: must be a finite number > 0"),
        ({"material.gamma": -0.5}, "material.gamma = -0.5"),
        ({"grid.n": 0}, "grid.n = 0 is invalid"),
        ({"grid.dx": float("nan")}, "grid.dx = NaN"),
        ({"protocol.load_step": 0.0}, "protocol.load_step = 0"),
        ({"grid.bogus": 1}, "bogus"),
        ({"grid.n": "many"}, 'n = "many"'),
    ],
)
def test_scene_errors_name_the_field(small_sphere, overrides, expected):
    with pytest.raises(tack.SceneError) as info:
        tack.run(small_sphere, overrides=overrides)
    assert expected in str(info.value)
    assert isinstance(info.value, ValueError) and isinstance(info.value, tack.TackError)


def test_missing_files():
    with pytest.raises(tack.SceneError, match="cannot read scene"):
        tack.run("no/such/scene.toml")
    with pytest.raises(tack.ResultFileError) as info:
        tack.read("no/such/result.h5")
    assert isinstance(info.value, ValueError)


def test_write_to_a_missing_directory(small_sphere, tmp_path):
    result = tack.run(small_sphere)
    with pytest.raises(tack.ResultFileError, match="does not exist"):
        result.write(tmp_path / "missing" / "out.h5")


def test_threads_are_validated(small_sphere):
    for bad in [0, -1, tack.MAX_THREADS + 1]:
        with pytest.raises(tack.TackError, match=f"threads = {bad} is invalid"):
            tack.run(small_sphere, threads=bad)
    with pytest.raises(TypeError):
        tack.run(small_sphere, threads=2.5)
    assert tack.run(small_sphere, threads=2).pull_off_force < 0


def test_pull_off_errors_name_the_field():
    heights = tack.surface.sphere(32, dx=0.45, radius=8.0)
    with pytest.raises(tack.TackError, match="gamma = 0 is invalid"):
        tack.pull_off(heights, dx=0.45, e_star=1.0, gamma=0.0)
    # The Python arguments are named, not the scene fields the library writes from them.
    with pytest.raises(ValueError, match="^e_star = -1 is invalid"):
        tack.pull_off(heights, dx=0.45, e_star=-1.0, gamma=0.1)
    with pytest.raises(ValueError, match="^dx = 0 is invalid"):
        tack.pull_off(heights, dx=0.0, e_star=1.0, gamma=0.1)
    bad = heights.copy()
    bad[3, 4] = np.nan
    with pytest.raises(ValueError, match=r"heights\[3, 4\] = NaN"):
        tack.pull_off(bad, dx=0.45, e_star=1.0, gamma=0.1)
    with pytest.raises(ValueError, match="max_approach is required"):
        tack.pull_off(np.zeros((16, 16)), dx=0.1, e_star=1.0, gamma=0.1)
    with pytest.raises(ValueError, match="too small for the pull-off"):
        tack.pull_off(heights, dx=0.45, e_star=1.0, gamma=0.125, max_approach=5.0)
    with pytest.raises(ValueError, match="snapshots"):
        tack.pull_off(heights, dx=0.45, e_star=1.0, gamma=0.125, snapshots="some")
    with pytest.raises(ValueError, match="2-D"):
        tack.pull_off(np.zeros(5), dx=0.45, e_star=1.0, gamma=0.125)


def test_pull_off_errors_give_python_advice():
    # Advice in a message is spelled as Python takes it: the JKR limit is law=tack.JkrLimit(),
    # and pull_off has no step cap of its own (a longer path is a scene's, run by tack.run).
    heights = tack.surface.sphere(64, dx=1 / 64, radius=1.0)
    with pytest.raises(ValueError) as info:
        tack.pull_off(heights, dx=1 / 64, e_star=1.0, gamma=1e-3,
                      law=tack.Exponential(range=1e-9))
    message = str(info.value)
    assert "law=tack.JkrLimit()" in message and "jkr_limit" not in message, message
    with pytest.raises(ValueError) as info:
        tack.pull_off(heights, dx=1 / 64, e_star=1.0, gamma=1e-3, law=tack.Dugdale(sigma0=1e-7))
    message = str(info.value)
    assert "pull_off's step cap" in message and "tack.run" in message, message
    assert "protocol." not in message, message


def test_contact_errors_name_the_field():
    heights = tack.surface.sphere(16, dx=0.1, radius=1.0)
    with pytest.raises(ValueError, match="e_star"):
        tack.contact(heights, dx=0.1, e_star=0.0, approach=0.01)
    with pytest.raises(ValueError, match="approach = inf"):
        tack.contact(heights, dx=0.1, e_star=1.0, approach=float("inf"))
    with pytest.raises(ValueError, match="tolerance"):
        tack.contact(heights, dx=0.1, e_star=1.0, approach=0.01, tolerance=2.0)


def test_surface_errors_name_the_field():
    with pytest.raises(ValueError, match="hurst"):
        tack.surface.random(16, dx=0.1, rms=0.1, hurst=1.5)
    with pytest.raises(ValueError, match="rms"):
        tack.surface.random(16, dx=0.1, hurst=0.5)
    with pytest.raises(ValueError, match="radius"):
        tack.surface.sphere(16, dx=0.1, radius=-1.0)


def test_a_panic_becomes_internal_error():
    with pytest.raises(tack.InternalError, match="deliberate panic"):
        tack._tack._panic_for_tests()
