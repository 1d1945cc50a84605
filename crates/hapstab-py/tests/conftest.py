"""Shared fixtures: the repository root, the Rust side's reference values, loops built from
their descriptions through the Python API."""

import json
import os
import subprocess
from pathlib import Path

import pytest

import hapstab as hs

ROOT = Path(__file__).resolve().parents[3]


def target_dir() -> Path:
    return Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))


@pytest.fixture(scope="session")
def reference():
    """The seeded reference values written by the library's own test
    (crates/hapstab/tests/engine/python_reference.rs), regenerated here so that they match the
    library being bound."""
    subprocess.run(
        ["cargo", "test", "-q", "-p", "hapstab", "--test", "engine", "python_reference::"],
        cwd=ROOT,
        check=True,
        stdout=subprocess.DEVNULL,
    )
    with open(target_dir() / "tmp" / "python_reference.json") as f:
        return json.load(f)


def plant_of(p: dict):
    """A plant object from hapstab's serde form of a plant model."""
    kind = p["kind"]
    if kind == "mass_spring_damper":
        return hs.MassSpringDamper(p["mass"], p["damping"], p["stiffness"])
    if kind == "two_mass":
        arm = p["arm"]
        return hs.TwoMass(
            p["motor_mass"],
            p["transmission_stiffness"],
            motor_damping=p["motor_damping"],
            handle_mass=p["handle_mass"],
            transmission_damping=p["transmission_damping"],
            arm_mass=arm["mass"],
            arm_damping=arm["damping"],
            arm_stiffness=arm["stiffness"],
        )
    if kind == "transfer_function":
        return hs.TransferFunction(p["num"], p["den"])
    raise AssertionError(kind)


def loop_of(d: dict) -> hs.Loop:
    """The loop a reference case describes, through the constructor it names."""
    if d["kind"] == "normalized":
        return hs.Loop.normalized(gamma=d["gamma"], delta=d["delta"], d=d["d"])
    if d["kind"] == "paper":
        dev, arm = d["device"], d["arm"]
        return hs.Loop.paper(
            device_mass=dev["mass"],
            device_damping=dev["damping"],
            arm_mass=arm["mass"],
            arm_damping=arm["damping"],
            arm_stiffness=arm["stiffness"],
            period=d["period"],
            delay=d["delay"],
        )
    return hs.Loop(
        plant_of(d["plant"]),
        period=d["period"],
        delay=d["delay_time"],
        velocity=d["velocity"],
        force_lag=d["force_lag"],
    )


@pytest.fixture(scope="session")
def hapstab_cli() -> Path:
    """The command-line binary of this checkout: $HAPSTAB_BIN when set, else the one that
    `cargo test --workspace` builds (as .ci/run does before pytest, so there this is a no-op;
    run alone it builds), located from cargo's artifact messages. Never stale, never skipped."""
    given = os.environ.get("HAPSTAB_BIN")
    if given:
        return Path(given)
    done = subprocess.run(
        ["cargo", "test", "--workspace", "--no-run", "--message-format=json-render-diagnostics"],
        cwd=ROOT,
        check=True,
        stdout=subprocess.PIPE,
        text=True,
    )
    exes = [
        m["executable"]
        for m in map(json.loads, done.stdout.splitlines())
        if m.get("reason") == "compiler-artifact"
        and m["target"]["name"] == "hapstab"
        and "bin" in m["target"]["kind"]
        and not m["profile"]["test"]  # the binary itself, not its unit-test harness
    ]
    assert len(exes) == 1 and Path(exes[0]).is_file(), exes
    return Path(exes[0])
