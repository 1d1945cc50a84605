"""The parity matrix, Python against the command line: for every kind of loop of the
command line's matrix against the explorer (crates/hapstab-cli/tests/cli/serve_parity_matrix.rs:
the paper's loop in physical and normalized units, a device without an arm, a two-mass device,
a transfer function of order 5, the estimators average, low-pass, Butterworth and IIR, an
actuator lag and a fractional delay), every analysis — check with its margins, K_max at a damping, over a band and
overall, the stable region, the map, passivity, the sweep, the Z-width and the simulated
contact — gives from Python the numbers of `hapstab … --json`, bit for bit where both compute
the same thing. The explorer's API answers the command line's objects bit for bit (the Rust
matrix); `test_explorer_equals_python` compares Python with the explorer's new endpoints
directly as well, on the explorer's query of Python's own loop file (`/api/open`)."""

import csv as csvlib
import json
import math
import re
import subprocess
import urllib.parse
import urllib.request

import numpy as np
import pytest

import hapstab as hs


def order_5():
    """The transfer function of order 5 of the Rust matrix: the paper's device and arm
    (1.1 s² + 7.5 s + 350) behind a lightly damped 80 Hz mode and a 0.5 ms lag, descending
    coefficients multiplied out in the same order."""
    w = 2 * math.pi * 80

    def mul(p, q):
        r = [0.0] * (len(p) + len(q) - 1)
        for i, a in enumerate(p):
            for j, b in enumerate(q):
                r[i + j] += a * b
        return r

    den = mul(mul([1.1, 7.5, 350.0], [1.0, 2 * 0.05 * w, w * w]), [5e-4, 1.0])
    return [w * w], den


NUM5, DEN5 = order_5()


def text(c):
    return ",".join(repr(x) for x in c)


def paper_device(**kw):
    return hs.Loop(hs.MassSpringDamper.from_device_and_arm(), **kw)


# name, Python loop, command-line flags, sweep (param, lo, hi, n), where K_max is taken
KINDS = [
    ("paper loop, physical", lambda: hs.Loop.paper(delay=1e-3),
     ["--period", "0.001", "--delay", "1"], ("arm-stiffness", 0, 700, 5), None),
    ("paper loop, normalized", lambda: hs.Loop.normalized(gamma=0.001, delta=0.015, d=1),
     ["--gamma", "0.001", "--delta", "0.015", "--delay", "1"], None, None),
    ("mass-spring-damper without arm",
     lambda: hs.Loop(hs.MassSpringDamper(0.25, 2.0), period=5e-4),
     ["--no-arm", "--device-mass", "0.25", "--device-damping", "2", "--period", "0.0005"],
     ("mass", 0.2, 0.3, 5), (0.0, 20.0)),
    ("two-mass device",
     lambda: hs.Loop(hs.TwoMass(0.3, 2300.0, handle_mass=0.1), period=0.002),
     ["--motor-mass", "0.3", "--transmission-stiffness", "2300", "--handle-mass", "0.1",
      "--period", "0.002"], ("transmission-stiffness", 2000, 3000, 5), 2.0),
    ("transfer function of order 5",
     lambda: hs.Loop(hs.TransferFunction(NUM5, DEN5), period=1e-3, delay_samples=1),
     ["--plant-num", text(NUM5), "--plant-den", text(DEN5), "--delay", "1"],
     ("delay-time", 0, 0.002, 5), 2.0),
    ("estimator average:3", lambda: paper_device(delay_samples=1, velocity="average:3"),
     ["--velocity", "average:3", "--delay", "1"], ("window", 1, 5, 5), 2.0),
    ("estimator lowpass:100", lambda: paper_device(velocity="lowpass:100"),
     ["--velocity", "lowpass:100"], ("cutoff", 50, 250, 5), 2.0),
    ("estimator butterworth:2:150", lambda: paper_device(velocity="butterworth:2:150"),
     ["--velocity", "butterworth:2:150"], ("cutoff", 50, 250, 5), 2.0),
    ("estimator iir", lambda: paper_device(velocity="iir:0.5,0,-0.5/1,-0.2"),
     ["--velocity", "iir:0.5,0,-0.5/1,-0.2"], ("period", 0.0005, 0.0015, 5), 2.0),
    ("force lag", lambda: paper_device(delay_samples=1, force_lag=4e-4),
     ["--force-lag", "0.0004", "--delay", "1"], ("force-lag", 0, 0.0008, 5), 2.0),
    ("fractional delay", lambda: paper_device(delay=3.7e-4),
     ["--delay-time", "0.00037"], ("delay-time", 0.0002, 0.0006, 5), 2.0),
]
IDS = [k[0] for k in KINDS]
PHYSICAL = [i for i, k in enumerate(KINDS) if k[3] is not None]


