"""Arguments are checked as a Python user expects: a wrong type raises TypeError naming the
argument and the type it expects, a bad value TackError (a ValueError) naming the argument,
never a scene field (`material.gamma`, `grid.nx`) or a Rust path (`tack_solver::...`)."""

import math
import os
import re

import numpy as np
import pytest

import tack
from tack import analytics

SPHERE = tack.surface.sphere(32, dx=0.45, radius=8.0)
PULL_OFF = dict(dx=0.45, e_star=1.0, gamma=0.125)
CONTACT = dict(dx=0.1, e_star=1.0, approach=0.01)
SMALL = tack.surface.sphere(16, dx=0.1, radius=1.0)

# Values of the wrong type for a numeric argument, even where float() would convert them.
NOT_NUMBERS = ["0.1", b"0.1", True, np.True_, 1 + 0j, np.complex128(1.0), [0.1], object()]

# What no message about a Python argument may contain.
SCENE_OR_RUST = re.compile(r"material\.|grid\.|protocol\.|solver\.|output\.|roughness\.|::")


def assert_names(info, argument):
    """The message starts with the argument's name and carries no scene field or Rust path."""
    message = str(info.value)
    assert re.match(rf"{re.escape(argument)}(\[[0-9, ]+\])?[ :=]", message), message
    assert not SCENE_OR_RUST.search(message), message


# --- wrong types -----------------------------------------------------------------------------


@pytest.mark.parametrize("value", NOT_NUMBERS, ids=repr)
@pytest.mark.parametrize(
    "argument",
    ["dx", "e_star", "gamma", "radius", "max_approach", "unload_step", "coarse_unload_step"],
)
def test_pull_off_numbers_refuse_other_types(argument, value):
    with pytest.raises(TypeError) as info:
        tack.pull_off(SPHERE, **{**PULL_OFF, argument: value})
    assert_names(info, argument)
    assert "expected a real number" in str(info.value)


@pytest.mark.parametrize("argument", ["dx", "e_star", "gamma"])
def test_required_numbers_refuse_none(argument):
    with pytest.raises(TypeError) as info:
        tack.pull_off(SPHERE, **{**PULL_OFF, argument: None})
    assert_names(info, argument)


@pytest.mark.parametrize("value", NOT_NUMBERS + [None], ids=repr)
@pytest.mark.parametrize("argument", ["dx", "e_star", "tolerance"])
def test_contact_numbers_refuse_other_types(argument, value):
    if argument == "tolerance" and value is None:
        return  # None is the default
    with pytest.raises(TypeError) as info:
        tack.contact(SMALL, **{**CONTACT, argument: value})
    assert_names(info, argument)


@pytest.mark.parametrize("value", ["0.5", True, 1j, [0.5]], ids=repr)
@pytest.mark.parametrize("argument", ["thickness", "poisson"])
def test_layer_numbers_refuse_other_types(argument, value):
    with pytest.raises(TypeError) as info:
        tack.Layer(**{"thickness": 0.5, "poisson": 0.3, argument: value})
    assert_names(info, argument)


@pytest.mark.parametrize("value", ["0.5", True, 1j, [0.5]], ids=repr)
def test_law_numbers_refuse_other_types(value):
    with pytest.raises(TypeError) as info:
        tack.JkrLimit(kappa=value)
    assert_names(info, "kappa")
    with pytest.raises(TypeError) as info:
        tack.Dugdale(sigma0=value)
    assert_names(info, "sigma0")


