"""Loop files: a loop saved from Python loads in the command line and a loop the command line
echoes loads in Python, with identical answers; Python writes the same JSON the command line
echoes; malformed files are a ValueError naming the keyword and the field."""

import json
import subprocess

import pytest

import hapstab as hs

# (Python loop, the same loop as command-line flags, a wall (K, B))
CASES = [
    (hs.Loop.paper(), [], (3000.0, 2.0)),
    (
        hs.Loop(hs.MassSpringDamper(0.25, 2.0), period=5e-4, delay=1e-3),
        ["--mass", "0.25", "--damping", "2", "--period", "5e-4", "--delay-time", "1e-3"],
        (2000.0, 1.0),
    ),
    (
        hs.Loop(
            hs.TwoMass(0.3, 2300.0, handle_mass=0.1, arm_mass=2.0, arm_damping=3.0,
                       arm_stiffness=1200.0),
            period=0.002,
            velocity="lowpass:40",
        ),
        ["--motor-mass", "0.3", "--transmission-stiffness", "2300", "--handle-mass", "0.1",
         "--arm-mass", "2", "--arm-damping", "3", "--arm-stiffness", "1200",
         "--velocity", "lowpass:40", "--period", "0.002"],
        (5.0, 0.0),
    ),
    (
        hs.Loop(hs.TransferFunction([10.0], [1.0, 3.0, 10.0]), period=1e-3, delay=3.7e-4,
                velocity="iir:0.5,0,-0.5/1,-0.2", force_lag=4e-4),
        ["--plant-num", "10", "--plant-den", "1,3,10", "--delay-time", "3.7e-4",
         "--velocity", "iir:0.5,0,-0.5/1,-0.2", "--force-lag", "4e-4"],
        (20.0, 0.01),
    ),
]


def cli(exe, *args):
    done = subprocess.run([str(exe), *args, "--json"], check=True, capture_output=True,
                          text=True)
    return json.loads(done.stdout)


def same_check(py, k, b, out):
    c = hs.check(py, k, b)
    assert c.stable == out["stable"] and c.verdict == out["verdict"]
    assert c.spectral_radius == out["spectral_radius"]
    assert list(c.k_interval) == out["k_interval"]
    m = hs.margins(py, k, b)
    for key in ("gain_margin", "phase_margin_deg", "delay_margin", "stability_margin"):
        assert getattr(m, key) == out.get(key), key


@pytest.mark.parametrize("case", range(len(CASES)))
def test_python_writes_what_the_command_line_echoes(hapstab_cli, case):
    lp, flags, (k, b) = CASES[case]
    out = cli(hapstab_cli, "check", *flags, "--wall-stiffness", repr(k), "--wall-damping", repr(b))
    assert json.loads(lp.to_json(k, b)) == out["input"]


@pytest.mark.parametrize("case", range(len(CASES)))
def test_a_python_file_loads_in_the_command_line(hapstab_cli, tmp_path, case):
    lp, _, (k, b) = CASES[case]
    path = tmp_path / "loop.json"
    lp.save(path, k, b)
    out = cli(hapstab_cli, "check", "--loop", str(path))
    same_check(lp, k, b, out)


@pytest.mark.parametrize("case", range(len(CASES)))
def test_a_command_line_echo_loads_in_python(hapstab_cli, tmp_path, case):
    _, flags, (k, b) = CASES[case]
    out = cli(hapstab_cli, "check", *flags, "--wall-stiffness", repr(k), "--wall-damping", repr(b))
    path = tmp_path / "input.json"
    path.write_text(json.dumps(out["input"]))
    loaded = hs.Loop.load(path)
    assert hs.Loop.load_wall(path) == (k, b)
    same_check(loaded, k, b, out)
    # the whole report loads too, and text round-trips
    whole = tmp_path / "report.json"
    whole.write_text(json.dumps(out))
    assert repr(hs.Loop.load(whole)) == repr(loaded)
    assert repr(hs.Loop.from_json(loaded.to_json())) == repr(loaded)


def test_a_normalized_loop_round_trips(tmp_path):
    lp = hs.Loop.normalized(gamma=0.3, delta=0.1, d=2)
    path = tmp_path / "n.json"
    lp.save(path, 0.1, 0.05)
    back = hs.Loop.load(path)
    assert back.is_normalized and back.paper_view == lp.paper_view
    assert hs.Loop.load_wall(path) == (0.1, 0.05)


def test_malformed_files_name_the_keyword_and_the_field(tmp_path):
    with pytest.raises(ValueError, match="path"):
        hs.Loop.load(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"loop": {"period": "fast"}}')
    with pytest.raises(ValueError, match=r"loop\.period"):
        hs.Loop.load(bad)
    with pytest.raises(ValueError, match="perod"):
        hs.Loop.from_json('{"perod": 1}')
    with pytest.raises(ValueError, match="wall_damping"):
        hs.Loop.paper().to_json(1000.0)