def cli(exe, *args):
    done = subprocess.run([str(exe), *args, "--json"], capture_output=True, text=True)
    assert done.returncode == 0, (args, done.stderr)
    return json.loads(done.stdout)


def refused(exe, *args):
    done = subprocess.run([str(exe), *args], capture_output=True, text=True)
    assert done.returncode == 2, (args, done.stderr)
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
    return done.stderr


def same(got, want, what):
    """Equal bit for bit; the command line's null is Python's None or NaN."""
    if want is None:
        assert got is None or (isinstance(got, float) and math.isnan(got)), (what, got)
    elif isinstance(want, float) or isinstance(got, float):
        assert float(got) == float(want), (what, got, want)
    else:
        assert got == want, (what, got, want)


def same_array(got, want, what):
    got = np.asarray(got, dtype=float).reshape(-1, 2)
    want = np.asarray(want, dtype=float).reshape(-1, 2)
    assert got.shape == want.shape, (what, got.shape, want.shape)
    assert np.array_equal(got, want), (what, np.max(np.abs(got - want)))


def wall(exe, k):
    """A stable wall of a kind: half of K_max at the damping that reaches it (the command
    line's K_max over every damping), or (α, β) = (0.02, 0.02) for the normalized loop."""
    name, _, flags, sweep, _ = k
    if sweep is None:
        return 0.02, 0.02
    j = cli(exe, "kmax", *flags)
    return 0.5 * j["k_max"], j["b_at_k_max"]


def wall_flags(k, kb):
    if k[3] is None:
        return ["--alpha", repr(kb[0]), "--beta", repr(kb[1])]
    return ["--wall-stiffness", repr(kb[0]), "--wall-damping", repr(kb[1])]


def wall_kw(k, kb):
    if k[3] is None:
        return dict(alpha=kb[0], beta=kb[1])
    return dict(wall_stiffness=kb[0], wall_damping=kb[1])


MARGINS = ("gain_margin", "gain_margin_lower", "stiffness_margin", "phase_margin_deg",
           "gain_crossover_hz", "delay_margin", "delay_margin_pm_over_wc", "stability_margin",
           "peak_gain")


@pytest.mark.parametrize("i", range(len(KINDS)), ids=IDS)
def test_check_and_margins(hapstab_cli, i):
    k = KINDS[i]
    lp, kb = k[1](), wall(hapstab_cli, k)
    c = cli(hapstab_cli, "check", *k[2], *wall_flags(k, kb))
    p = hs.check(lp, **wall_kw(k, kb))
    assert p.verdict == c["verdict"] == "stable", k[0]
    same(p.spectral_radius, c["spectral_radius"], (k[0], "spectral_radius"))
    m = hs.margins(lp, **wall_kw(k, kb))
    for key in MARGINS:
        same(getattr(m, key), c[key], (k[0], key))


@pytest.mark.parametrize("i", PHYSICAL, ids=[IDS[i] for i in PHYSICAL])
def test_kmax_three_ways(hapstab_cli, i):
    name, make, flags, _, _ = KINDS[i]
    lp = make()
    keys = ("k_max", "b_at_k_max", "k_max_attained", "b_stable_near_k_max",
            "k_stable_near_k_max", "k_max_at_zero_damping", "k_linear")
    at = cli(hapstab_cli, "kmax", *flags, "--wall-damping", "2")
    p = hs.kmax(lp, wall_damping=2.0)
    same(p.k_max, at["k_max"], (name, "at B = 2"))
    same(list(p.k_interval), at["k_interval"], (name, "k_interval"))
    same(p.k_linear, at.get("k_linear"), (name, "k_linear"))
    for rng, py_rng in (("0:20", (0.0, 20.0)), ("1:inf", (1.0, math.inf))):
        band = cli(hapstab_cli, "kmax", *flags, "--damping-range", rng)
        p = hs.kmax(lp, damping_range=py_rng)
        for key in keys:
            same(getattr(p, key), band.get(key), (name, rng, key))
    overall = cli(hapstab_cli, "kmax", *flags)
    p = hs.kmax(lp)
    for key in keys:
        same(getattr(p, key), overall.get(key), (name, "overall", key))
    rb = overall["renderable"]
    for key, want in rb.items():
        same(getattr(p.renderable, key), want, (name, "renderable", key))


