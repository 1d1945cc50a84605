"""sweep and zwidth: the numbers of `hapstab sweep --json` and `hapstab zwidth --json` on the
same loops, bit for bit; bad arguments name the keyword."""

import json
import math
import subprocess

import numpy as np
import pytest

import hapstab as hs

# (Python loop, the same loop as command-line flags)
LOOPS = [
    (hs.Loop.paper(delay=1e-3), ["--delay-time", "1e-3"]),
    (
        hs.Loop(hs.MassSpringDamper(0.25, 2.0), period=5e-4, velocity="lowpass:200"),
        ["--mass", "0.25", "--damping", "2", "--period", "5e-4", "--velocity", "lowpass:200"],
    ),
    (
        hs.Loop(hs.TwoMass(0.3, 2300.0, handle_mass=0.1), period=0.002, delay=3e-3),
        ["--motor-mass", "0.3", "--transmission-stiffness", "2300", "--handle-mass", "0.1",
         "--period", "0.002", "--delay-time", "3e-3"],
    ),
]


def cli(exe, *args):
    done = subprocess.run([str(exe), *args, "--json"], check=True, capture_output=True,
                          text=True)
    return json.loads(done.stdout)


def same(got, want):
    """A float of Python (NaN for none) against the command line's number or null."""
    if want is None:
        assert math.isnan(got), got
    else:
        assert got == want, (got, want)


@pytest.mark.parametrize("case", range(len(LOOPS)))
@pytest.mark.parametrize("at", [[], ["--wall-damping", "5"], ["--damping-range", "0:inf"]])
def test_sweep_equals_the_command_line(hapstab_cli, case, at):
    lp, flags = LOOPS[case]
    want = cli(hapstab_cli, "sweep", *flags, "--param", "arm-stiffness:100:800:4", *at)
    kw = {}
    if at and at[0] == "--wall-damping":
        kw["wall_damping"] = 5.0
    if at and at[0] == "--damping-range":
        kw["damping_range"] = (0.0, math.inf)
    got = hs.sweep(lp, "arm-stiffness", np.linspace(100, 800, 4), **kw)
    assert got.param == "arm-stiffness" and got.unit == want["unit"]
    for i, p in enumerate(want["points"]):
        assert got.values[i] == p["value"]
        for key in ("k_max", "b_at_k_max", "k_max_passive", "k_max_passive_with_arm"):
            same(getattr(got, key)[i], p[key])
        assert got.notes[i] == p["note"]
        assert got.passive_notes[i] == p["passive_note"]


@pytest.mark.parametrize("case", range(len(LOOPS)))
def test_zwidth_equals_the_command_line(hapstab_cli, case):
    lp, flags = LOOPS[case]
    want = cli(hapstab_cli, "zwidth", *flags, "--table-damping", "0,2,10")["loops"][0]
    got = hs.zwidth(lp, table_damping=[0, 2, 10])
    assert got.stable_area == want["stable_area"]
    assert (got.k_max, got.b_at_k_max) == (want["k_max"]["stiffness"], want["k_max"]["damping"])
    for g, w in zip(got.stable, want["stable"]):
        np.testing.assert_array_equal(g, [[v["stiffness"], v["damping"]] for v in w])
    if want["passive"] is None:
        assert got.passive is None
    else:
        same(got.passive.k_max, want["passive"]["k_max"])  # NaN for an empty region
        assert got.passive.area == want["passive"]["area"]
    assert got.passive_inside_stable == want["passive_inside_stable"]
    for i, row in enumerate(want["table"]):
        assert got.table_damping[i] == row["damping"]
        for key in ("k_max", "k_min", "k_max_passive", "k_linear"):
            same(getattr(got, "table_" + key)[i], row[key])


def test_bad_arguments_name_the_keyword():
    lp = hs.Loop.paper()
    with pytest.raises(ValueError, match="^param"):
        hs.sweep(lp, "colour", [1.0, 2.0])
    with pytest.raises(ValueError, match="^values"):
        hs.sweep(lp, "arm-stiffness", [1.0, float("nan")])
    with pytest.raises(ValueError, match="wall_damping, damping_range"):
        hs.sweep(lp, "arm-stiffness", [1.0], wall_damping=1.0, damping_range=(0, 1))
    with pytest.raises(ValueError, match="^table_damping"):
        hs.zwidth(lp, table_damping=[float("inf")])