def test_laws_and_bodies_check_values_and_show_themselves():
    with pytest.raises(ValueError, match=r"^sigma0 = -1 is invalid: must be a finite number > 0"):
        tack.Dugdale(sigma0=-1.0)
    with pytest.raises(ValueError, match=r"^kappa = 0 is invalid"):
        tack.JkrLimit(kappa=0)
    with pytest.raises(ValueError, match=r"^poisson = 0.6 is invalid: must be a number in \(-1, 0.5\]"):
        tack.Layer(thickness=1.0, poisson=0.6)
    with pytest.raises(ValueError, match=r"^thickness = 0 is invalid"):
        tack.Layer(thickness=0.0, poisson=0.3)
    with pytest.raises(ValueError, match=r"^interface = 'glued' is invalid"):
        tack.Layer(thickness=1.0, poisson=0.3, interface="glued")
    with pytest.raises(ValueError, match=r"^lam = -2 is invalid"):
        tack.Dugdale.from_lambda(-2.0, radius=1.0, e_star=1.0, gamma=0.1)
    assert repr(tack.Dugdale(sigma0=0.5)) == "tack.Dugdale(sigma0=0.5)"
    assert repr(tack.JkrLimit()) == "tack.JkrLimit(kappa=None)"
    assert repr(tack.HalfSpace()) == "tack.HalfSpace()"
    layer = tack.Layer(thickness=2, poisson=0.4)
    assert repr(layer) == "tack.Layer(thickness=2.0, poisson=0.4, interface='bonded')"
    assert layer == tack.Layer(thickness=2.0, poisson=0.4, interface="bonded")
    with pytest.raises(AttributeError):
        layer.thickness = 3.0
    with pytest.raises(TypeError, match=r"^law: expected tack.JkrLimit"):
        tack.pull_off(SPHERE, **PULL_OFF, law="dugdale")
    with pytest.raises(TypeError, match=r"^body: expected tack.HalfSpace"):
        tack.contact(SMALL, **CONTACT, body=tack.Dugdale(sigma0=1.0))


# Tabor's relation (R gamma^2 / (E*^2 l^3))^(1/3) = R^(1/3) (gamma/E*)^(2/3) / l, read either
# way: arguments whose powers leave the floats (gamma^2, mu^3) while the result does not.
TABOR_IN_RANGE = [
    (1e-300, dict(radius=1.0, e_star=1.0, gamma=1e-3)),  # mu^3 underflows: range 1e298
    (1.0, dict(radius=1.0, e_star=1e200, gamma=1.0)),  # e_star^2 overflows: range 4.6e-134
    (1.0, dict(radius=1.0, e_star=1.0, gamma=1e-200)),  # gamma^2 underflows: range 4.6e-134
    (1e200, dict(radius=1e250, e_star=1e-100, gamma=1e150)),  # range 1e100
    (0.37, dict(radius=2.0, e_star=3.0, gamma=0.5)),
]


def tabor_log(length, radius, e_star, gamma):
    return (math.log(radius) + 2 * math.log(gamma) - 2 * math.log(e_star)) / 3 - math.log(length)


@pytest.mark.parametrize("law", [tack.Exponential, tack.LennardJones])
@pytest.mark.parametrize("mu, sphere", TABOR_IN_RANGE)
def test_tabor_relation_holds_wherever_its_result_is_a_float(law, mu, sphere):
    made = law.from_tabor(mu, **sphere)
    assert math.isclose(math.log(made.range), tabor_log(mu, **sphere), abs_tol=1e-13)
    assert math.isclose(made.tabor(**sphere), mu, rel_tol=1e-14)


@pytest.mark.parametrize("law", [tack.Exponential, tack.LennardJones])
def test_tabor_of_a_range_whose_cube_underflows(law):
    assert math.isclose(law(range=1e-120).tabor(radius=1.0, e_star=1.0, gamma=1e-3), 1e118,
                        rel_tol=1e-14)
    assert law.from_tabor(1.0, radius=1.0, e_star=1.0, gamma=1.0) == law(range=1.0)


@pytest.mark.parametrize(
    "call, named",
    [
        # range about 1e800 and 1e-800; named in the order of their share.
        (lambda: tack.Exponential.from_tabor(1e-300, radius=1e300, e_star=1e-300, gamma=1e300),
         "mu = 1e-300, gamma = 1e+300, e_star = 1e-300 and radius = 1e+300 put the range "),
        (lambda: tack.LennardJones.from_tabor(1e300, radius=1e-300, e_star=1e300, gamma=1e-300),
         "mu = 1e+300, gamma = 1e-300, e_star = 1e+300 and radius = 1e-300 put the range "),
        # range about 1e-333: below the normal floats; mu = 1 is not to blame.
        (lambda: tack.Exponential.from_tabor(1.0, radius=1e-200, e_star=1e200, gamma=1e-200),
         "gamma = 1e-200, e_star = 1e+200 and radius = 1e-200 put the range "),
        (lambda: tack.Exponential.from_tabor(5e-324, radius=1.0, e_star=1.0, gamma=1.0),
         "mu = 5e-324 puts the range "),
        # Tabor's mu about 1e323 and 1e-600.
        (lambda: tack.LennardJones(range=5e-324).tabor(radius=1.0, e_star=1.0, gamma=1.0),
         "this law's range = 5e-324 puts Tabor's mu "),
        (lambda: tack.Exponential(range=1e300).tabor(radius=1e-300, e_star=1e300, gamma=1.0),
         "this law's range = 1e+300, e_star = 1e+300 and radius = 1e-300 put Tabor's mu "),
    ],
)
def test_tabor_results_beyond_the_floats_name_the_arguments(call, named):
    with pytest.raises(ValueError) as info:
        call()
    message = str(info.value)
    assert isinstance(info.value, tack.TackError)
    assert message.startswith(named + "beyond what a float holds"), message
    assert re.search(r"would be about 1e[+-]\d+, (above|below) the (largest|least normal) float",
                     message), message


