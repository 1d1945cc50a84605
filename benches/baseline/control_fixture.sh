#!/usr/bin/env bash
# Regenerates crates/hapstab/tests/fixtures/control_loops.json: the closed loops computed by
# python-control (control_fixture.py), then refereed in mpmath (control_mpmath.py --write).
# Installs python-control, numpy and mpmath into a venv under target/ (never committed).
# Usage: bash benches/baseline/control_fixture.sh [--seed S] [--loops N]
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=target/control-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet control numpy mpmath
fi
fixture=crates/hapstab/tests/fixtures/control_loops.json
"$venv/bin/python" benches/baseline/control_fixture.py --out "$fixture" "$@"
"$venv/bin/python" benches/baseline/control_mpmath.py "$fixture" --write >/dev/null
echo "fixture and its mpmath reference written to $fixture"
