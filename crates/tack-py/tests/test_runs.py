"""Scene runs, results, result files, pull-offs of height arrays, the non-adhesive solver."""

import math
import threading
import time

import numpy as np
import pytest

import tack


def test_hertz_against_the_closed_form():
    radius, d = 1.0, 0.01
    a = math.sqrt(radius * d)  # Hertz contact radius 0.1
    dx = a / 10
    heights = tack.surface.sphere(41, dx=dx, radius=radius)
    state = tack.contact(heights, dx=dx, e_star=1.0, approach=d)
    assert state.converged
    hertz = tack.analytics.hertz_force(e_star=1.0, radius=radius, d=d)
    assert state.force == pytest.approx(hertz, rel=0.01)
    assert abs(math.sqrt(state.area / math.pi) - a) < dx
    assert state.pressure.shape == heights.shape == state.gap.shape
    assert (state.pressure >= 0).all()
    # In contact the gap closes; elsewhere it is open.
    assert np.abs(state.gap[state.pressure > 0]).max() < 1e-6 * d
    assert (state.gap[state.pressure == 0] >= -1e-9 * d).all()


def test_contact_over_several_approaches_follows_hertz():
    dx = 0.01
    heights = tack.surface.sphere(41, dx=dx, radius=1.0)
    ds = [0.0025, 0.005, 0.01]
    states = tack.contact_sweep(heights, dx=dx, e_star=2.0, approaches=ds)
    assert [s.approach for s in states] == ds
    forces = np.array([s.force for s in states])
    expected = tack.analytics.hertz_force(e_star=2.0, radius=1.0, d=np.array(ds))
    np.testing.assert_allclose(forces, expected, rtol=0.03)


def test_contact_on_a_layer_tends_to_the_half_space_and_stiffens_as_it_thins():
    # Hertz contact, a ≈ 0.1 at d = 0.01 (R = 1): a film 100 a thick answers as the
    # half-space (its correction is of order a/h), a thinner bonded incompressible film is
    # stiffer (a rigid base under it), and a frictionless base is softer than a bonded one.
    dx = 0.01
    heights = tack.surface.sphere(41, dx=dx, radius=1.0)
    d = 0.01
    half = tack.contact(heights, dx=dx, e_star=1.0, approach=d).force
    def layer(h, nu, interface="bonded"):
        body = tack.Layer(thickness=h, poisson=nu, interface=interface)
        s = tack.contact(heights, dx=dx, e_star=1.0, approach=d, body=body)
        assert s.converged
        return s.force
    thick = layer(10.0, 0.5)
    assert half < thick < 1.02 * half
    assert layer(0.2, 0.5) > 1.2 * half
    assert layer(0.2, 0.3, "frictionless") < layer(0.2, 0.3, "bonded")


def test_contact_gives_the_same_bits_on_any_thread_count():
    # 128² periodic: large enough for the FFTs to run in lanes on 2 threads.
    dx = 1.0 / 128
    heights = tack.surface.random((128, 128), dx=dx, rms=1e-3, hurst=0.8, seed=4)
    runs = [
        tack.contact(heights, dx=dx, e_star=1.0, approach=-2e-3, periodic=True, threads=t)
        for t in (1, 2)
    ]
    assert runs[0].converged and 0 < runs[0].area < 1
    assert np.array_equal(runs[0].pressure, runs[1].pressure)
    assert runs[0].force == runs[1].force
    with pytest.raises(ValueError, match="threads = 0"):
        tack.contact(heights, dx=dx, e_star=1.0, approach=1e-3, periodic=True, threads=0)