def test_contact_interface_refuses_other_types():
    with pytest.raises(TypeError) as info:
        tack.Layer(thickness=0.5, poisson=0.3, interface=1)
    assert_names(info, "interface")


@pytest.mark.parametrize("value", ["0.01", b"0.01", None, True, 1j, ["0.01"], [0.01, 1j],
                                   [True, False], [0.01, None]], ids=repr)
def test_contact_approach_refuses_other_types(value):
    with pytest.raises(TypeError) as info:
        tack.contact(SMALL, **{**CONTACT, "approach": value})
    assert_names(info, "approach")


def test_numpy_scalars_and_ints_are_numbers():
    a = tack.contact(SMALL, dx=np.float64(0.1), e_star=np.int64(1), approach=np.float64(0.01),
                     tolerance=np.float64(1e-8), max_iterations=np.int32(100))
    b = tack.contact(SMALL, dx=0.1, e_star=1, approach=0.01, tolerance=1e-8,
                     max_iterations=100)
    assert tack.contact(SMALL, dx=np.float32(0.1), e_star=1.0, approach=0.01).converged
    assert isinstance(a, tack.ContactResult) and a.force == b.force
    # A 0-d array is a number; a 1-D array of approaches is a sequence.
    assert isinstance(tack.contact(SMALL, dx=0.1, e_star=1, approach=np.array(0.01)),
                      tack.ContactResult)
    sweep = tack.contact_sweep(SMALL, dx=0.1, e_star=1, approaches=np.array([0.005, 0.01]))
    assert len(sweep) == 2 and all(isinstance(s, tack.ContactResult) for s in sweep)
    assert isinstance(sweep[0].n_contact, int)
    # One return type each: a sequence is not an approach, one approach is still a sweep.
    with pytest.raises(TypeError, match=r"^approach: .*tack.contact_sweep"):
        tack.contact(SMALL, dx=0.1, e_star=1, approach=[0.005, 0.01])
    assert len(tack.contact_sweep(SMALL, dx=0.1, e_star=1, approaches=[0.01])) == 1
    # Integer heights are heights.
    flat = tack.contact(np.zeros((8, 8), dtype=np.int32), dx=0.1, e_star=1, approach=0.01)
    assert flat.n_contact == 64


@pytest.mark.parametrize("value", [10.0, "10", None, True], ids=repr)
def test_integers_refuse_other_types(value):
    if value is not None:
        with pytest.raises(TypeError) as info:
            tack.contact(SMALL, **CONTACT, max_iterations=value)
        assert_names(info, "max_iterations")
        assert "expected an int" in str(info.value)
    with pytest.raises(TypeError) as info:
        tack.surface.random(16, dx=0.1, rms=0.1, hurst=0.5, seed=value)
    assert_names(info, "seed")
    with pytest.raises(TypeError) as info:
        tack.surface.sphere((16, value), dx=0.1, radius=1.0)
    assert_names(info, "shape[1]")


@pytest.mark.parametrize("value", ["no", 1, 0, None, 1.0], ids=repr)
def test_flags_refuse_other_types(value):
    with pytest.raises(TypeError, match="^periodic: expected a bool"):
        tack.contact(SMALL, **CONTACT, periodic=value)
    with pytest.raises(TypeError, match="^periodic: expected a bool"):
        tack.pull_off(SPHERE, **PULL_OFF, periodic=value)
    with pytest.raises(TypeError, match="^refine_pull_off: expected a bool"):
        tack.pull_off(SPHERE, **PULL_OFF, refine_pull_off=value)
    with pytest.raises(TypeError, match="^richardson: expected a bool"):
        tack.run("no/such/scene.toml", richardson=value)
    # numpy bools are bools.
    assert not tack.contact(SMALL, **CONTACT, periodic=np.False_).full_contact


