#!/usr/bin/env bash
# Measures the 1000×1000 stability map with hapstab (criterion) and with numpy.roots point by
# point (benches/baseline/numpy_map.py) in one run, and prints the ratio per point; likewise
# the simulator, and all roots of p(z) at d = 10, 200, 2000 (benches/baseline/numpy_roots.py).
# Usage: bash benches/compare.sh [all|map|roots|general]   (installs numpy into a venv under target/
# if needed)
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/baseline-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet numpy
fi
what=${1:-all}
if [ "$what" = all ] || [ "$what" = map ]; then
cargo bench -p hapstab --bench map -- --noplot >/dev/null 2>&1
for d in 0 10; do
  est=target/criterion/map_1000x1000/schur/$d/new/estimates.json
  rust_ns=$(python3 -c "import json;print(json.load(open('$est'))['mean']['point_estimate'])")
  # OPENBLAS_CORETYPE/OPENBLAS_L2_SIZE slow a current numpy; unset both for the baseline only.
  py=$(env -u OPENBLAS_CORETYPE -u OPENBLAS_L2_SIZE "$venv/bin/python" benches/baseline/numpy_map.py $d 10)
  python3 - "$rust_ns" "$py" <<'PY'
import json, sys
rust_total_ns = float(sys.argv[1]); py = json.loads(sys.argv[2])
rust_pp = rust_total_ns / 1e6
print(f"d={py['d']}: hapstab {rust_total_ns/1e6:.1f} ms per 1e6-point map ({rust_pp:.1f} ns/point); "
      f"numpy.roots {py['ns_per_point']/1e3:.1f} us/point ({py['points_timed']} points timed, "
      f"{py['ns_per_point']*1e6/1e9:.1f} s per map); ratio {py['ns_per_point']/rust_pp:.0f}x")
PY
done

# Simulation: criterion bench vs a per-sample numpy loop.
cargo bench -p hapstab --bench simulation -- --noplot linear_bilateral_d1 >/dev/null 2>&1
est=target/criterion/simulate/linear_bilateral_d1/new/estimates.json
rust_ns=$(python3 -c "import json;print(json.load(open('$est'))['mean']['point_estimate'])")
py=$(env -u OPENBLAS_CORETYPE -u OPENBLAS_L2_SIZE "$venv/bin/python" benches/baseline/sim_python.py 200000)
python3 - "$rust_ns" "$py" <<'PY'
import json, sys
rust_ns = float(sys.argv[1]); py = json.loads(sys.argv[2])
rust_sps = 1e6 / (rust_ns * 1e-9)
print(f"simulation: hapstab {rust_sps/1e6:.1f} M samples/s; numpy loop {py['samples_per_second']/1e3:.1f} k samples/s; "
      f"ratio {rust_sps/py['samples_per_second']:.0f}x")
PY
fi

if [ "$what" = all ] || [ "$what" = general ]; then
# A general loop (two-mass device, actuator lag, low-pass velocity, d = 1): the map and the
# region + K_max benches, and numpy.roots over the same map.
cargo build --release -p hapstab-cli >/dev/null 2>&1
cargo bench -p hapstab --bench map -- --noplot general_loop >/dev/null 2>&1
cargo bench -p hapstab --bench region -- --noplot general_loop >/dev/null 2>&1
est=target/criterion/map_1000x1000/general_loop_order5_d1/new/estimates.json
rust_ns=$(python3 -c "import json;print(json.load(open('$est'))['mean']['point_estimate'])")
py=$(env -u OPENBLAS_CORETYPE -u OPENBLAS_L2_SIZE OPENBLAS_NUM_THREADS=1 "$venv/bin/python" benches/baseline/numpy_general_map.py target/release/hapstab 50)
python3 - "$rust_ns" "$py" <<'PY'
import json, sys
rust_total_ns = float(sys.argv[1]); py = json.loads(sys.argv[2])
rust_pp = rust_total_ns / 1e6
print(f"general map (degree {py['degree']}): hapstab {rust_total_ns/1e6:.1f} ms per 1e6-point map "
      f"({rust_pp:.1f} ns/point); numpy.roots {py['ns_per_point']/1e3:.1f} us/point "
      f"({py['points_timed']} points timed, stable {py['stable_fraction']:.3f}); ratio {py['ns_per_point']/rust_pp:.0f}x")
PY
for label in 0 1 10 1.5; do
  est=target/criterion/region/general_loop_order5/$label/new/estimates.json
  python3 -c "import json;print('region + K_max, general loop, delay $label samples: %.3f ms' % (json.load(open('$est'))['mean']['point_estimate']/1e6))"
done
fi

if [ "$what" = all ] || [ "$what" = roots ]; then
# Roots: criterion (Aberth–Ehrlich, and the whole Analysis) vs numpy.roots, same polynomials.
cargo bench -p hapstab --bench roots -- --noplot >/dev/null 2>&1
# One BLAS thread: numpy.roots is 2-4x faster so on this shared 2-core machine.
py=$(cd benches/baseline && env -u OPENBLAS_CORETYPE -u OPENBLAS_L2_SIZE OPENBLAS_NUM_THREADS=1 "../../$venv/bin/python" numpy_roots.py 10 200 2000)
python3 - "$py" <<'PY'
import json, sys
mean = lambda path: json.load(open(path))["mean"]["point_estimate"]
for line in sys.argv[1].splitlines():
    py = json.loads(line); d = py["d"]
    ab = mean(f"target/criterion/roots/aberth/{d}/new/estimates.json")
    an = mean(f"target/criterion/roots/analysis/{d}/new/estimates.json")
    np_ns = py["seconds_per_call"] * 1e9
    print(f"roots d={d}: hapstab Aberth {ab/1e3:.1f} us (Analysis {an/1e3:.1f} us); "
          f"numpy.roots {np_ns/1e3:.1f} us ({py['calls']} calls); ratio {np_ns/ab:.0f}x")
PY
fi