@pytest.mark.parametrize("i", range(len(KINDS)), ids=IDS)
def test_region(hapstab_cli, i):
    name, make, flags, sweep, _ = KINDS[i]
    r = hs.region(make())
    b = cli(hapstab_cli, "boundary", *flags)
    if sweep is None:
        # the paper's normalized loop: its view is the command line's answer in α and β, and
        # with m = T = 1 its polygons in K and B are the command line's in α and β
        for key in ("alpha_max", "beta_at_alpha_max", "area"):
            same(r.normalized[key], b[key], (name, key))
        for got, want in zip(r.polygons, b["polygons"]):
            same_array(got, want, (name, "polygon"))
        return
    assert r.wall_units == b["wall_units"], name
    assert r.normalized == b.get("normalized"), name
    for key in ("k_max", "b_at_k_max", "k_max_attained", "b_stable_near_k_max",
                "k_stable_near_k_max", "area"):
        same(getattr(r, key), b[key], (name, key))
    assert len(r.polygons) == len(b["polygons"]), name
    for got, want in zip(r.polygons, b["polygons"]):
        same_array(got, want, (name, "polygon"))


@pytest.mark.parametrize("i", range(len(KINDS)), ids=IDS)
def test_map(hapstab_cli, tmp_path, i):
    """The map's verdicts are the command line's at every point; the spectral radii agree to
    1e-12: Python grids the K and B it is given (np.linspace, divided by the loop's units),
    the command line the loop's units between the ends' (lo + (hi − lo)·i/(n − 1)), so a
    point may differ by an ulp of its wall."""
    name, make, flags, sweep, _ = KINDS[i]
    lp = make()
    if sweep is None:
        kx, by = 0.1, 0.4
        axes = ["--x", "alpha:0:0.1:5", "--y", "beta:0:0.4:5"]
    else:
        j = cli(hapstab_cli, "kmax", *flags)
        kx, by = 1.2 * j["k_max"], 2.0 * max(abs(j["b_at_k_max"]), 1.0)
        axes = ["--x", f"K:0:{kx!r}:5", "--y", f"B:0:{by!r}:5"]
    out = tmp_path / "map.csv"
    c = cli(hapstab_cli, "map", *flags, *axes, "--radius", "--out", str(out))
    m = hs.stability_map(lp, np.linspace(0, kx, 5), np.linspace(0, by, 5), spectral_radius=True)
    with open(out) as f:
        rows = list(csvlib.reader(f))[1:]
    stable = np.array([r[2] == "1" for r in rows]).reshape(5, 5)
    radius = np.array([float(r[3]) for r in rows]).reshape(5, 5)
    assert np.array_equal(np.asarray(m.stable), stable), name
    assert int(np.sum(m.stable)) == c["stable_points"], name
    np.testing.assert_allclose(np.asarray(m.spectral_radius), radius, rtol=1e-12, err_msg=name)


@pytest.mark.parametrize("i", range(len(KINDS)), ids=IDS)
def test_passivity(hapstab_cli, i):
    k = KINDS[i]
    kb = wall(hapstab_cli, k)
    c = cli(hapstab_cli, "passivity", *k[2], *wall_flags(k, kb))
    p = hs.passivity(k[1](), **wall_kw(k, kb))
    for key in ("b_required", "binding_frequency_hz", "binding_theta", "dc_stiffness",
                "device_damping", "meets", "verdict", "stable"):
        same(getattr(p, key), c[key], (k[0], key))
    same(p.effective_damping, c.get("effective_damping"), (k[0], "effective_damping"))
    same(p.effective_verdict, c.get("effective_verdict"), (k[0], "effective_verdict"))
    want = c["passive_region"]
    if want is None:
        assert p.passive_region is None, k[0]
        return
    got = p.passive_region
    for key in ("k_max", "b_at_k_max", "area", "bounded"):
        same(getattr(got, key), want[key], (k[0], "passive_region", key))
    same_array(got.vertices, want["vertices"], (k[0], "passive_region.vertices"))


