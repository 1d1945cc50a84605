#!/usr/bin/env bash
# P(stable) over a population and robust K_max over a box: hapstab (criterion,
# crates/hapstab/benches/population.rs) and numpy.roots per operator / a bisection on K with
# numpy.roots per plant (benches/baseline/population_numpy.py), in one run, with the ratios.
# Usage: bash benches/population_compare.sh   (installs numpy into a venv under target/ if needed)
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/baseline-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet numpy
fi
cargo bench -p hapstab --bench population -- --noplot >/dev/null 2>&1
est() { python3 -c "import json;print(json.load(open('target/criterion/population/$1/new/estimates.json'))['median']['point_estimate'])"; }
wall_ns=$(est wall_1e5); curve_ns=$(est curve_1e4); robust_ns=$(est robust_box)
# OPENBLAS_CORETYPE/OPENBLAS_L2_SIZE slow a current numpy; unset both for the baseline only.
py=$(env -u OPENBLAS_CORETYPE -u OPENBLAS_L2_SIZE "$venv/bin/python" benches/baseline/population_numpy.py 20000 50)
python3 - "$wall_ns" "$curve_ns" "$robust_ns" "$py" <<'PY'
import json, sys
wall, curve, robust = (float(x) for x in sys.argv[1:4]); py = json.loads(sys.argv[4])
np_wall = py["wall_us_per_operator"] * 1e-6 * 1e5
np_robust = py["robust_ms_per_plant"] * 1e-3 * 1e3
print(f"P(stable) at a wall, 1e5 operators: hapstab {wall/1e9:.3f} s, numpy.roots {np_wall:.2f} s "
      f"({py['wall_us_per_operator']:.1f} us/operator); ratio {np_wall/(wall/1e9):.0f}x")
print(f"P(stable) curve, 1e4 operators (exact intervals): hapstab {curve/1e9:.3f} s")
print(f"robust K_max over the box: hapstab {robust/1e9:.3f} s (all stages, 1e4 plants verified); "
      f"numpy bisection over 1e3 plants {np_robust:.2f} s ({py['robust_ms_per_plant']:.2f} ms/plant); "
      f"ratio {np_robust/(robust/1e9):.0f}x")
PY