@pytest.mark.parametrize("value", ["16", 16.0, None, (16,), (16, 16, 1), (16.0, 16)], ids=repr)
def test_surface_shape(value):
    with pytest.raises((TypeError, ValueError)) as info:
        tack.surface.sphere(value, dx=0.1, radius=1.0)
    assert_names(info, "shape")


@pytest.mark.parametrize(
    "call, argument",
    [
        (lambda v: tack.surface.random(16, dx=v, rms=0.1, hurst=0.5), "dx"),
        (lambda v: tack.surface.random(16, dx=0.1, rms=v, hurst=0.5), "rms"),
        (lambda v: tack.surface.random(16, dx=0.1, rms=0.1, hurst=v), "hurst"),
        (lambda v: tack.surface.random(16, dx=0.1, rms=0.1, hurst=0.5, q0=v), "q0"),
        (lambda v: tack.surface.random(16, dx=0.1, rms=0.1, hurst=0.5, q1=v), "q1"),
        (lambda v: tack.surface.random(16, dx=0.1, hurst=0.5, alpha_star=v, e_star=1.0,
                                       gamma=1e-4), "alpha_star"),
        (lambda v: tack.surface.random(16, dx=0.1, hurst=0.5, alpha_star=0.3, e_star=v,
                                       gamma=1e-4), "e_star"),
        (lambda v: tack.surface.random(16, dx=0.1, hurst=0.5, alpha_star=0.3, e_star=1.0,
                                       gamma=v), "gamma"),
        (lambda v: tack.surface.sphere(16, dx=v, radius=1.0), "dx"),
        (lambda v: tack.surface.sphere(16, dx=0.1, radius=v), "radius"),
        (lambda v: tack.surface.power_law(16, dx=0.1, c=v, exponent=1.0), "c"),
        (lambda v: tack.surface.power_law(16, dx=0.1, c=0.5, exponent=v), "exponent"),
        (lambda v: tack.surface.coordinates(16, dx=v), "dx"),
        (lambda v: tack.surface.band(16, dx=v), "dx"),
    ],
)
@pytest.mark.parametrize("value", ["0.5", 0.5j, True], ids=repr)
def test_surface_numbers_refuse_other_types(call, argument, value):
    with pytest.raises(TypeError) as info:
        call(value)
    assert_names(info, argument)


CLOSED_FORMS = [
    ("hertz_force", (1.0, 1.0, 0.01)),
    ("hertz_contact_radius", (1.0, 0.01)),
    ("hertz_max_pressure", (1.0, 1.0, 0.01)),
    ("jkr_pull_off_force", (0.1, 1.0)),
    ("jkr_pull_off_approach", (1.0, 0.1, 1.0)),
    ("jkr_pull_off_radius", (1.0, 0.1, 1.0)),
    ("jkr_approach_scale", (1.0, 0.1, 1.0)),
    ("jkr_force_from_radius", (1.0, 0.1, 1.0, 0.5)),
    ("jkr_approach_from_radius", (1.0, 0.1, 1.0, 0.5)),
    ("jkr_force_from_approach", (1.0, 0.1, 1.0, 0.01)),
    ("kendall_pull_off", (1.0, 0.1, 0.5)),
    ("power_law_pull_off_force", (1.0, 0.1, 0.5, 1.0)),
    ("johnson_alpha", (1.0, 0.1, 0.01, 1.0)),
    ("westergaard_p_star", (1.0, 0.01, 1.0)),
    ("johnson_2d_p_star", (1.0, 0.01, 1.0)),
    ("lambda_fit", (0.3,)),
    ("alpha_star", (1.0, 1e-4, 0.002, 0.5, 6.28, 400.0)),
    ("rms_height_from_alpha_star", (1.0, 1e-4, 0.3, 0.5, 6.28, 400.0)),
    ("lambda_star", (0.3,)),
    ("critical_stress", (1.0, 0.1, 0.01, 0.47)),
    ("maugis_lambda", (1.0, 0.1, 1.0, 0.5)),
    ("maugis_pull_off_force", (1.0, 0.1, 1.0, 0.5)),
    ("maugis_dissipated_energy", (1.0, 0.1, 1.0, 2.0)),
    ("maugis_force_from_approach", (1.0, 0.1, 1.0, 0.5, 0.05)),
    ("maugis_jump_out_approach", (1.0, 0.1, 1.0, 0.5)),
    ("maugis_jump_out_force", (1.0, 0.1, 1.0, 0.5)),
    ("maugis_jump_in_approach", (1.0, 0.1, 1.0, 0.5)),
    ("maugis_jump_in_force", (1.0, 0.1, 1.0, 0.5)),
    ("maugis_sigma0", (0.5, 1.0, 0.1, 1.0)),
]