@pytest.mark.parametrize("i", PHYSICAL, ids=[IDS[i] for i in PHYSICAL])
def test_sweep(hapstab_cli, i):
    name, make, flags, (param, lo, hi, n), at = KINDS[i]
    if at is None:
        extra, kw = [], {}
    elif isinstance(at, tuple):
        extra, kw = ["--damping-range", f"{at[0]!r}:{at[1]!r}"], dict(damping_range=at)
    else:
        extra, kw = ["--wall-damping", repr(at)], dict(wall_damping=at)
    c = cli(hapstab_cli, "sweep", *flags, "--param", f"{param}:{lo!r}:{hi!r}:{n}", *extra)
    # the swept values as the command line computes them (lo + (hi − lo)·i/(n − 1))
    values = [p["value"] for p in c["points"]]
    s = hs.sweep(make(), param, values, **kw)
    assert s.param == c["input"]["param"] and s.unit == c["unit"], name
    for j, p in enumerate(c["points"]):
        for key in ("k_max", "b_at_k_max", "k_max_passive", "k_max_passive_with_arm"):
            same(float(getattr(s, key)[j]), p[key], (name, key, j))
        assert s.notes[j] == p["note"], (name, j)


@pytest.mark.parametrize("i", PHYSICAL, ids=[IDS[i] for i in PHYSICAL])
def test_zwidth(hapstab_cli, i):
    name, make, flags, _, _ = KINDS[i]
    lp = make()
    for table, extra in (([0.0, 2.0], ["--table-damping", "0,2"]), (None, [])):
        z = hs.zwidth(lp, table_damping=table)
        c = cli(hapstab_cli, "zwidth", *flags, *extra)["loops"][0]
        same(z.stable_area, c["stable_area"], name)
        same(z.k_max, c["k_max"]["stiffness"], name)
        same(z.b_at_k_max, c["k_max"]["damping"], name)
        nn = c["k_max_nonnegative_damping"]
        assert z.k_max_nonnegative_damping == (nn and (nn["stiffness"], nn["damping"])), name
        for got, want in zip(z.stable, c["stable"]):
            same_array(got, [[w["stiffness"], w["damping"]] for w in want], (name, "stable"))
        lin = c["linear"]
        assert z.linear == (lin and (lin["damping"], lin["effective_delay"])), name
        arm = c["k_max_passive_with_arm"]
        assert z.k_max_passive_with_arm == (arm and (arm["stiffness"], arm["damping"])), name
        assert z.passive_inside_stable == c["passive_inside_stable"], name
        for col in ("damping", "k_max", "k_min", "k_max_passive", "k_linear"):
            got = np.asarray(getattr(z, f"table_{col}"))
            want = [np.nan if r[col] is None else r[col] for r in c["table"]]
            assert np.array_equal(got, want, equal_nan=True), (name, col)
        if c["passive"] is not None:
            same(z.passive.k_max, c["passive"]["k_max"], name)
            same(z.passive.area, c["passive"]["area"], name)


@pytest.mark.parametrize("i", range(len(KINDS)), ids=IDS)
def test_simulate(hapstab_cli, i):
    """The explorer's contact (unilateral, 1 N push, entered at x = 0 with 10 mm/s; the Rust
    matrix compares it with the command line's) run from Python and from the command line."""
    k = KINDS[i]
    kb = wall(hapstab_cli, k)
    c = cli(hapstab_cli, "simulate", *k[2], *wall_flags(k, kb), "--unilateral", "--push", "1",
            "--initial-position", "0", "--initial-velocity", "0.01",
            "--duration-samples", "600")
    s = hs.simulate(k[1](), **wall_kw(k, kb), samples=600, human_force=1.0,
                    initial_position=0.0, initial_velocity=0.01, contact="unilateral")
    # one answer schema: the run, its time window and units, and the echoed loop, wall,
    # effects, push and initial state under `input`
    for key in ("outcome", "reason", "samples", "linear_window", "measured_growth_per_sample",
                "spectral_radius", "linear_verdict", "requested_samples", "max_samples",
                "duration", "judged_from", "judged_to", "units", "final_position"):
        same(getattr(s, key), c[key], (k[0], key))
    assert s.input == c["input"], (k[0], s.input, c["input"])
    assert s.judged_samples == (c["judged_from_sample"], c["judged_to_sample"]), k[0]


