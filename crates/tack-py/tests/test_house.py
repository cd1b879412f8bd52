"""The Python face of the newer physics: Richardson on height arrays, the warning family, the
reference gamma of patterns (the same rule as scenes), overrides' messages, integer counts."""

import re
import warnings

import numpy as np
import pytest

import tack

SCENE_FIELDS = re.compile(r"material\.|adhesion\.|grid\.|protocol\.|solver\.|--set")
SPHERE = tack.surface.sphere(32, dx=0.45, radius=8.0)
PULL_OFF = dict(dx=0.45, e_star=1.0, gamma=0.125)


def test_richardson_on_a_sphere_array_extrapolates_towards_jkr():
    r = tack.pull_off(SPHERE, **PULL_OFF, richardson=True, snapshots="none")
    rich = r.richardson
    assert rich["fine"] == r.pull_off_force
    assert rich["extrapolated"] == 2 * rich["fine"] - rich["coarse"]
    assert rich["order"] == 1.0 and rich["error_estimate"] > 0
    # The criterion's first-order error: the extrapolated ratio lies closer to 1.
    assert abs(rich["ratio"] - 1) < abs(r.pull_off_ratio - 1)
    assert rich["ratio"] == pytest.approx(rich["extrapolated"] / r.summary["f_jkr"])
    assert tack.pull_off(SPHERE, **PULL_OFF, snapshots="none").richardson is None


def test_richardson_under_a_smooth_law_takes_its_second_order():
    # The peers' case (mu = 3) on 64^2: a smooth law converges at second order, so the
    # extrapolation is fine + (fine - coarse)/3, not the criterion's 2 fine - coarse.
    n, dx = 64, 1 / 64
    sphere = tack.surface.sphere(n, dx=dx, radius=1.0)
    # Its process zone spans 0.6 elements here: the run says so.
    with pytest.warns(tack.UnderResolvedWarning, match="process zone"):
        r = tack.pull_off(sphere, dx=dx, e_star=1.0, gamma=1e-3, radius=1.0,
                          law=tack.Exponential(range=3.3333e-3), richardson=True,
                          snapshots="none")
    rich = r.richardson
    assert rich["order"] == 2.0
    assert rich["extrapolated"] == rich["fine"] + (rich["fine"] - rich["coarse"]) / 3


