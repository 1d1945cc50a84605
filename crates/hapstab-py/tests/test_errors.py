"""Bad arguments raise ValueError whose message starts with the keyword argument's name."""

import numpy as np
import pytest

import hapstab as hs

LOOP = hs.Loop.paper()
MSD = hs.MassSpringDamper(1.0, 5.0, 100.0)

CASES = [
    ("period", lambda: hs.Loop.paper(period=0.0)),
    ("period", lambda: hs.Loop(MSD, period=float("nan"))),
    ("delay", lambda: hs.Loop(MSD, delay=-1e-3)),
    ("delay", lambda: hs.Loop(MSD, delay=10.0)),
    ("delay_samples", lambda: hs.Loop(MSD, delay_samples=5000)),
    ("delay, delay_samples", lambda: hs.Loop(MSD, delay=1e-3, delay_samples=1)),
    ("force_lag", lambda: hs.Loop(MSD, force_lag=-1e-3)),
    ("velocity", lambda: hs.Loop(MSD, velocity="forward")),
    ("velocity", lambda: hs.Loop(MSD, velocity="lowpass:0")),
    ("velocity", lambda: hs.Loop(MSD, velocity="average:0")),
    ("velocity", lambda: hs.Loop(MSD, velocity="iir:1,-1/0,1")),
    ("mass", lambda: hs.MassSpringDamper(0.0)),
    ("damping", lambda: hs.MassSpringDamper(1.0, -1.0)),
    ("stiffness", lambda: hs.MassSpringDamper(1.0, 0.0, float("inf"))),
    ("device_mass", lambda: hs.MassSpringDamper.from_device_and_arm(device_mass=-0.1)),
    ("arm_stiffness", lambda: hs.MassSpringDamper.from_device_and_arm(arm_stiffness=-1.0)),
    ("device_mass + arm_mass", lambda: hs.MassSpringDamper.from_device_and_arm(device_mass=0.0, arm_mass=0.0)),
    ("arm_damping", lambda: hs.Loop.paper(arm_damping=float("nan"))),
    ("motor_mass", lambda: hs.TwoMass(0.0, 1e4)),
    ("transmission_stiffness", lambda: hs.TwoMass(0.1, -1.0)),
    ("handle_mass", lambda: hs.TwoMass(0.1, 1e4, handle_mass=-0.1)),
    ("num", lambda: hs.TransferFunction([0.0], [1.0, 2.0])),
    ("num, den", lambda: hs.TransferFunction([1.0, 2.0], [1.0, 2.0])),
    ("den", lambda: hs.TransferFunction([1.0], [1.0] + [0.0] * 13)),
    ("den", lambda: hs.TransferFunction([1.0], [1.0, float("nan")])),
    ("gamma", lambda: hs.Loop.normalized(gamma=-1.0)),
    ("delta", lambda: hs.Loop.normalized(delta=float("nan"))),
    ("d", lambda: hs.Loop.normalized(d=2001)),
    ("wall_stiffness", lambda: hs.check(LOOP, float("nan"), 1.0)),
    ("wall_damping", lambda: hs.check(LOOP, 1.0, float("inf"))),
    ("wall_stiffness, wall_damping", lambda: hs.check(LOOP, 1.0)),
    ("alpha, beta", lambda: hs.check(LOOP, alpha=0.1)),
    ("wall_stiffness, wall_damping, alpha, beta", lambda: hs.check(LOOP, 1.0, 1.0, alpha=0.1, beta=0.1)),
    ("alpha, beta", lambda: hs.check(hs.Loop(hs.TwoMass(0.1, 1e4)), alpha=0.1, beta=0.1)),
    ("alpha", lambda: hs.check(LOOP, alpha=float("nan"), beta=0.1)),
    ("wall_damping", lambda: hs.kmax(LOOP, wall_damping=float("nan"))),
    ("damping_range", lambda: hs.kmax(LOOP, damping_range=(5.0, 1.0))),
    ("wall_damping, damping_range", lambda: hs.kmax(LOOP, wall_damping=1.0, damping_range=(0.0, 1.0))),
    ("wall_stiffness", lambda: hs.stability_map(LOOP, [1.0, np.nan], [1.0])),
    ("wall_damping", lambda: hs.stability_map(LOOP, [1.0], [np.inf])),
    ("wall_stiffness, wall_damping", lambda: hs.stability_map(LOOP, np.zeros((2, 3)), np.zeros((3, 2)))),
    ("wall_stiffness, wall_damping", lambda: hs.stability_map(LOOP, np.zeros(2), np.zeros((2, 2)))),
    ("wall_stiffness", lambda: hs.discretize(LOOP, float("nan"), 1.0)),
    ("coulomb_friction", lambda: hs.simulate(hs.Loop(hs.TransferFunction([1.0], [1.0, 5.0, 100.0])), 1e3, 1.0, coulomb_friction=0.5)),
    ("duration", lambda: hs.simulate(LOOP, 1e3, 1.0, duration=-1.0)),
    ("duration, samples", lambda: hs.simulate(LOOP, 1e3, 1.0, duration=1.0, samples=100)),
    ("samples", lambda: hs.simulate(LOOP, 1e3, 1.0, samples=1)),
    ("max_samples", lambda: hs.simulate(LOOP, 1e3, 1.0, samples=100, max_samples=10)),
    ("contact", lambda: hs.simulate(LOOP, 1e3, 1.0, contact="sticky")),
    ("quantization", lambda: hs.simulate(LOOP, 1e3, 1.0, quantization=0.0)),
    ("saturation", lambda: hs.simulate(LOOP, 1e3, 1.0, saturation=-1.0)),
    ("static_friction", lambda: hs.simulate(LOOP, 1e3, 1.0, coulomb_friction=1.0, static_friction=0.5)),
    ("coulomb_friction", lambda: hs.simulate(LOOP, 1e3, 1.0, coulomb_friction=-1.0)),
    ("wall_position", lambda: hs.simulate(LOOP, 1e3, 1.0, wall_position=float("nan"))),
    ("human_force", lambda: hs.simulate(LOOP, 1e3, 1.0, human_force=float("nan"))),
    ("human_force", lambda: hs.simulate(LOOP, 1e3, 1.0, human_force=[0.0, float("inf")])),
    ("human_force", lambda: hs.simulate(LOOP, 1e3, 1.0, human_force="push")),
    ("initial_position", lambda: hs.simulate(LOOP, 1e3, 1.0, initial_position=float("nan"))),
    ("trace_rows", lambda: hs.simulate(LOOP, 1e3, 1.0, trace_rows=1)),
]