def closed_form_arguments():
    for name, args in CLOSED_FORMS:
        params = list(analytics.__dict__[name].__code__.co_varnames[: len(args)])
        for k, argument in enumerate(params):
            yield pytest.param(name, args, k, argument, id=f"{name}-{argument}")


def keywords(name, args, k=None, value=None):
    """The closed form's keyword arguments: ``args`` by name, the k-th replaced by ``value``."""
    params = analytics.__dict__[name].__code__.co_varnames[: len(args)]
    out = dict(zip(params, args))
    if k is not None:
        out[params[k]] = value
    return out


@pytest.mark.parametrize("name, args, k, argument", list(closed_form_arguments()))
def test_closed_forms_check_every_argument(name, args, k, argument):
    f = getattr(analytics, name)
    assert isinstance(f(**keywords(name, args)), float)
    assert isinstance(f(**keywords(name, args, k, np.array([args[k]] * 3))), np.ndarray)
    for wrong in ["1", None, True, 1j, np.array(["1"]), np.array([1j]), np.array([True]),
                  np.array([1.0, None])]:
        with pytest.raises(TypeError) as info:
            f(**keywords(name, args, k, wrong))
        assert_names(info, argument)
    bad = -1.0 if argument not in ("d", "hurst") else float("nan")
    with pytest.raises(ValueError) as info:
        f(**keywords(name, args, k, bad))
    assert_names(info, argument)
    with pytest.raises(ValueError) as info:
        f(**keywords(name, args, k, np.array([args[k], bad])))
    assert_names(info, argument)
    assert str(info.value).startswith(f"{argument}[1] = ")


@pytest.mark.parametrize("name", [n for n, _ in CLOSED_FORMS])
def test_closed_forms_are_keyword_only(name):
    # jkr_pull_off_radius(R, E, g) once returned another formula's number without a word.
    args = dict(CLOSED_FORMS)[name]
    with pytest.raises(TypeError, match="positional"):
        getattr(analytics, name)(*args)


def test_closed_forms_value_rules():
    with pytest.raises(ValueError, match=r"^radius\[1\] = -1 is invalid: must be a finite"):
        analytics.hertz_force(e_star=1.0, radius=[1.0, -1.0], d=0.01)
    with pytest.raises(ValueError, match=r"^q1 = 10 is invalid: must be > q0 = 100"):
        analytics.alpha_star(e_star=1.0, gamma=1e-4, h=0.002, hurst=0.5, q0=100.0, q1=10.0)
    with pytest.raises(ValueError, match=r"^alpha_star = 0 is invalid"):
        analytics.rms_height_from_alpha_star(
            e_star=1.0, gamma=1e-4, alpha_star=0.0, hurst=0.5, q0=6.28, q1=400.0
        )
    with pytest.raises(ValueError, match=r"^hertz_force: the arguments' shapes do not broadcast"):
        analytics.hertz_force(e_star=1.0, radius=[1.0, 2.0], d=[0.01, 0.02, 0.03])
    # Broadcasting and empty arrays work as in numpy.
    assert analytics.hertz_force(e_star=1.0, radius=[[1.0], [2.0]], d=[0.01, 0.02, 0.03]).shape == (2, 3)
    assert analytics.hertz_force(e_star=1.0, radius=1.0, d=np.array([])).shape == (0,)
    assert analytics.lambda_star(alpha_star=0) == pytest.approx(
        1.023 * np.exp(-((0.3619 / 0.1188) ** 2))
    )


def test_paths_refuse_other_types(small_sphere, tmp_path):
    result = tack.run(small_sphere, overrides={"protocol.max_steps": 3})
    for wrong in [3, None, b"out.h5", ["out.h5"]]:
        with pytest.raises(TypeError, match=r"^path: expected a path \(str or os.PathLike\)"):
            result.write(wrong)
        with pytest.raises(TypeError, match=r"^path: expected a path \(str or os.PathLike\)"):
            tack.read(wrong)
    for wrong in [3, None, b"scene.toml"]:
        with pytest.raises(TypeError, match=r"^scene: expected a path"):
            tack.run(wrong)
    # str and os.PathLike work.
    result.write(str(tmp_path / "a.h5"))
    result.write(tmp_path / "b.h5")
    assert len(tack.read(os.fspath(tmp_path / "a.h5"))) == len(tack.read(tmp_path / "b.h5"))


