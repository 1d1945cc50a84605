#!/usr/bin/env bash
# The 1000×1000 stability map from Python (hapstab.stability_map, and python-control point by
# point on a subset of the grid) beside the Rust bench `cargo bench -p hapstab --bench map`,
# measured in one run. Builds the package into the venv .ci/run uses (target/python-venv).
# Usage: bash benches/python_compare.sh
set -euo pipefail
cd "$(dirname "$0")/.."
venv="$PWD/target/python-venv"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/pip" install --quiet --disable-pip-version-check maturin numpy control
PATH="$venv/bin:$PATH" CARGO_TARGET_DIR="$PWD/target" \
  "$venv/bin/pip" install --quiet --disable-pip-version-check --no-build-isolation ./crates/hapstab-py
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
cargo bench -p hapstab --bench map -- --noplot schur >/dev/null 2>&1
# OPENBLAS_CORETYPE/OPENBLAS_L2_SIZE slow a current numpy; unset both for the baseline only.
py=$(env -u OPENBLAS_CORETYPE -u OPENBLAS_L2_SIZE "$venv/bin/python" benches/baseline/python_map.py)
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "$py" | while read -r line; do
  d=$(python3 -c "import json,sys;print(json.loads(sys.argv[1])['d'])" "$line")
  est=target/criterion/map_1000x1000/schur/$d/new/estimates.json
  python3 - "$est" "$line" <<'PY'
import json, sys
rust = json.load(open(sys.argv[1]))["mean"]["point_estimate"] / 1e9
py = json.loads(sys.argv[2])
print(f"d={py['d']}: Rust bench {rust*1e3:.1f} ms; Python stability_map {py['hapstab_mean_s']*1e3:.1f} ms mean, "
      f"{py['hapstab_min_s']*1e3:.1f} ms best (x{py['hapstab_mean_s']/rust:.2f} of Rust); "
      f"python-control {py['control_s_per_point']*1e3:.3f} ms/point ({py['control_points_timed']} points timed), "
      f"{py['control_s_per_map']:.0f} s per map, ratio {py['control_s_per_map']/py['hapstab_mean_s']:.0f}x")
PY
done
