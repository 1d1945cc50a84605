"""stability_probability: P(stable) at a wall equals the fraction an independent referee
counts on the same drawn operators — python-control's sampled plant (c2d, ZOH) in feedback
with the wall K + B(1 − z⁻¹)/T and one sample of delay, its poles inside the unit circle — for
the same seed; the curve agrees with the wall counts; equal to `hapstab population --json`."""

import json
import subprocess

import control
import numpy as np
import pytest

import hapstab as hs

T, DEVICE_M, DEVICE_B = 1e-3, 0.1, 1.5


def referee_stable(m_h, b_h, k_h, k, b, d):
    """The closed loop's poles by python-control, independently of hapstab."""
    plant = control.tf([1.0], [DEVICE_M + m_h, DEVICE_B + b_h, k_h])
    h = control.sample_system(plant, T, method="zoh")
    z = control.tf([1.0, 0.0], [1.0], T)
    wall = k + b * (1 - 1 / z) / T
    loop = wall * h * (1 / z) ** d
    poles = control.poles(control.feedback(loop, 1))
    return bool(np.max(np.abs(poles)) < 1.0)


@pytest.mark.parametrize("k, b, d", [(2e4, 5.0, 0), (8e3, 2.0, 1)])
def test_wall_probability_equals_the_referee_count(k, b, d):
    lp = hs.Loop(hs.MassSpringDamper.from_device_and_arm(), period=T, delay=d * T)
    r = hs.stability_probability(lp, wall_stiffness=k, wall_damping=b, samples=400, seed=5)
    names = list(r.param_names)
    draws = np.asarray(r.draws)
    got = [referee_stable(row[names.index("arm-mass")], row[names.index("arm-damping")],
                          row[names.index("arm-stiffness")], k, b, d) for row in draws]
    assert list(r.verdicts) == got
    assert r.stable == sum(got) and r.probability == sum(got) / 400
    assert r.interval[0] <= r.probability <= r.interval[1]


def test_curve_agrees_with_the_wall_and_the_command_line(hapstab_cli):
    lp = hs.Loop(hs.MassSpringDamper.from_device_and_arm())
    c = hs.stability_probability(lp, wall_damping=5.0, samples=2000, seed=3)
    w = hs.stability_probability(lp, wall_stiffness=1.2e4, wall_damping=5.0, samples=2000, seed=3)
    iv = np.asarray(c.intervals)
    assert w.stable == int(np.sum((iv[:, 0] < 1.2e4) & (1.2e4 < iv[:, 1])))
    out = subprocess.run([hapstab_cli, "population", "--wall-damping", "5", "--samples", "2000",
                          "--seed", "3", "--json"], capture_output=True, text=True, check=True)
    cli = json.loads(out.stdout)
    assert list(c.probability) == cli["probability"]
    assert [lv[1] for lv in c.levels] == [lv["k"] for lv in cli["levels"]]
    q, k99 = c.levels[0][0], c.levels[0][1]
    assert q == 0.99 and c.levels[0][2] <= k99 <= c.levels[0][3]


@pytest.mark.parametrize("kwargs, keyword", [
    (dict(distributions={"foo": "uniform:0:1"}), "distributions"),
    (dict(distributions={"arm-mass": "uniform:2:1"}), "distributions"),
    (dict(levels=[1.5]), "levels"),
    (dict(samples=0), "samples"),
    (dict(wall_stiffness=float("nan")), "wall_stiffness"),
])
def test_refusals_name_the_keyword(kwargs, keyword):
    with pytest.raises(ValueError) as e:
        hs.stability_probability(hs.Loop.paper(), **kwargs)
    assert str(e.value).startswith(keyword), str(e.value)
