#!/usr/bin/env bash
# K_max without the polygon: hapstab (criterion, crates/hapstab/benches/kmax.rs, single-threaded)
# against the θ scan and the exact region it replaces (same run) and against a bisection on K
# with numpy.roots (benches/baseline/kmax_numpy.py), with the ratios.
# Usage: bash benches/kmax_compare.sh [runs]   (criterion runs, default 5; the median of the
# runs' medians is reported; installs numpy into a venv under target/ if needed)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
venv=target/baseline-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet numpy
fi
cargo build --release -p hapstab-cli >/dev/null 2>&1
out=target/kmax-compare; rm -rf "$out"; mkdir -p "$out"
for r in $(seq 1 "$runs"); do
  RAYON_NUM_THREADS=1 cargo bench -p hapstab --bench kmax -- --noplot --warm-up-time 1 --measurement-time 2 >/dev/null 2>&1
  for f in target/criterion/kmax/*/*/new/estimates.json; do
    id=$(echo "$f" | sed 's|target/criterion/kmax/||; s|/new/estimates.json||; s|/|.|')
    python3 -c "import json;print(json.load(open('$f'))['median']['point_estimate'])" >> "$out/$id"
  done
done
env -u OPENBLAS_CORETYPE -u OPENBLAS_L2_SIZE OPENBLAS_NUM_THREADS=1 "$venv/bin/python" \
  benches/baseline/kmax_numpy.py target/release/hapstab > "$out/numpy.jsonl"
for d in 0 1 10; do
  target/release/hapstab kmax "--motor-mass=0.05" "--motor-damping=0.5" "--handle-mass=0.05" \
    "--transmission-stiffness=2e4" "--transmission-damping=2" "--force-lag=2e-4" \
    "--velocity=lowpass:200" "--delay=$d" --wall-damping 5 --json > "$out/hapstab_at5_$d.json"
done
python3 - "$out" <<'PY'
import json, os, statistics, sys
out = sys.argv[1]
def med(id):
    xs = [float(x) for x in open(os.path.join(out, id))]
    return statistics.median(xs), min(xs), max(xs)
np = {r["d"]: r for r in map(json.loads, open(os.path.join(out, "numpy.jsonl")))}
for d in (0, 1, 10):
    at, at_lo, at_hi = med(f"at_damping.{d}")
    scan = med(f"at_damping_scan.{d}")[0]
    band, band_lo, band_hi = med(f"band.{d}")
    region = med(f"band_region.{d}")[0]
    q_at = med(f"query_at_damping.{d}")[0]
    q_band = med(f"query_band.{d}")[0]
    n = np[d]
    k = json.load(open(os.path.join(out, f"hapstab_at5_{d}.json")))["k_max"]
    print(f"d = {d} (degree {n['degree']}):")
    print(f"  at B = 5 Ns/m: {at/1e3:.1f} us (runs {at_lo/1e3:.1f}-{at_hi/1e3:.1f}); θ scan {scan/1e3:.1f} us "
          f"({scan/at:.1f}x); numpy bisection {n['at_damping_s']*1e6:.0f} us ({n['at_damping_s']*1e9/at:.0f}x); "
          f"whole kmax query from the loop {q_at/1e3:.1f} us")
    print(f"     K_max: hapstab {k:.10g} N/m, numpy bisection {n['k_max_at_5']:.10g} N/m")
    print(f"  over B >= 0: {band/1e3:.1f} us (runs {band_lo/1e3:.1f}-{band_hi/1e3:.1f}); region {region/1e3:.0f} us "
          f"({region/band:.1f}x); numpy grid of 50 dampings {n['band_grid_s']*1e3:.1f} ms "
          f"({n['band_grid_s']*1e9/band:.0f}x); whole kmax query {q_band/1e3:.1f} us")
PY