@pytest.mark.parametrize("value", [1j, np.complex128(1.0), None, object()], ids=repr)
def test_overrides_refuse_values_without_a_toml_form(small_sphere, value):
    with pytest.raises(TypeError, match=r"^overrides\['material.gamma'\]: a value of type"):
        tack.run(small_sphere, overrides={"material.gamma": value})


def test_other_argument_types(small_sphere):
    with pytest.raises(TypeError, match="^overrides: expected a dict"):
        tack.run(small_sphere, overrides=[("grid.n", 16)])
    with pytest.raises(TypeError, match="^progress: expected True/False or a callable"):
        tack.run(small_sphere, progress=1)
    with pytest.raises(TypeError, match="^snapshots: expected"):
        tack.pull_off(SPHERE, **PULL_OFF, snapshots=True)
    with pytest.raises(TypeError, match=r"^snapshots\[0\]: expected an int"):
        tack.pull_off(SPHERE, **PULL_OFF, snapshots=[1.5])


# --- arrays ----------------------------------------------------------------------------------


def solve(kind, heights):
    if kind == "pull_off":
        return tack.pull_off(heights, **PULL_OFF)
    return tack.contact(heights, **CONTACT)


@pytest.mark.parametrize("kind", ["pull_off", "contact"])
@pytest.mark.parametrize(
    "heights, dtype_words",
    [
        (np.array([["1", "2"], ["3", "4"]]), "strings"),
        ([[1.0, None], [2.0, 3.0]], "Python objects"),
        (np.ones((4, 4), dtype=complex), "complex numbers"),
        (np.ones((4, 4), dtype=bool), "booleans"),
        (np.array([[b"1"]]), "bytes"),
    ],
    ids=["str", "object", "complex", "bool", "bytes"],
)
def test_arrays_of_non_numbers_are_type_errors(kind, heights, dtype_words):
    with pytest.raises(TypeError) as info:
        solve(kind, heights)
    assert_names(info, "heights")
    assert f"an array of {dtype_words}" in str(info.value)


@pytest.mark.parametrize("kind", ["pull_off", "contact"])
def test_array_shapes_name_the_argument(kind):
    for wrong in [np.zeros(5), np.zeros((2, 2, 2)), np.array(1.0)]:
        with pytest.raises(ValueError, match="^heights: expected a 2-D array") as info:
            solve(kind, wrong)
        assert_names(info, "heights")
    for wrong in ["heights", None, 1.0]:
        with pytest.raises(TypeError) as info:
            solve(kind, wrong)
        assert_names(info, "heights")
    with pytest.raises(ValueError, match=r"^heights: cannot be read as an array"):
        solve(kind, [[1.0, 2.0], [3.0]])


@pytest.mark.parametrize("kind", ["pull_off", "contact"])
@pytest.mark.parametrize("shape", [(0, 5), (5, 0), (0, 0)])
def test_empty_arrays_name_the_argument(kind, shape):
    with pytest.raises(ValueError) as info:
        solve(kind, np.zeros(shape))
    assert str(info.value).startswith(
        f"heights: the array is empty ({shape[0]} × {shape[1]})"
    )
    assert_names(info, "heights")


@pytest.mark.parametrize("kind", ["pull_off", "contact"])
def test_non_finite_heights_are_named_by_index(kind):
    heights = np.zeros((6, 7))
    heights[3, 4] = np.inf
    with pytest.raises(ValueError, match=r"^heights\[3, 4\] = inf is invalid: must be a finite"):
        solve(kind, heights)


def test_approach_sequences():
    sweep = lambda v: tack.contact_sweep(SMALL, dx=0.1, e_star=1.0, approaches=v)
    with pytest.raises(ValueError, match="^approaches: the sequence is empty"):
        sweep([])
    with pytest.raises(ValueError, match=r"^approaches: expected a number or a 1-D sequence"):
        sweep([[0.01]])
    with pytest.raises(ValueError, match=r"^approaches\[1\] = inf is invalid"):
        sweep([0.01, float("inf")])
    with pytest.raises(ValueError, match=r"^approach = NaN is invalid"):
        tack.contact(SMALL, dx=0.1, e_star=1.0, approach=float("nan"))
    with pytest.raises(TypeError, match=r"^approaches: expected a 1-D sequence.*tack.contact\("):
        sweep(0.01)
    states = sweep((0.005, np.float32(0.01)))
    assert [s.approach for s in states] == [0.005, float(np.float32(0.01))]