def test_richardson_warns_when_the_roughness_aliases_and_refuses_what_cannot_hold():
    n, dx = 64, 1 / 64
    sphere = tack.surface.sphere(n, dx=dx, radius=1.0)
    q0, _ = tack.surface.band(n, dx=dx)
    common = dict(dx=dx, e_star=1.0, gamma=5e-4, radius=1.0, richardson=True, snapshots="none")
    limited = sphere + tack.surface.random(
        n, dx=dx, hurst=0.5, rms=2e-3, seed=2, q0=q0, q1=np.pi / (2 * dx)
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error", tack.RichardsonWarning)
        assert tack.pull_off(limited, **common).richardson["aliased_rms"] >= 0
    full = sphere + tack.surface.random(n, dx=dx, hurst=0.5, rms=2e-3, seed=2)
    with pytest.warns(tack.RichardsonWarning, match=r"coarse run samples another body"):
        tack.pull_off(full, **common)
    with pytest.raises(tack.TackError, match=r"^heights.shape\[0\] = 33 is invalid"):
        tack.pull_off(tack.surface.sphere((33, 32), dx=0.45, radius=8.0), **PULL_OFF,
                      richardson=True)
    with pytest.raises(tack.TackError, match="gamma is given as an array"):
        tack.pull_off(SPHERE, dx=0.45, e_star=1.0, gamma=np.full((32, 32), 0.125),
                      richardson=True)


def test_warnings_are_python_warnings_in_the_arguments_names():
    law = tack.Dugdale.from_lambda(5.0, radius=8.0, e_star=1.0, gamma=0.125)
    with pytest.warns(tack.UnderResolvedWarning) as record:
        r = tack.pull_off(SPHERE, **PULL_OFF, law=law, snapshots="none")
    [zone] = [w for w in record if "cohesive zone" in str(w.message)]
    message = str(zone.message)
    assert message.startswith("tack.pull_off: under-resolved cohesive zone")
    assert "refine dx or lower law.sigma0" in message, message
    assert not SCENE_FIELDS.search(message), message
    assert zone.filename == __file__
    # The summary keeps the sentences, in the same names.
    assert any(s in message for s in r.summary["warnings"])
    assert issubclass(tack.UnderResolvedWarning, tack.TackWarning)
    assert issubclass(tack.FullContactWarning, tack.TackWarning)
    assert issubclass(tack.TackWarning, UserWarning)
    assert issubclass(tack.EdgeContactWarning, RuntimeWarning)


def test_scene_runs_warn_in_the_scenes_names(small_sphere):
    with pytest.warns(tack.ConvergenceWarning, match=r"tack.run: incomplete: .*protocol.max_steps"):
        tack.run(small_sphere, overrides={"protocol.max_steps": 3})


def test_overrides_errors_name_the_dict_entry(small_sphere):
    with pytest.raises(tack.SceneError) as info:
        tack.run(small_sphere, overrides={"material.colour": 1})
    message = str(info.value)
    assert message.startswith('overrides["material.colour"] = 1: unknown field'), message
    assert "--set" not in message


def test_counts_are_integers():
    r = tack.pull_off(SPHERE, **PULL_OFF, snapshots="none")
    for key in ("non_converged_steps", "edge_contact_steps", "full_contact_steps"):
        assert type(r.summary[key]) is int, key
    state = tack.contact(SPHERE, dx=0.45, e_star=1.0, approach=0.5)
    assert type(state.n_contact) is int and type(state.iterations) is int


def test_the_reference_gamma_of_a_pattern_is_the_scenes():
    # One example through a scene and through pull_off: rings of gamma_b = 0.08 in a surface
    # of gamma = 0.02. The reference is the gamma given as a number (the scene's
    # material.gamma; pull_off's gamma_reference), so both give the same ratio; an array alone
    # is referred to its mean.
    n, dx, radius = 64, 0.05, 1.0
    sphere = tack.surface.sphere(n, dx=dx, radius=radius)
    rings = tack.surface.rings(n, dx=dx, gamma=0.02, gamma_b=0.08, period=4.0, fraction=0.2)
    common = dict(dx=dx, e_star=1.0, radius=radius, snapshots="none")
    explicit = tack.pull_off(sphere, gamma=rings, gamma_reference=0.02, **common)
    mean = tack.pull_off(sphere, gamma=rings, **common)
    scene = tack.run(
        explicit.scene,
        overrides={
            "geometry": {"shape": "sphere", "radius": radius},
            "adhesion": {"pattern": "rings", "gamma_b": 0.08, "period": 4.0, "fraction": 0.2},
            "output.surface": False,
        },
    )
    assert scene.summary["f_jkr"] == pytest.approx(explicit.summary["f_jkr"], rel=1e-12)
    assert scene.pull_off_ratio == pytest.approx(explicit.pull_off_ratio, rel=1e-6)
    assert mean.summary["f_jkr"] == pytest.approx(-1.5 * np.pi * rings.mean() * radius)
    with pytest.raises(tack.TackError, match="^gamma_reference is given with a uniform gamma"):
        tack.pull_off(sphere, gamma=0.02, gamma_reference=0.02, **common)
    with pytest.raises(tack.TackError, match="^gamma_reference = -1 is invalid"):
        tack.pull_off(sphere, gamma=rings, gamma_reference=-1.0, **common)


def test_a_loop_its_approach_does_not_resolve_warns(repo):
    # The exponential example's sphere at Tabor mu = 1 (range 0.01), loaded in steps of 1.07
    # ranges from out of reach: keeping every other approach step moves the loop 30 times over.
    coarse = {
        "adhesion.range": 0.01,
        "protocol.start": -0.1947,
        "protocol.max_approach": 0.03,
        "protocol.load_step": 0.0107,
        "protocol.coarse_unload_step": 0.002,
        "protocol.unload_step": 2e-4,
    }
    scene = repo / "data/examples/exponential_sphere.toml"
    with pytest.warns(tack.UnderResolvedWarning, match=r"tack.run: dissipated_energy: the loop"):
        r = tack.run(scene, overrides=coarse)
    assert any(w.startswith("dissipated_energy:") for w in r.summary["warnings"])
    # The uncertainty the warning names is recorded: 30 times the loop here.
    s = r.summary
    assert s["dissipated_energy_sampling"] > 10 * abs(s["dissipated_energy"]), s


def test_a_body_the_references_do_not_describe_warns_in_their_class(small_sphere):
    # A sphere on a periodic strip is a row of spheres: "no F_JKR reference" is a
    # ReferenceWarning, not a bare TackWarning.
    # (The strip also warns of full contact and of a pull-off on few elements.)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        tack.run(
            small_sphere,
            overrides={"grid": {"nx": 32, "ny": 1, "dx": 0.45, "boundary": "periodic"}},
        )
    [reference] = [w for w in record if "no F_JKR reference" in str(w.message)]
    assert type(reference.message) is tack.ReferenceWarning
    assert all(type(w.message) is not tack.TackWarning for w in record), record


def test_an_edge_below_a_one_step_load_is_an_edge_contact_warning(small_sphere, tmp_path):
    # A map roughness that dips one element of the outermost ring below the approach of a
    # one-step load.
    # The sphere's own height there is 3.24; the approach 1.0, from its vertex at 0.
    dip = np.zeros((32, 32))
    dip[0, 16] = 0.5 - SPHERE[0, 16]
    np.savetxt(tmp_path / "dip.txt", dip)
    overrides = {
        "roughness": {"kind": "file", "path": str(tmp_path / "dip.txt")},
        "protocol.start": 1.0,
        "protocol.max_approach": 1.0,
        "protocol.load_step": 1.0,
    }
    with pytest.warns(tack.EdgeContactWarning) as record:
        tack.run(small_sphere, overrides=overrides)
    [edge] = [w for w in record if "the one-step load to" in str(w.message)]
    assert type(edge.message) is tack.EdgeContactWarning


def test_an_array_without_a_radius_is_told_in_the_arguments_names():
    with pytest.raises(tack.SceneError) as info:
        tack.pull_off(np.zeros((32, 32)), **PULL_OFF)
    message = str(info.value)
    assert "a radius (radius=...) or a sphere-like height array" in message, message
    assert not SCENE_FIELDS.search(message) and "geometry." not in message, message
