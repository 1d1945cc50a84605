"""The parity matrix: for each kind of loop, every analysis from the command line (`--json`),
from Python and from the explorer's API (`hapstab serve`) gives the same numbers — bit for bit
where the three compute the same thing. The analyses defined only for the paper's normalized
loop, or only for physical loops, are refused by the front ends that do not offer them."""

import json
import math
import re
import subprocess
import urllib.parse
import urllib.request

import numpy as np
import pytest

import hapstab as hs

ARM = {"arm_mass": "1", "arm_damping": "6", "arm_stiffness": "350"}


def tf_order_5():
    """A two-mass-like transfer function of order 5: the paper's device and arm behind a
    lightly damped 80 Hz mode and a 0.5 ms lag (descending coefficients)."""
    w = 2 * math.pi * 80
    den = np.polymul(np.polymul([1.1, 7.5, 350.0], [1.0, 2 * 0.05 * w, w * w]), [5e-4, 1.0])
    return [w * w], [float(c) for c in den]


NUM5, DEN5 = tf_order_5()


def csv(c):
    return ",".join(repr(x) for x in c)


# name, Python loop, command-line flags, explorer query, normalized
LOOPS = [
    (
        "paper physical",
        hs.Loop.paper(delay=1e-3),
        ["--delay", "1"],
        dict(mode="physical", device_mass="0.1", device_damping="1.5", period="0.001", d="1", **ARM),
        False,
    ),
    (
        "paper normalized",
        hs.Loop.normalized(gamma=0.001, delta=0.015, d=1),
        ["--gamma", "0.001", "--delta", "0.015", "--delay", "1"],
        dict(mode="normalized", gamma="0.001", delta="0.015", d="1"),
        True,
    ),
    (
        "device without arm",
        hs.Loop(hs.MassSpringDamper(0.25, 2.0), period=5e-4),
        ["--mass", "0.25", "--damping", "2", "--period", "5e-4"],
        dict(mode="physical", device_mass="0.25", device_damping="2", arm_mass="0",
             arm_damping="0", arm_stiffness="0", period="0.0005", d="0"),
        False,
    ),
    (
        "two-mass, low-pass",
        hs.Loop(hs.TwoMass(0.3, 2300.0, handle_mass=0.1), period=0.002, velocity="lowpass:40"),
        ["--motor-mass", "0.3", "--transmission-stiffness", "2300", "--handle-mass", "0.1",
         "--velocity", "lowpass:40", "--period", "0.002"],
        dict(mode="physical", motor_mass="0.3", transmission_stiffness="2300", handle_mass="0.1",
             estimator="lowpass:40", period="0.002", d="0", **ARM),
        False,
    ),
    (
        "order 5, lag, fractional delay, iir",
        hs.Loop(hs.TransferFunction(NUM5, DEN5), period=1e-3, delay=3.7e-4, force_lag=2e-4,
                velocity="iir:0.5,0,-0.5/1,-0.2"),
        ["--plant-num", csv(NUM5), "--plant-den", csv(DEN5), "--delay-time", "3.7e-4",
         "--force-lag", "2e-4", "--velocity", "iir:0.5,0,-0.5/1,-0.2"],
        dict(mode="physical", plant_num=csv(NUM5), plant_den=csv(DEN5), delay_time="0.00037",
             force_lag="0.0002", estimator="iir:0.5,0,-0.5/1,-0.2", period="0.001"),
        False,
    ),
    (
        "paper device, average, fractional delay",
        hs.Loop(hs.MassSpringDamper.from_device_and_arm(), period=1e-3, delay=3.7e-4,
                velocity="average:3"),
        ["--delay-time", "3.7e-4", "--velocity", "average:3"],
        dict(mode="physical", device_mass="0.1", device_damping="1.5", period="0.001",
             delay_time="0.00037", estimator="average:3", **ARM),
        False,
    ),
]
IDS = [c[0] for c in LOOPS]