# --- bad values ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "changes, message",
    [
        ({"gamma": -0.1}, "gamma = -0.1 is invalid: must be a finite number > 0 (a pull-off "
                          "needs adhesion; for contact without it use tack.contact)"),
        ({"gamma": 0}, "gamma = 0 is invalid"),
        ({"e_star": -1.0}, "e_star = -1 is invalid: must be a finite number > 0"),
        ({"dx": float("nan")}, "dx = NaN is invalid"),
        ({"radius": -8.0}, "radius = -8 is invalid"),
        ({"unload_step": 0.0}, "unload_step = 0 is invalid"),
        ({"coarse_unload_step": float("inf")}, "coarse_unload_step = inf is invalid"),
        ({"max_approach": float("-inf")}, "max_approach = -inf is invalid"),
        # Found by the library, not the argument checks: its scene fields are renamed.
        ({"max_approach": -1.0}, "max_approach = -1 never touches the surface"),
        ({"snapshots": 0}, "snapshots = 0 is invalid"),
        ({"snapshots": "some"}, "snapshots = 'some' is invalid"),
        ({"snapshots": [3, -1]}, "snapshots[1] = -1 is invalid"),
    ],
)
def test_pull_off_values_name_the_argument(changes, message):
    with pytest.raises(tack.TackError) as info:
        tack.pull_off(SPHERE, **{**PULL_OFF, **changes})
    assert str(info.value).startswith(message), str(info.value)
    assert_names(info, next(iter(changes)))


@pytest.mark.parametrize(
    "changes, message",
    [
        ({"e_star": 0.0}, "e_star = 0 is invalid"),
        ({"dx": -0.1}, "dx = -0.1 is invalid"),
        ({"tolerance": 2.0}, "tolerance = 2 is invalid: must be a number in (0, 1)"),
        ({"max_iterations": 0}, "max_iterations = 0 is invalid: must be an integer ≥ 1"),
        ({"approach": float("inf")}, "approach = inf is invalid"),
    ],
)
def test_contact_values_name_the_argument(changes, message):
    with pytest.raises(tack.TackError) as info:
        tack.contact(SMALL, **{**CONTACT, **changes})
    assert str(info.value).startswith(message), str(info.value)
    assert_names(info, next(iter(changes)))


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: tack.surface.sphere(0, dx=0.1, radius=1.0), "shape = 0 is invalid"),
        (lambda: tack.surface.sphere((4, -1), dx=0.1, radius=1.0), "shape = (4, -1) is invalid"),
        (lambda: tack.surface.sphere(4, dx=0.0, radius=1.0), "dx = 0 is invalid"),
        (lambda: tack.surface.sphere(4, dx=0.1, radius=-1), "radius = -1 is invalid"),
        (lambda: tack.surface.random(16, dx=0.1, rms=0.1, hurst=1.5), "hurst = 1.5 is invalid"),
        (lambda: tack.surface.random(16, dx=0.1, rms=-0.1, hurst=0.5), "rms = -0.1 is invalid"),
        (lambda: tack.surface.random(16, dx=0.1, rms=0.1, hurst=0.5, seed=-1),
         "seed = -1 is invalid"),
        # The band check is the generator's; its fields are renamed.
        (lambda: tack.surface.random(16, dx=0.1, rms=0.1, hurst=0.5, q0=1000.0, q1=2000.0),
         "q0/q1 = [1000, 2000] is invalid"),
        (lambda: tack.surface.random(16, dx=0.1, hurst=0.5, alpha_star=-0.3, e_star=1.0,
                                     gamma=1e-4), "alpha_star = -0.3 is invalid"),
    ],
)
def test_surface_values_name_the_argument(call, message):
    with pytest.raises(tack.TackError) as info:
        call()
    assert str(info.value).startswith(message), str(info.value)
    assert not SCENE_OR_RUST.search(str(info.value))


