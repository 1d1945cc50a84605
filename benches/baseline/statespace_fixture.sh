#!/usr/bin/env bash
# Regenerates crates/hapstab/tests/fixtures/statespace_loops.json: seeded random haptic loops
# and the audit loops, refereed in state space (statespace_referee.py: numpy/scipy, mpmath at
# 40 digits where double precision is doubtful). The referee is first checked against
# python-control's fixture and the paper's closed form (statespace_validate.py); the fixture
# is written only when that passes. Installs numpy, scipy, mpmath and gmpy2 (mpmath's fast
# backend) into a venv under target/ (never committed). About 35 minutes on two cores.
# Usage: bash benches/baseline/statespace_fixture.sh [--seed S] [--loops N] [--jobs J]
# STATESPACE_FIXTURE=PATH writes elsewhere (a larger run for HAPSTAB_REFEREE_FIXTURE=PATH cargo
# test -p hapstab --test engine statespace_referee::).
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=target/referee-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet numpy scipy mpmath gmpy2
fi
fixture=${STATESPACE_FIXTURE:-crates/hapstab/tests/fixtures/statespace_loops.json}
"$venv/bin/python" benches/baseline/statespace_validate.py
"$venv/bin/python" benches/baseline/statespace_fixture.py --jobs 2 "$@" --out "$fixture"
# the radii the fixture took from the double path, spot-checked at 40 digits
"$venv/bin/python" benches/baseline/statespace_validate.py --fixture "$fixture" --sample 200
echo "fixture written to $fixture"