@pytest.fixture(scope="module")
def server(hapstab_cli):
    """`hapstab serve` on a free port; its base URL."""
    proc = subprocess.Popen([str(hapstab_cli), "serve", "--port", "0"], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    line = proc.stdout.readline()
    m = re.search(r"http://[0-9.:]+/", line)
    assert m, line
    yield m.group(0)
    proc.terminate()
    proc.wait(timeout=10)


def api(base, path, query):
    with urllib.request.urlopen(base + path + "?" + urllib.parse.urlencode(query)) as r:
        return json.load(r)


def cli(exe, *args):
    done = subprocess.run([str(exe), *args, "--json"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def refused(exe, *args):
    done = subprocess.run([str(exe), *args], capture_output=True, text=True)
    assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1, done.stderr
    return done.stderr


def wall_of(lp, normalized):
    """A stable wall: 40 % of K_max at a damping inside the region."""
    b = 0.05 if normalized else 2.0
    k = hs.kmax(lp, wall_damping=b).k_max
    assert k is not None and k > 0
    return 0.4 * k, b


def wall_flags(normalized, k, b):
    if normalized:
        return ["--alpha", repr(k), "--beta", repr(b)]
    return ["--wall-stiffness", repr(k), "--wall-damping", repr(b)]


def nan_or(x):
    return float("nan") if x is None else x


def same(got, want, what):
    if want is None or (isinstance(want, float) and math.isnan(want)):
        assert got is None or math.isnan(got), (what, got, want)
    else:
        assert got == want, (what, got, want)


@pytest.mark.parametrize("case", range(len(LOOPS)), ids=IDS)
def test_check_margins_and_passivity(hapstab_cli, server, case):
    name, lp, flags, query, normalized = LOOPS[case]
    k, b = wall_of(lp, normalized)
    out = cli(hapstab_cli, "check", *flags, *wall_flags(normalized, k, b))
    c = hs.check(lp, k, b)
    m = hs.margins(lp, k, b)
    wall_q = {"alpha": repr(k), "beta": repr(b)} if normalized else {
        "wall_stiffness": repr(k), "wall_damping": repr(b)}
    p = api(server, "api/point", {**query, **wall_q})
    assert c.verdict == out["verdict"] == p["verdict"] == "stable", name
    assert c.spectral_radius == out["spectral_radius"] == p["spectral_radius"], name
    for key in ("gain_margin", "gain_margin_lower", "stiffness_margin", "phase_margin_deg",
                "gain_crossover_hz", "delay_margin", "delay_margin_pm_over_wc",
                "stability_margin", "peak_gain"):
        same(getattr(m, key), out[key], (name, key))
        assert p["margins"][key] == out[key], (name, key)
    ps = hs.passivity(lp, k, b)
    pc = cli(hapstab_cli, "passivity", *flags, *wall_flags(normalized, k, b))
    assert ps.b_required == pc["b_required"] == p["passivity"]["requirement"]["b_required"], name
    assert ps.verdict == pc["verdict"] == p["passivity"]["verdict"], name
    assert ps.device_damping == pc["device_damping"], name


@pytest.mark.parametrize("case", range(len(LOOPS)), ids=IDS)
def test_region_and_kmax(hapstab_cli, server, case):
    name, lp, flags, query, normalized = LOOPS[case]
    r = hs.region(lp)
    bo = cli(hapstab_cli, "boundary", *flags)
    ex = api(server, "api/region", query)["region"]
    if normalized:
        view = r.normalized
        assert ex["alpha_max"] == view["alpha_max"], name
        assert (view["alpha_max"], view["area"]) == (bo["alpha_max"], bo["area"]), name
        refused(hapstab_cli, "kmax", *flags)
        return
    assert (r.k_max, r.b_at_k_max, r.area) == (bo["k_max"], bo["b_at_k_max"], bo["area"]), name
    assert (ex["k_max"], ex["b_at_k_max"], ex["area"]) == (r.k_max, r.b_at_k_max, r.area), name
    # K_max at a damping, over a band (the command line's default 0 ≤ B), overall
    at = cli(hapstab_cli, "kmax", *flags, "--wall-damping", "2")
    assert hs.kmax(lp, wall_damping=2.0).k_max == at["k_max"], name
    band = cli(hapstab_cli, "kmax", *flags)
    kb = hs.kmax(lp, damping_range=(0.0, math.inf))
    assert (kb.k_max, kb.b_at_k_max) == (band["k_max"], band["b_at_k_max"]), name
    # without a damping: B ≥ 0, B = 0 and the renderable band, as the command line gives them
    kd = hs.kmax(lp)
    assert (kd.k_max, kd.b_at_k_max) == (band["k_max"], band["b_at_k_max"]), name
    assert kd.k_max_at_zero_damping == band["k_max_at_zero_damping"], name
    rb = band["renderable"]
    assert {f: getattr(kd.renderable, f) for f in rb} == rb, name


@pytest.mark.parametrize("case", range(len(LOOPS)), ids=IDS)
def test_sweep_zwidth_and_simulate(hapstab_cli, case):
    name, lp, flags, _, normalized = LOOPS[case]
    if normalized:
        refused(hapstab_cli, "zwidth", *flags)
        refused(hapstab_cli, "sweep", *flags, "--param", "period:1e-3:2e-3:2")
        return
    sw = cli(hapstab_cli, "sweep", *flags, "--param", "period:5e-4:2e-3:3", "--wall-damping", "2")
    ps = hs.sweep(lp, "period", [5e-4, 1.25e-3, 2e-3], wall_damping=2.0)
    for i, p in enumerate(sw["points"]):
        same(ps.k_max[i], p["k_max"], (name, "sweep k_max", i))
        same(ps.k_max_passive[i], p["k_max_passive"], (name, "sweep passive", i))
    zw = cli(hapstab_cli, "zwidth", *flags, "--table-damping", "0,2")["loops"][0]
    z = hs.zwidth(lp, table_damping=[0.0, 2.0])
    assert (z.k_max, z.stable_area) == (zw["k_max"]["stiffness"], zw["stable_area"]), name
    for i, row in enumerate(zw["table"]):
        same(z.table_k_max[i], row["k_max"], (name, "zwidth table", i))
    k, b = wall_of(lp, normalized)
    si = cli(hapstab_cli, "simulate", *flags, *wall_flags(False, k, b), "--duration-samples", "400")
    s = hs.simulate(lp, k, b, samples=400)
    assert s.outcome == si["outcome"], name
    assert s.measured_growth_per_sample == si["measured_growth_per_sample"], name
    assert s.final_position == si["final_position"], name


def test_locus_crossing_frequency(hapstab_cli):
    """The root locus's crossing frequency is one number: the command line's JSON and Python
    give the same double, and it is |arg z|/(2πT) of the crossing root (numpy's angle)."""
    lp = hs.Loop.paper(delay=1e-3)
    py = hs.root_locus(lp, 2.0)
    out = cli(hapstab_cli, "locus", "--delay", "1", "--wall-damping", "2")
    assert py.crossing is not None
    assert out["crossing"]["frequency_hz"] == py.crossing_frequency_hz
    want = abs(np.angle(py.crossing)) / (2 * math.pi * 1e-3)
    assert abs(py.crossing_frequency_hz - want) <= 1e-12 * want
    assert abs(out["crossing"]["re"] - py.crossing.real) == 0.0