def test_the_compiled_core_renames_library_fields():
    """Below the argument checks, the bindings map the library's messages to the arguments
    (for whatever the checks let through); the compiled functions are called directly here."""
    core = tack._tack
    cases = [
        (lambda: core.pull_off(SPHERE, dx=0.45, e_star=-1.0, gamma=0.1), "e_star = -1 "),
        (lambda: core.pull_off(SPHERE, dx=0.0, e_star=1.0, gamma=0.1), "dx = 0 "),
        (lambda: core.pull_off(SPHERE, dx=0.45, e_star=1.0, gamma=0.1, kappa=-1.0),
         "law.kappa = -1 "),
        (lambda: core.pull_off(np.zeros((0, 4)), dx=0.45, e_star=1.0, gamma=0.1),
         "heights.shape[0] = 0 "),
        (lambda: core.contact(SMALL, dx=-0.1, e_star=1.0, approaches=[0.01]), "dx = -0.1 "),
        (lambda: core.contact(SMALL, dx=0.1, e_star=0.0, approaches=[0.01]), "e_star = 0 "),
        (lambda: core.contact(np.zeros((4, 0)), dx=0.1, e_star=1.0, approaches=[0.01]),
         "heights.shape[1] = 0 "),
        (lambda: core.contact(SMALL, dx=0.1, e_star=1.0, approaches=[0.01], tolerance=2.0),
         "tolerance = 2 "),
        (lambda: core.rough(16, 16, dx=0.1, rms=-1.0, hurst=0.5), "rms = -1 "),
        (lambda: core.rough(16, 16, dx=0.1, rms=1.0, hurst=1.5), "hurst = 1.5 "),
        (lambda: core.sphere(0, 4, dx=0.1, radius=1.0), "shape[0] = 0 "),
        (lambda: core.sphere(4, 4, dx=0.1, radius=-1.0), "radius = -1 "),
    ]
    for call, message in cases:
        with pytest.raises(tack.TackError) as info:
            call()
        assert str(info.value).startswith(message), str(info.value)
        assert not SCENE_OR_RUST.search(str(info.value)), str(info.value)
    with pytest.raises(tack.TackError) as info:
        core.pull_off(SPHERE, dx=0.45, e_star=1.0, gamma=-0.1)
    assert "tack.contact" in str(info.value) and "tack_solver" not in str(info.value)


def test_scene_runs_keep_the_scene_fields(small_sphere):
    # In a scene the user wrote the fields, so they are the names to report.
    with pytest.raises(tack.SceneError, match=r"^material.gamma = -0.5 is invalid"):
        tack.run(small_sphere, overrides={"material.gamma": -0.5})


# --- threads ---------------------------------------------------------------------------------


def run_threads(kind, small_sphere, threads):
    if kind == "run":
        return tack.run(small_sphere, threads=threads)
    if kind == "pull_off":
        return tack.pull_off(SPHERE, **PULL_OFF, threads=threads)
    return tack.contact(SMALL, **CONTACT, threads=threads)


@pytest.mark.parametrize("kind", ["run", "pull_off", "contact"])
def test_threads_are_checked_the_same_everywhere(kind, small_sphere):
    for wrong in [2.5, 2.0, "2", True, np.True_, 1j, [2]]:
        with pytest.raises(TypeError) as info:
            run_threads(kind, small_sphere, wrong)
        assert str(info.value).startswith("threads: expected an int (or None for every core)")
    for bad in [0, -1, tack.MAX_THREADS + 1, 2**70]:
        with pytest.raises(tack.TackError) as info:
            run_threads(kind, small_sphere, bad)
        assert str(info.value) == (
            f"threads = {bad} is invalid: must be an integer from 1 to {tack.MAX_THREADS}"
        )
    assert run_threads(kind, small_sphere, np.int64(1)) is not None
    assert run_threads(kind, small_sphere, None) is not None


def test_maugis_sigma0_beyond_the_floats_names_the_material():
    # E* = 1e200: K^2 overflows, so lambda per unit sigma0 is 0 (a ZeroDivisionError before).
    with pytest.raises(ValueError, match=r"^e_star = 1e\+?200, gamma = 1 and radius = 1 put"):
        tack.analytics.maugis_sigma0(lam=1.0, e_star=1e200, gamma=1.0, radius=1.0)
    with pytest.raises(ValueError, match="beyond the floats"):
        tack.Dugdale.from_lambda(1.0, radius=1.0, e_star=1e200, gamma=1.0)
    # Ordinary materials are unchanged.
    sigma0 = tack.analytics.maugis_sigma0(lam=1.0, e_star=1.0, gamma=1.0, radius=1.0)
    assert abs(tack.analytics.maugis_lambda(e_star=1.0, gamma=1.0, radius=1.0, sigma0=sigma0) - 1.0) < 1e-12