def test_refusals(hapstab_cli, tmp_path):
    """What only a physical loop has (K_max in N/m, the sweep, the Z-width) is refused by the
    command line for the normalized loop in one line; the linear condition, defined for the
    paper's loop only, is refused by both front ends for every other loop."""
    flags = KINDS[1][2]
    refused(hapstab_cli, "kmax", *flags)
    refused(hapstab_cli, "zwidth", *flags)
    refused(hapstab_cli, "sweep", *flags, "--param", "period:0.001:0.002:5")
    for name, make, flags, sweep, _ in KINDS:
        lp = make()
        paper = lp.paper_view is not None
        file = tmp_path / "loop.json"
        file.write_text(lp.to_json())
        if paper:
            cli(hapstab_cli, "linear", "--loop", str(file))
            hs.linear_condition(lp)
            continue
        refused(hapstab_cli, "linear", "--loop", str(file))
        with pytest.raises(ValueError, match="loop"):
            hs.linear_condition(lp)


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


def explorer(base, path, query, **extra):
    """The explorer's answer at `path` for the page's `query` and extra parameters."""
    url = f"{base}{path}?{query}&{urllib.parse.urlencode(extra)}"
    with urllib.request.urlopen(url) as r:
        return json.load(r)


@pytest.mark.parametrize("i", PHYSICAL, ids=[IDS[i] for i in PHYSICAL])
def test_explorer_equals_python(hapstab_cli, server, i):
    """Python's loop saved as a loop file, opened by the explorer (`/api/open`), analysed by
    `/api/kmax`, `/api/passivity`, `/api/sweep` and `/api/zwidth`: Python's numbers."""
    name, make, _, (param, lo, hi, n), _ = KINDS[i]
    lp = make()
    q = explorer(server, "api/open", "", file=lp.to_json())["query"]
    keys = ("k_max", "b_at_k_max", "k_max_attained", "k_max_at_zero_damping", "k_linear")
    for kw, extra in ((dict(wall_damping=2.0), dict(wall_damping=2)),
                      (dict(damping_range=(0.0, 20.0)), dict(damping_lo=0, damping_hi=20)),
                      ({}, {})):
        a, p = explorer(server, "api/kmax", q, **extra), hs.kmax(lp, **kw)
        # at a given damping Python's answer echoes it as b_at_k_max, the JSON under `input`
        for key in keys if "wall_damping" not in kw else ("k_max", "k_linear"):
            same(getattr(p, key), a.get(key), (name, "kmax", extra, key))
    kb = wall(hapstab_cli, KINDS[i])
    a = explorer(server, "api/passivity", q, wall_stiffness=repr(kb[0]),
                 wall_damping=repr(kb[1]))
    p = hs.passivity(lp, *kb)
    for key in ("b_required", "binding_theta", "dc_stiffness", "verdict", "stable"):
        same(getattr(p, key), a[key], (name, "passivity", key))
    if a["passive_region"] is not None:
        same_array(p.passive_region.vertices, a["passive_region"]["vertices"], name)
    a = explorer(server, "api/sweep", q, param=param, lo=lo, hi=hi, n=n)
    s = hs.sweep(lp, param, [pt["value"] for pt in a["points"]])
    for j, pt in enumerate(a["points"]):
        for key in ("k_max", "b_at_k_max", "k_max_passive", "k_max_passive_with_arm"):
            same(float(getattr(s, key)[j]), pt[key], (name, "sweep", key, j))
    a = explorer(server, "api/zwidth", q, table_damping="0,2")["loops"][0]
    z = hs.zwidth(lp, table_damping=[0.0, 2.0])
    same(z.stable_area, a["stable_area"], (name, "zwidth"))
    same(z.k_max, a["k_max"]["stiffness"], (name, "zwidth"))
    same_array(np.asarray(z.table_k_max), [r["k_max"] for r in a["table"]], (name, "table"))