def test_pull_off_gives_the_same_bits_on_any_thread_count():
    # The height-array pull-off runs through the library's run engine, which installs the pool
    # of `threads` (it used to ignore it); 192² periodic: its FFTs split into lanes.
    n = 192
    dx = 1.0 / n
    x = (np.arange(n) - n // 2) * dx
    heights = 0.01 * (1 - np.cos(2 * np.pi * x)[:, None] * np.cos(2 * np.pi * x)[None, :])
    runs = [
        tack.pull_off(
            heights,
            dx=dx,
            e_star=1.0,
            gamma=1e-4,
            periodic=True,
            max_approach=0.009,
            unload_step=0.001,
            coarse_unload_step=0.001,
            threads=t,
        )
        for t in (1, 2)
    ]
    assert len(runs[0]) == len(runs[1]) > 3
    assert np.array_equal(runs[0].curve["force"], runs[1].curve["force"])
    assert runs[0].pull_off_force == runs[1].pull_off_force < 0


def test_the_jkr_example_ratio(repo):
    result = tack.run(repo / "data/examples/smooth_jkr_sphere.toml")
    assert round(result.pull_off_ratio, 4) == 1.1343
    assert result.summary["pull_off_ratio"] == result.pull_off_ratio
    assert result.summary["status"] == "complete"
    assert result.summary["warnings"] == []
    assert result.pull_off_force == result.curve["force"].min()
    assert result.curve["force"][result.pull_off_step] == result.pull_off_force
    assert result.wall_time is not None and result.wall_time > 0
    # A path given as a str works too, and so do overrides.
    finer = tack.run(
        str(repo / "data/examples/smooth_jkr_sphere.toml"),
        overrides={"grid.n": 96, "grid.dx": 0.15, "output.snapshots": "none"},
    )
    assert finer.pull_off_ratio < result.pull_off_ratio
    assert finer.snapshots == {}
    assert 'snapshots = "none"' in finer.scene


def test_result_fields(small_sphere):
    result = tack.run(small_sphere, overrides={"output.snapshots": "pull_off"})
    curve = result.curve
    n = len(result)
    for name in ["approach", "force", "area", "mean_pressure"]:
        assert curve[name].dtype == np.float64 and curve[name].shape == (n,)
    for name in ["n_bonded", "n_clusters", "iterations", "active_set_iterations"]:
        assert curve[name].dtype == np.int64
    assert curve["converged"].dtype == np.bool_ and curve["converged"].all()
    assert curve["full_contact"].dtype == np.bool_
    summary = result.summary
    assert summary["f_jkr"] == pytest.approx(-1.5 * math.pi * 0.125 * 8.0)
    assert summary["johnson_alpha"] is None and summary["alpha_star"] is None
    assert summary["d_jkr"] == pytest.approx(
        tack.analytics.jkr_pull_off_approach(e_star=1.0, gamma=0.125, radius=8.0)
    )
    steps = list(result.snapshots)
    assert steps[0] == result.pull_off_step
    snap = result.snapshots[steps[0]]
    assert snap["pressure"].shape == snap["bonded"].shape == (32, 32)
    assert snap["bonded"].dtype == np.bool_
    assert snap["bonded"].sum() == curve["n_bonded"][steps[0]]
    assert snap["approach"] == curve["approach"][steps[0]]
    surface = result.surface
    np.testing.assert_array_equal(
        surface["heights"], tack.surface.sphere(32, dx=0.45, radius=8.0)
    )
    assert surface["dx"] == 0.45
    prov = result.provenance
    assert prov["tack_version"] == tack.__version__
    assert prov["seed"] is None and "version = 1" in prov["scene"]
    assert result.curve is result.curve  # built once
    assert "pull_off_ratio" in repr(result)


def test_write_read_round_trip(small_sphere, tmp_path):
    result = tack.run(
        small_sphere,
        overrides={"output.snapshots": {"every": 10}, "roughness.kind": "random",
                   "roughness.h": 0.01, "roughness.hurst": 0.7, "roughness.seed": 4},
    )
    out = tmp_path / "run.h5"
    result.write(out)
    back = tack.read(out)
    assert back.wall_time is None
    assert back.curve.keys() == result.curve.keys()
    for name, column in result.curve.items():
        np.testing.assert_array_equal(back.curve[name], column)
    assert back.summary.keys() == result.summary.keys()
    for name, value in result.summary.items():
        other = back.summary[name]
        assert other == value or (math.isnan(other) and math.isnan(value)), name
    assert back.snapshots.keys() == result.snapshots.keys()
    for step, snap in result.snapshots.items():
        np.testing.assert_array_equal(back.snapshots[step]["pressure"], snap["pressure"])
        np.testing.assert_array_equal(back.snapshots[step]["bonded"], snap["bonded"])
    np.testing.assert_array_equal(back.surface["heights"], result.surface["heights"])
    assert back.provenance == result.provenance
    assert back.provenance["seed"] == 4
    # The scene's random roughness is tack.surface.random with the same seed.
    expected = tack.surface.sphere(32, dx=0.45, radius=8.0) + tack.surface.random(
        32, dx=0.45, rms=0.01, hurst=0.7, seed=4
    )
    np.testing.assert_allclose(back.surface["heights"], expected, rtol=0, atol=1e-15)


def test_pull_off_of_a_sphere_given_as_an_array(tmp_path):
    dx, radius = 0.45, 8.0
    heights = tack.surface.sphere(32, dx=dx, radius=radius)
    result = tack.pull_off(heights, dx=dx, e_star=1.0, gamma=0.125)
    # The radius is fitted, so F_JKR applies; a_c/dx ≈ 7 overshoots by about 20%.
    assert result.summary["f_jkr"] == pytest.approx(-1.5 * math.pi * 0.125 * radius)
    assert 1.0 < result.pull_off_ratio < 1.4
    assert "(fitted)" in result.scene
    np.testing.assert_array_equal(result.surface["heights"], heights)
    assert len(result.snapshots) == 2
    result.write(tmp_path / "pull_off.h5")
    back = tack.read(tmp_path / "pull_off.h5")
    np.testing.assert_array_equal(back.surface["heights"], heights)
    assert back.scene == result.scene and back.pull_off_force == result.pull_off_force
    # The default path: one load step to 3 d_s, then retraction.
    d_s = tack.analytics.jkr_approach_scale(e_star=1.0, gamma=0.125, radius=radius)
    assert result.curve["approach"][0] == pytest.approx(3 * d_s)
    # Any array-like of numbers works (here float32 and a list of lists).
    again = tack.pull_off(heights.astype(np.float32).tolist(), dx=dx, e_star=1.0,
                          gamma=0.125, radius=radius, snapshots="none")
    assert again.snapshots == {}
    assert again.pull_off_ratio == pytest.approx(result.pull_off_ratio, rel=0.02)
    # The zero-range criterion adds no law column; the file keeps that too.
    assert result.law_columns == {} and back.law_columns == {}
    assert "n_cohesive" not in result.curve


def test_refined_retraction_finds_the_fine_pull_off_in_fewer_steps():
    dx = 0.25
    heights = tack.surface.sphere(64, dx=dx, radius=8.0) + tack.surface.random(
        64, dx=dx, rms=0.3, hurst=0.5, seed=2
    )
    common = dict(dx=dx, e_star=1.0, gamma=0.125, radius=8.0, unload_step=0.01, snapshots="none")
    fine = tack.pull_off(heights, **common, coarse_unload_step=0.01)
    refined = tack.pull_off(heights, **common, coarse_unload_step=0.1, refine_pull_off=True)
    assert refined.pull_off_force == pytest.approx(fine.pull_off_force, rel=2e-3)
    assert len(refined) < len(fine) / 2
    assert "refine_pull_off = true" in refined.scene


def test_pull_off_on_a_layer_runs_the_scene_body_and_tends_to_the_half_space():
    # The same sphere as above on a film 100 a_c thick (a_c ≈ 3.3): the pull-off of the
    # half-space within 2%, the layer in the summary, the half-space references flagged.
    dx, radius = 0.45, 8.0
    heights = tack.surface.sphere(32, dx=dx, radius=radius)
    half = tack.pull_off(heights, dx=dx, e_star=1.0, gamma=0.125, snapshots="none")
    with pytest.warns(tack.ReferenceWarning, match="half-space's: the layer of body.thickness"):
        film = tack.pull_off(heights, dx=dx, e_star=1.0, gamma=0.125, snapshots="none",
                             body=tack.Layer(thickness=330.0, poisson=0.5))
    assert film.summary["layer_thickness"] == 330.0
    assert film.summary["layer_poisson"] == 0.5
    assert "kind = \"layer\"" in film.scene
    assert any("half-space" in w for w in film.summary["warnings"])
    assert film.pull_off_force == pytest.approx(half.pull_off_force, rel=0.02)
    with pytest.raises(TypeError, match="poisson"):
        tack.Layer(thickness=1.0)
    with pytest.raises(tack.TackError, match="^thickness = -1 is invalid"):
        tack.Layer(thickness=-1.0, poisson=0.3)


def test_pull_off_of_a_rough_sphere_is_deterministic():
    n, radius = 64, 1.0
    dx = radius / n
    e_star, gamma = 1.0, 5e-4
    heights = tack.surface.sphere(n, dx=dx, radius=radius) + tack.surface.random(
        n, dx=dx, hurst=0.5, alpha_star=0.4, e_star=e_star, gamma=gamma, seed=2
    )
    a = tack.pull_off(heights, dx=dx, e_star=e_star, gamma=gamma, radius=radius)
    b = tack.pull_off(heights, dx=dx, e_star=e_star, gamma=gamma, radius=radius)
    np.testing.assert_array_equal(a.curve["force"], b.curve["force"])
    assert a.pull_off_force < 0 and a.curve["converged"].all()


def test_progress_callback_sees_steps_and_can_stop_the_run(repo):
    seen = []
    tack.run(repo / "data/examples/smooth_jkr_sphere.toml", progress=seen.append)
    assert seen and seen[-1]["step"] == 804
    assert set(seen[-1]) >= {"step", "phase", "approach", "force", "n_bonded"}

    class Stop(Exception):
        pass

    def stop(info):
        raise Stop(info["step"])

    with pytest.raises(Stop):
        tack.run(repo / "data/examples/smooth_jkr_sphere.toml",
                 overrides={"grid.n": 96, "grid.dx": 0.15}, progress=stop)


def test_the_gil_is_released_during_a_run(repo):
    done = threading.Event()
    ticks = 0

    def work():
        try:
            tack.run(repo / "data/examples/smooth_jkr_sphere.toml",
                     overrides={"grid.n": 96, "grid.dx": 0.15})
        finally:
            done.set()

    thread = threading.Thread(target=work)
    started = time.perf_counter()
    thread.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    thread.join()
    elapsed = time.perf_counter() - started
    # The main thread kept running Python while the solve ran.
    assert elapsed > 0.1 and ticks > 0.1 * elapsed / 0.0011, (ticks, elapsed)


def test_richardson(small_sphere):
    result = tack.run(small_sphere, richardson=True)
    extra = result.summary
    assert extra["pull_off_force_richardson"] == pytest.approx(
        2 * result.pull_off_force - extra["pull_off_force_coarse"]
    )


def test_richardson_on_band_limited_roughness(repo):
    scene = repo / "data/examples/sphere_random_roughness.toml"
    # The default band follows the grid (q1 = pi/dx): one surface per grid is impossible.
    with pytest.raises(ValueError, match="roughness.q1"):
        tack.run(scene, richardson=True)
    # dx = 0.25: the coarse grid's Nyquist wave is pi/(2 dx) = 2 pi.
    result = tack.run(scene, overrides={"roughness.q1": 6.28}, richardson=True)
    extra = result.summary
    change = abs(result.pull_off_force - extra["pull_off_force_coarse"])
    assert extra["pull_off_error_estimate"] >= change > 0


def test_a_stopped_run_says_so(repo):
    result = tack.run(
        repo / "data/examples/smooth_jkr_sphere.toml",
        overrides={"protocol.max_steps": 30},
    )
    assert result.summary["status"] == "stopped at protocol.max_steps"
    assert any("protocol.max_steps = 30" in w for w in result.summary["warnings"])


def test_dugdale_pull_off_of_a_sphere_matches_maugis_and_has_both_branches():
    # R = E* = gamma = 1 at Maugis lambda = 1 (sigma0 = 0.887): the zone l = 1.0 spans 10
    # elements of 0.1; the pull-off lies +7.5% beyond Maugis' -1.601 pi gamma R at this mesh
    # (docs/theory.md §3.7), so 15% bounds it.
    dx, n = 0.1, 69
    x = (np.arange(n) - n // 2) * dx
    heights = (x[:, None] ** 2 + x[None, :] ** 2) / 2.0
    sigma0 = 0.8871133596609792  # lambda = 2 sigma0 (R/(pi gamma K^2))^(1/3) = 1, K = 4/3
    r = tack.pull_off(
        heights, dx=dx, e_star=1.0, gamma=1.0, radius=1.0, law=tack.Dugdale(sigma0=sigma0)
    )
    s = r.summary
    assert s["adhesion_model"] == "dugdale"
    assert abs(s["maugis_lambda"] - 1.0) < 1e-9
    assert abs(s["f_maugis"] / (-1.6007349 * np.pi) - 1) < 1e-6
    assert 1.0 < r.pull_off_force / s["f_maugis"] < 1.15
    # Both branches: the approach starts out of range and jumps in with tension.
    assert r.curve["force"][0] == 0 and s["jump_in_force"] < 0 and s["dissipated_energy"] > 0
    assert "n_cohesive" in r.curve and "cohesive zone" in r.law_columns["n_cohesive"]


def test_smoothed_dugdale_pull_off_is_closer_to_maugis_on_the_same_mesh():
    # The same sphere and mesh as above (lambda = 1, zone of 10 elements of 0.1): the smoothed
    # law's pull-off lies +0.67% beyond Maugis' (docs/theory.md section 3.7, steps dx/16; the
    # default path's steps here), against the Dugdale law's +7.5%; 2% bounds it.
    dx, n = 0.1, 69
    x = (np.arange(n) - n // 2) * dx
    heights = (x[:, None] ** 2 + x[None, :] ** 2) / 2.0
    law = tack.SmoothedDugdale(sigma0=0.8871133596609792)
    assert isinstance(law, tack.Dugdale) and law != tack.Dugdale(sigma0=law.sigma0)
    r = tack.pull_off(heights, dx=dx, e_star=1.0, gamma=1.0, radius=1.0, law=law)
    s = r.summary
    assert s["adhesion_model"] == "smoothed_dugdale"
    assert abs(s["maugis_lambda"] - 1.0) < 1e-9
    assert 1.0 < r.pull_off_force / s["f_maugis"] < 1.02
    assert s["jump_in_force"] < 0 and s["dissipated_energy"] > 0
    with pytest.raises(ValueError, match="^sigma0 = 0 is invalid"):
        tack.SmoothedDugdale(sigma0=0.0)


def test_dugdale_arguments_are_checked():
    heights = np.zeros((8, 8))
    with pytest.raises(TypeError, match="^law: expected"):
        tack.pull_off(heights, dx=0.1, e_star=1.0, gamma=1.0, max_approach=0.1,
                      unload_step=0.01, law="dugdale")
    with pytest.raises(ValueError, match="^sigma0 = -1 is invalid"):
        tack.Dugdale(sigma0=-1.0)
    with pytest.raises(TypeError, match="sigma0"):
        tack.Dugdale()
    # The old flat keywords are gone (unpublished 0.1.0): law= and body= take objects.
    with pytest.raises(TypeError, match="model"):
        tack.pull_off(heights, dx=0.1, e_star=1.0, gamma=1.0, max_approach=0.1,
                      unload_step=0.01, model="dugdale")


def test_exponential_pull_off_lies_between_jkr_and_dmt():
    # Sphere R = 1, E* = 1, gamma = 1 at Tabor mu = 1 (range rho = 1): the pull-off lies between
    # JKR (1.5 pi gamma R) and DMT (2 pi gamma R); at mu = 1 the axisymmetric reference of
    # crates/tack-solver/tests gives about 1.7 pi gamma R. The process zone (8/3 pi) rho^2 = 0.85
    # spans 3.4 elements at dx = 0.25.
    law = tack.Exponential.from_tabor(1.0, radius=1.0, e_star=1.0, gamma=1.0)
    assert abs(law.range - 1.0) < 1e-12 and repr(law) == "tack.Exponential(range=1.0)"
    assert abs(law.tabor(radius=1.0, e_star=1.0, gamma=1.0) - 1.0) < 1e-12
    dx = 0.25
    x = (np.arange(48) - 23.5) * dx
    heights = (x[:, None] ** 2 + x[None, :] ** 2) / 2.0
    r = tack.pull_off(heights, dx=dx, e_star=1.0, gamma=1.0, radius=1.0, law=law)
    s = r.summary
    assert s["adhesion_model"] == "exponential"
    assert abs(s["tabor_mu"] - 1.0) < 1e-9 and s["range"] == 1.0
    assert abs(s["peak_tension"] - 1.0) < 1e-12
    hat = r.pull_off_force / (-np.pi)
    assert 1.5 < hat < 2.0, hat
    assert all(r.curve["converged"])
    # The law's column: its process zone, said so beside it.
    assert "process zone" in r.law_columns["n_cohesive"]
    assert r.curve["n_cohesive"].max() > 0


def test_smooth_law_arguments_are_checked():
    with pytest.raises(ValueError, match="^range = -1 is invalid"):
        tack.Exponential(range=-1.0)
    with pytest.raises(ValueError, match="^range = NaN is invalid"):
        tack.LennardJones(range=float("nan"))
    with pytest.raises(TypeError, match="range"):
        tack.Exponential()
    with pytest.raises(ValueError, match="^mu = 0 is invalid"):
        tack.LennardJones.from_tabor(0.0, radius=1.0, e_star=1.0, gamma=1.0)
    assert tack.LennardJones(range=0.5) != tack.Exponential(range=0.5)
    heights = np.zeros((8, 8))
    # A smooth law needs gamma > 0: the error names the argument.
    with pytest.raises(ValueError, match="gamma"):
        tack.pull_off(heights, dx=0.1, e_star=1.0, gamma=0.0, max_approach=0.1,
                      unload_step=0.01, law=tack.Exponential(range=0.1))


def test_pull_off_runs_a_viscoelastic_solid_given_as_a_material():
    # The study's sphere (R = 1, gamma = 1e-3, exponential law rho = 0.01, E0 = 1, one arm
    # E1 = 9, tau = 1) on a coarse grid, loaded slowly: a slow retraction stays near the
    # elastic E0 pull-off, a fast one is stronger (docs/theory.md section 3.10).
    dx = 1.2 / 32
    heights = tack.surface.sphere((32, 32), dx=dx, radius=1.0)
    law = tack.Exponential(range=0.01)
    path = dict(max_approach=0.02, load_step=0.002, unload_step=0.001)

    def pull(unload_speed=None):
        material = None
        if unload_speed is not None:
            material = tack.Viscoelastic([(9.0, 1.0)], speed=1e-4, unload_speed=unload_speed)
        return tack.pull_off(heights, dx=dx, e_star=1.0, gamma=1e-3, law=law,
                             material=material, snapshots="none", **path)

    elastic, slow, fast = pull(), pull(1e-4), pull(1.0)
    assert "time" not in elastic.curve
    time = slow.curve["time"]
    assert time[0] == 0.0 and np.all(np.diff(time) > 0.0)
    assert slow.summary["e_instantaneous"] == 10.0
    assert slow.summary["speed"] == 1e-4 and fast.summary["unload_speed"] == 1.0
    # Measured at 96² (README): 1.20 slow, 3.54 fast, elastic 1.11.
    assert abs(slow.pull_off_ratio / elastic.pull_off_ratio - 1.0) < 0.2
    assert fast.pull_off_ratio > 2.0 * slow.pull_off_ratio > 0.0
    v = tack.Viscoelastic([(9.0, 1.0)], speed=1e-4, dwell=2.0, dwell_steps=4)
    assert eval(repr(v)) == v and v.prony == ((9.0, 1.0),)
    held = tack.pull_off(heights, dx=dx, e_star=1.0, gamma=1e-3, law=law, material=v,
                         snapshots="none", **path)
    # The hold: four steps of half a tau at the deepest approach, after the load's last.
    approach = held.curve["approach"]
    times = held.curve["time"][approach == approach.max()]
    assert len(times) == 5 and np.allclose(np.diff(times), 0.5)


def test_viscoelastic_pull_off_names_its_bad_input():
    dx = 1.2 / 16
    heights = tack.surface.sphere((16, 16), dx=dx, radius=1.0)
    solid = tack.Viscoelastic([(9.0, 1.0)], speed=1e-3)
    base = dict(dx=dx, e_star=1.0, gamma=1e-3, law=tack.Exponential(range=0.01),
                max_approach=0.02, load_step=0.002)
    with pytest.raises(TypeError, match=r"^material: expected None"):
        tack.pull_off(heights, material="pdms", **base)
    with pytest.raises(TypeError, match=r"^prony: expected a non-empty sequence"):
        tack.Viscoelastic(9.0, speed=1.0)
    with pytest.raises(TypeError, match=r"^prony\[0\]: expected a pair"):
        tack.Viscoelastic([(9.0, 1.0, 2.0)], speed=1.0)
    with pytest.raises(tack.TackError, match=r"^prony\[0\]\[0\] = -1 is invalid"):
        tack.Viscoelastic([(-1.0, 1.0)], speed=1.0)
    with pytest.raises(tack.TackError, match=r"^prony\[1\]\[1\] = 0 is invalid"):
        tack.Viscoelastic([(1.0, 1.0), (1.0, 0.0)], speed=1.0)
    with pytest.raises(tack.TackError, match=r"^prony = \[\] is invalid"):
        tack.Viscoelastic([], speed=1.0)
    with pytest.raises(tack.TackError, match=r"^speed = 0 is invalid"):
        tack.Viscoelastic([(1.0, 1.0)], speed=0.0)
    with pytest.raises(tack.TackError, match=r"^dwell = -1 is invalid"):
        tack.Viscoelastic([(1.0, 1.0)], speed=1.0, dwell=-1.0)
    with pytest.raises(TypeError, match=r"^speed: expected"):
        tack.Viscoelastic([(1.0, 1.0)], speed="fast")
    # The scene's checks, named by the arguments.
    with pytest.raises(tack.TackError, match=r"load_step"):
        tack.pull_off(heights, **{**base, "load_step": None}, material=solid)
    with pytest.raises(tack.TackError, match=r"^material.prony with adhesion needs a "
                                             r"finite-range law"):
        tack.pull_off(heights, **{**base, "law": tack.JkrLimit()}, material=solid)
    with pytest.raises(tack.TackError, match=r"^refine_pull_off retraces steps"):
        tack.pull_off(heights, **base, material=solid, refine_pull_off=True,
                      unload_step=0.001, coarse_unload_step=0.004)
    with pytest.raises(tack.TackError, match=r"material.dwell_steps"):
        tack.pull_off(heights, **base,
                      material=tack.Viscoelastic([(9.0, 1.0)], speed=1.0, dwell_steps=3))


def test_a_viscoelastic_scene_records_time_and_names_its_bad_input(repo):
    # The standard linear solid of data/examples/viscoelastic_sphere.toml: each step lasts
    # 0.1 tau, the hold one tau in ten steps; the arms' dissipation at the front doubles the
    # pull-off of both elastic limits (docs/theory.md section 3.10).
    scene = repo / "data/examples/viscoelastic_sphere.toml"
    result = tack.run(scene)
    time = result.curve["time"]
    assert time.dtype == np.float64 and time.shape == (len(result),)
    assert time[0] == 0.0 and np.allclose(np.diff(time), 0.1)
    assert result.summary["e_instantaneous"] == 10.0
    assert 2.0 < result.pull_off_ratio < 3.2
    # An elastic scene has no time column.
    assert "time" not in tack.run(repo / "data/examples/smooth_jkr_sphere.toml").curve
    with pytest.raises(tack.SceneError, match=r"^material.prony = -1 is invalid"):
        tack.run(scene, overrides={"material.prony": [[-1.0, 1.0]]})
    with pytest.raises(tack.SceneError, match=r"^protocol.speed = -1 is invalid"):
        tack.run(scene, overrides={"protocol.speed": -1.0})