@pytest.mark.parametrize("name, call", CASES, ids=[f"{i}-{n}" for i, (n, _) in enumerate(CASES)])
def test_bad_argument_names_the_parameter(name, call):
    with pytest.raises(ValueError) as e:
        call()
    msg = str(e.value)
    assert msg.startswith(name + ": "), msg
    assert "\n" not in msg


def test_a_wrong_plant_type_is_a_type_error():
    with pytest.raises(TypeError, match="plant"):
        hs.Loop("1/(s^2)")


def test_numerical_error_is_a_runtime_error():
    assert issubclass(hs.NumericalError, RuntimeError)


def test_a_mass_too_small_is_named():
    # the loop file's checks: the mass's range first, then δ = bT/m finite (Table I)
    with pytest.raises(ValueError, match=r"^plant.mass: mass m must be in \[1e-6, 1e6\] kg \(got 1e-310\)"):
        hs.Loop(hs.MassSpringDamper(1e-310, 1e6, 0.0), period=1e-3)


def api_keywords():
    """Every parameter name of the package's functions and methods, from its type stubs."""
    import ast
    from pathlib import Path

    stub = Path(hs.__file__).with_name("_hapstab.pyi")
    names = set()
    for node in ast.walk(ast.parse(stub.read_text())):
        if isinstance(node, ast.FunctionDef):
            a = node.args
            names.update(x.arg for x in a.posonlyargs + a.args + a.kwonlyargs)
    return names - {"self"}


def test_every_parameter_keyword_is_a_keyword_of_the_api():
    from hapstab import _hapstab

    keywords = api_keywords()
    table = _hapstab._parameter_keywords()
    assert len({key for key, _ in table}) == len(table)
    for key, kw in table:
        if kw is None:
            continue
        for part in kw.replace("+", ",").split(","):
            assert part.strip() in keywords, (key, kw)


def test_a_sweep_names_its_values():
    with pytest.raises(ValueError, match=r"^values: sampling period T must be > 0"):
        hs.sweep(LOOP, "period", [1e-3, 0.0])


def test_a_box_names_its_bounds():
    with pytest.raises(ValueError, match=r"^bounds: "):
        hs.robust_kmax(LOOP, {"arm-stiffness": (-10.0, 1.0)})
