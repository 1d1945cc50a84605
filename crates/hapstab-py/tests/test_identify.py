"""identify: the plant from numpy arrays of a recording made by the independent simulator
(benches/baseline/identify_data.py): equal to `hapstab identify --json` bit for bit, the
simulator's parameters inside their 95 % intervals; bad data and arguments raise ValueError
naming the keyword; the result pickles."""

import json
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hapstab as hs

FIXTURES = Path(__file__).resolve().parents[2] / "hapstab" / "tests" / "fixtures" / "identify"


def recording(name):
    t, f, x = np.loadtxt(FIXTURES / f"{name}.csv", delimiter=",", skiprows=1).T
    return t, f, x


def test_equals_the_command_line_and_holds_the_truth(hapstab_cli):
    t, f, x = recording("held_prbs_40db")
    fixed = {"device-mass": 0.1, "device-damping": 1.5}
    r = hs.identify(t, f, x, fixed=fixed, draws=50)
    out = subprocess.run([hapstab_cli, "identify", "--data", str(FIXTURES / "held_prbs_40db.csv"),
                          "--fix", "device-mass=0.1", "--fix", "device-damping=1.5",
                          "--draws", "50", "--json"],
                         capture_output=True, text=True, check=True)
    cli = json.loads(out.stdout)
    assert r.model == cli["model"] == "held-device"
    assert list(r.values) == [p["value"] for p in cli["parameters"]]
    assert r.k_max == cli["stiffness_limit"]["k_max"]
    assert list(r.k_max_spread) == cli["stiffness_limit"]["spread"]
    assert list(r.k_max_box_range) == cli["stiffness_limit"]["box_range"]
    truth = {"arm-mass": 1.0, "arm-damping": 6.0, "arm-stiffness": 350.0}
    for name, v, lo, hi in zip(r.names, r.values, r.ci_low, r.ci_high):
        if name in truth:
            assert abs(v / truth[name] - 1) < 0.02 and lo <= truth[name] <= hi, name
    assert r.fixed == [True, True, False, False, False]
    assert hs.kmax(r.fitted_loop, wall_damping=0.0).k_max == pytest.approx(r.k_max, rel=1e-12)
    back = pickle.loads(pickle.dumps(r))
    assert list(back.values) == list(r.values) and repr(back) == repr(r)


def bad(match, *args, **kwargs):
    with pytest.raises(ValueError) as e:
        hs.identify(*args, **kwargs)
    assert str(e.value).startswith(match), str(e.value)


def test_bad_data_names_the_keyword():
    t, f, x = recording("msd_chirp_40db")
    t_bad = t.copy()
    t_bad[[10, 11]] = t_bad[[11, 10]]
    bad("t: column 't': not increasing", t_bad, f, x)
    x_bad = x.copy()
    x_bad[5] = np.nan
    bad("position: column 'position': sample 6 is NaN", t, f, x_bad)
    bad("force: column 'force': constant", t, np.ones_like(f), x)
    bad("t: data: 5 samples", t[:5], f[:5], x[:5])
    bad("fixed: parameter 'spring'", t, f, x, fixed={"spring": 1.0})
    bad("model: parameter 'model'", t, f, x, model="three-mass")
    rng = np.random.default_rng(1)
    bad("model: the model cannot fit", t, f, rng.normal(0, 1e-3, t.size))


def test_scipy_least_squares_on_the_same_problem_agrees(hapstab_cli):
    """benches/baseline/identify_least_squares.py: scipy's least_squares on the output-error
    problem built without hapstab gives the parameters of `hapstab identify` to 1e-6."""
    pytest.importorskip("scipy")
    script = Path(__file__).resolve().parents[3] / "benches" / "baseline" / "identify_least_squares.py"
    runs = [str(FIXTURES / f"{n}.csv") for n in ("msd_chirp_40db", "held_prbs_40db")]
    out = subprocess.run([sys.executable, str(script), "--hapstab", str(hapstab_cli), *runs],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "largest relative difference" in out.stdout


def test_the_delay_is_fitted():
    t, f, x = recording("msd_prbs_40db_delay2")
    r = hs.identify(t, f, x, fit_delay=True, draws=20)
    assert r.names[-1] == "delay-time"
    assert abs(r.values[-1] / 2e-3 - 1) < 0.02 and r.ci_low[-1] <= 2e-3 <= r.ci_high[-1]


def test_a_frequency_response_gives_the_command_line_s_tf(hapstab_cli):
    f, db, deg = np.loadtxt(FIXTURES / "tf3_freqresp_0.1db_1deg.csv", delimiter=",", skiprows=1).T
    h = 10 ** (db / 20) * np.exp(1j * np.radians(deg))
    r = hs.identify_frequency(f, h, period=1e-3, model="tf:0/3", draws=20)
    truth = dict(zip(["b0", "a0", "a1", "a2"], [2000.0, 20000.0, 4000.0, 60.0]))
    for name, v in zip(r.names, r.values):
        assert abs(v / truth[name] - 1) < 0.01, name
    out = subprocess.run([hapstab_cli, "identify", "--frequency-data",
                          str(FIXTURES / "tf3_freqresp_0.1db_1deg.csv"), "--model", "tf:0/3",
                          "--draws", "20", "--json"], capture_output=True, text=True, check=True)
    cli = json.loads(out.stdout)
    assert list(r.values) == pytest.approx([p["value"] for p in cli["parameters"]], rel=1e-9)
    with pytest.raises(ValueError) as e:
        hs.identify_frequency(f * 10, h, period=1e-3, model="tf:0/3")
    assert str(e.value).startswith("frequency_hz: row"), str(e.value)
