"""robust_kmax over a box of loop parameters: equal to `hapstab kmax --robust --box --json`
bit for bit; the worst plant, rebuilt, has the robust K_max as its own K_max; refusals name
the keyword; the result pickles."""

import json
import pickle
import subprocess

import pytest

import hapstab as hs


def test_equals_the_command_line(hapstab_cli):
    lp = hs.Loop(hs.MassSpringDamper.from_device_and_arm(), velocity="lowpass:150")
    r = hs.robust_kmax(lp, {"arm-stiffness": (0.0, 2000.0), "arm-mass": (0.2, 2.0)},
                       wall_damping=5.0, verify=2000)
    out = subprocess.run([hapstab_cli, "kmax", "--robust", "--velocity", "lowpass:150",
                          "--box", "arm-stiffness:0:2000", "--box", "arm-mass:0.2:2",
                          "--wall-damping", "5", "--verify", "2000", "--json"],
                         capture_output=True, text=True, check=True)
    cli = json.loads(out.stdout)
    for key in ("k_max", "k_min", "k_max_nominal", "plants_evaluated", "plants_verified",
                "verification_found"):
        assert getattr(r, key) == cli[key], key
    assert r.worst_plant == [(p["param"], p["value"]) for p in cli["worst_plant"]]
    back = pickle.loads(pickle.dumps(r))
    assert (back.k_max, back.worst_plant) == (r.k_max, r.worst_plant)


def test_the_worst_plant_has_the_robust_k_max():
    lp = hs.Loop.paper()
    r = hs.robust_kmax(lp, {"arm-stiffness": (100.0, 1500.0), "arm-damping": (2.0, 10.0)},
                       wall_damping=20.0, verify=1000)
    worst = dict(r.worst_plant)
    held = hs.Loop.paper(arm_stiffness=worst["arm-stiffness"], arm_damping=worst["arm-damping"])
    assert hs.kmax(held, wall_damping=20.0).k_max == pytest.approx(r.k_max, rel=1e-12)
    assert r.k_max <= r.k_max_nominal


@pytest.mark.parametrize("bounds", [{"foo": (0.0, 1.0)}, {"mass": (2.0, 1.0)},
                                    {"mass": "x"}, {}])
def test_refusals_name_bounds(bounds):
    with pytest.raises(ValueError) as e:
        hs.robust_kmax(hs.Loop.paper(), bounds)
    assert str(e.value).startswith("bounds"), str(e.value)
